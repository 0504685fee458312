/* pgs_wide.h — the bullet mode's velocity sweeps (warm start, normal rows, friction rows: what
 * pgs_edges.h's solve_contact does with contact_rows.h) eight contacts of one colour at a time in
 * the lanes of float8, for CPU devices (pgs_wide_passes.h's kernels). A CPU device runs a
 * work-group's work-items one after another, each contact's rows as scalar code: the solve was
 * about half of a PoCL frame of cubes 8,000. The contacts of a colour share no dynamic body, so
 * their rows can run side by side (Box2D v3's contact_solver.c, b2FloatW), as the soft step's
 * already do (soft_wide.h, whose lane helpers these rows use). Each expression is written as its
 * scalar counterpart in contact_rows.h / solver_rows.h is (the same operations in the same order
 * in one statement, so the compiler contracts the same products into the same fused
 * multiply-adds): lane by lane the same arithmetic, the same results bit for bit
 * (SolveConstraints tests against the one-launch solves, the bench's state hash). Served: the
 * rows without contact cfm, rolling, anisotropic directions, friction anchors, interleave or
 * SOLVER_RANDMIZE_ORDER (pgsWideServed on the host: otherwise the scalar sweeps); one or two
 * friction directions. Device only (OpenCL vectors); the CPU reference is contact_rows.h. */
#ifndef BTG_PGS_WIDE_H
#define BTG_PGS_WIDE_H
#include "contact_rows.h"
#include "soft_wide.h"

/* A contact's fields in a chunk's block of lanes (field f of lane l at f * 8 + l): the normal,
 * friction and tangent plane, then per point k its lever arms and row fields. */
enum {
    BTG_PW_NX, BTG_PW_NY, BTG_PW_NZ, BTG_PW_FRICTION, BTG_PW_T1X, BTG_PW_T1Y, BTG_PW_T1Z, BTG_PW_T2X, BTG_PW_T2Y,
    BTG_PW_T2Z, BTG_PW_POINT0, /* then per point: */
    BTG_PW_AX = 0, BTG_PW_AY, BTG_PW_AZ, BTG_PW_BX, BTG_PW_BY, BTG_PW_BZ, BTG_PW_NMASS, BTG_PW_NTARGET, BTG_PW_NIMP,
    BTG_PW_COS, BTG_PW_SIN, BTG_PW_F1MASS, BTG_PW_F1IMP, BTG_PW_F2MASS, BTG_PW_F2IMP, BTG_PW_PER_POINT
};
#define BTG_PW_FIELDS BTG_PGS_WIDE_FIELDS /* the host sizes the blocks by it (contact_rows.h) */
typedef char BtgPwFieldsCheck[BTG_PW_POINT0 + BTG_MAX_POINTS * BTG_PW_PER_POINT == BTG_PW_FIELDS ? 1 : -1];
#define BTG_PW_AT(k, f) (BTG_PW_POINT0 + (k) * BTG_PW_PER_POINT + (f))

/* Lane l of a block from contact c as btgLoadContactRows gives a velocity sweep its fields (c 0:
 * an empty lane, no points: every row mass zero). Lanes past the contact's points hold zeros. */
