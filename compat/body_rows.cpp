// body_rows.cpp — reading Bullet bodies into rows.
#include "body_rows.h"
#include "private_member.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>

namespace btgpu {

// btRigidBody's additional damping, set through btRigidBodyConstructionInfo only (no getter, no
// setter); tags of private_member.h, at namespace scope as its explicit instantiations must be.
BTGPU_PRIVATE_MEMBER(AdditionalDamping, btRigidBody, bool, m_additionalDamping);
BTGPU_PRIVATE_MEMBER(AdditionalDampingFactor, btRigidBody, btScalar, m_additionalDampingFactor);
BTGPU_PRIVATE_MEMBER(AdditionalLinearThresholdSqr, btRigidBody, btScalar, m_additionalLinearDampingThresholdSqr);
BTGPU_PRIVATE_MEMBER(AdditionalAngularThresholdSqr, btRigidBody, btScalar, m_additionalAngularDampingThresholdSqr);

namespace {
BtgFloat4 f4(const btVector3& v, float w = 0.0f) { return btgMake4(v.x(), v.y(), v.z(), w); }
bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
}  // namespace

BtgBodyProps bodyProps(const btCollisionObject* obj, int shapeRow, const BtgShape& shape, bool excluded)
{
    BtgBodyProps p{};
    const btRigidBody* rb = btRigidBody::upcast(obj);
    uint flags = 0;
    // Kinematic first: a body made with mass 0 keeps CF_STATIC_OBJECT when the app adds
    // CF_KINEMATIC_OBJECT, and Bullet still drives it as kinematic.
    if (rb && obj->isKinematicObject()) flags |= BTG_BODY_KINEMATIC;
    else if (obj->isStaticObject() || !rb) flags |= BTG_BODY_STATIC;
    else flags |= BTG_BODY_DYNAMIC;
    if (!obj->hasContactResponse()) flags |= BTG_BODY_NO_RESPONSE;
    if (obj->getCollisionShape()->getShapeType() == EMPTY_SHAPE_PROXYTYPE) flags |= BTG_BODY_NO_SHAPE;
    int state = obj->getActivationState();
    if (state == ISLAND_SLEEPING) flags |= BTG_BODY_SLEEPING;
    // A ghost's overlaps come from the host broadphase (ghost_objects.h). One with contact
    // response is Bullet's fixed body in the solver: flagged static, a static row; otherwise
    // a kinematic row with zero velocity, never asleep and waking what it touches (stock's
    // kinematic objects wake what they touch; a ghost that merges islands keeps them awake,
    // held further by heldAwakeByGhosts). Without contact response (a trigger) it is a
    // kinematic row that is never solved and wakes nothing: stock's dispatcher still collides
    // it (a ghost is never deactivated) and the app reads those manifolds.
    const bool ghost = obj->getInternalType() == btCollisionObject::CO_GHOST_OBJECT;
    if (ghost && (!obj->hasContactResponse() || obj->isKinematicObject() || !obj->isStaticOrKinematicObject()))
        flags = (flags & ~BTG_BODY_STATIC) | BTG_BODY_KINEMATIC | BTG_BODY_NEVER_SLEEP;
    if (state == DISABLE_SIMULATION || excluded) flags |= BTG_BODY_EXCLUDED;
    if (state == DISABLE_DEACTIVATION || obj->isKinematicObject()) flags |= BTG_BODY_NEVER_SLEEP;
    if (shape.type == BTG_SHAPE_PLANE) flags = (flags & ~(BTG_BODY_DYNAMIC | BTG_BODY_KINEMATIC)) | BTG_BODY_STATIC;
    // Its manifolds go to the app's gContactAddedCallback before the solve (contact_callbacks.h).
    if (gContactAddedCallback && (obj->getCollisionFlags() & btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK))
        flags |= BTG_BODY_CUSTOM_MATERIAL;
    if (rb) {
        if (rb->getFlags() & BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY) flags |= BTG_BODY_GYRO;
        if (rb->getFlags() & BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT) flags |= BTG_BODY_GYRO_EXPLICIT;
        if (rb->getFlags() & BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD) flags |= BTG_BODY_GYRO_WORLD;
        p.invMass = (flags & BTG_BODY_DYNAMIC) ? rb->getInvMass() : 0.0f;
        p.invInertiaLocal = f4(rb->getInvInertiaDiagLocal());
        p.linearFactor = f4(rb->getLinearFactor());
        p.angularFactor = f4(rb->getAngularFactor());
        p.linearDamping = rb->getLinearDamping();
        p.angularDamping = rb->getAngularDamping();
        p.gravity = f4(rb->getGravity());
        p.sleepLinear = rb->getLinearSleepingThreshold();
        p.sleepAngular = rb->getAngularSleepingThreshold();
        if (rb->*member(AdditionalDamping())) {
            flags |= BTG_BODY_ADDITIONAL_DAMPING;
            p.additionalDampingFactor = rb->*member(AdditionalDampingFactor());
            p.additionalLinearThresholdSqr = rb->*member(AdditionalLinearThresholdSqr());
            p.additionalAngularThresholdSqr = rb->*member(AdditionalAngularThresholdSqr());
        }
    } else {
        p.linearFactor = btgMake4(1, 1, 1, 0);
        p.angularFactor = btgMake4(1, 1, 1, 0);
    }
    if (obj->getCollisionFlags() & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING) flags |= BTG_BODY_STIFFNESS_DAMPING;
    if (obj->getCollisionFlags() & btCollisionObject::CF_HAS_FRICTION_ANCHOR) flags |= BTG_BODY_FRICTION_ANCHOR;
    if (obj->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION)) flags |= BTG_BODY_ANISOTROPIC;
    if (obj->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION))
        flags |= BTG_BODY_ANISOTROPIC_ROLLING;
    p.anisotropicFriction = f4(obj->getAnisotropicFriction());
    p.rollingFriction = obj->getRollingFriction();
    p.spinningFriction = obj->getSpinningFriction();
    p.contactStiffness = obj->getContactStiffness();
    p.contactDamping = obj->getContactDamping();
    p.contactProcessingThreshold = obj->getContactProcessingThreshold();
    p.friction = obj->getFriction();
    p.restitution = obj->getRestitution();
    p.shape = shapeRow;
    p.flags = flags;
    const btBroadphaseProxy* proxy = obj->getBroadphaseHandle();
    p.group = proxy ? proxy->m_collisionFilterGroup : -1;
    p.mask = proxy ? proxy->m_collisionFilterMask : -1;
    p.proxyOrder = proxy ? proxy->m_uniqueId : 0;
    return p;
}

