// leaf_pairs.cpp — stock's pair cache from the device's leaf-pair changes, with the timing of
// btDbvtBroadphase's lazy removal (collide(): m_cupdates 10 %, m_newpairs, round robin from m_cid),
// and the world's use of it around a device call (GpuWorld::startLeafPairs, noteLeafPairs).
#include "leaf_pairs.h"

#include "ghost_objects.h"
#include "gpu_world.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <set>

namespace btgpu {

void LeafPairCache::clear()
{
    m_pairs.clear();
    m_index.clear();
    m_overlapping.clear();
    m_cid = 0;
    m_cleared = true;
}

void LeafPairCache::removeAt(size_t at)
{
    m_left.push_back(m_pairs[at]);
    m_index.erase(key(m_pairs[at]));
    if (at + 1 != m_pairs.size()) {
        m_pairs[at] = m_pairs.back();
        m_index[key(m_pairs[at])] = at;
    }
    m_pairs.pop_back();
}

void LeafPairCache::apply(const LeafChanges& changes, int steps)
{
    m_joined.clear();
    m_left.clear();
    m_fresh = m_cleared;
    m_cleared = false;
    for (const BtgPair& p : changes.removed) m_overlapping.erase(key(p));
    // setAabb's tree collisions add the pairs before collide() cleans up.
    for (const BtgPair& p : changes.added) {
        m_overlapping.insert(key(p));
        if (m_index.emplace(key(p), m_pairs.size()).second) {
            m_pairs.push_back({p.a, p.b, 0, 0});
            m_joined.push_back(m_pairs.back());
        }
    }
    // Met only on the way (a moved leaf against a neighbour's old one): in the cache, for the
    // cleanup to drop.
    for (const BtgPair& p : changes.transient)
        if (m_index.emplace(key(p), m_pairs.size()).second) {
            m_pairs.push_back({p.a, p.b, 0, 0});
            m_joined.push_back(m_pairs.back());
        }
    // m_needcleanup: some leaf moved (a pair can only stop overlapping then).
    if (changes.moved == 0) return;
    for (int step = 0; step < std::max(steps, 1); ++step) {
        int size = int(m_pairs.size());
        if (size == 0) {
            m_cid = 0;
            return;
        }
        // The last step's overlaps are the counted ones (a call's earlier steps start at 1).
        const int newPairs = 1 + (step == steps - 1 ? int(changes.newPairs) : 0);
        int ni = std::min(size, std::max(newPairs, (size * 10) / 100));
        for (int i = 0; i < ni; ++i) {
            const size_t at = size_t((m_cid + i) % int(m_pairs.size()));
            if (!m_overlapping.count(key(m_pairs[at]))) {
                removeAt(at);
                --ni;
                --i;
                if (m_pairs.empty()) break;
            }
        }
        m_cid = m_pairs.empty() ? 0 : (m_cid + ni) % int(m_pairs.size());
    }
}

bool GpuWorld::deviceLeafPairs() const
{
    return m_config.fillDispatcherManifolds && m_config.deviceEmptyManifolds && !broadphaseAsStock() &&
           m_world.getForceUpdateAllAabbs() && m_world.getNumCollisionObjects() <= m_config.deviceEmptyManifoldsUpTo;
}

void GpuWorld::startLeafPairs()
{
    LeafBuffers& l = m_dev->leaves;
    l.continuous = m_world.getDispatchInfo().m_useContinuous;
    l.threshold = float(gContactBreakingThreshold);
    startLeafCall(*m_dev);
}

void GpuWorld::noteLeafPairs(int steps)
{
    const LeafChanges changes = readLeafChanges(*m_dev);
    m_leafPairs.apply(changes, steps);
    if (ghostsFromDevice()) followGhostPairs();
    if (!deviceLeafPairs()) return;  // the stage runs for the ghosts only: no empty manifolds
    if (m_leafPairs.fresh())
        m_manifolds.noteLeafPairs(m_world.getDispatcher(), m_leafPairs.pairs(), m_rows, m_removed);
    else
        m_manifolds.noteLeafChanges(m_world.getDispatcher(), m_leafPairs.joined(), m_leafPairs.left(), m_rows, m_removed);
}

bool GpuWorld::ghostsFromDevice() const
{
    // Triggers only (ghosts without contact response): a character's ghost is moved by its action,
    // whose setAabb calls move stock's Dbvt leaf within the step (Bullet's immediate pair test,
    // and the leaf the next step's update starts from), which the device's leaves do not follow.
    const bool triggers = std::none_of(m_ghostResponds.begin(), m_ghostResponds.end(), [](char r) { return r != 0; });
    return !m_ghosts.empty() && triggers && m_config.ghostPairsFromDevice && !m_overlapFilter &&
           !(m_config.fillDispatcherManifolds && m_config.stockEmptyManifolds) && dbvtBroadphase() &&
           m_world.getForceUpdateAllAabbs() && m_world.getNumCollisionObjects() > m_config.ghostPairsExactUpTo;
}

void GpuWorld::followGhostPairs()
{
    btOverlappingPairCache* cache = m_world.getPairCache();
    btDispatcher* dispatcher = m_world.getDispatcher();
    auto object = [&](int row) -> btCollisionObject* {
        btCollisionObject* o = row >= 0 && size_t(row) < m_rows.size() ? m_rows.at(size_t(row)) : nullptr;
        return o && !m_removed.count(o) && o->getBroadphaseHandle() ? o : nullptr;
    };
    auto ghost = [](const btCollisionObject* o) { return o->getInternalType() == btCollisionObject::CO_GHOST_OBJECT; };
    // As stock's tree collider hands a pair to the cache (DBVT_BP_SORTPAIRS): the cache orders the
    // proxies itself, filters by group and mask, and calls the ghost callback for a new pair.
    auto each = [&](const std::vector<BtgPair>& pairs, bool add) {
        for (const BtgPair& p : pairs) {
            btCollisionObject *a = object(p.a), *b = object(p.b);
            if (!a || !b || (!ghost(a) && !ghost(b))) continue;
            btBroadphaseProxy *pa = a->getBroadphaseHandle(), *pb = b->getBroadphaseHandle();
            if (pa > pb) std::swap(pa, pb);
            if (add) cache->addOverlappingPair(pa, pb);
            else cache->removeOverlappingPair(pa, pb, dispatcher);
        }
    };
    if (m_leafPairs.fresh()) {
        // The leaves started afresh (rows re-uploaded, or this mode just began): a ghost pair
        // Bullet's cache holds that the device's pairs do not goes.
        using ProxyPair = std::pair<const btBroadphaseProxy*, const btBroadphaseProxy*>;
        auto ordered = [](const btBroadphaseProxy* x, const btBroadphaseProxy* y) {
            return x < y ? ProxyPair(x, y) : ProxyPair(y, x);
        };
        std::set<ProxyPair> now;
        for (const BtgPair& p : m_leafPairs.pairs()) {
            btCollisionObject *a = object(p.a), *b = object(p.b);
            if (a && b) now.insert(ordered(a->getBroadphaseHandle(), b->getBroadphaseHandle()));
        }
        std::vector<std::pair<btBroadphaseProxy*, btBroadphaseProxy*>> gone;
        const btBroadphasePairArray& held = cache->getOverlappingPairArray();
        for (int i = 0; i < held.size(); ++i) {
            btBroadphaseProxy *pa = held[i].m_pProxy0, *pb = held[i].m_pProxy1;
            auto *a = static_cast<btCollisionObject*>(pa->m_clientObject), *b = static_cast<btCollisionObject*>(pb->m_clientObject);
            if ((ghost(a) || ghost(b)) && !now.count(ordered(pa, pb))) gone.push_back({pa, pb});
        }
        for (const auto& [pa, pb] : gone) cache->removeOverlappingPair(pa, pb, dispatcher);
    }
    // setAabb's tree collisions add the step's pairs before collide()'s cleanup removes.
    each(m_leafPairs.joined(), true);
    each(m_leafPairs.left(), false);
    // Stock's islands: a ghost with contact response holds awake what it has a pair with.
    heldAwakeByGhosts(m_world, m_rows, &m_heldAwake);
}

}  // namespace btgpu
