/* contact_rows.h — the contacts' part of btSequentialImpulseConstraintSolver, shared by the
 * contact kernels (contact_cache, prepare_contacts, solve_constraints, solve_jacobi) and their
 * CPU references: contact geometry and warm-start matching, the rows of a manifold
 * (setupContactConstraint / setupFrictionConstraint, the restitution curve, m_sor, cfm and soft
 * contacts), and their solve as solver_rows.h rows (resolveSingleConstraintRow*,
 * resolveSplitPenetrationImpulse), all on private copies. Rolling and anisotropic friction:
 * material_rows.h. */
#ifndef BTG_CONTACT_ROWS_H
#define BTG_CONTACT_ROWS_H
#include "counters.h"
#include "prelude.h"
#include "types.h"
#include "math.h"
#include "solver_rows.h"
#include "cache_search.h"

#define BTG_MAX_FRICTION 10.0f       /* btManifoldResult::calculateCombinedFriction's clamp */
#define BTG_NORMAL_UPPER_LIMIT 1e10f /* setupContactConstraint's m_upperLimit */
#define BTG_SIMD_EPSILON 1.1920929e-07f /* Bullet's SIMD_EPSILON (FLT_EPSILON) */

/* Which optional row fields the solver passes read (their `rows` argument): bit 0 is the
 * second friction rows (SOLVER_USE_2_FRICTION_DIRECTIONS), so a caller passing 0 or 1 there
 * reads no more than it always did. */
#define BTG_ROWS_TWO_FRICTION 1
#define BTG_ROWS_CFM 2     /* normalCfm: m_globalCfm or contact stiffness and damping */
#define BTG_ROWS_ROLLING 4 /* BtgRollingContact rows (rolling and spinning friction) */
#define BTG_ROWS_ANISOTROPIC 8 /* friction directions from BtgFrictionDirs (anisotropic friction) */
#define BTG_ROWS_ANCHORS 16    /* friction rows' positional targets from BtgFrictionAnchor (friction anchors) */
#define BTG_ROWS_INTERLEAVE 32 /* a velocity iteration is one sweep, each point's normal then friction rows
                                  (BTG_PASS_VELOCITY), not a normal sweep and a friction sweep */

/* Floats a contact takes in a CPU device's wide sweeps' block of lanes, per lane (pgs_wide.h's
 * BTG_PW_FIELDS: 10 of the contact's, 15 per point). */
#define BTG_PGS_WIDE_FIELDS 70

/* The optional rows a step's solve reads. */
static inline int btgRowFlags(BtgStepParams p)
{
    int rows = p.twoFrictionDirections ? BTG_ROWS_TWO_FRICTION : 0;
    if (p.globalCfm != 0.0f || (p.solverFlags & BTG_SOLVER_SOFT_CONTACTS) != 0u) rows |= BTG_ROWS_CFM;
    if ((p.solverFlags & BTG_SOLVER_ROLLING_FRICTION) != 0u) rows |= BTG_ROWS_ROLLING;
    if ((p.solverFlags & BTG_SOLVER_ANISOTROPIC_FRICTION) != 0u) rows |= BTG_ROWS_ANISOTROPIC;
    if ((p.solverFlags & BTG_SOLVER_FRICTION_ANCHORS) != 0u) rows |= BTG_ROWS_ANCHORS;
    if ((p.solverFlags & BTG_SOLVER_INTERLEAVE) != 0u) rows |= BTG_ROWS_INTERLEAVE;
    return rows;
}

/* What btManifoldResult::addContactPoint gives a pair's points from its two bodies (Bullet's
 * gCalculateCombined*Callback defaults), and what setupContactConstraint makes of contact
 * stiffness and damping. */
typedef struct {
    float friction;
    float restitution;
    float rollingFriction;
    float spinningFriction;
    int stiffnessDamping;  /* either body has CF_HAS_CONTACT_STIFFNESS_DAMPING */
    float stiffness;       /* combined: 1 / (1/k_A + 1/k_B), N/m */
    float damping;         /* combined: d_A + d_B, N s/m */
    float processingThreshold; /* m: the manifold's contact processing threshold (btgProcessingThreshold),
                                  BTG_NO_PROCESSING_THRESHOLD without BTG_SOLVER_PROCESSING_THRESHOLD */
} BtgPairMaterial;

/* A manifold's contact processing threshold is the smaller of its bodies' (getNewManifold);
 * without one on any body no point is compared with it (BTG_NO_PROCESSING_THRESHOLD, which
 * every finite distance is below: the rows are what they were before the setting existed). */
#define BTG_NO_PROCESSING_THRESHOLD 1e18f /* Bullet's BT_LARGE_FLOAT, its default */
static inline float btgProcessingThreshold(BtgBodyProps a, BtgBodyProps b)
{
    return a.contactProcessingThreshold < b.contactProcessingThreshold ? a.contactProcessingThreshold
                                                                       : b.contactProcessingThreshold;
}
/* convertContacts solves a point only while getDistance() <= the manifold's threshold; the
 * point stays in the manifold (callbacks and the app see it) with the impulses it had. Written
 * as "not farther" so that a NaN distance is taken as it was before the setting existed. */
static inline int btgPointProcessed(float distance, float threshold)
{
    return !(distance > threshold);
}

/* A contact's two bodies as the kernels that prepare its rows read them: their rows, solver
 * bodies, and velocities before (0: restitution) and after (1: friction directions) this
 * substep's forces. */
