// color_constraints.cpp — CPU reference of the batching stage: the device's claim/assign
// sub-rounds over the constraint graph's edges (lowest hashed priority wins each free dynamic
// body) replayed in order.
#include "reference/contact_solver_reference.h"

#include <algorithm>
#include <climits>

#include "shared/coloring.h"

namespace btgpu::ref {

std::vector<int> colorConstraints(const std::vector<BtgEdge>& edges, const ContactBodies& bodies, int maxColors)
{
    if (maxColors < 1) maxColors = 1;
    const int rounds = maxColors - 1;
    std::vector<int> colors(edges.size(), -1);
    std::vector<uint> claim(bodies.props.size());
    std::vector<int> used(bodies.props.size(), -1);
    auto dynamic = [&](int b) { return btgIsSolverDynamic(bodies.props[b].flags) != 0; };
    auto freeIn = [&](int b, int color) { return !dynamic(b) || used[b] != color; };
    for (int color = 0; color < rounds; ++color) {
        for (int sub = 0; sub < BTG_COLOR_SUB_ROUNDS; ++sub) {
            std::fill(claim.begin(), claim.end(), UINT_MAX);
            for (int i = 0; i < int(edges.size()); ++i) {
                const BtgEdge& e = edges[i];
                if (colors[i] >= 0 || !freeIn(e.bodyA, color) || !freeIn(e.bodyB, color)) continue;
                const uint p = btgColorPriority(i);
                if (dynamic(e.bodyA)) claim[e.bodyA] = std::min(claim[e.bodyA], p);
                if (dynamic(e.bodyB)) claim[e.bodyB] = std::min(claim[e.bodyB], p);
            }
            for (int i = 0; i < int(edges.size()); ++i) {
                const BtgEdge& e = edges[i];
                if (colors[i] >= 0 || !freeIn(e.bodyA, color) || !freeIn(e.bodyB, color)) continue;
                const uint p = btgColorPriority(i);
                if ((dynamic(e.bodyA) && claim[e.bodyA] != p) || (dynamic(e.bodyB) && claim[e.bodyB] != p)) continue;
                colors[i] = color;
                if (dynamic(e.bodyA)) used[e.bodyA] = color;
                if (dynamic(e.bodyB)) used[e.bodyB] = color;
            }
        }
    }
    for (int& c : colors)
        if (c < 0) c = rounds;
    return colors;
}

}  // namespace btgpu::ref
