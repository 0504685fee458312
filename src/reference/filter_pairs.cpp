// filter_pairs.cpp (reference) — see filter_pairs.h.
#include "reference/filter_pairs.h"

#include "shared/pair_filter.h"

namespace btgpu::ref {

void filterPairs(const std::vector<BtgPair>& ignored, const std::vector<BtgPair>& pairs,
                 std::vector<BtgManifoldRange>& pairManifolds)
{
    for (const BtgPair& q : ignored) {
        const int n = int(pairs.size());
        for (int i = btgFindPair(pairs.data(), n, q); i >= 0 && i < n && pairs[size_t(i)].a == q.a &&
                                                      pairs[size_t(i)].b == q.b;
             ++i)
            pairManifolds[size_t(i)].count = 0;
    }
}

}  // namespace btgpu::ref