typedef struct {
    BtgBodyProps pa, pb;
    BtgSolverBody a, b;
    BtgBodyVel a0, b0, a1, b1;
} BtgContactBodies;

static inline BtgContactBodies btgLoadContactBodies(BtgContact c, BTG_CONST_GLOBAL BtgBodyProps* props,
                                                    BTG_CONST_GLOBAL BtgFloat4* invInertiaWorld,
                                                    BTG_CONST_GLOBAL BtgFloat4* linVel0, BTG_CONST_GLOBAL BtgFloat4* angVel0,
                                                    BTG_CONST_GLOBAL BtgFloat4* linVel, BTG_CONST_GLOBAL BtgFloat4* angVel)
{
    BtgContactBodies t;
    t.pa = props[c.bodyA];
    t.pb = props[c.bodyB];
    t.a = btgMakeSolverBody(t.pa, invInertiaWorld[3 * c.bodyA], invInertiaWorld[3 * c.bodyA + 1],
                            invInertiaWorld[3 * c.bodyA + 2]);
    t.b = btgMakeSolverBody(t.pb, invInertiaWorld[3 * c.bodyB], invInertiaWorld[3 * c.bodyB + 1],
                            invInertiaWorld[3 * c.bodyB + 2]);
    t.a0 = btgMakeBodyVel(t.a.moving, linVel0[c.bodyA], angVel0[c.bodyA]);
    t.b0 = btgMakeBodyVel(t.b.moving, linVel0[c.bodyB], angVel0[c.bodyB]);
    t.a1 = btgMakeBodyVel(t.a.moving, linVel[c.bodyA], angVel[c.bodyA]);
    t.b1 = btgMakeBodyVel(t.b.moving, linVel[c.bodyB], angVel[c.bodyB]);
    return t;
}

/* convertContact skips pairs of two infinite masses; the dispatcher skips no-response bodies. */
static inline int btgContactSolvable(uint flagsA, uint flagsB)
{
    if (((flagsA | flagsB) & BTG_BODY_NO_RESPONSE) != 0u) return 0;
    return btgIsSolverDynamic(flagsA) || btgIsSolverDynamic(flagsB);
}

/* ---- contact cache: geometry and warm start ---- */

/* A contact's geometry from its manifold: rA from the point on A, rB from the point on B (as
 * Bullet's rel_pos1/rel_pos2), and each point's signed distance, which prepare turns into the
 * targets. The contact's normal is its first point's (a manifold's points share one today).
 * Impulses start at zero; the caller warm-starts them. */
static inline BtgContact btgContactFromManifold(BtgManifold m, BtgFloat4 posA, BtgFloat4 posB)
{
    BtgContact c;
    c.bodyA = m.bodyA;
    c.bodyB = m.bodyB;
    c.numPoints = m.numPoints;
    c.friction = 0.0f;
    c.normal = m.numPoints > 0 ? btgMake4(m.points[0].nx, m.points[0].ny, m.points[0].nz, 0.0f)
                               : btgMake4(0.0f, 1.0f, 0.0f, 0.0f);
    c.separation = btgZero4();
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        c.rA[k] = btgZero4();
        c.rB[k] = btgZero4();
        if (k < m.numPoints) {
            BtgManifoldPoint p = m.points[k];
            BtgFloat4 pb = btgMake4(p.px, p.py, p.pz, 0.0f);
            BtgFloat4 pa = pb + btgMake4(p.nx, p.ny, p.nz, 0.0f) * p.distance;
            c.rA[k] = pa - btgXyz(posA);
            c.rB[k] = pb - btgXyz(posB);
            btgSetLane(&c.separation, k, p.distance);
        }
    }
    c.normalMass = btgZero4();
    c.normalTarget = btgZero4();
    c.normalImpulse = btgZero4();
    c.tangent1 = btgZero4();
    c.tangent2 = btgZero4();
    c.frictionCos = btgZero4();
    c.frictionSin = btgZero4();
    c.friction1Mass = btgZero4();
    c.friction1Impulse = btgZero4();
    c.friction2Mass = btgZero4();
    c.friction2Impulse = btgZero4();
    c.pushTarget = btgZero4();
    c.pushImpulse = btgZero4();
    c.normalCfm = btgZero4();
    return c;
}

/* The cache key of a point: the point on A in A's body frame (rA rotated back), w = 0. The
 * same value whether taken when the contact is built or after the solve, as long as A has not
 * been integrated in between (rA's xyz and A's rotation are unchanged until then). */
static inline BtgFloat4 btgContactKey(BtgMat3 rotA, BtgFloat4 rA)
{
    return btgMat3TMulVec(rotA, btgXyz(rA));
}

/* A solved contact as the cache keeps it: its keys and impulses, and the identity of its
 * manifold *m (sub-shape keys) and points (feature ids), read field by field (a pointer: the
 * kernel loads 32 of the manifold's 160 bytes). rotA is A's rotation when the contact was built. */
