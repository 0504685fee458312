// find_pairs.h (reference) — brute-force O(n^2) broadphase with the kernel's own rules
// (shared/broadphase.h): every row pair is tested, no grid, no large/small distinction.
#pragma once
#include "shared/types.h"

#include <vector>

namespace btgpu::ref {
// All pairs (a < b) sorted by (a, b): planes against non-planes by the plane test, other rows
// by AABB overlap, both under btgPairAllowed.
std::vector<BtgPair> findPairs(const std::vector<BtgFloat4>& aabbMin, const std::vector<BtgFloat4>& aabbMax,
                               const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes,
                               const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot);
}  // namespace btgpu::ref
