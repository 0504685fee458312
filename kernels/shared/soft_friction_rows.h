/* soft_friction_rows.h — the soft step's friction rows of a contact point: its two tangents
 * bounded together by a cone (soft_rows.h includes it where its contact and rows are defined;
 * soft_quad_rows.h calls btgSoftFrictionPair with its fetched Jacobians). */
#ifndef BTG_SOFT_FRICTION_ROWS_H
#define BTG_SOFT_FRICTION_ROWS_H

/* Point k's two friction rows, driven to no slip, bounded together (a friction cone): row 1 and
 * then row 2 solved without a bound (Gauss-Seidel); where that pair lies within friction x the
 * point's normal impulse of this substep it stands, bit for bit the steps of rows clamped each on
 * its own. A point that slips beyond it takes both rows' step from the velocities before either,
 * on one mass for both (the harmonic mean of the rows': the step then points against the slip,
 * Coulomb's sliding friction), scaled onto that circle, row 1's step already applied corrected
 * (btgSoftFrictionSlip). Clamped each on its own (a pyramid), a box sliding across the tangents
 * took up to sqrt 2 times its friction and its slide bent toward a tangent: sent along the ground
 * at (1.2, 0, 1.6) m/s it stopped at (0.29, 0.51), 0.59 m from its start, where stock (its first
 * friction direction follows the slip) and the physics stop it 0.78 m along the throw. Scaled from
 * the Gauss-Seidel pair, a box landing while sliding kept 0.79 m/s of its 2 where stock keeps 0.71
 * (row 2's answer to the turn row 1 gave the box took a share of the cone); on each row's own mass,
 * a box sliding down a slope across the tangents slid 4% fast and 3 degrees off the fall line.
 * Both rows from the same velocities at every point (Jolt's order) threw the opt-in held pairs
 * (heldMassRatio 100: a 1,000:1 pair at 393 m/s). */
#define BTG_SOFT_FRICTION_FREE 3.0e38f /* a row's bound that never binds */
static BTG_ALWAYS_INLINE int btgSoftFrictionCone(float lim, float n1, float n2)
{
    return n1 * n1 + n2 * n2 > lim * lim;
}
/* A slipping point's impulses (c1, c2): from the old ones and the slip before either row (v1, v2)
 * on the rows' masses' harmonic mean, scaled onto the circle of radius lim where beyond it. */
static BTG_ALWAYS_INLINE void btgSoftFrictionSlip(float lim, float o1, float o2, float v1, float v2, float m1, float m2,
                                                  float* c1, float* c2)
{
    const float m = m2 != 0.0f ? 2.0f * m1 * m2 / (m1 + m2) : m1;
    const float t1 = o1 - m * v1, t2 = m2 != 0.0f ? o2 - m * v2 : o2;
    *c1 = t1;
    *c2 = t2;
    if (!btgSoftFrictionCone(lim, t1, t2)) return;
    const float scale = lim / btgSqrt(t1 * t1 + t2 * t2);
    *c1 = t1 * scale;
    *c2 = t2 * scale;
}
/* The pair of rows j1, j2 (masses m1, m2, impulses o1, o2 so far) within the cone of radius lim:
 * the new impulses in n1, n2, the bodies' velocities moved (btgSoftFrictionRows; the quads' rows
 * call it with their fetched Jacobians). */
static BTG_ALWAYS_INLINE void btgSoftFrictionPair(BtgJacobian j1, BtgJacobian j2, float m1, float m2, float o1, float o2,
                                                  float lim, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                                  BtgBodyVel* vb, float* n1Out, float* n2Out)
{
    /* the slip before row 1 moves the bodies (where the point slips) */
    const float slip1 = btgRowVelocity(j1, *va, *vb), slip2 = btgRowVelocity(j2, *va, *vb);
    float n1 = o1, n2 = o2;
    /* a row without mass (Bullet's one direction: no second row) keeps its impulse (zero) */
    if (m1 != 0.0f) {
        BtgSolverRow r = btgMakeSolverRow(j1, m1, 0.0f, -BTG_SOFT_FRICTION_FREE, BTG_SOFT_FRICTION_FREE, o1);
        btgRowSolve(&r, a, b, va, vb);
        n1 = r.impulse;
    }
    float d2 = 0.0f;
    if (m2 != 0.0f) {
        d2 = (0.0f - btgRowVelocity(j2, *va, *vb)) * m2 - o2 * 0.0f; /* btgRowSolve's unbounded step */
        n2 = o2 + d2;
    }
    if (m1 != 0.0f && btgSoftFrictionCone(lim, n1, n2)) {
        float c1, c2;
        btgSoftFrictionSlip(lim, o1, o2, slip1, slip2, m1, m2, &c1, &c2);
        btgRowApply(j1, a, b, va, vb, c1 - n1);
        d2 = c2 - o2;
        n1 = c1;
        n2 = c2;
    }
    if (m2 != 0.0f || d2 != 0.0f) btgRowApply(j2, a, b, va, vb, d2);
    *n1Out = n1;
    *n2Out = n2;
}
static BTG_ALWAYS_INLINE void btgSoftFrictionRows(BtgSoftContact* s, int k, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                                  BtgBodyVel* vb, const BtgFrictionDirs* dirs)
{
    if (btgLane(s->normalMass, k) == 0.0f) return;
    const float o1 = btgLane(s->tangent1Impulse, k), o2 = btgLane(s->tangent2Impulse, k);
    const float m1 = btgLane(s->tangent1Mass, k), m2 = btgLane(s->tangent2Mass, k);
    const BtgFloat4 rA = btgSoftArmA(s, k), rB = btgSoftArmB(s, k);
    const BtgJacobian j1 = btgPointJacobian(btgSoftDir1(s, dirs, k), rA, rB, a, b);
    const BtgJacobian j2 = btgPointJacobian(btgSoftDir2(s, dirs, k), rA, rB, a, b);
    float n1, n2;
    btgSoftFrictionPair(j1, j2, m1, m2, o1, o2, s->friction * btgLane(s->normalImpulse, k), a, b, va, vb, &n1, &n2);
    btgSetLane(&s->tangent1Impulse, k, n1);
    btgSetLane(&s->tangent2Impulse, k, n2);
    btgSetLane(&s->total1, k, btgLane(s->total1, k) + (n1 - o1));
    btgSetLane(&s->total2, k, btgLane(s->total2, k) + (n2 - o2));
}

#endif
