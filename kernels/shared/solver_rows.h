/* solver_rows.h — the solver row every constraint kind is solved as (btSolverConstraint's
 * role; Jolt's AxisConstraintPart): a Jacobian on two bodies, an effective mass, impulse bounds,
 * a target velocity and an accumulated impulse, with the projected Gauss-Seidel step on it.
 * Shared by the solver kernels and their CPU references; contacts build their rows from
 * contact_rows.h's BtgContact, joints (issue 11) from their own stored rows. */
#ifndef BTG_SOLVER_ROWS_H
#define BTG_SOLVER_ROWS_H
#include "prelude.h"
#include "types.h"
#include "math.h"

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

/* A row's Jacobian J = [linear, angularA; -linear, angularB] with the angular parts of
 * M^-1 J^T (Bullet's m_contactNormal1/2, m_relpos1/2CrossNormal, m_angularComponentA/B; B's
 * angular part is stored already negated, as Bullet does). */
typedef struct {
    BtgFloat4 linear;   /* unit direction on A; B's linear part is -linear */
    BtgFloat4 angularA; /* rA x linear */
    BtgFloat4 angularB; /* -(rB x linear) */
    BtgFloat4 responseA; /* invI_A angularA * angularFactor_A: A's angular velocity per N s */
    BtgFloat4 responseB; /* invI_B angularB * angularFactor_B */
} BtgJacobian;

/* One scalar constraint row between the two bodies of its constraint's graph edge: J v is
 * driven towards target while the accumulated impulse stays in [lower, upper]. Rows live in
 * private memory for one pass: each constraint kind stores what it needs to rebuild them (a
 * contact: a point's lever arms, its manifold's directions and lane k of its row fields; see
 * BtgContact) and writes the impulse back. A friction row's bounds are its friction
 * coefficient times the impulse of the normal row at the same point, taken when the row is
 * built (after that point's normal row in the same pass). */
typedef struct {
    BtgJacobian jacobian;
    float mass;    /* effective mass 1/(J M^-1 J^T), kg (kg m^2 for angular rows); 0: not solved */
    float target;  /* velocity J v is driven to, m/s: restitution, Baumgarte bias, motor speed */
    float lower;   /* impulse bounds, N s */
    float upper;
    float impulse; /* accumulated impulse, N s */
    float cfm;     /* Bullet's m_cfm: the step gives up cfm times the accumulated impulse (a contact's
                      m_globalCfm or stiffness and damping; 0 for friction and rolling rows) */
} BtgSolverRow;

/* The points 0..n-1 of a contact, in a loop a GPU's compiler unrolls: with k a constant in each
 * copy, btgLane, btgSetLane and btgPick4 are register moves; with k known only at run time the
 * compiler turns their selects into an indexed vector element, which a GPU keeps in local
 * memory (a store of the vector and a load, every lane of every row). Use with a braced body. */
#define BTG_FOR_POINTS(k, n) BTG_UNROLL for (int k = 0; k < BTG_MAX_POINTS; ++k) if (k < (n))

static inline float btgLane(BtgFloat4 v, int k)
{
    return k == 0 ? v.x : (k == 1 ? v.y : (k == 2 ? v.z : v.w));
}
/* Element k of a private four-element array (a contact's lever arms, a point's friction
 * directions), picked by selects: an index known only at run time into a private array keeps
 * the whole struct around it in a GPU's local memory (the H100's soft_resident had a
 * 1,584-byte stack frame, every contact field a load and a store through it). */
