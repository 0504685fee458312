/* contact_rows.h — the per-point math of btSequentialImpulseConstraintSolver, shared by the
 * contact kernels (contact_cache, prepare_contacts, solve_constraints) and their CPU references:
 * contact geometry and warm-start matching, Jacobian rows and effective masses
 * (setupContactConstraint), the restitution curve, and the clamped row solve
 * (resolveSingleConstraintRow*, resolveSplitPenetrationImpulse), all on private copies. */
#ifndef BTG_CONTACT_ROWS_H
#define BTG_CONTACT_ROWS_H
#include "counters.h"
#include "prelude.h"
#include "types.h"
#include "math.h"

/* BTG_WARMSTART_FRICTION (friction impulses kept across steps) is in types.h. */
#define BTG_MAX_FRICTION 10.0f       /* btManifoldResult::calculateCombinedFriction's clamp */
#define BTG_NORMAL_UPPER_LIMIT 1e10f /* setupContactConstraint's m_upperLimit */

/* A body as the solver sees it (btSolverBody): infinite mass unless dynamic. */
typedef struct {
    BtgMat3 invI;          /* world inverse inertia, zero unless dynamic */
    BtgFloat4 invMassLin;  /* invMass * linearFactor (btSolverBody::m_invMass) */
    BtgFloat4 linFactor;
    BtgFloat4 angFactor;
    float invMass;         /* 1/kg, zero unless dynamic */
    int dynamic;
    int moving;            /* dynamic or kinematic: its velocity enters the rows */
    int pad0;
} BtgSolverBody;

/* Linear and angular velocity of one body (or its push/turn velocity for split impulse). */
typedef struct {
    BtgFloat4 lin;
    BtgFloat4 ang;
} BtgBodyVel;

/* One Jacobian row along dir: Bullet's m_contactNormal1/2, m_relpos1/2CrossNormal and
 * m_angularComponentA/B (the B side is stored already negated, as Bullet does). */
typedef struct {
    BtgFloat4 dir;
    BtgFloat4 crossA; /* rA x dir */
    BtgFloat4 crossB; /* -(rB x dir) */
    BtgFloat4 angA;   /* invI_A crossA * angularFactor_A */
    BtgFloat4 angB;   /* invI_B crossB * angularFactor_B */
} BtgRow;

static inline float btgLane(BtgFloat4 v, int k)
{
    return k == 0 ? v.x : (k == 1 ? v.y : (k == 2 ? v.z : v.w));
}
static inline void btgSetLane(BtgFloat4* v, int k, float x)
{
    if (k == 0) (*v).x = x;
    else if (k == 1) (*v).y = x;
    else if (k == 2) (*v).z = x;
    else (*v).w = x;
}

/* Kinematic bodies take part with their velocity but infinite mass (Bullet gives them a solver
 * body of their own); excluded and static rows are Bullet's shared fixed body. */
static inline int btgIsSolverDynamic(uint flags)
{
    /* A sleeping body holds still like a static one until the activation stage wakes it. */
    return (flags & BTG_BODY_DYNAMIC) != 0u &&
           (flags & (BTG_BODY_KINEMATIC | BTG_BODY_STATIC | BTG_BODY_EXCLUDED | BTG_BODY_SLEEPING)) == 0u;
}
static inline int btgIsSolverMoving(uint flags)
{
    return btgIsSolverDynamic(flags) ||
           ((flags & BTG_BODY_KINEMATIC) != 0u && (flags & BTG_BODY_EXCLUDED) == 0u);
}
/* convertContact skips pairs of two infinite masses; the dispatcher skips no-response bodies. */
static inline int btgContactSolvable(uint flagsA, uint flagsB)
{
    if (((flagsA | flagsB) & BTG_BODY_NO_RESPONSE) != 0u) return 0;
    return btgIsSolverDynamic(flagsA) || btgIsSolverDynamic(flagsB);
}

