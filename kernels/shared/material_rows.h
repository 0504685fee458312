/* material_rows.h — the rows a pair's materials add to its contact rows (contact_rows.h), as
 * Bullet 3.24's convertContact builds them: rolling and spinning friction (BtgRollingContact:
 * addTorsionalFrictionConstraint's angular rows and solveSingleIteration's rolling sweep) and
 * anisotropic friction (applyAnisotropicFriction; BtgFrictionDirs). Shared by prepare_contacts,
 * solve_constraints and their CPU references; only scenes with these materials reach them. */
#ifndef BTG_MATERIAL_ROWS_H
#define BTG_MATERIAL_ROWS_H
#include "contact_rows.h"

/* ---- rolling and spinning friction (BtgRollingContact) ---- */

/* An angular row about `axis` as setupTorsionalFrictionConstraint builds it: no linear part,
 * A's lever -axis, B's +axis, responses with the angular factors. */
static inline BtgJacobian btgAngularJacobian(BtgFloat4 axis, BtgSolverBody a, BtgSolverBody b)
{
    BtgJacobian j;
    j.linear = btgZero4();
    j.angularA = -btgXyz(axis);
    j.angularB = btgXyz(axis);
    j.responseA = btgMat3MulVec(a.invI, j.angularA) * a.angFactor;
    j.responseB = btgMat3MulVec(b.invI, j.angularB) * b.angFactor;
    return j;
}
/* Its m_jacDiagABInv: 1 / (J_A I_A^-1 J_A + J_B I_B^-1 J_B), without the angular factors and
 * without relaxation, as Bullet has it; 0 (no row) where neither body can turn (Bullet would
 * divide by zero). */
static inline float btgAngularRowMass(BtgJacobian j, BtgSolverBody a, BtgSolverBody b)
{
    float sum = 0.0f;
    sum += btgDot3(btgMat3MulVec(a.invI, j.angularA), j.angularA);
    sum += btgDot3(btgMat3MulVec(b.invI, j.angularB), j.angularB);
    return sum > 0.0f ? 1.0f / sum : 0.0f;
}
/* btVector3::normalize as the float Linux build has it: v * (1 / |v|). */
static inline BtgFloat4 btgNormalizeBullet(BtgFloat4 v)
{
    return v * (1.0f / btgSqrt(btgDot3(v, v)));
}

/* applyAnisotropicFriction: a body with the anisotropy `mode` (BTG_BODY_ANISOTROPIC*) scales
 * dir per axis of its own frame (rot: its orientation). */
static inline BtgFloat4 btgApplyAnisotropy(BtgFloat4 dir, BtgFloat4 rot, BtgBodyProps p, uint mode)
{
    if ((p.flags & mode) == 0u) return dir;
    BtgMat3 m = btgQuatToMat3(rot);
    BtgFloat4 inBody = btgMat3TMulVec(m, dir) * btgXyz(p.anisotropicFriction);
    return btgMat3MulVec(m, inBody);
}

/* Both bodies' anisotropy on dir in convertContact's order: body 0 of Bullet's manifold first,
 * which for two convex bodies is the one of the lower proxy id (two anisotropic bodies whose
 * manifold another algorithm orders, a compound's or a concave one's, are not on the GPU path). */
static inline BtgFloat4 btgApplyBothAnisotropies(BtgFloat4 dir, BtgFloat4 rotA, BtgFloat4 rotB, BtgBodyProps pa,
                                                 BtgBodyProps pb, uint mode)
{
    if (pa.proxyOrder <= pb.proxyOrder) return btgApplyAnisotropy(btgApplyAnisotropy(dir, rotA, pa, mode), rotB, pb, mode);
    return btgApplyAnisotropy(btgApplyAnisotropy(dir, rotB, pb, mode), rotA, pa, mode);
}

/* convertContact's rolling rows of a prepared contact c: only when the combined rolling
 * friction is positive (spinning friction alone adds no row in 3.24), and only while c is
 * solvable (its normal rows have mass). Impulses start at zero (Bullet never warm-starts
 * them). The axes take both bodies' anisotropic rolling friction, body 0's first (rotA, rotB,
 * pa, pb: the bodies' orientations and rows). */
static inline BtgRollingContact btgPrepareRolling(const BtgContact* c, BtgSolverBody a, BtgSolverBody b,
                                                  BtgPairMaterial mat, int solvable, BtgFloat4 rotA, BtgFloat4 rotB,
                                                  BtgBodyProps pa, BtgBodyProps pb)
{
    BtgRollingContact r;
    BtgFloat4 t1, t2;
    btgPlaneSpace(btgXyz(c->normal), &t1, &t2);
    r.rollAxis1 = btgNormalizeBullet(btgXyz(t1));
    r.rollAxis2 = btgNormalizeBullet(btgXyz(t2));
    r.spinImpulse = btgZero4();
    r.roll1Impulse = btgZero4();
    r.roll2Impulse = btgZero4();
    r.spinningFriction = mat.spinningFriction;
    r.rollingFriction = mat.rollingFriction;
    r.pad0 = 0.0f;
    r.pad1 = 0.0f;
    r.pad2 = 0.0f;
    r.spinMass = 0.0f;
    r.roll1Mass = 0.0f;
    r.roll2Mass = 0.0f;
    if (!(mat.rollingFriction > 0.0f) || !solvable || c->numPoints == 0) return r;
    r.spinMass = btgAngularRowMass(btgAngularJacobian(c->normal, a, b), a, b);
    const uint mode = BTG_BODY_ANISOTROPIC_ROLLING;
    r.rollAxis1 = btgApplyBothAnisotropies(r.rollAxis1, rotA, rotB, pa, pb, mode);
    r.rollAxis2 = btgApplyBothAnisotropies(r.rollAxis2, rotA, rotB, pa, pb, mode);
    /* a row needs |axis| > 0.001 */
    if (btgLength3(r.rollAxis1) > 0.001f) r.roll1Mass = btgAngularRowMass(btgAngularJacobian(r.rollAxis1, a, b), a, b);
    if (btgLength3(r.rollAxis2) > 0.001f) r.roll2Mass = btgAngularRowMass(btgAngularJacobian(r.rollAxis2, a, b), a, b);
    return r;
}