static inline BtgCachedContact btgCachedContactFrom(BtgContact c, BtgFloat4 rotA, BTG_CONST_GLOBAL BtgManifold* m)
{
    BtgCachedContact e;
    BtgMat3 ra = btgQuatToMat3(rotA);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        e.point[k] = btgZero4();
        e.featureId[k] = BTG_FEATURE_UNKNOWN;
        if (k < c.numPoints) {
            e.point[k] = btgContactKey(ra, c.rA[k]);
            e.point[k].w = btgLane(c.normalImpulse, k);
            e.featureId[k] = m->points[k].featureId;
        }
    }
    e.friction1Impulse = c.friction1Impulse;
    e.friction2Impulse = c.friction2Impulse;
    e.partIdA = m->partIdA;
    e.indexA = m->indexA;
    e.partIdB = m->partIdB;
    e.indexB = m->indexB;
    e.bodyA = c.bodyA;
    e.bodyB = c.bodyB;
    e.numPoints = c.numPoints;
    e.pad0 = 0;
    return e;
}

/* Which old point of the cached manifold `old` each new point of `m` continues. First by
 * identity (box3d's featureId): the old point with the same feature id, each old point taken
 * so by one new point only. Bullet's breaking threshold still bounds every match (a point that
 * moved further in A's frame starts cold, as btPersistentManifold::getCacheEntry has it), so
 * identity decides only among old points close enough: the nearest may be another feature's
 * (clipping puts a face corner and an edge crossing a fraction of a millimetre apart), and
 * distance alone would hand one old impulse to both. A point no old point shares its id with
 * falls back to getCacheEntry: the old point nearest in A's frame, strictly within the
 * threshold, among those no identity match took. keys: the new points' keys (btgContactKey).
 * match[k]: the old point, or -1. */
static inline void btgMatchPoints(BtgManifold m, const BtgFloat4* keys, BtgCachedContact old, int* match)
{
    const float threshold = m.breakingThreshold;
    uint claimed = 0u;
    for (int k = 0; k < m.numPoints; ++k) {
        match[k] = -1;
        uint id = m.points[k].featureId;
        if (id == BTG_FEATURE_UNKNOWN) continue;
        for (int j = 0; j < old.numPoints && match[k] < 0; ++j) {
            if ((claimed >> j) & 1u || old.featureId[j] != id) continue;
            BtgFloat4 d = keys[k] - btgXyz(old.point[j]);
            if (!(btgDot3(d, d) < threshold * threshold)) continue;
            match[k] = j;
            claimed |= 1u << j;
        }
    }
    for (int k = 0; k < m.numPoints; ++k) {
        if (match[k] >= 0) continue;
        float best = threshold * threshold;
        for (int j = 0; j < old.numPoints; ++j) {
            if ((claimed >> j) & 1u) continue;
            BtgFloat4 d = keys[k] - btgXyz(old.point[j]);
            float d2 = btgDot3(d, d);
            if (d2 < best) {
                best = d2;
                match[k] = j;
            }
        }
    }
}

/* The warm start: each new point's impulses start from those of the old point it continues
 * (btgMatchPoints), scaled by the warm-start factor but for the points beyond the manifold's
 * processing threshold; the friction impulses too with `friction` (BTG_SOLVER_WARM_FRICTION: the
 * soft step), else they start at zero as Bullet 3.24's. rotA: A's rotation now (the new points'
 * keys). */
static inline void btgWarmStartFrom(BtgContact* c, BtgFloat4 rotA, BtgManifold m, BtgCachedContact old, float factor,
                                    float processingThreshold, int friction)
{
    BtgMat3 ra = btgQuatToMat3(rotA);
    BtgFloat4 keys[BTG_MAX_POINTS];
    int match[BTG_MAX_POINTS];
    for (int k = 0; k < BTG_MAX_POINTS; ++k) keys[k] = k < c->numPoints ? btgContactKey(ra, c->rA[k]) : btgZero4();
    btgMatchPoints(m, keys, old, match);
    for (int k = 0; k < c->numPoints; ++k) {
        int found = match[k];
        if (found < 0) continue;
        /* a point beyond the processing threshold is not converted: its btManifoldPoint keeps
         * the impulses unscaled (stock warm-starts from them again once it is solved) */
        const float f = btgPointProcessed(btgLane(c->separation, k), processingThreshold) ? factor : 1.0f;
        btgSetLane(&c->normalImpulse, k, old.point[found].w * f);
        if (friction) {
            btgSetLane(&c->friction1Impulse, k, btgLane(old.friction1Impulse, found) * f);
            btgSetLane(&c->friction2Impulse, k, btgLane(old.friction2Impulse, found) * f);
        }
    }
}

/* ---- a manifold's rows (setupContactConstraint / setupFrictionConstraint) ---- */

