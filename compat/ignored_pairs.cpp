// ignored_pairs.cpp — the collision-check exceptions of the rows as sorted row pairs.
#include "ignored_pairs.h"

#include <btBulletCollisionCommon.h>

#include <algorithm>

namespace btgpu {

bool IgnoredPairs::update(const RowMap& rows, DeviceWorld& w)
{
    std::vector<BtgPair> pairs;
    for (size_t r = 0; r < rows.size(); ++r) {
        btCollisionObject* o = rows.at(r);
        if (!o || o->getNumObjectsWithoutCollision() == 0) continue;
        for (int k = 0; k < o->getNumObjectsWithoutCollision(); ++k) {
            const int other = rows.rowOf(o->getObjectWithoutCollision(k));
            if (other < 0 || other == int(r)) continue;  // not in the world: nothing to filter
            BtgPair p;
            p.a = std::min(int(r), other);
            p.b = std::max(int(r), other);
            pairs.push_back(p);
        }
    }
    std::sort(pairs.begin(), pairs.end(), [](BtgPair x, BtgPair y) { return x.a < y.a || (x.a == y.a && x.b < y.b); });
    pairs.erase(std::unique(pairs.begin(), pairs.end(), [](BtgPair x, BtgPair y) { return x.a == y.a && x.b == y.b; }),
                pairs.end());
    const bool wasAny = any();
    const bool same = m_valid && pairs.size() == m_uploaded.size() &&
                      std::equal(pairs.begin(), pairs.end(), m_uploaded.begin(),
                                 [](BtgPair x, BtgPair y) { return x.a == y.a && x.b == y.b; });
    if (!same) {
        if (!pairs.empty()) w.ignoredPairs.upload(w.ctx, pairs);
        m_uploaded = pairs;
        m_valid = true;
    }
    w.numIgnoredPairs = int(m_uploaded.size());
    return wasAny != any();
}

}  // namespace btgpu
