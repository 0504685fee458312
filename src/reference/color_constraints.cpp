// color_constraints.cpp — CPU reference of the batching stage: the device's claim/assign
// sub-rounds over the constraint graph's edges (lowest hashed priority wins each free dynamic
// body) replayed in order.
#include "reference/contact_solver_reference.h"

#include <algorithm>
#include <climits>

#include "shared/coloring.h"

namespace btgpu::ref {

std::vector<int> colorConstraints(const std::vector<BtgEdge>& edges, const ContactBodies& bodies, int maxColors,
                                  const std::vector<int>& jointLevels, int firstJointEdge)
{
    if (maxColors < 1) maxColors = 1;
    const int rounds = maxColors - 1;
    std::vector<int> colors(edges.size(), -1);
    std::vector<uint> claim(bodies.props.size());
    std::vector<int> used(bodies.props.size(), -1);
    auto dynamic = [&](int b) { return btgIsSolverDynamic(bodies.props[b].flags) != 0; };
    auto freeIn = [&](int b, int color) { return !dynamic(b) || used[b] != color; };
    // Ordered joints (edges firstJointEdge + j): colour jointLevels[j], taken at that colour's
    // start; they bid for nothing.
    auto level = [&](int i) {
        const int j = i - firstJointEdge;
        return firstJointEdge >= 0 && j >= 0 && j < int(jointLevels.size()) ? jointLevels[size_t(j)] : -1;
    };
    for (int color = 0; color < rounds; ++color) {
        for (int i = 0; i < int(edges.size()); ++i) {
            if (level(i) != color) continue;
            colors[i] = color;
            if (dynamic(edges[i].bodyA)) used[edges[i].bodyA] = color;
            if (dynamic(edges[i].bodyB)) used[edges[i].bodyB] = color;
        }
        for (int sub = 0; sub < BTG_COLOR_SUB_ROUNDS; ++sub) {
            std::fill(claim.begin(), claim.end(), UINT_MAX);
            for (int i = 0; i < int(edges.size()); ++i) {
                const BtgEdge& e = edges[i];
                if (level(i) >= 0) continue;
                if (colors[i] >= 0 || !freeIn(e.bodyA, color) || !freeIn(e.bodyB, color)) continue;
                const uint p = btgColorPriority(i);
                if (dynamic(e.bodyA)) claim[e.bodyA] = std::min(claim[e.bodyA], p);
                if (dynamic(e.bodyB)) claim[e.bodyB] = std::min(claim[e.bodyB], p);
            }
            for (int i = 0; i < int(edges.size()); ++i) {
                const BtgEdge& e = edges[i];
                if (level(i) >= 0) continue;
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
