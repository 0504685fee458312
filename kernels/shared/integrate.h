/* integrate.h — per-body motion updates shared by kernels/integrate.cl and the CPU reference,
 * in the order Bullet 3.24 applies them: damping before collision detection
 * (predictUnconstraintMotion), external forces and the gyroscopic term at solver setup
 * (initSolverBody / convertBodies), then the split-impulse push and the velocity step
 * (writebackVelocityAndTransform, integrateTransforms). */
#ifndef BTG_INTEGRATE_H
#define BTG_INTEGRATE_H
#include "math.h"
#include "types.h"

/* Bodies the integrator moves: dynamic, awake, not excluded. */
static inline int btgIsMoving(uint flags)
{
    return (flags & BTG_BODY_DYNAMIC) && !(flags & (BTG_BODY_SLEEPING | BTG_BODY_EXCLUDED));
}

/* btRigidBody::applyDamping: v *= (1 - d)^dt. */
static inline BtgFloat4 btgDamp(BtgFloat4 v, float damping, float dt)
{
    return btgXyz(v) * btgPow(1.0f - damping, dt);
}

/* Linear velocity after app forces and gravity: force already carries the linear factor
 * (btRigidBody::applyCentralForce applies it), gravity gets it here (applyGravity). */
static inline BtgFloat4 btgApplyLinearForces(BtgFloat4 linVel, BtgFloat4 force, BtgBodyProps p, float dt)
{
    float invMass = p.invMass;
    BtgFloat4 g = btgXyz(p.gravity) * p.linearFactor;
    return btgXyz(linVel) + (btgXyz(force) * invMass + g) * dt;
}

/* Angular velocity after app torque (factor already applied by applyTorque) and, when asked,
 * Bullet's implicit body-frame gyroscopic term computed from the pre-torque velocity. */
static inline BtgFloat4 btgApplyAngularForces(BtgFloat4 angVel, BtgFloat4 torque, BtgFloat4 rot, BtgMat3 invIw,
                                             BtgBodyProps p, float dt)
{
    BtgFloat4 w = btgXyz(angVel) + btgMat3MulVec(invIw, torque) * dt;
    if (p.flags & BTG_BODY_GYRO) {
        BtgFloat4 ii = p.invInertiaLocal;
        BtgFloat4 inertia = btgMake4(ii.x != 0.0f ? 1.0f / ii.x : 0.0f, ii.y != 0.0f ? 1.0f / ii.y : 0.0f,
                                     ii.z != 0.0f ? 1.0f / ii.z : 0.0f, 0.0f);
        w += btgGyroscopicImpulse(rot, angVel, inertia, dt);
    }
    return w;
}

#endif
