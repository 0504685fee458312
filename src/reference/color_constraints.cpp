// color_constraints.cpp — CPU reference of the batching stage: the device's claim/assign
// sub-rounds (lowest hashed priority wins each free dynamic body) replayed in order.
#include "reference/contact_solver_reference.h"

#include <algorithm>
#include <climits>

#include "shared/coloring.h"

namespace btgpu::ref {

void colorConstraints(std::vector<BtgContact>& contacts, const ContactBodies& bodies, int maxColors)
{
    if (maxColors < 1) maxColors = 1;
    const int rounds = maxColors - 1;
    for (BtgContact& c : contacts) c.color = -1;
    std::vector<int> claim(bodies.props.size()), used(bodies.props.size(), -1);
    auto dynamic = [&](int b) { return btgIsSolverDynamic(bodies.props[b].flags) != 0; };
    auto freeIn = [&](int b, int color) { return !dynamic(b) || used[b] != color; };
    for (int color = 0; color < rounds; ++color) {
        for (int sub = 0; sub < BTG_COLOR_SUB_ROUNDS; ++sub) {
            std::fill(claim.begin(), claim.end(), INT_MAX);
            for (int i = 0; i < int(contacts.size()); ++i) {
                const BtgContact& c = contacts[i];
                if (c.color >= 0 || !freeIn(c.bodyA, color) || !freeIn(c.bodyB, color)) continue;
                int p = btgColorPriority(i);
                if (dynamic(c.bodyA)) claim[c.bodyA] = std::min(claim[c.bodyA], p);
                if (dynamic(c.bodyB)) claim[c.bodyB] = std::min(claim[c.bodyB], p);
            }
            for (int i = 0; i < int(contacts.size()); ++i) {
                BtgContact& c = contacts[i];
                if (c.color >= 0 || !freeIn(c.bodyA, color) || !freeIn(c.bodyB, color)) continue;
                int p = btgColorPriority(i);
                if ((dynamic(c.bodyA) && claim[c.bodyA] != p) || (dynamic(c.bodyB) && claim[c.bodyB] != p)) continue;
                c.color = color;
                if (dynamic(c.bodyA)) used[c.bodyA] = color;
                if (dynamic(c.bodyB)) used[c.bodyB] = color;
            }
        }
    }
    for (BtgContact& c : contacts)
        if (c.color < 0) c.color = rounds;
}

}  // namespace btgpu::ref
