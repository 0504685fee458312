// ghost_objects.cpp — the host side of ghost objects on the GPU path: which objects are ghosts,
// when one cannot be served, and stock's broadphase pair update at an internal step's start.
#include "ghost_objects.h"

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

std::string ghostReason(const btDiscreteDynamicsWorld& world, const std::vector<const btCollisionObject*>& ghosts)
{
    const btCollisionObject* responding = nullptr;
    for (const btCollisionObject* g : ghosts)
        if (g->hasContactResponse()) {
            responding = g;
            break;
        }
    if (!responding) return "";
    // Stock solves such a ghost as a fixed body against the bodies it touches and unites it
    // (never asleep) with them into one island over the broadphase pairs: neither is mirrored
    // on the device yet. Without a dynamic body that responds to contacts it changes nothing.
    const btCollisionObjectArray& objs = world.getCollisionObjectArray();
    for (int i = 0; i < objs.size(); ++i) {
        const btRigidBody* rb = btRigidBody::upcast(objs[i]);
        if (rb && !rb->isStaticOrKinematicObject() && rb->hasContactResponse())
            return "ghost object " + std::to_string(objs.findLinearSearch(const_cast<btCollisionObject*>(responding))) +
                   " has contact response (a character's ghost, no CF_NO_CONTACT_RESPONSE) and the world holds "
                   "dynamic body " + std::to_string(i) + ": such a ghost is not served beside dynamic bodies";
    }
    return "";
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