/* A contact's edge of the constraint graph. */
static inline BtgEdge btgContactEdge(BtgContact c)
{
    BtgEdge e;
    e.bodyA = c.bodyA;
    e.bodyB = c.bodyB;
    return e;
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

static inline float btgClampFriction(float f)
{
    if (f < -BTG_MAX_FRICTION) f = -BTG_MAX_FRICTION;
    if (f > BTG_MAX_FRICTION) f = BTG_MAX_FRICTION;
    return f;
}
static inline BtgPairMaterial btgPairMaterial(BtgBodyProps a, BtgBodyProps b)
{
    BtgPairMaterial m;
    m.friction = btgCombinedFriction(a.friction, b.friction);
    m.restitution = a.restitution * b.restitution;
    m.rollingFriction = btgClampFriction(a.rollingFriction * b.friction + b.rollingFriction * a.friction);
    m.spinningFriction = btgClampFriction(a.spinningFriction * b.friction + b.spinningFriction * a.friction);
    m.stiffnessDamping = ((a.flags | b.flags) & BTG_BODY_STIFFNESS_DAMPING) != 0u;
    m.stiffness = 1.0f / (1.0f / a.contactStiffness + 1.0f / b.contactStiffness);
    m.damping = a.contactDamping + b.contactDamping;
    m.processingThreshold = btgProcessingThreshold(a, b);
    return m;
}

/* Point k's friction directions (see BtgContact): 1 along its slip, 2 across it in the plane. */
static inline BtgFloat4 btgFrictionDir1(const BtgContact* c, int k)
{
    return c->tangent1 * btgLane(c->frictionCos, k) + c->tangent2 * btgLane(c->frictionSin, k);
}
static inline BtgFloat4 btgFrictionDir2(const BtgContact* c, int k)
{
    return c->tangent2 * btgLane(c->frictionCos, k) - c->tangent1 * btgLane(c->frictionSin, k);
}
/* The same, or the explicit directions of anisotropic friction where dirs is given. */
static inline BtgFloat4 btgFrictionDir1Of(const BtgContact* c, const BtgFrictionDirs* dirs, int k)
{
    return dirs ? btgPick4(dirs->dir1, k) : btgFrictionDir1(c, k);
}
static inline BtgFloat4 btgFrictionDir2Of(const BtgContact* c, const BtgFrictionDirs* dirs, int k)
{
    return dirs ? btgPick4(dirs->dir2, k) : btgFrictionDir2(c, k);
}

/* Solver rows of one contact. a0/b0: velocities before this substep's forces (restitution);
 * a1/b1: after them (the friction directions, as Bullet's getVelocityInLocalPointNoDelta).
 * Targets are velocities: the solver computes (target - J v) * mass against the live velocity,
 * which equals Bullet's rhs - J dv * mass with rhs = (target - J v_setup) * mass. */
static inline void btgPrepareContact(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel a0, BtgBodyVel b0,
                                     BtgBodyVel a1, BtgBodyVel b1, BtgPairMaterial mat, int solvable, BtgStepParams p)
{
    const float friction = mat.friction, restitution = mat.restitution;
    BtgFloat4 n = btgXyz(c->normal);
    BtgFloat4 t1, t2;
    btgPlaneSpace(n, &t1, &t2);
    c->normal = n;
    c->friction = friction;
    c->tangent1 = btgXyz(t1);
    c->tangent2 = btgXyz(t2);
    /* Bullet's default friction (convertContact): per point, one row along that point's slip
     * velocity (btPlaneSpace1's p when it slips less than sqrt(SIMD_EPSILON), or always with
     * SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION); a second, perpendicular row only
     * with SOLVER_USE_2_FRICTION_DIRECTIONS. SOLVER_ENABLE_FRICTION_DIRECTION_CACHING changes
     * none of it in 3.24 (cpu_path_rules.cpp says why). */
    c->frictionCos = btgMake4(1.0f, 1.0f, 1.0f, 1.0f);
    c->frictionSin = btgZero4();
    for (int k = 0; k < c->numPoints; ++k) {
        BtgFloat4 rA = btgXyz(c->rA[k]), rB = btgXyz(c->rB[k]);
        BtgFloat4 v = (a1.lin + btgCross3(a1.ang, rA)) - (b1.lin + btgCross3(b1.ang, rB));
        BtgFloat4 slip = v - n * btgDot3(v, n);
        float slip2 = btgDot3(slip, slip);
        if (!(p.solverFlags & BTG_SOLVER_VELOCITY_INDEPENDENT_FRICTION) && slip2 > BTG_SIMD_EPSILON) {
            BtgFloat4 d = slip * (1.0f / btgSqrt(slip2));
            btgSetLane(&c->frictionCos, k, btgDot3(d, t1));
            btgSetLane(&c->frictionSin, k, btgDot3(d, t2));
        }
    }
    c->normalMass = btgZero4();
    c->friction1Mass = btgZero4();
    c->friction2Mass = btgZero4();
    c->pushImpulse = btgZero4();
    c->normalCfm = btgZero4();
    float invDt = 1.0f / p.dt;
    /* setupContactConstraint: cfm = 1 / (dt k + d), erp = dt k / (dt k + d) for a soft
     * contact, else m_globalCfm and m_erp2; the relaxation m_sor scales the normal and
     * friction rows' masses (not the rolling rows'). */
    float cfm = p.globalCfm, erp = p.erp2;
    if (mat.stiffnessDamping) {
        float denom = p.dt * mat.stiffness + mat.damping;
        if (denom < BTG_SIMD_EPSILON) denom = BTG_SIMD_EPSILON;
        cfm = 1.0f / denom;
        erp = (p.dt * mat.stiffness) / denom;
    }
    cfm *= invDt;
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        BtgFloat4 rA = btgXyz(c->rA[k]);
        BtgFloat4 rB = btgXyz(c->rB[k]);
        float target = 0.0f, push = 0.0f;
        const int processed =
            !(p.solverFlags & BTG_SOLVER_PROCESSING_THRESHOLD) ||
            btgPointProcessed(btgLane(c->separation, k), mat.processingThreshold);
        if (k < c->numPoints && solvable && !processed) {
            /* not converted: no rows, its impulses kept (btgWarmStartFrom) */
        } else if (k < c->numPoints && solvable) {
            const BtgFloat4 d1 = btgFrictionDir1(c, k);
            const float normalMass = btgPointRowMassRelaxed(btgPointJacobian(n, rA, rB, a, b), rA, rB, a, b, p.sor, cfm);
            btgSetLane(&c->normalMass, k, normalMass);
            btgSetLane(&c->normalCfm, k, cfm * normalMass);
            btgSetLane(&c->friction1Mass, k,
                       btgPointRowMassRelaxed(btgPointJacobian(d1, rA, rB, a, b), rA, rB, a, b, p.sor, 0.0f));
            if (p.twoFrictionDirections) {
                const BtgFloat4 d2 = btgFrictionDir2(c, k);
                btgSetLane(&c->friction2Mass, k,
                           btgPointRowMassRelaxed(btgPointJacobian(d2, rA, rB, a, b), rA, rB, a, b, p.sor, 0.0f));
            }
            BtgFloat4 velA = a0.lin + btgCross3(a0.ang, rA);
            BtgFloat4 velB = b0.lin + btgCross3(b0.ang, rB);
            float penetration = btgLane(c->separation, k);
            target = btgRestitution(btgDot3(n, velA - velB), restitution, p.restitutionThreshold);
            float positional = 0.0f;
            if (penetration > 0.0f) target -= penetration * invDt; /* speculative: reach, not pass */
            else positional = -penetration * erp * invDt;          /* 3.24 uses m_erp2 for contacts */
            if (!p.splitImpulse || penetration > p.splitPenetrationThreshold) target += positional;
            else push = positional;
        } else {
            btgSetLane(&c->normalImpulse, k, 0.0f);
            btgSetLane(&c->friction1Impulse, k, 0.0f);
            btgSetLane(&c->friction2Impulse, k, 0.0f);
        }
        btgSetLane(&c->normalTarget, k, target);
        btgSetLane(&c->pushTarget, k, push);
    }
}

