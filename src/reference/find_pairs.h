// find_pairs.h (reference) — brute-force O(n^2) broadphase with the kernel's own rules
// (shared/broadphase.h): every row pair is tested, no grid, no large/small distinction; and
// the grouping of the sorted pairs by kind (shared/pair_kinds.h).
#pragma once
#include "shared/types.h"

#include <vector>

namespace btgpu::ref {
// All pairs (a < b) sorted by (a, b): planes against non-planes by the plane test, other rows
// by AABB overlap, both under btgPairAllowed.
std::vector<BtgPair> findPairs(const std::vector<BtgFloat4>& aabbMin, const std::vector<BtgFloat4>& aabbMax,
                               const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes,
                               const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot);

// The pairs grouped by kind, as find_pairs' kind pass leaves them: slots ordered by (kind, slot)
// and kind k's [start, end) of that order at ranges[BTG_KIND_RANGE_*(k)].
struct PairKindGroups {
    std::vector<uint> order;
    std::vector<uint> ranges;  // BTG_KIND_RANGES_SIZE
};
PairKindGroups groupPairsByKind(const std::vector<BtgPair>& pairs, const std::vector<BtgBodyProps>& props,
                                const std::vector<BtgShape>& shapes);
}  // namespace btgpu::ref