static BTG_ALWAYS_INLINE void btgPwPutContact(__global float* blk, int l, __global const BtgContact* c)
{
    const BtgFloat4 z = btgZero4();
    const int live = c != 0;
    const int points = live ? c->numPoints : 0;
    const BtgFloat4 n = live ? c->normal : z, t1 = live ? c->tangent1 : z, t2 = live ? c->tangent2 : z;
    BTG_W_PUT(blk, BTG_PW_NX, l, n.x);
    BTG_W_PUT(blk, BTG_PW_NY, l, n.y);
    BTG_W_PUT(blk, BTG_PW_NZ, l, n.z);
    BTG_W_PUT(blk, BTG_PW_FRICTION, l, live ? c->friction : 0.0f);
    BTG_W_PUT(blk, BTG_PW_T1X, l, t1.x);
    BTG_W_PUT(blk, BTG_PW_T1Y, l, t1.y);
    BTG_W_PUT(blk, BTG_PW_T1Z, l, t1.z);
    BTG_W_PUT(blk, BTG_PW_T2X, l, t2.x);
    BTG_W_PUT(blk, BTG_PW_T2Y, l, t2.y);
    BTG_W_PUT(blk, BTG_PW_T2Z, l, t2.z);
    const BtgFloat4 nm = live ? c->normalMass : z, nt = live ? c->normalTarget : z, ni = live ? c->normalImpulse : z;
    const BtgFloat4 fc = live ? c->frictionCos : z, fs = live ? c->frictionSin : z;
    const BtgFloat4 m1 = live ? c->friction1Mass : z, i1 = live ? c->friction1Impulse : z;
    const BtgFloat4 m2 = live ? c->friction2Mass : z, i2 = live ? c->friction2Impulse : z;
#pragma unroll
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        const int on = k < points;
        const BtgFloat4 rA = on ? c->rA[k] : z, rB = on ? c->rB[k] : z;
        btgWPutArms(blk, BTG_PW_AT(k, BTG_PW_AX), l, rA, rB);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_NMASS), l, on ? btgLane(nm, k) : 0.0f);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_NTARGET), l, on ? btgLane(nt, k) : 0.0f);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_NIMP), l, on ? btgLane(ni, k) : 0.0f);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_COS), l, on ? btgLane(fc, k) : 0.0f);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_SIN), l, on ? btgLane(fs, k) : 0.0f);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_F1MASS), l, on ? btgLane(m1, k) : 0.0f);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_F1IMP), l, on ? btgLane(i1, k) : 0.0f);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_F2MASS), l, on ? btgLane(m2, k) : 0.0f);
        BTG_W_PUT(blk, BTG_PW_AT(k, BTG_PW_F2IMP), l, on ? btgLane(i2, k) : 0.0f);
    }
}
/* Point field f of lane l as the contact's per-point float4, the lanes past its points kept from
 * `old` (the contact's own: a sweep never changes them). */
static BTG_ALWAYS_INLINE BtgFloat4 btgPwPoints(__global const float* blk, int l, int f, int points, BtgFloat4 old)
{
    BtgFloat4 v = old;
    for (int k = 0; k < points; ++k) btgSetLane(&v, k, blk[BTG_PW_AT(k, f) * BTG_SOFT_WIDE + l]);
    return v;
}

/* Point k's friction direction 1 or 2 (btgFrictionDir1/2), lanes. */
static BTG_ALWAYS_INLINE BtgV3W btgPwFrictionDir(__global const float* blk, int k, int second)
{
    const BtgV3W t1 = btgW3LoadG(blk, BTG_PW_T1X), t2 = btgW3LoadG(blk, BTG_PW_T2X);
    const BtgW cs = btgWLoadG(blk, BTG_PW_AT(k, BTG_PW_COS)), sn = btgWLoadG(blk, BTG_PW_AT(k, BTG_PW_SIN));
    if (second) return btgW3(t2.x * cs - t1.x * sn, t2.y * cs - t1.y * sn, t2.z * cs - t1.z * sn);
    return btgW3(t1.x * cs + t2.x * sn, t1.y * cs + t2.y * sn, t1.z * cs + t2.z * sn);
}
static BTG_ALWAYS_INLINE BtgJacobianW btgPwJacobian(__global const float* blk, int k, BtgV3W dir, const BtgBodyW* a,
                                                    const BtgBodyW* b)
{
    const BtgV3W rA = btgW3LoadG(blk, BTG_PW_AT(k, BTG_PW_AX)), rB = btgW3LoadG(blk, BTG_PW_AT(k, BTG_PW_BX));
    return btgWPointJacobian(dir, rA, rB, a, b);
}

