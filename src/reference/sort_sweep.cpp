// sort_sweep.cpp (reference) — the kernels' steps in plain loops: lane sums and halving tree
// as sap_axis does them, keys, a stable sort (the radix sort is stable), the sweep, and a final
// sort of the pairs by (a, b) as find_pairs does.
#include "reference/sort_sweep.h"

#include "shared/broadphase.h"
#include "shared/sort_sweep.h"

#include <algorithm>

namespace btgpu::ref {

uint sortSweepAxis(const std::vector<BtgFloat4>& aabbMin, const std::vector<BtgFloat4>& aabbMax,
                   const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes)
{
    BtgFloat4 sum[BTG_SAP_LANES], sumSq[BTG_SAP_LANES];
    const int n = int(props.size());
    for (int lane = 0; lane < BTG_SAP_LANES; ++lane) {
        BtgFloat4 s = btgZero4(), q = btgZero4();
        for (int i = lane; i < n; i += BTG_SAP_LANES) {
            if (!btgGridded(props[size_t(i)], shapes.data())) continue;
            BtgFloat4 c = btgSapCentre(aabbMin[size_t(i)], aabbMax[size_t(i)]);
            s = s + c;
            q = q + btgSapSquare(c);
        }
        sum[lane] = s;
        sumSq[lane] = q;
    }
    for (int half = BTG_SAP_LANES / 2; half > 0; half >>= 1)
        for (int lane = 0; lane < half; ++lane) {
            sum[lane] = sum[lane] + sum[lane + half];
            sumSq[lane] = sumSq[lane] + sumSq[lane + half];
        }
    return btgSapAxis(sum[0], sumSq[0]);
}

std::vector<BtgPair> sortSweepPairs(const std::vector<BtgFloat4>& aabbMin, const std::vector<BtgFloat4>& aabbMax,
                                    const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes)
{
    const uint axis = sortSweepAxis(aabbMin, aabbMax, props, shapes);
    struct Entry {
        uint key;
        int row;
    };
    std::vector<Entry> sorted;
    for (size_t i = 0; i < props.size(); ++i)
        if (btgGridded(props[i], shapes.data())) sorted.push_back({btgSapKey(btgAxisValue(aabbMin[i], axis)), int(i)});
    std::stable_sort(sorted.begin(), sorted.end(), [](const Entry& x, const Entry& y) { return x.key < y.key; });
    std::vector<BtgPair> out;
    for (size_t k = 0; k < sorted.size(); ++k) {
        const int i = sorted[k].row;
        const float reach = btgAxisValue(aabbMax[size_t(i)], axis);
        for (size_t m = k + 1; m < sorted.size(); ++m) {
            const int j = sorted[m].row;
            if (!(btgAxisValue(aabbMin[size_t(j)], axis) <= reach)) break;
            if (!btgAabbOverlap(aabbMin[size_t(i)], aabbMax[size_t(i)], aabbMin[size_t(j)], aabbMax[size_t(j)])) continue;
            if (!btgPairAllowed(props[size_t(i)], props[size_t(j)])) continue;
            out.push_back(BtgPair{std::min(i, j), std::max(i, j), BTG_WHOLE_BODY, BTG_WHOLE_BODY});
        }
    }
    std::sort(out.begin(), out.end(), [](const BtgPair& x, const BtgPair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    return out;
}

}  // namespace btgpu::ref
