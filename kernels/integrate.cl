/* integrate.cl — Stage: integrate (three kernels, one work-item per body row).
 * predict_motion   Reads props. Writes linVel, angVel (damping, additional damping).
 * apply_forces     Reads rot, props, extForce, extTorque. Writes invInertiaWorld, linVel0,
 *                  angVel0 (velocities before forces, for restitution), linVel, angVel,
 *                  pushLin/pushAng (zeroed for the split-impulse passes; not with push 0, the
 *                  soft step's, which holds a placeholder row of each).
 * integrate_transforms  Reads linVel, angVel, pushLin, pushAng, props. Writes pos, rot;
 *                  flags non-finite results in counters (status BTG_STATUS_NAN, lowest row). */
#include "shared/integrate.h"
#include "shared/counters.h"

__kernel void predict_motion(int n, __global const BtgBodyProps* restrict props, __global BtgFloat4* linVel,
                             __global BtgFloat4* angVel, float dt)
{
    int i = get_global_id(0);
    if (i >= n) return;
    BtgBodyProps p = props[i];
    if (!btgIsMoving(p.flags)) return;
    BtgFloat4 v = btgDamp(linVel[i], p.linearDamping, dt);
    BtgFloat4 w = btgDamp(angVel[i], p.angularDamping, dt);
    btgAdditionalDamping(&v, &w, p);
    linVel[i] = v;
    angVel[i] = w;
}

__kernel void apply_forces(int n, __global const BtgFloat4* restrict rot, __global const BtgBodyProps* restrict props,
                           __global const BtgFloat4* restrict extForce, __global const BtgFloat4* restrict extTorque,
                           __global BtgFloat4* invInertiaWorld, __global BtgFloat4* linVel0, __global BtgFloat4* angVel0,
                           __global BtgFloat4* linVel, __global BtgFloat4* angVel, __global BtgFloat4* pushLin,
                           __global BtgFloat4* pushAng, int push, float dt, float maxGyroscopicForce)
{
    int i = get_global_id(0);
    if (i >= n) return;
    BtgBodyProps p = props[i];
    BtgFloat4 q = rot[i];
    BtgFloat4 inv = p.invInertiaLocal;
    if (!(p.flags & BTG_BODY_DYNAMIC)) inv = btgZero4();
    BtgMat3 iw = btgInvInertiaWorld(q, inv);
    invInertiaWorld[3 * i + 0] = iw.r0;
    invInertiaWorld[3 * i + 1] = iw.r1;
    invInertiaWorld[3 * i + 2] = iw.r2;
    BtgFloat4 v = linVel[i];
    BtgFloat4 w = angVel[i];
    linVel0[i] = v;
    angVel0[i] = w;
    if (push) {  /* else one placeholder row each: the soft step has no split-impulse passes */
        pushLin[i] = btgZero4();
        pushAng[i] = btgZero4();
    }
    if (!btgIsMoving(p.flags)) return;
    linVel[i] = btgApplyLinearForces(v, extForce[i], p, dt);
    angVel[i] = btgApplyAngularForces(w, extTorque[i], q, iw, p, dt, maxGyroscopicForce);
}

__kernel void integrate_transforms(int n, __global const BtgBodyProps* restrict props,
                                   __global const BtgFloat4* restrict linVel, __global const BtgFloat4* restrict angVel,
                                   __global const BtgFloat4* restrict pushLin, __global const BtgFloat4* restrict pushAng,
                                   __global BtgFloat4* pos, __global BtgFloat4* rot, __global uint* counters, float dt,
                                   float turnErp)
{
    int i = get_global_id(0);
    if (i >= n) return;
    BtgBodyProps p = props[i];
    if (!btgIsMoving(p.flags)) return;
    BtgFloat4 x = pos[i];
    BtgFloat4 q = rot[i];
    BtgFloat4 pl = pushLin[i];
    BtgFloat4 pa = pushAng[i];
    /* The split impulse moves the body without leaving velocity behind (Bullet integrates the
     * push only when it is non-zero, so a body without one is not renormalised twice). */
    if (pl.x != 0.0f || pl.y != 0.0f || pl.z != 0.0f || pa.x != 0.0f || pa.y != 0.0f || pa.z != 0.0f) {
        x = btgXyz(x) + btgXyz(pl) * dt;
        q = btgIntegrateRotation(q, btgXyz(pa) * turnErp, dt);
    }
    BtgFloat4 v = linVel[i];
    x = btgXyz(x) + btgXyz(v) * dt;
    q = btgIntegrateRotation(q, angVel[i], dt);
    if (!btgIsFinite4(x) || !btgIsFinite4(q) || !btgIsFinite4(v) || !btgIsFinite4(angVel[i])) {
        atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_NAN);
        atomic_min(&counters[BTG_COUNTER_NAN_BODY], (uint)i);
    }
    pos[i] = x;
    rot[i] = q;
}