/* What the soft step reads of btgPrepareContact's work (solve_soft's prepare builds its own rows,
 * soft_rows.h): the normal with w zero, the pair's friction, and the impulses of points that get
 * no rows zeroed (past the count, or a pair that is not solved). The bullet mode's directions,
 * masses and targets are not made: the soft step's store writes the directions it solved along,
 * and a contact callback's material prepares the contact again in full (contact_material.h). */
static inline void btgPrepareSoftContact(BtgContact* c, BtgPairMaterial mat, int solvable)
{
    c->normal = btgXyz(c->normal);
    c->friction = mat.friction;
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        if (k < c->numPoints && solvable) continue;
        btgSetLane(&c->normalImpulse, k, 0.0f);
        btgSetLane(&c->friction1Impulse, k, 0.0f);
        btgSetLane(&c->friction2Impulse, k, 0.0f);
    }
}

/* ---- friction anchors (CF_HAS_FRICTION_ANCHOR) ---- */

/* Whether a pair's points are friction anchors: btManifoldResult flags every point it adds
 * (BT_CONTACT_FLAG_FRICTION_ANCHOR) when either body has CF_HAS_FRICTION_ANCHOR. */
static inline int btgAnchoredPair(uint flagsA, uint flagsB)
{
    return ((flagsA | flagsB) & BTG_BODY_FRICTION_ANCHOR) != 0u;
}
/* A persistent manifold's contact takes its points on A from the manifold's body-frame points
 * (refreshContactPoints' m_positionWorldOnA = trA(m_localPointA)), not from the point on B and
 * the distance: a kept anchor drifts sideways, and that drift is what its friction rows pull
 * back. pm is the pair's manifold as the narrowphase left it (its points in the contact's
 * order), posA/rotA A's pose. */
static inline void btgAnchorLeverArms(BtgContact* c, BtgPersistentManifold pm, BtgFloat4 posA, BtgFloat4 rotA)
{
    if (pm.numPoints != c->numPoints || pm.bodyA != c->bodyA || pm.bodyB != c->bodyB) return;
    const BtgMat3 r = btgQuatToMat3(rotA);
    for (int k = 0; k < c->numPoints; ++k) {
        const BtgFloat4 worldA = btgXyz(posA) + btgMat3MulVec(r, pm.localA[k]);
        c->rA[k] = worldA - btgXyz(posA);
    }
}
/* setupFrictionConstraint's positional error of an anchored point: -(pA - pB).dir m_frictionERP
 * / dt joins each friction row's velocity target (dirs: anisotropic friction's explicit
 * directions, or none). Zero targets for a pair without anchors or a point without rows. */
static inline BtgFrictionAnchor btgPrepareFrictionAnchor(const BtgContact* c, const BtgFrictionDirs* dirs, BtgFloat4 posA,
                                                         BtgFloat4 posB, int anchored, BtgStepParams p)
{
    BtgFrictionAnchor f;
    f.target1 = btgZero4();
    f.target2 = btgZero4();
    if (!anchored) return f;
    const float rate = p.frictionErp / p.dt;
    for (int k = 0; k < c->numPoints; ++k) {
        if (btgLane(c->friction1Mass, k) == 0.0f && btgLane(c->friction2Mass, k) == 0.0f) continue;
        const BtgFloat4 d = (btgXyz(posA) + btgXyz(c->rA[k])) - (btgXyz(posB) + btgXyz(c->rB[k]));
        btgSetLane(&f.target1, k, -btgDot3(d, btgFrictionDir1Of(c, dirs, k)) * rate);
        if (p.twoFrictionDirections) btgSetLane(&f.target2, k, -btgDot3(d, btgFrictionDir2Of(c, dirs, k)) * rate);
    }
    return f;
}

