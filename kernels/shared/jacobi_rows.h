/* jacobi_rows.h — mass splitting (Tonge, Benevolenski, Sheffield 2012) on top of contact_rows.h,
 * shared by kernels/solve_jacobi.cl and its CPU reference: a dynamic body touched by n contacts
 * lends each of them a copy with 1/n of its mass; a contact solves all its points (normal, then
 * friction) against its copies and reports how much it changed them. Averaging the n copies,
 * v + (1/n) sum(dv_i), equals applying every contact's impulse to the real body. */
#ifndef BTG_JACOBI_ROWS_H
#define BTG_JACOBI_ROWS_H
#include "contact_rows.h"

/* The body as one of its n contacts sees it: inverse mass and inertia times n (n >= 1). */
static inline BtgSolverBody btgSplitBody(BtgSolverBody b, uint n)
{
    float s = n > 1u ? (float)n : 1.0f;
    b.invMass = b.invMass * s;
    b.invMassLin = b.invMassLin * s;
    b.invI.r0 = b.invI.r0 * s;
    b.invI.r1 = b.invI.r1 * s;
    b.invI.r2 = b.invI.r2 * s;
    return b;
}

/* Effective masses against the split bodies. Rows prepare_contacts marked immobile (0) stay 0;
 * splitting only scales a mobile row's denominator, so no row changes between the two. */
static inline void btgContactSplitMasses(BtgContact* c, BtgSolverBody a, BtgSolverBody b)
{
    for (int k = 0; k < c->numPoints; ++k) {
        BtgFloat4 rA = btgXyz(c->rA[k]), rB = btgXyz(c->rB[k]);
        if (btgLane(c->normalMass, k) != 0.0f)
            btgSetLane(&c->normalMass, k, btgPointRowMass(btgPointJacobian(c->normal, rA, rB, a, b), rA, rB, a, b));
        if (btgLane(c->friction1Mass, k) != 0.0f)
            btgSetLane(&c->friction1Mass, k, btgPointRowMass(btgPointJacobian(btgFrictionDir1(c, k), rA, rB, a, b), rA, rB, a, b));
        if (btgLane(c->friction2Mass, k) != 0.0f)
            btgSetLane(&c->friction2Mass, k, btgPointRowMass(btgPointJacobian(btgFrictionDir2(c, k), rA, rB, a, b), rA, rB, a, b));
    }
}

/* One contact's Jacobi step. mode 0: warm start, 1: velocity iteration, 2: push iteration.
 * Every row is visited (second friction rows too: without two friction directions their mass
 * is 0 and they are skipped on that).
 * a, b: split bodies; va, vb: the bodies' current (averaged) velocities, zero unless moving
 * (push: unless dynamic). Updates the contact's accumulated impulses (modes 1, 2) and returns
 * the change of each copy in dA, dB (lin, ang). */
static inline void btgJacobiContact(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel va, BtgBodyVel vb,
                                    int mode, BtgBodyVel* dA, BtgBodyVel* dB)
{
    BtgContact s = *c;
    btgContactSplitMasses(&s, a, b);
    BtgBodyVel ca = va, cb = vb;
    if (mode == BTG_PASS_WARM_START) btgContactWarmStart(&s, a, b, &ca, &cb, 1);
    else if (mode == BTG_PASS_VELOCITY) btgContactSolveVelocity(&s, a, b, &ca, &cb, 1);
    else btgContactSolvePush(&s, a, b, &ca, &cb);
    c->normalImpulse = s.normalImpulse;
    c->friction1Impulse = s.friction1Impulse;
    c->friction2Impulse = s.friction2Impulse;
    c->pushImpulse = s.pushImpulse;
    dA->lin = ca.lin - va.lin;
    dA->ang = ca.ang - va.ang;
    dB->lin = cb.lin - vb.lin;
    dB->ang = cb.ang - vb.ang;
}

/* A body's velocity after averaging its n copies: v + (1/n) * (sum of the copies' changes,
 * added in the fixed order of its contact list). */
static inline BtgFloat4 btgJacobiAverage(BtgFloat4 v, BtgFloat4 sum, uint n)
{
    float inv = 1.0f / (float)n;
    return btgMake4(v.x + sum.x * inv, v.y + sum.y * inv, v.z + sum.z * inv, v.w);
}

#endif