BodyState bodyState(const btCollisionObject* obj)
{
    BodyState s{};
    const btTransform& t = obj->getWorldTransform();
    btQuaternion q = t.getRotation();
    s.pos = f4(t.getOrigin());
    s.rot = btgMake4(q.x(), q.y(), q.z(), q.w());
    if (const btRigidBody* rb = btRigidBody::upcast(obj)) {
        s.linVel = f4(rb->getLinearVelocity());
        s.angVel = f4(rb->getAngularVelocity());
        s.force = f4(rb->getTotalForce());
        s.torque = f4(rb->getTotalTorque());
    }
    return s;
}

std::string badInput(const btCollisionObject* obj)
{
    const btTransform& t = obj->getWorldTransform();
    const btMatrix3x3& b = t.getBasis();
    if (!finite(t.getOrigin()) || !finite(b[0]) || !finite(b[1]) || !finite(b[2])) return "non-finite transform";
    if (!std::isfinite(obj->getFriction())) return "non-finite friction";
    if (!std::isfinite(obj->getRestitution())) return "non-finite restitution";
    if (!std::isfinite(obj->getRollingFriction()) || !std::isfinite(obj->getSpinningFriction()))
        return "non-finite rolling or spinning friction";
    const btRigidBody* rb = btRigidBody::upcast(obj);
    if (!rb) return "";
    if (!finite(rb->getLinearVelocity()) || !finite(rb->getAngularVelocity())) return "non-finite velocity";
    if (!finite(rb->getTotalForce()) || !finite(rb->getTotalTorque())) return "non-finite force or torque";
    if (!std::isfinite(rb->getInvMass()) || rb->getInvMass() < 0.0f) return "negative or non-finite mass";
    btVector3 ii = rb->getInvInertiaDiagLocal();
    if (!finite(ii) || ii.x() < 0.0f || ii.y() < 0.0f || ii.z() < 0.0f) return "negative or non-finite inertia";
    if (!obj->isStaticOrKinematicObject() && rb->getInvMass() == 0.0f)
        return "zero inverse mass on a body that is neither static nor kinematic";
    if (!finite(rb->getGravity())) return "non-finite gravity";
    if (!std::isfinite(rb->getLinearDamping()) || !std::isfinite(rb->getAngularDamping())) return "non-finite damping";
    if (!finite(rb->getLinearFactor()) || !finite(rb->getAngularFactor())) return "non-finite linear or angular factor";
    // An infinite threshold is a legal "always slow enough" (Bullet compares v^2 < t^2); NaN is not.
    if (std::isnan(rb->getLinearSleepingThreshold()) || std::isnan(rb->getAngularSleepingThreshold()))
        return "NaN sleeping threshold";
    return "";
}

bool aabbOverflows(const btCollisionObject* obj, const BtgShape& shape, float dt, bool continuous)
{
    if (obj->isStaticObject() || shape.type == BTG_SHAPE_PLANE || obj->getActivationState() == DISABLE_SIMULATION)
        return false;
    const btMatrix3x3& b = obj->getWorldTransform().getBasis();
    btVector3 h(0.5f * (shape.localAabbMax.x - shape.localAabbMin.x), 0.5f * (shape.localAabbMax.y - shape.localAabbMin.y),
                0.5f * (shape.localAabbMax.z - shape.localAabbMin.z));
    btVector3 size;
    for (int i = 0; i < 3; ++i)
        size[i] = 2.0f * (std::fabs(b[i][0]) * h.x() + std::fabs(b[i][1]) * h.y() + std::fabs(b[i][2]) * h.z()) +
                  2.0f * gContactBreakingThreshold;
    const btRigidBody* rb = btRigidBody::upcast(obj);
    if (continuous && rb && !obj->isStaticOrKinematicObject()) {
        // The predicted transform moved by the velocity over the step (its turn changes the
        // extents too little to matter against a 1e6 m bound).
        const btVector3& v = rb->getLinearVelocity();
        size += btVector3(std::fabs(v.x()), std::fabs(v.y()), std::fabs(v.z())) * dt;
    }
    return !(size.length2() < 1e12f);
}

}  // namespace btgpu
