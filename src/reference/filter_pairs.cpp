// filter_pairs.cpp (reference) — see filter_pairs.h.
#include "reference/filter_pairs.h"

#include "shared/pair_filter.h"

namespace btgpu::ref {

void filterPairs(const std::vector<BtgPair>& ignored, const std::vector<BtgPair>& pairs,
                 std::vector<BtgManifoldRange>& pairManifolds)
{
    for (const BtgPair& q : ignored) {
        int i = btgFindPair(pairs.data(), int(pairs.size()), q);
        if (i >= 0) pairManifolds[size_t(i)].count = 0;
    }
}

}  // namespace btgpu::ref
