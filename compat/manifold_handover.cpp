// manifold_handover.cpp — ManifoldSync::handToStock: the GPU path's manifolds given to stock's
// algorithms when Bullet's own step takes over, so that a resting contact keeps its points
// (stock's box algorithm refreshes them and adds its detector's) instead of starting anew.
#include "manifold_sync.h"

#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <unordered_map>
#include <vector>

#include "shared/types.h"

namespace btgpu {

namespace {
bool convexLeaf(const btCollisionObject* o)
{
    const btCollisionShape* s = o->getCollisionShape();
    return s && !s->isCompound() && !s->isConcave() && !s->isSoftBody() && s->getShapeType() != SPHERE_SHAPE_PROXYTYPE;
}

// The point as seen with the bodies' roles swapped.
btManifoldPoint swapped(const btManifoldPoint& p)
{
    btManifoldPoint q = p;
    q.m_localPointA = p.m_localPointB;
    q.m_localPointB = p.m_localPointA;
    q.m_positionWorldOnA = p.m_positionWorldOnB;
    q.m_positionWorldOnB = p.m_positionWorldOnA;
    q.m_normalWorldOnB = -p.m_normalWorldOnB;
    q.m_partId0 = p.m_partId1;
    q.m_partId1 = p.m_partId0;
    q.m_index0 = p.m_index1;
    q.m_index1 = p.m_index0;
    return q;
}
}  // namespace

int ManifoldSync::handToStock(btCollisionWorld& world)
{
    btDispatcher* dispatcher = world.getDispatcher();
    btBroadphaseInterface* broadphase = world.getBroadphase();
    btOverlappingPairCache* cache = broadphase ? broadphase->getOverlappingPairCache() : nullptr;
    // The points first (their user data goes with them, not destroyed), then every manifold of
    // ours given back: the dispatcher then holds none of them, whatever order the map releases
    // them in, so the algorithms' manifolds made next sit in the pair cache's order, as stock's
    // near callback leaves them (the CPU path's solve order: bitwise repeatable).
    struct Held {
        const btCollisionObject* body0;
        int numPoints;
        btManifoldPoint points[4];
    };
    std::unordered_map<const void*, std::unordered_map<const void*, Held>> held;
    if (dispatcher && cache)
        m_map.forEach([&](Node* node) {
            btPersistentManifold* m = node->second.manifold;
            const Key& key = node->first;
            if (!m || m->getNumContacts() == 0 || key.sub0 >= 0 || key.sub1 >= 0) return;
            if (!convexLeaf(m->getBody0()) || !convexLeaf(m->getBody1())) return;
            Held h{m->getBody0(), std::min(m->getNumContacts(), 4), {}};
            for (int j = 0; j < h.numPoints; ++j) {
                h.points[j] = m->getContactPoint(j);
                m->getContactPoint(j).m_userPersistentData = nullptr;
            }
            m->setNumContacts(0);
            const void* lo = std::min<const void*>(m->getBody0(), m->getBody1());
            const void* hi = std::max<const void*>(m->getBody0(), m->getBody1());
            held[lo][hi] = h;
        });
    releaseAll(dispatcher);
    if (held.empty()) return 0;
    int handed = 0;
    btManifoldArray manifolds;
    btBroadphasePairArray& pairs = cache->getOverlappingPairArray();
    for (int i = 0; i < pairs.size(); ++i) {
        btBroadphasePair& pair = pairs[i];
        btCollisionObject* o0 = static_cast<btCollisionObject*>(pair.m_pProxy0->m_clientObject);
        btCollisionObject* o1 = static_cast<btCollisionObject*>(pair.m_pProxy1->m_clientObject);
        auto outer = held.find(std::min<const void*>(o0, o1));
        if (outer == held.end()) continue;
        auto inner = outer->second.find(std::max<const void*>(o0, o1));
        if (inner == outer->second.end()) continue;
        const Held& h = inner->second;
        if (!pair.m_algorithm) {
            // As btCollisionDispatcher::defaultNearCallback makes it.
            if (!dispatcher->needsCollision(o0, o1)) continue;
            btCollisionObjectWrapper w0(nullptr, o0->getCollisionShape(), o0, o0->getWorldTransform(), -1, -1);
            btCollisionObjectWrapper w1(nullptr, o1->getCollisionShape(), o1, o1->getWorldTransform(), -1, -1);
            pair.m_algorithm = dispatcher->findAlgorithm(&w0, &w1, nullptr, BT_CONTACT_POINT_ALGORITHMS);
            if (!pair.m_algorithm) continue;
        }
        manifolds.resize(0);
        pair.m_algorithm->getAllContactManifolds(manifolds);
        if (manifolds.size() != 1 || manifolds[0]->getNumContacts() != 0) continue;
        btPersistentManifold* target = manifolds[0];
        const bool swap = target->getBody0() != h.body0;
        for (int j = 0; j < h.numPoints; ++j) target->addManifoldPoint(swap ? swapped(h.points[j]) : h.points[j]);
        inner->second.numPoints = 0;  // handed over
        ++handed;
    }
    // Points no algorithm took (a lazily made manifold, a pair stock would not collide): their
    // user data is destroyed, as the release would have.
    for (auto& [lo, inners] : held)
        for (auto& [hi, h] : inners)
            for (int j = 0; j < h.numPoints; ++j)
                if (h.points[j].m_userPersistentData && gContactDestroyedCallback)
                    gContactDestroyedCallback(h.points[j].m_userPersistentData);
    return handed;
}

int ManifoldSync::takeFromStock(btDispatcher* dispatcher)
{
    if (!dispatcher) return 0;
    int taken = 0;
    const int n = dispatcher->getNumManifolds();
    std::vector<btPersistentManifold*> theirs;
    for (int i = 0; i < n; ++i) theirs.push_back(dispatcher->getManifoldByIndexInternal(i));
    for (btPersistentManifold* m : theirs) {
        const btCollisionObject* a = m->getBody0();
        const btCollisionObject* b = m->getBody1();
        if (m->getNumContacts() == 0 || !a || !b || a->getCollisionShape()->isCompound() || b->getCollisionShape()->isCompound() ||
            a->getCollisionShape()->isConcave() || b->getCollisionShape()->isConcave())
            continue;
        const Key key{a, b, -1, -1};
        Node* node = m_map.find(key);
        if (node && node->second.manifold) continue;
        if (!node) node = m_map.insert(key);
        m_dead.erase(node);
        node->second = Entry{};
        btPersistentManifold* mine = dispatcher->getNewManifold(a, b);
        mine->setContactBreakingThreshold(m->getContactBreakingThreshold());
        mine->setContactProcessingThreshold(m->getContactProcessingThreshold());
        const int count = std::min(m->getNumContacts(), 4);
        for (int j = 0; j < count; ++j) {
            mine->addManifoldPoint(m->getContactPoint(j));
            node->second.ids[j] = BTG_FEATURE_SINGLE | unsigned(j);  // the seeded device manifold's
            node->second.moved[j] = false;
        }
        for (int j = 0; j < m->getNumContacts(); ++j) m->getContactPoint(j).m_userPersistentData = nullptr;
        m->setNumContacts(0);  // freed with its algorithm: no ended callback, nothing destroyed
        node->second.manifold = mine;
        m_byObject[a].push_back(node);
        if (b != a) m_byObject[b].push_back(node);
        m_live.push_back(node);
        ++taken;
    }
    return taken;
}

}  // namespace btgpu
