// color_constraints.cpp — CPU reference of the batching stage: the device's claim/assign
// rounds (lowest contact index wins each dynamic body) replayed one after the other.
#include "reference/contact_solver_reference.h"

#include <algorithm>
#include <climits>

namespace btgpu::ref {

void colorConstraints(std::vector<BtgContact>& contacts, const ContactBodies& bodies, int maxColors)
{
    if (maxColors < 1) maxColors = 1;
    for (BtgContact& c : contacts) c.color = -1;
    std::vector<int> claim(bodies.props.size());
    auto dynamic = [&](int b) { return btgIsSolverDynamic(bodies.props[b].flags) != 0; };
    for (int round = 0; round < maxColors - 1; ++round) {
        std::fill(claim.begin(), claim.end(), INT_MAX);
        for (int i = 0; i < int(contacts.size()); ++i) {
            const BtgContact& c = contacts[i];
            if (c.color >= 0) continue;
            if (dynamic(c.bodyA)) claim[c.bodyA] = std::min(claim[c.bodyA], i);
            if (dynamic(c.bodyB)) claim[c.bodyB] = std::min(claim[c.bodyB], i);
        }
        for (int i = 0; i < int(contacts.size()); ++i) {
            BtgContact& c = contacts[i];
            if (c.color >= 0) continue;
            bool ownA = !dynamic(c.bodyA) || claim[c.bodyA] == i;
            bool ownB = !dynamic(c.bodyB) || claim[c.bodyB] == i;
            if (ownA && ownB) c.color = round;
        }
    }
    for (BtgContact& c : contacts)
        if (c.color < 0) c.color = maxColors - 1;
}

}  // namespace btgpu::ref