/* ---- solve (one contact, bodies loaded by the caller) ---- */

/* The order key of a solver pass (solver_rows.h, SOLVER_RANDMIZE_ORDER): phase 1 the joints'
 * edges, else the contacts' sweep `mode` of velocity iteration `iteration`; 0 for the passes whose
 * order stays (the warm start, the rolling sweep) and without a seed. */
static inline uint btgPassKey(uint seed, int mode, int phase, int iteration)
{
    if (seed == 0u) return 0u;
    if (phase) return btgSweepKey(seed, iteration, BTG_ORDER_JOINTS);
    if (mode == BTG_PASS_NORMALS || mode == BTG_PASS_VELOCITY) return btgSweepKey(seed, iteration, BTG_ORDER_NORMALS);
    if (mode == BTG_PASS_FRICTION) return btgSweepKey(seed, iteration, BTG_ORDER_FRICTION);
    if (mode == BTG_PASS_PUSH) return btgSweepKey(seed, iteration, BTG_ORDER_PUSH);
    return 0u;
}

/* What pass `mode` reads of contact i (see BtgContact), the rest zero: a solver pass loads
 * these fields and nothing else (a copy of the whole contact would read all its bytes every
 * pass), the lever arms of the contact's points only. twoFriction: the second friction rows
 * exist (SOLVER_USE_2_FRICTION_DIRECTIONS). */
static inline BtgContact btgLoadContactRows(BTG_CONST_GLOBAL BtgContact* contacts, int i, int mode, int rows)
{
    BtgContact c;
    c.bodyA = contacts[i].bodyA;
    c.bodyB = contacts[i].bodyB;
    c.numPoints = contacts[i].numPoints;
    /* a friction sweep needs no normal targets, a normal sweep no friction rows */
    const int frictionRows = mode == BTG_PASS_VELOCITY || mode == BTG_PASS_FRICTION;
    const int normalRows = mode == BTG_PASS_VELOCITY || mode == BTG_PASS_NORMALS;
    c.friction = frictionRows ? contacts[i].friction : 0.0f;
    c.normal = contacts[i].normal;
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        c.rA[k] = k < c.numPoints ? contacts[i].rA[k] : btgZero4();
        c.rB[k] = k < c.numPoints ? contacts[i].rB[k] : btgZero4();
    }
    c.normalMass = contacts[i].normalMass;
    const int push = mode == BTG_PASS_PUSH, noFriction = push || mode == BTG_PASS_NORMALS;
    const int second = !noFriction && (rows & BTG_ROWS_TWO_FRICTION) != 0;
    c.normalTarget = normalRows ? contacts[i].normalTarget : btgZero4();
    c.normalImpulse = push ? btgZero4() : contacts[i].normalImpulse;
    c.tangent1 = noFriction ? btgZero4() : contacts[i].tangent1;
    c.tangent2 = noFriction ? btgZero4() : contacts[i].tangent2;
    c.frictionCos = noFriction ? btgZero4() : contacts[i].frictionCos;
    c.frictionSin = noFriction ? btgZero4() : contacts[i].frictionSin;
    c.friction1Mass = noFriction ? btgZero4() : contacts[i].friction1Mass;
    c.friction1Impulse = noFriction ? btgZero4() : contacts[i].friction1Impulse;
    c.friction2Mass = second ? contacts[i].friction2Mass : btgZero4();
    c.friction2Impulse = second ? contacts[i].friction2Impulse : btgZero4();
    c.pushTarget = push ? contacts[i].pushTarget : btgZero4();
    c.pushImpulse = push ? contacts[i].pushImpulse : btgZero4();
    c.separation = btgZero4();
    c.normalCfm = (rows & BTG_ROWS_CFM) != 0 && (normalRows || push) ? contacts[i].normalCfm : btgZero4();
    return c;
}
/* What pass `mode` changed of contact c, written back to slot i: its accumulated impulses. */
static inline void btgStoreContactImpulses(BTG_GLOBAL BtgContact* contacts, int i, const BtgContact* c, int mode,
                                           int rows)
{
    const int twoFriction = (rows & BTG_ROWS_TWO_FRICTION) != 0;
    if (mode == BTG_PASS_VELOCITY || mode == BTG_PASS_NORMALS) contacts[i].normalImpulse = c->normalImpulse;
    if (mode == BTG_PASS_VELOCITY || mode == BTG_PASS_FRICTION) {
        contacts[i].friction1Impulse = c->friction1Impulse;
        if (twoFriction) contacts[i].friction2Impulse = c->friction2Impulse;
    } else if (mode == BTG_PASS_PUSH) {
        contacts[i].pushImpulse = c->pushImpulse;
    }
}

/* Point k's lever arms, picked by selects rather than an index: the rows run with k known only
 * at run time, and one indexed read of rA/rB keeps the whole contact in a GPU's local memory,
 * every field of it then a load and a store there (btgSoftArmA: the same in the soft step). */