/* btgContactWarmStartDirs (no explicit directions), lanes. */
static BTG_ALWAYS_INLINE void btgPwWarmStart(__global const float* blk, const BtgBodyW* a, const BtgBodyW* b, BtgVelW* va,
                                             BtgVelW* vb, int twoFriction)
{
    const BtgV3W n = btgW3LoadG(blk, BTG_PW_NX);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        const int8 rowed = btgWLoadG(blk, BTG_PW_AT(k, BTG_PW_NMASS)) != 0.0f;
        if (!any(rowed)) continue;
        BtgVelW a0 = *va, b0 = *vb;
        BtgJacobianW j = btgPwJacobian(blk, k, n, a, b);
        btgWRowApply(&j, a, b, va, vb, btgWLoadG(blk, BTG_PW_AT(k, BTG_PW_NIMP)));
        btgWKeep(va, a0, rowed);
        btgWKeep(vb, b0, rowed);
        for (int s = 0; s < 1 + twoFriction; ++s) {
            const int8 on = rowed & (btgWLoadG(blk, BTG_PW_AT(k, s ? BTG_PW_F2MASS : BTG_PW_F1MASS)) != 0.0f);
            if (!any(on)) continue;
            a0 = *va;
            b0 = *vb;
            j = btgPwJacobian(blk, k, btgPwFrictionDir(blk, k, s), a, b);
            btgWRowApply(&j, a, b, va, vb, btgWLoadG(blk, BTG_PW_AT(k, s ? BTG_PW_F2IMP : BTG_PW_F1IMP)));
            btgWKeep(va, a0, on);
            btgWKeep(vb, b0, on);
        }
    }
}
/* btgContactSolveNormals (cfm 0), lanes. */
static BTG_ALWAYS_INLINE void btgPwNormals(__global float* blk, const BtgBodyW* a, const BtgBodyW* b, BtgVelW* va,
                                           BtgVelW* vb)
{
    const BtgV3W n = btgW3LoadG(blk, BTG_PW_NX);
    const BtgW zero = (BtgW)(0.0f);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        const BtgW mass = btgWLoadG(blk, BTG_PW_AT(k, BTG_PW_NMASS));
        const int8 solved = mass != 0.0f;
        if (!any(solved)) continue;
        const BtgJacobianW j = btgPwJacobian(blk, k, n, a, b);
        const BtgW impulse = btgWLoadG(blk, BTG_PW_AT(k, BTG_PW_NIMP));
        const BtgW next = btgWRowSolve(&j, mass, btgWLoadG(blk, BTG_PW_AT(k, BTG_PW_NTARGET)), zero, zero,
                                       (BtgW)(BTG_NORMAL_UPPER_LIMIT), impulse, solved, a, b, va, vb);
        btgWStoreG(blk, BTG_PW_AT(k, BTG_PW_NIMP), next);
    }
}
/* btgContactSolveFriction (no explicit directions, no anchors), lanes: a point's rows while its
 * normal impulse is positive, bounded by friction times it. */
static BTG_ALWAYS_INLINE void btgPwFriction(__global float* blk, const BtgBodyW* a, const BtgBodyW* b, BtgVelW* va,
                                            BtgVelW* vb, int twoFriction)
{
    const BtgW friction = btgWLoadG(blk, BTG_PW_FRICTION), zero = (BtgW)(0.0f);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        const BtgW normal = btgWLoadG(blk, BTG_PW_AT(k, BTG_PW_NIMP));
        const int8 pushing = normal > 0.0f;
        if (!any(pushing)) continue;
        const BtgW lim = friction * normal;
        for (int s = 0; s < 1 + twoFriction; ++s) {
            const int fm = s ? BTG_PW_F2MASS : BTG_PW_F1MASS, fi = s ? BTG_PW_F2IMP : BTG_PW_F1IMP;
            const BtgW mass = btgWLoadG(blk, BTG_PW_AT(k, fm));
            const int8 solved = pushing & (mass != 0.0f);
            if (!any(solved)) continue;
            const BtgJacobianW j = btgPwJacobian(blk, k, btgPwFrictionDir(blk, k, s), a, b);
            const BtgW next = btgWRowSolve(&j, mass, zero, zero, -lim, lim, btgWLoadG(blk, BTG_PW_AT(k, fi)), solved, a,
                                           b, va, vb);
            btgWStoreG(blk, BTG_PW_AT(k, fi), next);
        }
    }
}

#endif
