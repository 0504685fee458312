// find_pairs.cpp (reference) — two nested loops over the rows that can pair at all, in row
// order, so the output is already sorted by (a, b); the kind grouping by one sweep per kind.
#include "reference/find_pairs.h"

#include "shared/broadphase.h"
#include "shared/pair_kinds.h"

#include <algorithm>

namespace btgpu::ref {
std::vector<BtgPair> findPairs(const std::vector<BtgFloat4>& aabbMin, const std::vector<BtgFloat4>& aabbMax,
                               const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes,
                               const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot)
{
    std::vector<BtgPair> out;
    const int n = int(props.size());
    auto isPlane = [&](int i) { return shapes[size_t(props[size_t(i)].shape)].type == BTG_SHAPE_PLANE; };
    // Excluded rows never pair: dropping them first keeps sparse scenes with many rows (the
    // two-pass pair sort needs > 65536) quick to check.
    std::vector<int> live;
    for (int i = 0; i < n; ++i)
        if (!(props[size_t(i)].flags & BTG_BODY_EXCLUDED)) live.push_back(i);
    for (size_t ia = 0; ia < live.size(); ++ia) {
        for (size_t ib = ia + 1; ib < live.size(); ++ib) {
            const int a = live[ia], b = live[ib];
            const BtgBodyProps& pa = props[size_t(a)];
            const BtgBodyProps& pb = props[size_t(b)];
            if (!btgPairAllowed(pa, pb)) continue;
            bool planeA = isPlane(a), planeB = isPlane(b);
            bool keep;
            if (planeA && planeB) {
                keep = false;
            } else if (planeA || planeB) {
                int p = planeA ? a : b, o = planeA ? b : a;
                BtgFloat4 plane = btgPlaneWorld(pos[size_t(p)], rot[size_t(p)], shapes[size_t(props[size_t(p)].shape)].param);
                keep = btgAabbReachesPlane(aabbMin[size_t(o)], aabbMax[size_t(o)], plane);
            } else {
                keep = btgAabbOverlap(aabbMin[size_t(a)], aabbMax[size_t(a)], aabbMin[size_t(b)], aabbMax[size_t(b)]);
            }
            if (keep) out.push_back(BtgPair{a, b, BTG_WHOLE_BODY, BTG_WHOLE_BODY});
        }
    }
    return out;
}

PairKindGroups groupPairsByKind(const std::vector<BtgPair>& pairs, const std::vector<BtgBodyProps>& props,
                                const std::vector<BtgShape>& shapes)
{
    auto kindOf = [&](uint slot) {
        const BtgPair& p = pairs[slot];
        return btgPairKind(shapes[size_t(props[size_t(p.a)].shape)].type, shapes[size_t(props[size_t(p.b)].shape)].type);
    };
    PairKindGroups g;
    g.ranges.assign(BTG_KIND_RANGES_SIZE, 0u);
    for (int kind = 0; kind < BTG_NUM_PAIR_KINDS; ++kind) {
        g.ranges[BTG_KIND_RANGE_START(kind)] = uint(g.order.size());
        for (uint slot = 0; slot < uint(pairs.size()); ++slot)
            if (kindOf(slot) == kind) g.order.push_back(slot);
        g.ranges[BTG_KIND_RANGE_END(kind)] = uint(g.order.size());
    }
    return g;
}
}  // namespace btgpu::ref
