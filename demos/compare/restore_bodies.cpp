// restore_bodies.cpp — the fields btWorldImporter::convertRigidBody{Float,Double} leaves out
// (it keeps the transform, friction, restitution and the two factors, and recomputes the
// inertia from the shape), each set back with Bullet's own setter so the body's derived state
// (world inertia, flags) stays consistent. Counted only where the file's value differs from
// what the importer left, so the report lists what mattered for this scene.
#include "compare/restore_bodies.h"

#include <cmath>

namespace btgpu::compare {
namespace {

btVector3 vec(const btVector3FloatData& d)
{
    btVector3 v;
    v.deSerializeFloat(d);
    return v;
}
btVector3 vec(const btVector3DoubleData& d)
{
    btVector3 v;
    v.deSerializeDouble(d);
    return v;
}
btTransform xf(btTransformFloatData d)
{
    btTransform t;
    t.deSerializeFloat(d);
    return t;
}
btTransform xf(btTransformDoubleData d)
{
    btTransform t;
    t.deSerializeDouble(d);
    return t;
}
bool same(const btTransform& a, const btTransform& b)
{
    return a.getOrigin() == b.getOrigin() && a.getBasis()[0] == b.getBasis()[0] && a.getBasis()[1] == b.getBasis()[1] &&
           a.getBasis()[2] == b.getBasis()[2];
}

// A mass m with 1/m == inverseMass exactly in float (btRigidBody::setMassProps stores 1/m), so
// the body's inverse mass is the file's to the bit, not 1/(1/x).
btScalar massFor(btScalar inverseMass)
{
    btScalar m = btScalar(1) / inverseMass;
    for (int i = 0; i < 4 && btScalar(1) / m != inverseMass; ++i)
        m = std::nextafter(m, btScalar(1) / m > inverseMass ? HUGE_VALF : 0.0f);
    return m;
}

template <class CO>
void restoreObject(btRigidBody& b, const CO& c, Restoration& r)
{
    auto note = [&](bool differs, const char* field) {
        if (differs) ++r.restored[field];
    };
    const int importedFlags = b.getCollisionFlags();
    note(b.getFriction() != btScalar(c.m_friction), "friction");
    b.setFriction(btScalar(c.m_friction));
    note(b.getRestitution() != btScalar(c.m_restitution), "restitution");
    b.setRestitution(btScalar(c.m_restitution));
    note(b.getRollingFriction() != btScalar(c.m_rollingFriction), "rolling friction");
    b.setRollingFriction(btScalar(c.m_rollingFriction));
    const btVector3 af = vec(c.m_anisotropicFriction);
    note(b.getAnisotropicFriction() != af || b.hasAnisotropicFriction(c.m_hasAnisotropicFriction) != (c.m_hasAnisotropicFriction != 0),
         "anisotropic friction");
    b.setAnisotropicFriction(af, c.m_hasAnisotropicFriction);  // the mode (friction, rolling friction) as saved
    note(b.getContactStiffness() != btScalar(c.m_contactStiffness) || b.getContactDamping() != btScalar(c.m_contactDamping),
         "contact stiffness and damping");
    b.setContactStiffnessAndDamping(btScalar(c.m_contactStiffness), btScalar(c.m_contactDamping));
    note(b.getContactProcessingThreshold() != btScalar(c.m_contactProcessingThreshold), "contact processing threshold");
    b.setContactProcessingThreshold(btScalar(c.m_contactProcessingThreshold));
    note(b.getCcdMotionThreshold() != btScalar(c.m_ccdMotionThreshold) ||
             b.getCcdSweptSphereRadius() != btScalar(c.m_ccdSweptSphereRadius),
         "CCD motion threshold and swept sphere radius");
    b.setCcdMotionThreshold(btScalar(c.m_ccdMotionThreshold));
    b.setCcdSweptSphereRadius(btScalar(c.m_ccdSweptSphereRadius));
    note(b.getHitFraction() != btScalar(c.m_hitFraction), "hit fraction");
    b.setHitFraction(btScalar(c.m_hitFraction));
    const btTransform it = xf(c.m_interpolationWorldTransform);
    note(!same(b.getInterpolationWorldTransform(), it), "interpolation transform");
    b.setInterpolationWorldTransform(it);
    note(b.getInterpolationLinearVelocity() != vec(c.m_interpolationLinearVelocity) ||
             b.getInterpolationAngularVelocity() != vec(c.m_interpolationAngularVelocity),
         "interpolation velocities");
    b.setInterpolationLinearVelocity(vec(c.m_interpolationLinearVelocity));
    b.setInterpolationAngularVelocity(vec(c.m_interpolationAngularVelocity));
    // Last: the setters above add CF_HAS_CONTACT_STIFFNESS_DAMPING; the file's flags are the truth
    // (kinematic, static, no contact response, custom material callback, ...).
    note(importedFlags != c.m_collisionFlags, "collision flags (kinematic, no contact response, ...)");
    b.setCollisionFlags(c.m_collisionFlags);
    // Which objects a body ignores (setIgnoreCollisionCheck) is not in the file; constraints
    // that disable collisions between their bodies set the same switch and are imported.
    if (c.m_checkCollideWith && b.getNumConstraintRefs() == 0) ++r.lost["ignored collision pairs (setIgnoreCollisionCheck)"];
}

template <class RB>
void restoreRigid(btRigidBody& b, const RB& d, Restoration& r)
{
    auto note = [&](bool differs, const char* field) {
        if (differs) ++r.restored[field];
    };
    restoreObject(b, d.m_collisionObjectData, r);
    const btScalar inverseMass = btScalar(d.m_inverseMass);
    const btVector3 invInertia = vec(d.m_invInertiaLocal);
    if (b.getInvMass() != 0 && inverseMass != 0) {
        if (b.getInvMass() != inverseMass) {
            ++r.restored["inverse mass (to the bit)"];
            btVector3 inertia(invInertia.x() != 0 ? 1 / invInertia.x() : 0, invInertia.y() != 0 ? 1 / invInertia.y() : 0,
                              invInertia.z() != 0 ? 1 / invInertia.z() : 0);
            b.setMassProps(massFor(inverseMass), inertia);
        }
        note(b.getInvInertiaDiagLocal() != invInertia, "local inertia (the importer recomputes it from the shape)");
        b.setInvInertiaDiagLocal(invInertia);
        b.updateInertiaTensor();
    } else if (b.getInvMass() != inverseMass) {
        ++r.lost["mass of a body on a shape Bullet keeps static (the importer makes it static)"];
    }
    note(b.getLinearVelocity() != vec(d.m_linearVelocity) || b.getAngularVelocity() != vec(d.m_angularVelocity),
         "linear and angular velocity");
    b.setLinearVelocity(vec(d.m_linearVelocity));
    b.setAngularVelocity(vec(d.m_angularVelocity));
    note(b.getLinearDamping() != btScalar(d.m_linearDamping) || b.getAngularDamping() != btScalar(d.m_angularDamping),
         "linear and angular damping");
    b.setDamping(btScalar(d.m_linearDamping), btScalar(d.m_angularDamping));
    note(b.getLinearSleepingThreshold() != btScalar(d.m_linearSleepingThreshold) ||
             b.getAngularSleepingThreshold() != btScalar(d.m_angularSleepingThreshold),
         "sleeping thresholds");
    b.setSleepingThresholds(btScalar(d.m_linearSleepingThreshold), btScalar(d.m_angularSleepingThreshold));
    note(b.getLinearFactor() != vec(d.m_linearFactor) || b.getAngularFactor() != vec(d.m_angularFactor),
         "linear and angular factors");
    b.setLinearFactor(vec(d.m_linearFactor));
    b.setAngularFactor(vec(d.m_angularFactor));
    // Forces applied since the last step: Bullet stores them multiplied by the factors, and
    // applyCentralForce/applyTorque multiply again, so they are applied under unit factors and
    // the factors put back (exactly the stored sums).
    const btVector3 force = vec(d.m_totalForce), torque = vec(d.m_totalTorque);
    if (!force.isZero() || !torque.isZero()) {
        const btVector3 linearFactor = b.getLinearFactor(), angularFactor = b.getAngularFactor();
        b.setLinearFactor(btVector3(1, 1, 1));
        b.setAngularFactor(btVector3(1, 1, 1));
        b.clearForces();
        b.applyCentralForce(force);
        b.applyTorque(torque);
        b.setLinearFactor(linearFactor);
        b.setAngularFactor(angularFactor);
        ++r.restored["forces and torques applied since the last step"];
    }
    // btRigidBody keeps these private and sets them only from its construction info.
    if (d.m_additionalDamping) ++r.lost["additional damping (m_additionalDamping: construction info only)"];
}

template <class CO>
void restoreObjectAfterAdd(btRigidBody& b, const CO& c, Restoration& r)
{
    if (b.getActivationState() != c.m_activationState1) ++r.restored["activation state (sleeping, disabled deactivation)"];
    b.forceActivationState(c.m_activationState1);
    if (b.getDeactivationTime() != btScalar(c.m_deactivationTime)) ++r.restored["deactivation time"];
    b.setDeactivationTime(btScalar(c.m_deactivationTime));
}

template <class RB>
void restoreRigidAfterAdd(btRigidBody& b, const RB& d, Restoration& r)
{
    const btVector3 g = vec(d.m_gravity_acceleration);
    if (b.getGravity() != g && b.getInvMass() != 0) ++r.restored["per-body gravity"];
    b.setGravity(g);
    restoreObjectAfterAdd(b, d.m_collisionObjectData, r);
}

}  // namespace

void restoreRigidBody(btRigidBody& body, const btRigidBodyFloatData& record, Restoration& r) { restoreRigid(body, record, r); }
void restoreRigidBody(btRigidBody& body, const btRigidBodyDoubleData& record, Restoration& r) { restoreRigid(body, record, r); }
void restoreCollisionObject(btRigidBody& body, const btCollisionObjectFloatData& record, Restoration& r)
{
    restoreObject(body, record, r);
}
void restoreCollisionObject(btRigidBody& body, const btCollisionObjectDoubleData& record, Restoration& r)
{
    restoreObject(body, record, r);
}
void restoreAfterAdd(btRigidBody& body, const btRigidBodyFloatData& record, Restoration& r)
{
    restoreRigidAfterAdd(body, record, r);
}
void restoreAfterAdd(btRigidBody& body, const btRigidBodyDoubleData& record, Restoration& r)
{
    restoreRigidAfterAdd(body, record, r);
}
void restoreAfterAdd(btRigidBody& body, const btCollisionObjectFloatData& record, Restoration& r)
{
    restoreObjectAfterAdd(body, record, r);
}
void restoreAfterAdd(btRigidBody& body, const btCollisionObjectDoubleData& record, Restoration& r)
{
    restoreObjectAfterAdd(body, record, r);
}

}  // namespace btgpu::compare
