/* math.h — quaternion and 3x3 matrix helpers shared by kernels and CPU references.
 * Quaternions are (x, y, z, w) in a BtgFloat4, as btQuaternion stores them; a matrix is three
 * row vectors (BtgMat3). Formulas follow Bullet's btQuaternion/btMatrix3x3/btTransformUtil so
 * results track stock Bullet to float rounding. */
#ifndef BTG_MATH_H
#define BTG_MATH_H
#include "prelude.h"

typedef struct {
    BtgFloat4 r0, r1, r2; /* rows; w unused */
} BtgMat3;

static inline BtgFloat4 btgQuatMul(BtgFloat4 q, BtgFloat4 p)
{
    return btgMake4(q.w * p.x + q.x * p.w + q.y * p.z - q.z * p.y,
                    q.w * p.y + q.y * p.w + q.z * p.x - q.x * p.z,
                    q.w * p.z + q.z * p.w + q.x * p.y - q.y * p.x,
                    q.w * p.w - q.x * p.x - q.y * p.y - q.z * p.z);
}
static inline BtgFloat4 btgQuatConj(BtgFloat4 q) { return btgMake4(-q.x, -q.y, -q.z, q.w); }
static inline BtgFloat4 btgQuatNormalize(BtgFloat4 q)
{
    float l = btgSqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    return l > 0.0f ? q * (1.0f / l) : btgMake4(0.0f, 0.0f, 0.0f, 1.0f);
}
/* Rotates v by unit quaternion q (v' = q v q*), via the matrix to match btMatrix3x3 rounding. */
static inline BtgMat3 btgQuatToMat3(BtgFloat4 q)
{
    float d = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
    float s = 2.0f / d;
    float xs = q.x * s, ys = q.y * s, zs = q.z * s;
    float wx = q.w * xs, wy = q.w * ys, wz = q.w * zs;
    float xx = q.x * xs, xy = q.x * ys, xz = q.x * zs;
    float yy = q.y * ys, yz = q.y * zs, zz = q.z * zs;
    BtgMat3 m;
    m.r0 = btgMake4(1.0f - (yy + zz), xy - wz, xz + wy, 0.0f);
    m.r1 = btgMake4(xy + wz, 1.0f - (xx + zz), yz - wx, 0.0f);
    m.r2 = btgMake4(xz - wy, yz + wx, 1.0f - (xx + yy), 0.0f);
    return m;
}
static inline BtgFloat4 btgMat3MulVec(BtgMat3 m, BtgFloat4 v)
{
    return btgMake4(btgDot3(m.r0, v), btgDot3(m.r1, v), btgDot3(m.r2, v), 0.0f);
}
/* m^T v: the inverse rotation for an orthonormal m. */
static inline BtgFloat4 btgMat3TMulVec(BtgMat3 m, BtgFloat4 v)
{
    return btgXyz(m.r0 * v.x + m.r1 * v.y + m.r2 * v.z);
}
static inline BtgFloat4 btgQuatRotate(BtgFloat4 q, BtgFloat4 v) { return btgMat3MulVec(btgQuatToMat3(q), v); }
static inline BtgMat3 btgMat3Transpose(BtgMat3 m)
{
    BtgMat3 t;
    t.r0 = btgMake4(m.r0.x, m.r1.x, m.r2.x, 0.0f);
    t.r1 = btgMake4(m.r0.y, m.r1.y, m.r2.y, 0.0f);
    t.r2 = btgMake4(m.r0.z, m.r1.z, m.r2.z, 0.0f);
    return t;
}
static inline BtgMat3 btgMat3Mul(BtgMat3 a, BtgMat3 b)
{
    BtgMat3 bt = btgMat3Transpose(b);
    BtgMat3 m;
    m.r0 = btgMake4(btgDot3(a.r0, bt.r0), btgDot3(a.r0, bt.r1), btgDot3(a.r0, bt.r2), 0.0f);
    m.r1 = btgMake4(btgDot3(a.r1, bt.r0), btgDot3(a.r1, bt.r1), btgDot3(a.r1, bt.r2), 0.0f);
    m.r2 = btgMake4(btgDot3(a.r2, bt.r0), btgDot3(a.r2, bt.r1), btgDot3(a.r2, bt.r2), 0.0f);
    return m;
}
/* World inverse inertia R diag(d) R^T, as btRigidBody::updateInertiaTensor computes it. */
static inline BtgMat3 btgInvInertiaWorld(BtgFloat4 rot, BtgFloat4 invInertiaLocal)
{
    BtgMat3 r = btgQuatToMat3(rot);
    BtgMat3 rs;
    rs.r0 = r.r0 * invInertiaLocal;
    rs.r1 = r.r1 * invInertiaLocal;
    rs.r2 = r.r2 * invInertiaLocal;
    rs.r0.w = 0.0f; rs.r1.w = 0.0f; rs.r2.w = 0.0f;
    return btgMat3Mul(rs, btgMat3Transpose(r));
}
/* Any two unit vectors orthogonal to n (btPlaneSpace1), so friction directions are a pure
 * function of the normal and warm-started impulses keep their meaning across frames. */