static inline BtgFloat4 btgContactArmA(const BtgContact* c, int k)
{
    return btgXyz(btgPick4(c->rA, k));
}
static inline BtgFloat4 btgContactArmB(const BtgContact* c, int k)
{
    return btgXyz(btgPick4(c->rB, k));
}
/* Point k's rows as solver rows (see BtgContact): the normal row is unilateral, the friction
 * rows are bounded by friction times the point's normal impulse as it stands, the push row
 * shares the normal row's direction and mass. */
static inline BtgSolverRow btgContactNormalRow(const BtgContact* c, int k, BtgSolverBody a, BtgSolverBody b)
{
    BtgFloat4 rA = btgContactArmA(c, k), rB = btgContactArmB(c, k);
    BtgSolverRow r = btgMakeSolverRow(btgPointJacobian(c->normal, rA, rB, a, b), btgLane(c->normalMass, k),
                                      btgLane(c->normalTarget, k), 0.0f, BTG_NORMAL_UPPER_LIMIT,
                                      btgLane(c->normalImpulse, k));
    r.cfm = btgLane(c->normalCfm, k);
    return r;
}
static inline BtgSolverRow btgContactFrictionRow(const BtgContact* c, int k, BtgFloat4 dir, float mass, float impulse,
                                                 float target, BtgSolverBody a, BtgSolverBody b)
{
    BtgFloat4 rA = btgContactArmA(c, k), rB = btgContactArmB(c, k);
    float lim = c->friction * btgLane(c->normalImpulse, k);
    return btgMakeSolverRow(btgPointJacobian(dir, rA, rB, a, b), mass, target, -lim, lim, impulse);
}
static inline BtgSolverRow btgContactPushRow(const BtgContact* c, int k, BtgSolverBody a, BtgSolverBody b)
{
    BtgFloat4 rA = btgContactArmA(c, k), rB = btgContactArmB(c, k);
    BtgSolverRow r = btgMakeSolverRow(btgPointJacobian(c->normal, rA, rB, a, b), btgLane(c->normalMass, k),
                                      btgLane(c->pushTarget, k), 0.0f, BTG_NORMAL_UPPER_LIMIT,
                                      btgLane(c->pushImpulse, k));
    r.cfm = btgLane(c->normalCfm, k);
    return r;
}

/* The setup-time warm start: accumulated impulses applied once before the iterations.
 * twoFriction: SOLVER_USE_2_FRICTION_DIRECTIONS (without it the second friction rows have no
 * mass, and are not read at all). */
static inline void btgContactWarmStartDirs(const BtgContact* c, const BtgFrictionDirs* dirs, BtgSolverBody a,
                                           BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb, int rows)
{
    const int twoFriction = (rows & BTG_ROWS_TWO_FRICTION) != 0;
    for (int k = 0; k < c->numPoints; ++k) {
        BtgFloat4 rA = btgContactArmA(c, k), rB = btgContactArmB(c, k);
        if (btgLane(c->normalMass, k) == 0.0f) continue;
        btgRowApply(btgPointJacobian(c->normal, rA, rB, a, b), a, b, va, vb, btgLane(c->normalImpulse, k));
        if (btgLane(c->friction1Mass, k) != 0.0f)
            btgRowApply(btgPointJacobian(btgFrictionDir1Of(c, dirs, k), rA, rB, a, b), a, b, va, vb,
                        btgLane(c->friction1Impulse, k));
        if (twoFriction && btgLane(c->friction2Mass, k) != 0.0f)
            btgRowApply(btgPointJacobian(btgFrictionDir2Of(c, dirs, k), rA, rB, a, b), a, b, va, vb,
                        btgLane(c->friction2Impulse, k));
    }
}
static inline void btgContactWarmStart(const BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                       BtgBodyVel* vb, int rows)
{
    btgContactWarmStartDirs(c, 0, a, b, va, vb, rows);
}
/* A velocity iteration's normal rows of one contact (BTG_PASS_NORMALS), its points in the order
 * `key` permutes them to (btgPermute; 0: in order). */
static inline void btgContactSolveNormalsOrdered(BtgContact* c, uint key, BtgSolverBody a, BtgSolverBody b,
                                                 BtgBodyVel* va, BtgBodyVel* vb)
{
    for (int j = 0; j < c->numPoints; ++j) {
        const int k = btgPermute(key, c->numPoints, j);
        if (btgLane(c->normalMass, k) == 0.0f) continue;
        BtgSolverRow r = btgContactNormalRow(c, k, a, b);
        btgRowSolve(&r, a, b, va, vb);
        btgSetLane(&c->normalImpulse, k, r.impulse);
    }
}
static inline void btgContactSolveNormals(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb)
{
    btgContactSolveNormalsOrdered(c, 0u, a, b, va, vb);
}
/* Its friction rows (directions 1 and 2 per point) whose normal impulse is positive
 * (BTG_PASS_FRICTION). */
