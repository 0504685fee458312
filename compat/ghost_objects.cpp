// ghost_objects.cpp — the host side of ghost objects on the GPU path: which objects are ghosts,
// when one cannot be served, and stock's broadphase pair update at an internal step's start.
#include "ghost_objects.h"

#include "row_map.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>

namespace btgpu {

std::vector<const btCollisionObject*> findGhosts(const btDiscreteDynamicsWorld& world)
{
    std::vector<const btCollisionObject*> ghosts;
    const btCollisionObjectArray& objs = world.getCollisionObjectArray();
    for (int i = 0; i < objs.size(); ++i)
        if (objs[i]->getInternalType() == btCollisionObject::CO_GHOST_OBJECT) ghosts.push_back(objs[i]);
    return ghosts;
}

void heldAwakeByGhosts(btDiscreteDynamicsWorld& world, const RowMap& rows, std::vector<char>* held)
{
    held->assign(rows.size(), 0);
    const btBroadphasePairArray& pairs = world.getPairCache()->getOverlappingPairArray();
    for (int i = 0; i < pairs.size(); ++i) {
        auto* a = static_cast<btCollisionObject*>(pairs[i].m_pProxy0->m_clientObject);
        auto* b = static_cast<btCollisionObject*>(pairs[i].m_pProxy1->m_clientObject);
        if (!a->mergesSimulationIslands() || !b->mergesSimulationIslands()) continue;
        const bool ga = a->getInternalType() == btCollisionObject::CO_GHOST_OBJECT;
        const bool gb = b->getInternalType() == btCollisionObject::CO_GHOST_OBJECT;
        if (ga == gb) continue;  // a ghost with a ghost unites no body; body with body: the device's islands
        btRigidBody* body = btRigidBody::upcast(ga ? b : a);
        if (!body) continue;
        const int r = rows.rowOf(body);
        if (r < 0) continue;
        (*held)[size_t(r)] = 1;
        if (body->getActivationState() == ISLAND_SLEEPING) {
            body->setActivationState(WANTS_DEACTIVATION);
            body->setDeactivationTime(0);
        }
    }
}

namespace {

// Each dynamic body's interpolation transform its predicted one, as stock's
// predictUnconstraintMotion leaves it for updateAabbs.
void predictAsStock(btDiscreteDynamicsWorld& world, float dt)
{
    // applyDamping and predictIntegratedTransform are stock's own (additional damping
    // included); the velocities they damp are put back, since the device does the damping.
    btCollisionObjectArray& objs = world.getCollisionObjectArray();
    for (int i = 0; i < objs.size(); ++i) {
        btRigidBody* body = btRigidBody::upcast(objs[i]);
        if (!body || body->isStaticOrKinematicObject()) continue;
        const btVector3 lin = body->getLinearVelocity(), ang = body->getAngularVelocity();
        body->applyDamping(dt);
        body->predictIntegratedTransform(dt, body->getInterpolationWorldTransform());
        body->setLinearVelocity(lin);
        body->setAngularVelocity(ang);
    }
}

struct LeafCollector : btDbvt::ICollide {
    std::vector<btBroadphaseProxy*> proxies;
    void Process(const btDbvtNode* leaf) override { proxies.push_back(static_cast<btBroadphaseProxy*>(leaf->data)); }
};

}  // namespace

void updateBroadphaseAsStock(btDiscreteDynamicsWorld& world, float dt)
{
    predictAsStock(world, dt);
    world.updateAabbs();
    world.computeOverlappingPairs();
}

void updateGhostPairsFromTree(btDiscreteDynamicsWorld& world, btDbvtBroadphase& dbvt,
                              const std::vector<const btCollisionObject*>& ghosts, float dt)
{
    predictAsStock(world, dt);
    // The leaves move as stock's setAabb moves them; the pair tests wait (deferred), and only
    // the ghosts' are made below.
    const bool deferred = dbvt.m_deferedcollide;
    dbvt.m_deferedcollide = true;
    world.updateAabbs();
    dbvt.m_deferedcollide = deferred;
    btOverlappingPairCache* cache = dbvt.getOverlappingPairCache();
    btDispatcher* dispatcher = world.getDispatcher();
    // A ghost's pairs whose leaves stopped overlapping go (the test stock's cleanup makes), the
    // ghost callback taking each off the ghost's list.
    std::vector<const btBroadphaseProxy*> ghostProxies;
    for (const btCollisionObject* g : ghosts) ghostProxies.push_back(g->getBroadphaseHandle());
    auto isGhost = [&](const btBroadphaseProxy* p) {
        return std::find(ghostProxies.begin(), ghostProxies.end(), p) != ghostProxies.end();
    };
    std::vector<std::pair<btBroadphaseProxy*, btBroadphaseProxy*>> gone;
    const btBroadphasePairArray& pairs = cache->getOverlappingPairArray();
    for (int i = 0; i < pairs.size(); ++i) {
        auto* a = static_cast<btDbvtProxy*>(pairs[i].m_pProxy0);
        auto* b = static_cast<btDbvtProxy*>(pairs[i].m_pProxy1);
        if ((isGhost(a) || isGhost(b)) && a->leaf && b->leaf && !Intersect(a->leaf->volume, b->leaf->volume))
            gone.push_back({a, b});
    }
    for (const auto& [a, b] : gone) cache->removeOverlappingPair(a, b, dispatcher);
    for (const btCollisionObject* g : ghosts) {
        auto* gp = static_cast<btDbvtProxy*>(const_cast<btCollisionObject*>(g)->getBroadphaseHandle());
        if (!gp || !gp->leaf) continue;
        // New pairs: the leaves the ghost's meets in both trees, in the trees' order, added as
        // stock's tree collider adds them (the pair cache filters and calls the ghost callback).
        LeafCollector meet;
        dbvt.m_sets[0].collideTV(dbvt.m_sets[0].m_root, gp->leaf->volume, meet);
        dbvt.m_sets[1].collideTV(dbvt.m_sets[1].m_root, gp->leaf->volume, meet);
        for (btBroadphaseProxy* p : meet.proxies) {
            if (p == gp || cache->findPair(gp, p)) continue;
            btBroadphaseProxy* a = gp;
            btBroadphaseProxy* b = p;
            if (a > b) std::swap(a, b);  // DBVT_BP_SORTPAIRS
            cache->addOverlappingPair(a, b);
        }
    }
}

}  // namespace btgpu