static inline void btgPlaneSpace(BtgFloat4 n, BtgFloat4* p, BtgFloat4* q)
{
    if (btgAbs(n.z) > 0.70710678f) {
        float a = n.y * n.y + n.z * n.z;
        float k = 1.0f / btgSqrt(a);
        *p = btgMake4(0.0f, -n.z * k, n.y * k, 0.0f);
        *q = btgMake4(a * k, -n.x * (*p).z, n.x * (*p).y, 0.0f);
    } else {
        float a = n.x * n.x + n.y * n.y;
        float k = 1.0f / btgSqrt(a);
        *p = btgMake4(-n.y * k, n.x * k, 0.0f, 0.0f);
        *q = btgMake4(-n.z * (*p).y, n.z * (*p).x, a * k, 0.0f);
    }
}

#define BTG_ANGULAR_MOTION_THRESHOLD 0.78539816f /* 0.5 * SIMD_HALF_PI, as Bullet */

/* btTransformUtil::integrateTransform's rotation part: the new orientation after dt. */
static inline BtgFloat4 btgIntegrateRotation(BtgFloat4 rot, BtgFloat4 angVel, float dt)
{
    float angle2 = btgDot3(angVel, angVel);
    float angle = angle2 > 1.1920929e-07f ? btgSqrt(angle2) : 0.0f;
    if (angle * dt > BTG_ANGULAR_MOTION_THRESHOLD) angle = BTG_ANGULAR_MOTION_THRESHOLD / dt;
    BtgFloat4 axis;
    if (angle < 0.001f)
        axis = btgXyz(angVel) * (0.5f * dt - (dt * dt * dt) * 0.020833333333f * angle * angle);
    else
        axis = btgXyz(angVel) * (btgSin(0.5f * angle * dt) / angle);
    BtgFloat4 dorn = btgMake4(axis.x, axis.y, axis.z, btgCos(angle * dt * 0.5f));
    /* As Bullet: safeNormalize, then keep the current orientation when nothing usable is left.
     * At huge angular speeds (1e22 rad/s) the product's length overflows to inf and the
     * normalized quaternion is zero: Bullet keeps the old basis, and so do we. */
    BtgFloat4 q = btgQuatMul(dorn, rot);
    float l2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
    if (l2 >= 1.1920929e-07f) q = q * (1.0f / btgSqrt(l2));
    float n2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
    return n2 > 1.1920929e-07f ? q : rot;
}