static inline void btgContactSolvePointFriction(BtgContact* c, int k, const BtgFrictionDirs* dirs,
                                                const BtgFrictionAnchor* anchor, BtgSolverBody a, BtgSolverBody b,
                                                BtgBodyVel* va, BtgBodyVel* vb, int rows)
{
    if (!(btgLane(c->normalImpulse, k) > 0.0f)) return;
    float m1 = btgLane(c->friction1Mass, k);
    if (m1 != 0.0f) {
        BtgSolverRow r = btgContactFrictionRow(c, k, btgFrictionDir1Of(c, dirs, k), m1, btgLane(c->friction1Impulse, k),
                                               anchor ? btgLane(anchor->target1, k) : 0.0f, a, b);
        btgRowSolve(&r, a, b, va, vb);
        btgSetLane(&c->friction1Impulse, k, r.impulse);
    }
    float m2 = (rows & BTG_ROWS_TWO_FRICTION) != 0 ? btgLane(c->friction2Mass, k) : 0.0f;
    if (m2 != 0.0f) {
        BtgSolverRow r = btgContactFrictionRow(c, k, btgFrictionDir2Of(c, dirs, k), m2, btgLane(c->friction2Impulse, k),
                                               anchor ? btgLane(anchor->target2, k) : 0.0f, a, b);
        btgRowSolve(&r, a, b, va, vb);
        btgSetLane(&c->friction2Impulse, k, r.impulse);
    }
}
static inline void btgContactSolveFrictionOrdered(BtgContact* c, const BtgFrictionDirs* dirs,
                                                  const BtgFrictionAnchor* anchor, uint key, BtgSolverBody a,
                                                  BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb, int rows)
{
    for (int j = 0; j < c->numPoints; ++j)
        btgContactSolvePointFriction(c, btgPermute(key, c->numPoints, j), dirs, anchor, a, b, va, vb, rows);
}
/* SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS (BTG_PASS_VELOCITY): each point's normal
 * row, then at once its friction rows bounded by the impulse just found, as 3.24's
 * solveSingleIteration walks its pools in that mode (friction of the point whose normal impulse
 * is positive only). */
static inline void btgContactSolveInterleavedOrdered(BtgContact* c, const BtgFrictionDirs* dirs,
                                                     const BtgFrictionAnchor* anchor, uint key, BtgSolverBody a,
                                                     BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb, int rows)
{
    for (int j = 0; j < c->numPoints; ++j) {
        const int k = btgPermute(key, c->numPoints, j);
        if (btgLane(c->normalMass, k) != 0.0f) {
            BtgSolverRow r = btgContactNormalRow(c, k, a, b);
            btgRowSolve(&r, a, b, va, vb);
            btgSetLane(&c->normalImpulse, k, r.impulse);
        }
        btgContactSolvePointFriction(c, k, dirs, anchor, a, b, va, vb, rows);
    }
}
static inline void btgContactSolveFrictionAnchored(BtgContact* c, const BtgFrictionDirs* dirs,
                                                   const BtgFrictionAnchor* anchor, BtgSolverBody a, BtgSolverBody b,
                                                   BtgBodyVel* va, BtgBodyVel* vb, int rows)
{
    btgContactSolveFrictionOrdered(c, dirs, anchor, 0u, a, b, va, vb, rows);
}
static inline void btgContactSolveFrictionDirs(BtgContact* c, const BtgFrictionDirs* dirs, BtgSolverBody a,
                                               BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb, int rows)
{
    btgContactSolveFrictionAnchored(c, dirs, 0, a, b, va, vb, rows);
}
static inline void btgContactSolveFriction(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                           BtgBodyVel* vb, int rows)
{
    btgContactSolveFrictionDirs(c, 0, a, b, va, vb, rows);
}
/* Both for one contact (the Jacobi solver's velocity pass, which sweeps every contact once). */
static inline void btgContactSolveVelocity(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                           BtgBodyVel* vb, int rows)
{
    btgContactSolveNormals(c, a, b, va, vb);
    btgContactSolveFriction(c, a, b, va, vb, rows);
}
/* Whether any of the contact's points has a push row (the push passes visit only such
 * contacts); read straight from the list, three fields. */
static inline int btgContactHasPush(BTG_CONST_GLOBAL BtgContact* contacts, int i)
{
    const int n = contacts[i].numPoints;
    const BtgFloat4 target = contacts[i].pushTarget, mass = contacts[i].normalMass;
    for (int k = 0; k < n; ++k)
        if (btgLane(target, k) != 0.0f && btgLane(mass, k) != 0.0f) return 1;
    return 0;
}
/* The normal impulses of the points that have rows (the rolling rows are convertContact's for
 * converted points only): lanes without a normal row read 0. */
static inline BtgFloat4 btgSolvedNormalImpulse(const BtgContact* c)
{
    BtgFloat4 n = c->normalImpulse;
    for (int k = 0; k < BTG_MAX_POINTS; ++k)
        if (btgLane(c->normalMass, k) == 0.0f) btgSetLane(&n, k, 0.0f);
    return n;
}
/* One split-impulse iteration (resolveSplitPenetrationImpulse) on push/turn velocities, the
 * points in key's order (0: in order). */
static inline void btgContactSolvePushOrdered(BtgContact* c, uint key, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* pa,
                                              BtgBodyVel* pb)
{
    for (int j = 0; j < c->numPoints; ++j) {
        const int k = btgPermute(key, c->numPoints, j);
        if (btgLane(c->normalMass, k) == 0.0f || btgLane(c->pushTarget, k) == 0.0f) continue;
        BtgSolverRow r = btgContactPushRow(c, k, a, b);
        btgRowSolve(&r, a, b, pa, pb);
        btgSetLane(&c->pushImpulse, k, r.impulse);
    }
}

static inline void btgContactSolvePush(BtgContact* c, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* pa, BtgBodyVel* pb)
{
    btgContactSolvePushOrdered(c, 0u, a, b, pa, pb);
}

#endif
