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
    /* Undamped (Bullet's default) skips the pow: pow(1, dt) is exactly 1, so the same bits, and
     * a CPU device's software pow was 3% of a PoCL frame of cubes 8,000. */
    if (damping == 0.0f) return btgXyz(v);
    return btgXyz(v) * btgPow(1.0f - damping, dt);
}

/* btRigidBody::applyDamping's additional damping (m_additionalDamping), after the plain
 * damping: a body slower than both thresholds is scaled by the factor; then a speed below the
 * damping coefficient itself (Bullet compares the two) is cut by 0.005 or to zero, linear and
 * angular alike. */
static inline BtgFloat4 btgCutSlow(BtgFloat4 v, float below)
{
    const float dampVel = 0.005f;
    float speed = btgSqrt(btgDot3(v, v));
    if (!(speed < below)) return v;
    if (speed > dampVel) return v - v * (dampVel / speed);
    return btgZero4();
}
static inline void btgAdditionalDamping(BtgFloat4* lin, BtgFloat4* ang, BtgBodyProps p)
{
    if (!(p.flags & BTG_BODY_ADDITIONAL_DAMPING)) return;
    if (btgDot3(*ang, *ang) < p.additionalAngularThresholdSqr && btgDot3(*lin, *lin) < p.additionalLinearThresholdSqr) {
        *ang = *ang * p.additionalDampingFactor;
        *lin = *lin * p.additionalDampingFactor;
    }
    *lin = btgCutSlow(*lin, p.linearDamping);
    *ang = btgCutSlow(*ang, p.angularDamping);
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
 * Bullet's gyroscopic terms computed from the pre-torque velocity, in convertBodies' order:
 * explicit (as a torque, bounded by maxGyro), implicit world frame, implicit body frame. */
static inline BtgFloat4 btgApplyAngularForces(BtgFloat4 angVel, BtgFloat4 torque, BtgFloat4 rot, BtgMat3 invIw,
                                             BtgBodyProps p, float dt, float maxGyro)
{
    BtgFloat4 w = btgXyz(angVel) + btgMat3MulVec(invIw, torque) * dt;
    if (!(p.flags & (BTG_BODY_GYRO | BTG_BODY_GYRO_EXPLICIT | BTG_BODY_GYRO_WORLD))) return w;
    /* getLocalInertia: the inverse of the inverse, 0 where that is 0. */
    BtgFloat4 ii = p.invInertiaLocal;
    BtgFloat4 inertia = btgMake4(ii.x != 0.0f ? 1.0f / ii.x : 0.0f, ii.y != 0.0f ? 1.0f / ii.y : 0.0f,
                                 ii.z != 0.0f ? 1.0f / ii.z : 0.0f, 0.0f);
    if (p.flags & (BTG_BODY_GYRO_EXPLICIT | BTG_BODY_GYRO_WORLD)) {
        BtgMat3 iw = btgInvInertiaWorld(rot, inertia); /* R diag(I) R^T */
        if (p.flags & BTG_BODY_GYRO_EXPLICIT) w -= btgMat3MulVec(invIw, btgGyroscopicForceExplicit(iw, angVel, maxGyro)) * dt;
        if (p.flags & BTG_BODY_GYRO_WORLD) w += btgGyroscopicImpulseWorld(iw, angVel, dt);
    }
    if (p.flags & BTG_BODY_GYRO) w += btgGyroscopicImpulse(rot, angVel, inertia, dt);
    return w;
}

#endif
