// pair_manifolds.cpp — Config::stockEmptyManifolds: the dispatcher holds a manifold for every pair
// stock's dispatcher has collided, touching or not, as stock's collision algorithms hold one from
// their pair's first collision until the pair leaves the pair cache (per compound child whose AABB
// overlaps the other side's), so that getNumManifolds() is stock's count. The pairs are read from
// Bullet's own pair cache, updated as stock's at the internal step's start (ghost_objects.cpp,
// Config::stockEmptyManifolds), or from the device's leaf pairs (leaf_pairs.h, the default).
#include "manifold_sync.h"

#include <btBulletCollisionCommon.h>

#include <algorithm>

namespace btgpu {

namespace {

btVector3 childAabb(const btCollisionObject* o, int child, btVector3* max)
{
    const auto* c = static_cast<const btCompoundShape*>(o->getCollisionShape());
    btVector3 min;
    c->getChildShape(child)->getAabb(o->getWorldTransform() * c->getChildTransform(child), min, *max);
    return min;
}

}  // namespace

std::vector<ManifoldSync::Key> ManifoldSync::algorithmKeys(const btCollisionObject* a, const btCollisionObject* b,
                                                         const RowMap& rows,
                                                         const std::unordered_set<const btCollisionObject*>& removed) const
{
    // The manifolds of one pair's algorithm as its collision this step leaves them: one for two
    // whole shapes (none for two concave ones: Bullet's empty algorithm); a compound's child
    // algorithms made for the children whose AABB overlaps the other side's and freed for those
    // that stopped (btCompoundCollisionAlgorithm::processCollision; child AABBs at the step's
    // start, without a threshold, as stock's discrete collision).
    std::vector<Key> keys;
    const int ra = rows.rowOf(a), rb = rows.rowOf(b);
    if (ra < 0 || rb < 0) return keys;
    const btCollisionShape* sa = a->getCollisionShape();
    const btCollisionShape* sb = b->getCollisionShape();
    if (sa->isConcave() && sb->isConcave()) return keys;
    const int na = sa->isCompound() ? static_cast<const btCompoundShape*>(sa)->getNumChildShapes() : 0;
    const int nb = sb->isCompound() ? static_cast<const btCompoundShape*>(sb)->getNumChildShapes() : 0;
    auto add = [&](int ia, int ib) {
        const Side s = orient(rows, ra, rb, ia, ib, removed);
        if (s.valid) keys.push_back(s.key);
    };
    if (!sa->isCompound() && !sb->isCompound()) {
        add(-1, -1);
        return keys;
    }
    btVector3 wholeMinA, wholeMaxA, wholeMinB, wholeMaxB;
    sa->getAabb(a->getWorldTransform(), wholeMinA, wholeMaxA);
    sb->getAabb(b->getWorldTransform(), wholeMinB, wholeMaxB);
    if (sa->isCompound() && sb->isCompound()) {
        for (int i = 0; i < na; ++i) {
            btVector3 maxA, minA = childAabb(a, i, &maxA);
            if (!TestAabbAgainstAabb2(minA, maxA, wholeMinB, wholeMaxB)) continue;
            for (int j = 0; j < nb; ++j) {
                btVector3 maxB, minB = childAabb(b, j, &maxB);
                if (TestAabbAgainstAabb2(minA, maxA, minB, maxB)) add(i, j);
            }
        }
    } else if (sa->isCompound()) {
        for (int i = 0; i < na; ++i) {
            btVector3 maxA, minA = childAabb(a, i, &maxA);
            if (TestAabbAgainstAabb2(minA, maxA, wholeMinB, wholeMaxB)) add(i, -1);
        }
    } else {
        for (int j = 0; j < nb; ++j) {
            btVector3 maxB, minB = childAabb(b, j, &maxB);
            if (TestAabbAgainstAabb2(wholeMinA, wholeMaxA, minB, maxB)) add(-1, j);
        }
    }
    return keys;
}

void ManifoldSync::notePairs(btDispatcher* dispatcher, btOverlappingPairCache* cache, const RowMap& rows,
                             const std::unordered_set<const btCollisionObject*>& removed)
{
    std::vector<StockPair> list;
    if (dispatcher && cache) {
        const btBroadphasePairArray& pairs = cache->getOverlappingPairArray();
        list.reserve(size_t(pairs.size()));
        for (int i = 0; i < pairs.size(); ++i) {
            const btBroadphasePair& pair = pairs[i];
            list.push_back({static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject),
                            static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject),
                            (static_cast<unsigned long long>(unsigned(pair.m_pProxy0->m_uniqueId)) << 32) |
                                unsigned(pair.m_pProxy1->m_uniqueId)});
        }
    }
    notePairList(dispatcher, dispatcher && cache, list, rows, removed);
}

