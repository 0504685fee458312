// ghost_objects.cpp — the host side of ghost objects on the GPU path: which objects are ghosts,
// when one cannot be served, and stock's broadphase pair update at an internal step's start.
#include "ghost_objects.h"

#include "row_map.h"

#include <btBulletDynamicsCommon.h>

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

void updateBroadphaseAsStock(btDiscreteDynamicsWorld& world, float dt)
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
    world.updateAabbs();
    world.computeOverlappingPairs();
}

}  // namespace btgpu
