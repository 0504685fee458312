// manifold_handover.cpp — ManifoldSync::handToStock: the GPU path's manifolds given to stock's
// algorithms when Bullet's own step takes over, so that a resting contact keeps its points
// (stock's box algorithm refreshes them and adds its detector's) instead of starting anew.
#include "manifold_sync.h"

#include <btBulletCollisionCommon.h>

#include <algorithm>
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
    if (!dispatcher || !cache) return 0;
    int handed = 0;
    btManifoldArray held;
    for (auto& [key, e] : m_map) {
        btPersistentManifold* m = e.manifold;
        if (!m || m->getNumContacts() == 0 || key.sub0 >= 0 || key.sub1 >= 0) continue;
        const btCollisionObject* a = m->getBody0();
        const btCollisionObject* b = m->getBody1();
        if (!convexLeaf(a) || !convexLeaf(b) || !a->getBroadphaseHandle() || !b->getBroadphaseHandle()) continue;
        btBroadphasePair* pair = cache->findPair(const_cast<btBroadphaseProxy*>(a->getBroadphaseHandle()),
                                                 const_cast<btBroadphaseProxy*>(b->getBroadphaseHandle()));
        if (!pair) continue;
        btCollisionObject* o0 = static_cast<btCollisionObject*>(pair->m_pProxy0->m_clientObject);
        btCollisionObject* o1 = static_cast<btCollisionObject*>(pair->m_pProxy1->m_clientObject);
        if (!pair->m_algorithm) {
            // As btCollisionDispatcher::defaultNearCallback makes it.
            if (!dispatcher->needsCollision(o0, o1)) continue;
            btCollisionObjectWrapper w0(nullptr, o0->getCollisionShape(), o0, o0->getWorldTransform(), -1, -1);
            btCollisionObjectWrapper w1(nullptr, o1->getCollisionShape(), o1, o1->getWorldTransform(), -1, -1);
            pair->m_algorithm = dispatcher->findAlgorithm(&w0, &w1, nullptr, BT_CONTACT_POINT_ALGORITHMS);
            if (!pair->m_algorithm) continue;
        }
        held.resize(0);
        pair->m_algorithm->getAllContactManifolds(held);
        if (held.size() != 1 || held[0]->getNumContacts() != 0) continue;
        btPersistentManifold* target = held[0];
        const bool swap = target->getBody0() != a;
        for (int j = 0; j < m->getNumContacts(); ++j) {
            btManifoldPoint& p = m->getContactPoint(j);
            target->addManifoldPoint(swap ? swapped(p) : p);
            p.m_userPersistentData = nullptr;  // it goes with the point, not destroyed here
        }
        m->setNumContacts(0);
        ++handed;
    }
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
        auto it = m_map.find(key);
        if (it != m_map.end() && it->second.manifold) continue;
        if (it == m_map.end()) it = m_map.emplace(key, Entry{}).first;
        Node* node = &*it;
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