namespace {

// A leaf pair (rows) as the pair cache holds it: (proxy0, proxy1), the lower unique id first.
bool cachePair(const RowMap& rows, const BtgPair& p, const btCollisionObject** a, const btCollisionObject** b,
               unsigned long long* id)
{
    *a = rows.at(size_t(p.a));
    *b = rows.at(size_t(p.b));
    if (!*a || !*b || !(*a)->getBroadphaseHandle() || !(*b)->getBroadphaseHandle()) return false;
    unsigned ia = unsigned((*a)->getBroadphaseHandle()->m_uniqueId), ib = unsigned((*b)->getBroadphaseHandle()->m_uniqueId);
    if (ia > ib) {
        std::swap(*a, *b);
        std::swap(ia, ib);
    }
    *id = (static_cast<unsigned long long>(ia) << 32) | ib;
    return true;
}

}  // namespace

void ManifoldSync::noteLeafPairs(btDispatcher* dispatcher, const std::vector<BtgPair>& pairs, const RowMap& rows,
                                 const std::unordered_set<const btCollisionObject*>& removed)
{
    std::vector<StockPair> list;
    list.reserve(pairs.size());
    for (const BtgPair& p : pairs) {
        StockPair q;
        if (cachePair(rows, p, &q.a, &q.b, &q.id)) list.push_back(q);
    }
    notePairList(dispatcher, dispatcher != nullptr, list, rows, removed);
}

void ManifoldSync::noteLeafChanges(btDispatcher* dispatcher, const std::vector<BtgPair>& joined,
                                   const std::vector<BtgPair>& left, const RowMap& rows,
                                   const std::unordered_set<const btCollisionObject*>& removed)
{
    std::vector<StockPair> in;
    std::vector<unsigned long long> out;
    for (const BtgPair& p : joined) {
        StockPair q;
        if (cachePair(rows, p, &q.a, &q.b, &q.id)) in.push_back(q);
    }
    for (const BtgPair& p : left) {
        StockPair q;
        if (cachePair(rows, p, &q.a, &q.b, &q.id)) out.push_back(q.id);
    }
    notePairChanges(dispatcher, in, out, rows, removed);
}

void ManifoldSync::notePairList(btDispatcher* dispatcher, bool valid, const std::vector<StockPair>& pairs,
                                const RowMap& rows, const std::unordered_set<const btCollisionObject*>& removed)
{
    m_wanted.clear();
    m_wantedSet.clear();
    m_wantedValid = valid;
    if (!m_wantedValid) {
        m_stockPairs.clear();
        m_uncollided.clear();
        m_compoundPairs.clear();
        return;
    }
    // Stock's near callback collides a pair only while needsCollision holds (an active body,
    // collisions not ignored); an algorithm made once lives on with its manifolds, untouched
    // while the pair is not collided (two sleeping bodies).
    std::unordered_map<unsigned long long, std::vector<Key>> next;
    m_uncollided.clear();
    m_compoundPairs.clear();
    for (const StockPair& pair : pairs) {
        const btCollisionObject* a = pair.a;
        const btCollisionObject* b = pair.b;
        if (!a || !b || (!removed.empty() && (removed.count(a) || removed.count(b)))) continue;
        const unsigned long long id = pair.id;
        if (a->getCollisionShape()->isCompound() || b->getCollisionShape()->isCompound()) m_compoundPairs[id] = pair;
        std::vector<Key> keys;
        if (dispatcher->needsCollision(a, b)) {
            keys = algorithmKeys(a, b, rows, removed);
        } else {
            auto it = m_stockPairs.find(id);
            if (it == m_stockPairs.end()) {  // never collided: no algorithm yet
                m_uncollided[id] = pair;
                continue;
            }
            keys = std::move(it->second);
        }
        for (const Key& k : keys)
            if (m_wantedSet.add(k)) m_wanted.push_back(k);
        next.emplace(id, std::move(keys));
    }
    m_stockPairs.swap(next);
}