static inline BtgSolverBody btgMakeSolverBody(BtgBodyProps p, BtgFloat4 i0, BtgFloat4 i1, BtgFloat4 i2)
{
    BtgSolverBody b;
    b.dynamic = btgIsSolverDynamic(p.flags);
    b.moving = btgIsSolverMoving(p.flags);
    b.pad0 = 0;
    b.linFactor = btgXyz(p.linearFactor);
    b.angFactor = btgXyz(p.angularFactor);
    if (b.dynamic) {
        b.invMass = p.invMass;
        b.invI.r0 = btgXyz(i0);
        b.invI.r1 = btgXyz(i1);
        b.invI.r2 = btgXyz(i2);
    } else {
        b.invMass = 0.0f;
        b.invI.r0 = btgZero4();
        b.invI.r1 = btgZero4();
        b.invI.r2 = btgZero4();
    }
    b.invMassLin = b.linFactor * b.invMass;
    return b;
}
/* Velocity a body contributes to a row: zero for the fixed body. */
static inline BtgBodyVel btgMakeBodyVel(int moving, BtgFloat4 lin, BtgFloat4 ang)
{
    BtgBodyVel v;
    v.lin = moving ? btgXyz(lin) : btgZero4();
    v.ang = moving ? btgXyz(ang) : btgZero4();
    return v;
}

/* ---- contact cache: geometry and warm start ---- */

/* A contact's geometry from its manifold: rA from the point on A, rB from the point on B (as
 * Bullet's rel_pos1/rel_pos2), rA.w = signed distance (prepare reads it, then writes the target
 * there). Impulses start at zero; the caller warm-starts them. */
static inline BtgContact btgContactFromManifold(BtgManifold m, BtgFloat4 posA, BtgFloat4 posB)
{
    BtgContact c;
    c.normal = btgXyz(m.normal);
    c.t1 = btgZero4();
    c.t2 = btgZero4();
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        c.rA[k] = btgZero4();
        c.rB[k] = btgZero4();
        if (k < m.numPoints) {
            BtgFloat4 pb = btgXyz(m.pointB[k]);
            float dist = m.pointB[k].w;
            BtgFloat4 pa = pb + c.normal * dist;
            c.rA[k] = pa - btgXyz(posA);
            c.rA[k].w = dist;
            c.rB[k] = pb - btgXyz(posB);
        }
    }
    c.normalImpulse = btgZero4();
    c.pushImpulse = btgZero4();
    c.friction1Impulse = btgZero4();
    c.friction2Impulse = btgZero4();
    c.normalMass = btgZero4();
    c.friction1Mass = btgZero4();
    c.friction2Mass = btgZero4();
    c.bodyA = m.bodyA;
    c.bodyB = m.bodyB;
    c.numPoints = m.numPoints;
    c.color = -1;
    return c;
}

/* The cache key of a point: the point on A in A's body frame (rA rotated back), w = 0. The
 * same value whether taken when the contact is built or after the solve, as long as A has not
 * been integrated in between (rA's xyz and A's rotation are unchanged until then). */
static inline BtgFloat4 btgContactKey(BtgMat3 rotA, BtgFloat4 rA)
{
    return btgMat3TMulVec(rotA, btgXyz(rA));
}

/* A solved contact as the cache keeps it; rotA is A's rotation when the contact was built. */
static inline BtgCachedContact btgCachedContactFrom(BtgContact c, BtgFloat4 rotA)
{
    BtgCachedContact e;
    BtgMat3 ra = btgQuatToMat3(rotA);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        e.point[k] = btgZero4();
        if (k < c.numPoints) {
            e.point[k] = btgContactKey(ra, c.rA[k]);
            e.point[k].w = btgLane(c.normalImpulse, k);
        }
    }
#if BTG_WARMSTART_FRICTION
    e.friction1Impulse = c.friction1Impulse;
    e.friction2Impulse = c.friction2Impulse;
#endif
    e.bodyA = c.bodyA;
    e.bodyB = c.bodyB;
    e.numPoints = c.numPoints;
    e.pad0 = 0;
    return e;
}

/* Contacts are in pair order, i.e. sorted by (min body, max body): the search key. */
static inline int btgPairKeyLess(int a0, int b0, int a1, int b1)
{
    return a0 < a1 || (a0 == a1 && b0 < b1);
}
/* Index of the cached contact of the same body pair (same orientation), or -1. */
static inline int btgFindPrevContact(BTG_CONST_GLOBAL BtgCachedContact* prev, int count, int bodyA, int bodyB)
{
    int ka = bodyA < bodyB ? bodyA : bodyB, kb = bodyA < bodyB ? bodyB : bodyA;
    int lo = 0, hi = count;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        int ma = prev[mid].bodyA, mb = prev[mid].bodyB;
        int pa = ma < mb ? ma : mb, pb = ma < mb ? mb : ma;
        if (btgPairKeyLess(pa, pb, ka, kb)) lo = mid + 1;
        else hi = mid;
    }
    if (lo < count && prev[lo].bodyA == bodyA && prev[lo].bodyB == bodyB) return lo;
    return -1;
}
/* btPersistentManifold::getCacheEntry: each new point takes the old point nearest in A's frame,
 * strictly within the breaking threshold; its impulses start scaled by the warm-start factor.
 * rotA: A's rotation now (the new points' keys). */