/* One row of the rolling sweep: bounded by the coefficient times the point's normal impulse,
 * at most the coefficient itself (solveSingleIteration), solved only while that impulse is
 * positive. Returns the new accumulated impulse. */
static inline float btgRollingRowSolve(BtgFloat4 axis, float mass, float friction, float normalImpulse, float impulse,
                                       BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb)
{
    if (mass == 0.0f || !(normalImpulse > 0.0f)) return impulse;
    float lim = friction * normalImpulse;
    if (lim > friction) lim = friction;
    BtgSolverRow row = btgMakeSolverRow(btgAngularJacobian(axis, a, b), mass, 0.0f, -lim, lim, impulse);
    btgRowSolve(&row, a, b, va, vb);
    return row.impulse;
}
/* The rolling sweep of one contact (BTG_PASS_ROLLING): per point, as Bullet adds them, the
 * torsional row about the normal, then the two rolling rows. normal, normalImpulse and
 * numPoints are the contact's. */
static inline void btgRollingSolve(BtgRollingContact* r, BtgFloat4 normal, BtgFloat4 normalImpulse, int numPoints,
                                   BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb)
{
    for (int k = 0; k < numPoints; ++k) {
        const float n = btgLane(normalImpulse, k);
        btgSetLane(&r->spinImpulse, k,
                   btgRollingRowSolve(normal, r->spinMass, r->spinningFriction, n, btgLane(r->spinImpulse, k), a, b, va, vb));
        btgSetLane(&r->roll1Impulse, k, btgRollingRowSolve(r->rollAxis1, r->roll1Mass, r->rollingFriction, n,
                                                           btgLane(r->roll1Impulse, k), a, b, va, vb));
        btgSetLane(&r->roll2Impulse, k, btgRollingRowSolve(r->rollAxis2, r->roll2Mass, r->rollingFriction, n,
                                                           btgLane(r->roll2Impulse, k), a, b, va, vb));
    }
}

/* ---- anisotropic friction (BtgFrictionDirs) ---- */

/* convertContact's friction directions where a body has CF_ANISOTROPIC_FRICTION, after
 * btgPrepareContact built c (its directions then are Bullet's before the scaling): direction 1
 * scaled by both bodies' anisotropy, body 0's first; with two directions, direction 2 is the scaled direction
 * 1 crossed with the normal and normalised (along a slip), or btPlaneSpace1's q (no slip, or
 * velocity-independent directions), each then scaled alike. The rows' masses follow the scaled
 * directions (setupFrictionConstraint takes them as they are: the inverse mass term unscaled).
 * rotA/rotB, pa/pb: the bodies' orientations and rows. */
static inline void btgPrepareAnisotropicFriction(BtgContact* c, BtgFrictionDirs* dirs, BtgSolverBody a, BtgSolverBody b,
                                                 BtgBodyVel a1, BtgBodyVel b1, BtgFloat4 rotA, BtgFloat4 rotB,
                                                 BtgBodyProps pa, BtgBodyProps pb, int solvable, BtgStepParams p)
{
    const uint mode = BTG_BODY_ANISOTROPIC;
    const BtgFloat4 n = btgXyz(c->normal);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        dirs->dir1[k] = btgZero4();
        dirs->dir2[k] = btgZero4();
        if (k >= c->numPoints) continue;
        const BtgFloat4 rA = btgXyz(c->rA[k]), rB = btgXyz(c->rB[k]);
        BtgFloat4 v = (a1.lin + btgCross3(a1.ang, rA)) - (b1.lin + btgCross3(b1.ang, rB));
        BtgFloat4 slip = v - n * btgDot3(v, n);
        const int alongSlip =
            !(p.solverFlags & BTG_SOLVER_VELOCITY_INDEPENDENT_FRICTION) && btgDot3(slip, slip) > BTG_SIMD_EPSILON;
        BtgFloat4 d1 = btgApplyBothAnisotropies(btgFrictionDir1(c, k), rotA, rotB, pa, pb, mode);
        BtgFloat4 d2 = alongSlip ? btgNormalizeBullet(btgCross3(d1, n)) : btgFrictionDir2(c, k);
        d2 = btgApplyBothAnisotropies(d2, rotA, rotB, pa, pb, mode);
        dirs->dir1[k] = d1;
        dirs->dir2[k] = d2;
        if (!solvable || (btgLane(c->normalMass, k) == 0.0f && (p.solverFlags & BTG_SOLVER_PROCESSING_THRESHOLD) != 0u))
            continue; /* no rows beyond the processing threshold */
        btgSetLane(&c->friction1Mass, k,
                   btgPointRowMassRelaxed(btgPointJacobian(d1, rA, rB, a, b), rA, rB, a, b, p.sor, 0.0f));
        if (p.twoFrictionDirections)
            btgSetLane(&c->friction2Mass, k,
                       btgPointRowMassRelaxed(btgPointJacobian(d2, rA, rB, a, b), rA, rB, a, b, p.sor, 0.0f));
    }
}

#endif