void ManifoldSync::notePairChanges(btDispatcher* dispatcher, const std::vector<StockPair>& joined,
                                   const std::vector<unsigned long long>& left, const RowMap& rows,
                                   const std::unordered_set<const btCollisionObject*>& removed)
{
    // What notePairList leaves, followed from the cache's change only: a pair of two whole
    // convex shapes keeps its one key from its first collision until it leaves, so only the pairs
    // that joined or left, those never collided yet and those with a compound side (child
    // algorithms come and go with the child AABBs) are looked at. m_wanted: the keys new this step
    // (their manifolds are made); m_wantedSet: every noted key.
    m_wanted.clear();
    m_wantedValid = dispatcher != nullptr;
    if (!m_wantedValid) return;
    auto drop = [&](unsigned long long id) {
        auto it = m_stockPairs.find(id);
        if (it == m_stockPairs.end()) return;
        for (const Key& k : it->second) m_wantedSet.eraseKey(k);
        m_stockPairs.erase(it);
    };
    auto collide = [&](const StockPair& pair) {
        std::vector<Key> keys = algorithmKeys(pair.a, pair.b, rows, removed);
        std::vector<Key>& held = m_stockPairs[pair.id];
        for (const Key& k : held)
            if (std::find(keys.begin(), keys.end(), k) == keys.end()) m_wantedSet.eraseKey(k);
        for (const Key& k : keys)
            if (m_wantedSet.add(k)) m_wanted.push_back(k);
        held = std::move(keys);
    };
    auto gone = [&](const StockPair& p) { return !removed.empty() && (removed.count(p.a) || removed.count(p.b)); };
    for (unsigned long long id : left) {
        drop(id);
        m_uncollided.erase(id);
        m_compoundPairs.erase(id);
    }
    for (const StockPair& pair : joined) {
        if (!pair.a || !pair.b || gone(pair)) continue;
        if (pair.a->getCollisionShape()->isCompound() || pair.b->getCollisionShape()->isCompound())
            m_compoundPairs[pair.id] = pair;
        if (dispatcher->needsCollision(pair.a, pair.b)) collide(pair);
        else m_uncollided[pair.id] = pair;
    }
    for (auto it = m_uncollided.begin(); it != m_uncollided.end();) {
        if (!gone(it->second) && dispatcher->needsCollision(it->second.a, it->second.b)) {
            collide(it->second);
            it = m_uncollided.erase(it);
        } else {
            ++it;
        }
    }
    for (const auto& [id, pair] : m_compoundPairs)
        if (m_stockPairs.count(id) && !gone(pair) && dispatcher->needsCollision(pair.a, pair.b)) collide(pair);
}

void ManifoldSync::holdStockPairs(btDispatcher* dispatcher, const std::unordered_set<const btCollisionObject*>& removed)
{
    // After the fill's own manifolds: each noted pair without one gets an empty manifold from
    // the dispatcher's pool, in the pair cache's order (getNewManifold, as stock's algorithm makes
    // it: no callback for an empty one; its contact starts when the device gives it points).
    for (const Key& k : m_wanted) {
        if (!removed.empty() && (removed.count(k.body0) || removed.count(k.body1))) continue;
        Node* node = m_map.find(k);
        if (node && node->second.manifold) continue;
        if (!node) node = m_map.insert(k);
        node->second = Entry{};
        node->second.manifold = dispatcher->getNewManifold(k.body0, k.body1);
        node->second.stamp = m_stamp;
        m_byObject[k.body0].push_back(node);
        if (k.body1 != k.body0) m_byObject[k.body1].push_back(node);
        m_nextLive.push_back(node);
    }
}

}  // namespace btgpu
