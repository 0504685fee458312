// filter_pairs.h (reference) — the pair filter on the CPU: the same binary search
// (kernels/shared/pair_filter.h) over the sorted pair list.
#pragma once
#include "shared/types.h"

#include <vector>

namespace btgpu::ref {

// Empties the manifold range of every pair of `pairs` (sorted) that is in `ignored`.
void filterPairs(const std::vector<BtgPair>& ignored, const std::vector<BtgPair>& pairs,
                 std::vector<BtgManifoldRange>& pairManifolds);

}  // namespace btgpu::ref