static inline BtgFloat4 btgPick4(const BtgFloat4* a, int k)
{
    return k == 0 ? a[0] : (k == 1 ? a[1] : (k == 2 ? a[2] : a[3]));
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

/* The Jacobian of a row along dir acting at lever arms rA, rB (a contact point's rows; a
 * joint's linear rows). */
static inline BtgJacobian btgPointJacobian(BtgFloat4 dir, BtgFloat4 rA, BtgFloat4 rB, BtgSolverBody a, BtgSolverBody b)
{
    BtgJacobian j;
    j.linear = btgXyz(dir);
    j.angularA = btgCross3(rA, j.linear);
    j.angularB = -btgCross3(rB, j.linear);
    j.responseA = btgMat3MulVec(a.invI, j.angularA) * a.angFactor;
    j.responseB = btgMat3MulVec(b.invI, j.angularB) * b.angFactor;
    return j;
}
/* The effective mass of a point row as setupContactConstraint forms it (m_jacDiagABInv with
 * relaxation 1 and cfm 0); 0 marks a row with no mobility (never solved). */
static inline float btgPointRowMass(BtgJacobian j, BtgFloat4 rA, BtgFloat4 rB, BtgSolverBody a, BtgSolverBody b)
{
    float denomA = a.invMass + btgDot3(j.linear, btgCross3(j.responseA, rA));
    float denomB = b.invMass + btgDot3(j.linear, btgCross3(-j.responseB, rB));
    float denom = denomA + denomB;
    return denom > 0.0f ? 1.0f / denom : 0.0f;
}
/* The same with setupContactConstraint's relaxation (m_sor) and cfm (already divided by the
 * step): relaxation / (denom + cfm); with 1 and 0 it is btgPointRowMass bit for bit. A row
 * without mobility stays 0 (never solved) whatever its cfm. */
static inline float btgPointRowMassRelaxed(BtgJacobian j, BtgFloat4 rA, BtgFloat4 rB, BtgSolverBody a, BtgSolverBody b,
                                           float relaxation, float cfm)
{
    float denomA = a.invMass + btgDot3(j.linear, btgCross3(j.responseA, rA));
    float denomB = b.invMass + btgDot3(j.linear, btgCross3(-j.responseB, rB));
    float denom = denomA + denomB;
    return denom > 0.0f ? relaxation / (denom + cfm) : 0.0f;
}
static inline BtgSolverRow btgMakeSolverRow(BtgJacobian j, float mass, float target, float lower, float upper,
                                            float impulse)
{
    BtgSolverRow r;
    r.jacobian = j;
    r.mass = mass;
    r.target = target;
    r.lower = lower;
    r.upper = upper;
    r.impulse = impulse;
    r.cfm = 0.0f;
    return r;
}

/* Relative velocity along the row, J v (vel1Dotn + vel2Dotn). */
static inline float btgRowVelocity(BtgJacobian j, BtgBodyVel va, BtgBodyVel vb)
{
    float v1 = btgDot3(j.linear, va.lin) + btgDot3(j.angularA, va.ang);
    float v2 = btgDot3(-j.linear, vb.lin) + btgDot3(j.angularB, vb.ang);
    return v1 + v2;
}
/* btSolverBody::internalApplyImpulse on both bodies: the linear and angular factors enter
 * twice (once in the component, once in the apply), as in Bullet. */
static inline void btgRowApply(BtgJacobian j, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb,
                               float impulse)
{
    va->lin = va->lin + (j.linear * a.invMassLin) * impulse * a.linFactor;
    va->ang = va->ang + j.responseA * (a.angFactor * impulse);
    vb->lin = vb->lin + (-j.linear * b.invMassLin) * impulse * b.linFactor;
    vb->ang = vb->ang + j.responseB * (b.angFactor * impulse);
}
/* One projected Gauss-Seidel step on a row (resolveSingleConstraintRowLowerLimit / Generic):
 * the impulse change that drives J v to the target, clamped so the accumulated impulse stays
 * within the bounds, applied to both bodies. */
static inline void btgRowSolve(BtgSolverRow* r, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb)
{
    float delta = (r->target - btgRowVelocity(r->jacobian, *va, *vb)) * r->mass - r->impulse * r->cfm;
    float sum = r->impulse + delta;
    if (sum < r->lower) {
        delta = r->lower - r->impulse;
        r->impulse = r->lower;
    } else if (sum > r->upper) {
        delta = r->upper - r->impulse;
        r->impulse = r->upper;
    } else {
        r->impulse = sum;
    }
    btgRowApply(r->jacobian, a, b, va, vb, delta);
}

/* ---- SOLVER_RANDMIZE_ORDER: the solve order permuted by the solver's own stream ----
 * Stock shuffles its constraint pools every iteration with its btRandInt2 stream; the batched
 * solver cannot follow that stream (its order is the colouring's), so it permutes what orders its
 * rows instead: the colours of each sweep and the points within each contact, by a stream of
 * its own, a pure function of the substep's seed (BtgStepParams.randomSeed, 0: off), the
 * iteration and the sweep, so two worlds (and the host's per-colour launches and the one-launch
 * kernel) take the same order. Integer arithmetic only. */
static inline uint btgOrderHash(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
/* The key of one sweep (0: the unpermuted order): the velocity iterations' normal (0) and
 * friction (1) sweeps and the joints' (2) each their own per iteration; the split-impulse
 * iterations one order for all (stock solves them in its last shuffled order). */
#define BTG_ORDER_NORMALS 0
#define BTG_ORDER_FRICTION 1
#define BTG_ORDER_JOINTS 2
#define BTG_ORDER_PUSH 3
static inline uint btgSweepKey(uint seed, int iteration, int sweep)
{
    if (seed == 0u) return 0u;
    if (sweep == BTG_ORDER_PUSH) iteration = 0;
    return btgOrderHash(btgOrderHash(seed) ^ (uint)(iteration * 4 + sweep + 1)) | 1u;
}
/* The key of one contact (or colour list) within a sweep. */
static inline uint btgItemKey(uint sweepKey, uint item)
{
    return sweepKey == 0u ? 0u : btgOrderHash(sweepKey + item * 0x9e3779b9u) | 1u;
}
/* Position i of [0, n) under key's permutation: an affine map i -> (a i + b) mod n, a a power of
 * the prime 67 (coprime to every n the solver permutes: up to 4 points, 63 colours) or its
 * reflection; no table and no loop, so a kernel that never permutes (key 0: the identity) keeps
 * its shape. */
static inline int btgPermute(uint key, int n, int i)
{
    if (key == 0u || n <= 1) return i;
    const uint un = (uint)n;
    const uint h = btgOrderHash(key);
    const uint p1 = 67u % un, p2 = (p1 * p1) % un, p3 = (p2 * p1) % un, p4 = (p2 * p2) % un;
    const uint pick = h & 3u;
    uint a = pick == 0u ? p1 : (pick == 1u ? p2 : (pick == 2u ? p3 : p4));
    if ((h >> 2) & 1u) a = un - a; /* the reflection: still coprime to n */
    const uint b = (h >> 3) % un;
    return (int)((a * (uint)i + b) % un);
}

#endif