/* Cramer's rule solve of m x = b (btMatrix3x3::solve33); zero when m is singular. */
static inline BtgFloat4 btgSolve33(BtgMat3 m, BtgFloat4 b)
{
    BtgFloat4 c0 = btgMake4(m.r0.x, m.r1.x, m.r2.x, 0.0f);
    BtgFloat4 c1 = btgMake4(m.r0.y, m.r1.y, m.r2.y, 0.0f);
    BtgFloat4 c2 = btgMake4(m.r0.z, m.r1.z, m.r2.z, 0.0f);
    float det = btgDot3(c0, btgCross3(c1, c2));
    if (btgAbs(det) > 1.1920929e-07f) det = 1.0f / det;
    return btgMake4(det * btgDot3(b, btgCross3(c1, c2)), det * btgDot3(c0, btgCross3(b, c2)),
                    det * btgDot3(c0, btgCross3(c1, b)), 0.0f);
}
static inline BtgMat3 btgSkew(BtgFloat4 v)
{
    BtgMat3 m;
    m.r0 = btgMake4(0.0f, -v.z, v.y, 0.0f);
    m.r1 = btgMake4(v.z, 0.0f, -v.x, 0.0f);
    m.r2 = btgMake4(-v.y, v.x, 0.0f, 0.0f);
    return m;
}
/* One Newton step on Euler's equation without torque, as Bullet's implicit gyroscopic terms take
 * it (evalEulerEqn, evalEulerEqnDeriv at w1 = w0): the correction dw to subtract from w, for the
 * inertia tensor in w's frame. */
static inline BtgFloat4 btgEulerNewtonStep(BtgMat3 inertia, BtgFloat4 w, float dt)
{
    BtgFloat4 iw = btgMat3MulVec(inertia, w);
    BtgFloat4 f = btgCross3(w, iw) * dt;
    BtgMat3 s0i = btgMat3Mul(btgSkew(w), inertia);
    BtgMat3 s1 = btgSkew(iw);
    BtgMat3 j;
    j.r0 = inertia.r0 + (s0i.r0 - s1.r0) * dt;
    j.r1 = inertia.r1 + (s0i.r1 - s1.r1) * dt;
    j.r2 = inertia.r2 + (s0i.r2 - s1.r2) * dt;
    return btgSolve33(j, f);
}
/* Bullet's implicit world-frame gyroscopic term (computeGyroscopicImpulseImplicit_World), with the
 * world inertia tensor iw (R diag(I) R^T): the change of angular velocity. */
static inline BtgFloat4 btgGyroscopicImpulseWorld(BtgMat3 iw, BtgFloat4 angVel, float dt)
{
    return -btgEulerNewtonStep(iw, btgXyz(angVel), dt);
}
/* Bullet's explicit gyroscopic force (computeGyroscopicForceExplicit): w x I w with the world
 * inertia tensor, its length bounded by maxForce. */
static inline BtgFloat4 btgGyroscopicForceExplicit(BtgMat3 iw, BtgFloat4 angVel, float maxForce)
{
    BtgFloat4 w = btgXyz(angVel);
    BtgFloat4 gf = btgCross3(w, btgMat3MulVec(iw, w));
    float l2 = btgDot3(gf, gf);
    if (l2 > maxForce * maxForce) gf = gf * (1.0f / btgSqrt(l2) * maxForce);
    return gf;
}
/* Bullet's implicit body-frame gyroscopic term (computeGyroscopicImpulseImplicit_Body): the step
 * in the body's frame; returns the change of world angular velocity. */
static inline BtgFloat4 btgGyroscopicImpulse(BtgFloat4 rot, BtgFloat4 angVel, BtgFloat4 localInertia, float dt)
{
    BtgFloat4 omegab = btgQuatRotate(btgQuatConj(rot), angVel);
    BtgMat3 ib;
    ib.r0 = btgMake4(localInertia.x, 0.0f, 0.0f, 0.0f);
    ib.r1 = btgMake4(0.0f, localInertia.y, 0.0f, 0.0f);
    ib.r2 = btgMake4(0.0f, 0.0f, localInertia.z, 0.0f);
    omegab = omegab - btgEulerNewtonStep(ib, omegab, dt);
    return btgQuatRotate(rot, omegab) - btgXyz(angVel);
}

#endif