static inline void btgWarmStartFrom(BtgContact* c, BtgFloat4 rotA, BtgCachedContact old, float threshold, float factor)
{
    BtgMat3 ra = btgQuatToMat3(rotA);
    for (int k = 0; k < c->numPoints; ++k) {
        BtgFloat4 key = btgContactKey(ra, c->rA[k]);
        float best = threshold * threshold;
        int found = -1;
        for (int j = 0; j < old.numPoints; ++j) {
            BtgFloat4 d = key - btgXyz(old.point[j]);
            float d2 = btgDot3(d, d);
            if (d2 < best) {
                best = d2;
                found = j;
            }
        }
        if (found < 0) continue;
        btgSetLane(&c->normalImpulse, k, old.point[found].w * factor);
#if BTG_WARMSTART_FRICTION
        btgSetLane(&c->friction1Impulse, k, btgLane(old.friction1Impulse, found) * factor);
        btgSetLane(&c->friction2Impulse, k, btgLane(old.friction2Impulse, found) * factor);
#endif
    }
}

/* ---- rows and effective masses (setupContactConstraint / setupFrictionConstraint) ---- */

static inline BtgRow btgMakeRow(BtgFloat4 dir, BtgFloat4 rA, BtgFloat4 rB, BtgSolverBody a, BtgSolverBody b)
{
    BtgRow r;
    r.dir = btgXyz(dir);
    r.crossA = btgCross3(rA, r.dir);
    r.crossB = -btgCross3(rB, r.dir);
    r.angA = btgMat3MulVec(a.invI, r.crossA) * a.angFactor;
    r.angB = btgMat3MulVec(b.invI, r.crossB) * b.angFactor;
    return r;
}
/* m_jacDiagABInv with relaxation 1 and cfm 0; 0 marks a row with no mobility (never solved). */
static inline float btgRowMass(BtgRow r, BtgFloat4 rA, BtgFloat4 rB, BtgSolverBody a, BtgSolverBody b)
{
    float denomA = a.invMass + btgDot3(r.dir, btgCross3(r.angA, rA));
    float denomB = b.invMass + btgDot3(r.dir, btgCross3(-r.angB, rB));
    float denom = denomA + denomB;
    return denom > 0.0f ? 1.0f / denom : 0.0f;
}
/* Relative velocity along the row (vel1Dotn + vel2Dotn). */
static inline float btgRowVelocity(BtgRow r, BtgBodyVel va, BtgBodyVel vb)
{
    float v1 = btgDot3(r.dir, va.lin) + btgDot3(r.crossA, va.ang);
    float v2 = btgDot3(-r.dir, vb.lin) + btgDot3(r.crossB, vb.ang);
    return v1 + v2;
}
/* btSolverBody::internalApplyImpulse on both bodies: the linear and angular factors enter
 * twice (once in the component, once in the apply), as in Bullet. */
static inline void btgRowApply(BtgRow r, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb, float impulse)
{
    va->lin = va->lin + (r.dir * a.invMassLin) * impulse * a.linFactor;
    va->ang = va->ang + r.angA * (a.angFactor * impulse);
    vb->lin = vb->lin + (-r.dir * b.invMassLin) * impulse * b.linFactor;
    vb->ang = vb->ang + r.angB * (b.angFactor * impulse);
}
/* One projected Gauss-Seidel step on a row: returns the impulse to apply, updates the sum. */
static inline float btgSolveRow(float target, float velocity, float mass, float* accumulated, float lo, float hi)
{
    float delta = (target - velocity) * mass;
    float sum = *accumulated + delta;
    if (sum < lo) {
        delta = lo - *accumulated;
        *accumulated = lo;
    } else if (sum > hi) {
        delta = hi - *accumulated;
        *accumulated = hi;
    } else {
        *accumulated = sum;
    }
    return delta;
}

