// broadphase_leaves.cpp (reference) — loops over the shared leaf functions; the pairs by testing
// every two rows (no sweep), so the kernel's sweep is checked against the plain definition.
#include "reference/broadphase_leaves.h"

#include "shared/broadphase_leaves.h"

#include <algorithm>

namespace btgpu::ref {

int updateLeaves(const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot,
                 const std::vector<BtgFloat4>& linVel, const std::vector<BtgFloat4>& angVel,
                 const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes, float threshold, float dt,
                 bool continuous, bool reset, std::vector<BtgFloat4>& leafMin, std::vector<BtgFloat4>& leafMax,
                 std::vector<BtgFloat4>& oldMin, std::vector<BtgFloat4>& oldMax, std::vector<unsigned>& moved)
{
    const size_t n = pos.size();
    leafMin.resize(n);
    leafMax.resize(n);
    oldMin.resize(n);
    oldMax.resize(n);
    moved.resize(n, 0u);
    int count = 0;
    for (size_t i = 0; i < n; ++i) {
        const BtgBodyProps& p = props[i];
        if (p.flags & BTG_BODY_EXCLUDED) {
            const BtgAabb e = btgEmptyAabb();
            leafMin[i] = oldMin[i] = e.lo;
            leafMax[i] = oldMax[i] = e.hi;
            continue;
        }
        const BtgShape& s = shapes[size_t(p.shape)];
        BtgAabb leaf;
        if (reset) {
            leaf = btgLeafShapeAabb(pos[i], rot[i], s, p.flags, 0.0f);
        } else {
            leaf.lo = leafMin[i];
            leaf.hi = leafMax[i];
        }
        oldMin[i] = leaf.lo;
        oldMax[i] = leaf.hi;
        const BtgAabb a = btgStockAabb(pos[i], rot[i], linVel[i], angVel[i], s, p.flags, threshold, dt, continuous);
        if (btgLeafUpdate(&leaf, a)) {
            moved[i] = 1u;
            ++count;
        }
        leafMin[i] = leaf.lo;
        leafMax[i] = leaf.hi;
    }
    return count;
}

std::vector<BtgPair> leafPairs(const std::vector<BtgBodyProps>& props, const std::vector<BtgFloat4>& leafMin,
                               const std::vector<BtgFloat4>& leafMax, const std::vector<BtgFloat4>& oldMin,
                               const std::vector<BtgFloat4>& oldMax, const std::vector<unsigned>& moved,
                               unsigned* newPairs, std::vector<BtgPair>* transient)
{
    std::vector<BtgPair> pairs;
    *newPairs = 0;
    transient->clear();
    const int n = int(props.size());
    for (int a = 0; a < n; ++a) {
        if (props[size_t(a)].flags & BTG_BODY_EXCLUDED) continue;
        const BtgAabb na{leafMin[size_t(a)], leafMax[size_t(a)]};
        for (int b = a + 1; b < n; ++b) {
            if (props[size_t(b)].flags & BTG_BODY_EXCLUDED) continue;
            const BtgAabb nb{leafMin[size_t(b)], leafMax[size_t(b)]};
            const BtgAabb ob{oldMin[size_t(b)], oldMax[size_t(b)]};
            int meets = 0;
            const unsigned share = btgLeafJudge(na, nb, ob, moved[size_t(a)], moved[size_t(b)], &meets);
            *newPairs += share;
            if (!btgLeafPairAllowed(props[size_t(a)], props[size_t(b)])) continue;
            if (meets) pairs.push_back({a, b, 0, 0});
            else if (share) transient->push_back({a, b, 0, 0});
        }
    }
    return pairs;
}

void leafDiff(const std::vector<BtgPair>& next, const std::vector<BtgPair>& prev, std::vector<BtgPair>* added,
              std::vector<BtgPair>* removed)
{
    added->clear();
    removed->clear();
    for (const BtgPair& p : next)
        if (!btgLeafPairIn(prev.data(), int(prev.size()), p)) added->push_back(p);
    for (const BtgPair& p : prev)
        if (!btgLeafPairIn(next.data(), int(next.size()), p)) removed->push_back(p);
}

}  // namespace btgpu::ref
