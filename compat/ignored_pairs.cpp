// ignored_pairs.cpp — the collision-check exceptions of the rows as sorted row pairs.
#include "ignored_pairs.h"

#include "parallel_rows.h"

#include <btBulletCollisionCommon.h>

#include <algorithm>

namespace btgpu {

bool IgnoredPairs::update(const RowMap& rows, DeviceWorld& w)
{
    // Rows are read in parallel chunks (a step visits every row: most scenes have no
    // exception at all), each chunk's pairs merged in row order.
    const size_t n = rows.size();
    const size_t minPerThread = 8192;
    std::vector<std::vector<BtgPair>> found(size_t(chunkCount(n, minPerThread)));
    forEachChunk(n, minPerThread, [&](size_t begin, size_t end, int chunk) {
        for (size_t r = begin; r < end; ++r) {
            btCollisionObject* o = rows.at(r);
            if (!o || o->getNumObjectsWithoutCollision() == 0) continue;
            for (int k = 0; k < o->getNumObjectsWithoutCollision(); ++k) {
                const int other = rows.rowOf(o->getObjectWithoutCollision(k));
                if (other < 0 || other == int(r)) continue;  // not in the world: nothing to filter
                BtgPair p{};
                p.a = std::min(int(r), other);
                p.b = std::max(int(r), other);
                found[size_t(chunk)].push_back(p);
            }
        }
    });
    std::vector<BtgPair> pairs;
    for (const std::vector<BtgPair>& list : found) pairs.insert(pairs.end(), list.begin(), list.end());
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