/* btSequentialImpulseConstraintSolver's restitutionCurve, clamped at zero as setup does. */
static inline float btgRestitution(float relVel, float restitution, float threshold)
{
    if (btgAbs(relVel) < threshold) return 0.0f;
    float r = restitution * -relVel;
    return r > 0.0f ? r : 0.0f;
}
/* Compared as Bullet compares (no fmin/fmax, which turn a NaN into a bound): a NaN stays NaN,
 * so it can never pose as a legal friction. Bodies with a non-finite friction are kept out on
 * the host before they get here. */
static inline float btgCombinedFriction(float fa, float fb)
{
    float f = fa * fb;
    if (f < -BTG_MAX_FRICTION) f = -BTG_MAX_FRICTION;
    if (f > BTG_MAX_FRICTION) f = BTG_MAX_FRICTION;
    return f;
}

/* Solver rows of one contact. a0/b0: velocities before this substep's forces (restitution).
 * Targets are velocities: the solver computes (target - J v) * mass against the live velocity,
 * which equals Bullet's rhs - J dv * mass with rhs = (target - J v_setup) * mass. */
static inline void btgPrepareContact(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel a0, BtgBodyVel b0,
                                     float friction, float restitution, int solvable, BtgStepParams p)
{
    BtgFloat4 n = btgXyz(c->normal);
    BtgFloat4 t1, t2;
    btgPlaneSpace(n, &t1, &t2);
    /* Bullet's default friction: one row along the slip velocity (btPlaneSpace when there is
     * none); a second, perpendicular row only with SOLVER_USE_2_FRICTION_DIRECTIONS. Bullet
     * takes the slip per point; here one direction serves the manifold (its mean slip). */
    BtgFloat4 slip = btgZero4();
    for (int k = 0; k < c->numPoints; ++k) {
        BtgFloat4 rA = btgXyz(c->rA[k]), rB = btgXyz(c->rB[k]);
        BtgFloat4 v = (a0.lin + btgCross3(a0.ang, rA)) - (b0.lin + btgCross3(b0.ang, rB));
        slip += v - n * btgDot3(v, n);
    }
    float slip2 = btgDot3(slip, slip);
    if (slip2 > 1.1920929e-07f * (float)(c->numPoints * c->numPoints)) {
        t1 = slip * (1.0f / btgSqrt(slip2));
        t2 = btgNormalize3(btgCross3(t1, n));
    }
    c->normal = n;
    c->normal.w = friction;
    c->t1 = t1;
    c->t1.w = restitution;
    c->t2 = t2;
    c->normalMass = btgZero4();
    c->friction1Mass = btgZero4();
    c->friction2Mass = btgZero4();
    c->pushImpulse = btgZero4();
    float invDt = 1.0f / p.dt;
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        BtgFloat4 rA = btgXyz(c->rA[k]);
        BtgFloat4 rB = btgXyz(c->rB[k]);
        float target = 0.0f, push = 0.0f;
        if (k < c->numPoints && solvable) {
            btgSetLane(&c->normalMass, k, btgRowMass(btgMakeRow(n, rA, rB, a, b), rA, rB, a, b));
            btgSetLane(&c->friction1Mass, k, btgRowMass(btgMakeRow(t1, rA, rB, a, b), rA, rB, a, b));
            if (p.twoFrictionDirections)
                btgSetLane(&c->friction2Mass, k, btgRowMass(btgMakeRow(t2, rA, rB, a, b), rA, rB, a, b));
            BtgFloat4 velA = a0.lin + btgCross3(a0.ang, rA);
            BtgFloat4 velB = b0.lin + btgCross3(b0.ang, rB);
            float penetration = c->rA[k].w; /* the distance, until the target replaces it below */
            target = btgRestitution(btgDot3(n, velA - velB), restitution, p.restitutionThreshold);
            float positional = 0.0f;
            if (penetration > 0.0f) target -= penetration * invDt; /* speculative: reach, not pass */
            else positional = -penetration * p.erp2 * invDt;       /* 3.24 uses m_erp2 for contacts */
            if (!p.splitImpulse || penetration > p.splitPenetrationThreshold) target += positional;
            else push = positional;
        } else {
            btgSetLane(&c->normalImpulse, k, 0.0f);
            btgSetLane(&c->friction1Impulse, k, 0.0f);
            btgSetLane(&c->friction2Impulse, k, 0.0f);
        }
        c->rA[k].w = target;
        c->rB[k].w = push;
    }
}

