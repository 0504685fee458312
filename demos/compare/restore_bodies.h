// restore_bodies.h — puts back what btBulletWorldImporter drops from a body, read from the
// file's own btRigidBody/btCollisionObject records (float or double files alike), and names
// what the file holds but Bullet offers no way to set.
#pragma once
#include <btBulletDynamicsCommon.h>

#include "compare/imported_world.h"

namespace btgpu::compare {

// Before the body is (re)added to the world: mass and local inertia, velocities, damping,
// factors, sleeping thresholds, friction, restitution and rolling friction, anisotropic
// friction, contact stiffness/damping, contact processing threshold, CCD settings, collision
// flags, interpolation transform and velocities, pending forces.
void restoreRigidBody(btRigidBody& body, const btRigidBodyFloatData& record, Restoration& r);
void restoreRigidBody(btRigidBody& body, const btRigidBodyDoubleData& record, Restoration& r);
void restoreCollisionObject(btRigidBody& body, const btCollisionObjectFloatData& record, Restoration& r);
void restoreCollisionObject(btRigidBody& body, const btCollisionObjectDoubleData& record, Restoration& r);

// After it is back in the world (adding resets them): per-body gravity, activation state and
// deactivation time.
void restoreAfterAdd(btRigidBody& body, const btRigidBodyFloatData& record, Restoration& r);
void restoreAfterAdd(btRigidBody& body, const btRigidBodyDoubleData& record, Restoration& r);
void restoreAfterAdd(btRigidBody& body, const btCollisionObjectFloatData& record, Restoration& r);
void restoreAfterAdd(btRigidBody& body, const btCollisionObjectDoubleData& record, Restoration& r);

}  // namespace btgpu::compare
