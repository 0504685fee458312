// ccd_steps.cpp — stock's CCD sweep (btDiscreteDynamicsWorld's createPredictiveContacts and
// integrateTransforms) asked only whether it hits: the same sphere, ends, filters and
// allowed penetration, through the app's world's own convexSweepTest.
#include "ccd_steps.h"

#include <btBulletDynamicsCommon.h>

namespace btgpu {

namespace {

// btDiscreteDynamicsWorld.cpp's btClosestNotMeConvexResultCallback (local to that file), its
// rules unchanged: not itself, filters and the dispatcher's needsCollision/needsResponse, no
// hit for an object without contact response or for motion away from the hit's normal.
struct NotMeSweep : btCollisionWorld::ClosestConvexResultCallback {
    btCollisionObject* me;
    btScalar allowedPenetration = 0;
    btOverlappingPairCache* pairCache;
    btDispatcher* dispatcher;
    NotMeSweep(btCollisionObject* self, const btVector3& from, const btVector3& to, btOverlappingPairCache* cache,
               btDispatcher* d)
        : ClosestConvexResultCallback(from, to), me(self), pairCache(cache), dispatcher(d)
    {
    }
    btScalar addSingleResult(btCollisionWorld::LocalConvexResult& r, bool normalInWorldSpace) override
    {
        if (r.m_hitCollisionObject == me || !r.m_hitCollisionObject->hasContactResponse()) return 1;
        const btVector3 relative = m_convexToWorld - m_convexFromWorld;
        if (r.m_hitNormalLocal.dot(relative) >= -allowedPenetration) return 1;
        return ClosestConvexResultCallback::addSingleResult(r, normalInWorldSpace);
    }
    bool needsCollision(btBroadphaseProxy* proxy) const override
    {
        if (proxy->m_clientObject == me || !ClosestConvexResultCallback::needsCollision(proxy)) return false;
        if (pairCache->getOverlapFilterCallback() && !pairCache->needsBroadphaseCollision(proxy, me->getBroadphaseHandle()))
            return false;
        auto* other = static_cast<btCollisionObject*>(proxy->m_clientObject);
        return dispatcher->needsCollision(me, other) && dispatcher->needsResponse(me, other);
    }
};

}  // namespace

btVector3 dampedVelocity(btRigidBody* body, float dt)
{
    const btVector3 lin = body->getLinearVelocity(), ang = body->getAngularVelocity();
    body->applyDamping(dt);
    const btVector3 damped = body->getLinearVelocity();
    body->setLinearVelocity(lin);
    body->setAngularVelocity(ang);
    return damped;
}

bool ccdSweepHits(btDiscreteDynamicsWorld& world, const std::vector<btRigidBody*>& bodies, float dt,
                  const std::function<btVector3(btRigidBody*)>& velocity, std::string* why)
{
    const btDispatcherInfo& info = world.getDispatchInfo();
    if (!info.m_useContinuous) return false;
    for (btRigidBody* body : bodies) {
        if (!body->isActive() || body->isStaticOrKinematicObject() || !body->getCollisionShape()->isConvex()) continue;
        const btScalar threshold2 = body->getCcdSquareMotionThreshold();
        const btTransform& from = body->getWorldTransform();
        // predictIntegratedTransform's origin; the sweep keeps the body's rotation.
        const btVector3 to = from.getOrigin() + velocity(body) * btScalar(dt);
        if (threshold2 == btScalar(0) || (to - from.getOrigin()).length2() <= threshold2) continue;
        btBroadphaseProxy* proxy = body->getBroadphaseHandle();
        if (!proxy) continue;
        NotMeSweep sweep(body, from.getOrigin(), to, world.getBroadphase()->getOverlappingPairCache(), world.getDispatcher());
        sweep.allowedPenetration = info.m_allowedCcdPenetration;
        sweep.m_collisionFilterGroup = proxy->m_collisionFilterGroup;
        sweep.m_collisionFilterMask = proxy->m_collisionFilterMask;
        btSphereShape sphere(body->getCcdSweptSphereRadius());
        btTransform end = from;
        end.setOrigin(to);
        world.convexSweepTest(&sphere, from, end, sweep);
        if (sweep.hasHit() && sweep.m_closestHitFraction < btScalar(1)) {
            const btCollisionObjectArray& objs = world.getCollisionObjectArray();
            *why = "continuous collision detection acts: body " + std::to_string(objs.findLinearSearch(body)) +
                   " (user index " + std::to_string(body->getUserIndex()) + ") would hit body " +
                   std::to_string(objs.findLinearSearch(const_cast<btCollisionObject*>(sweep.m_hitCollisionObject))) +
                   " at " + std::to_string(int(100 * sweep.m_closestHitFraction)) +
                   "% of its step (stock's swept-sphere contact and clamped motion: this step on Bullet's own path)";
            return true;
        }
    }
    return false;
}

}  // namespace btgpu