/* ---- solve (one contact, bodies loaded by the caller) ---- */

/* The setup-time warm start: accumulated impulses applied once before the iterations. */
static inline void btgContactWarmStart(const BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb)
{
    for (int k = 0; k < c->numPoints; ++k) {
        BtgFloat4 rA = btgXyz(c->rA[k]), rB = btgXyz(c->rB[k]);
        if (btgLane(c->normalMass, k) == 0.0f) continue;
        btgRowApply(btgMakeRow(c->normal, rA, rB, a, b), a, b, va, vb, btgLane(c->normalImpulse, k));
        if (btgLane(c->friction1Mass, k) != 0.0f)
            btgRowApply(btgMakeRow(c->t1, rA, rB, a, b), a, b, va, vb, btgLane(c->friction1Impulse, k));
        if (btgLane(c->friction2Mass, k) != 0.0f)
            btgRowApply(btgMakeRow(c->t2, rA, rB, a, b), a, b, va, vb, btgLane(c->friction2Impulse, k));
    }
}
/* One velocity iteration: all normal rows, then the friction rows (t1, t2 per point) whose
 * normal impulse is positive, clamped to friction * normal impulse (solveSingleIteration). */
static inline void btgContactSolveVelocity(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb)
{
    for (int k = 0; k < c->numPoints; ++k) {
        float m = btgLane(c->normalMass, k);
        if (m == 0.0f) continue;
        BtgFloat4 rA = btgXyz(c->rA[k]), rB = btgXyz(c->rB[k]);
        BtgRow r = btgMakeRow(c->normal, rA, rB, a, b);
        float acc = btgLane(c->normalImpulse, k);
        float d = btgSolveRow(c->rA[k].w, btgRowVelocity(r, *va, *vb), m, &acc, 0.0f, BTG_NORMAL_UPPER_LIMIT);
        btgSetLane(&c->normalImpulse, k, acc);
        btgRowApply(r, a, b, va, vb, d);
    }
    float friction = c->normal.w;
    for (int k = 0; k < c->numPoints; ++k) {
        float total = btgLane(c->normalImpulse, k);
        if (!(total > 0.0f)) continue;
        float lim = friction * total;
        BtgFloat4 rA = btgXyz(c->rA[k]), rB = btgXyz(c->rB[k]);
        float m1 = btgLane(c->friction1Mass, k);
        if (m1 != 0.0f) {
            BtgRow r = btgMakeRow(c->t1, rA, rB, a, b);
            float acc = btgLane(c->friction1Impulse, k);
            float d = btgSolveRow(0.0f, btgRowVelocity(r, *va, *vb), m1, &acc, -lim, lim);
            btgSetLane(&c->friction1Impulse, k, acc);
            btgRowApply(r, a, b, va, vb, d);
        }
        float m2 = btgLane(c->friction2Mass, k);
        if (m2 != 0.0f) {
            BtgRow r = btgMakeRow(c->t2, rA, rB, a, b);
            float acc = btgLane(c->friction2Impulse, k);
            float d = btgSolveRow(0.0f, btgRowVelocity(r, *va, *vb), m2, &acc, -lim, lim);
            btgSetLane(&c->friction2Impulse, k, acc);
            btgRowApply(r, a, b, va, vb, d);
        }
    }
}
/* One split-impulse iteration (resolveSplitPenetrationImpulse) on push/turn velocities. */
static inline void btgContactSolvePush(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* pa, BtgBodyVel* pb)
{
    for (int k = 0; k < c->numPoints; ++k) {
        float m = btgLane(c->normalMass, k);
        float target = c->rB[k].w;
        if (m == 0.0f || target == 0.0f) continue;
        BtgFloat4 rA = btgXyz(c->rA[k]), rB = btgXyz(c->rB[k]);
        BtgRow r = btgMakeRow(c->normal, rA, rB, a, b);
        float acc = btgLane(c->pushImpulse, k);
        float d = btgSolveRow(target, btgRowVelocity(r, *pa, *pb), m, &acc, 0.0f, BTG_NORMAL_UPPER_LIMIT);
        btgSetLane(&c->pushImpulse, k, acc);
        btgRowApply(r, a, b, pa, pb, d);
    }
}

#endif
