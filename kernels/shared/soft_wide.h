/* soft_wide.h — the soft step's solve and relax rows, eight contacts of one colour at a time in
 * the lanes of float8, for CPU devices (soft_wide_passes.h's kernels and soft_resident). A CPU
 * device runs a work-group's work-items one after another, each contact's rows as scalar code,
 * and so the sweeps were the soft step's cost there (54% of a PoCL run of cubes 8,000); the
 * contacts of a colour share no dynamic body, so they can go through the rows side by side, as
 * Box2D v3's contact solver runs them in SIMD lanes (contact_solver.c, b2FloatW). Each
 * expression below is written as its scalar counterpart in soft_rows.h / solver_rows.h / math.h
 * is (the same operations in the same order in one statement, so a compiler contracts the same
 * products into the same fused multiply-adds): lane by lane the same arithmetic as
 * soft_contact's, the same results bit for bit (SolveSoft.LaunchShapesAgreeBitwise, the bench's
 * state hash). Device only (OpenCL vectors): the CPU reference is soft_rows.h itself. The
 * contacts' lanes live in blocks of eight (soft_wide_pack), read and written as vectors; the
 * bodies' are gathered each sweep. Served: contacts with the soft step's own spring and the
 * tangents (not a pair's stiffness and damping, not Bullet's directions), points in order (no
 * SOLVER_RANDMIZE_ORDER), friction after the normals (no interleave), no held pairs, no rolling
 * rows; everything else goes to soft_edge. */
#ifndef BTG_SOFT_WIDE_H
#define BTG_SOFT_WIDE_H
#include "soft_rows.h"

typedef float8 BtgW;
typedef struct {
    BtgW x, y, z;
} BtgV3W;
typedef struct {
    BtgV3W r0, r1, r2;
} BtgM3W;

static BTG_ALWAYS_INLINE BtgV3W btgW3(BtgW x, BtgW y, BtgW z)
{
    BtgV3W v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}
static BTG_ALWAYS_INLINE BtgV3W btgW3Add(BtgV3W a, BtgV3W b) { return btgW3(a.x + b.x, a.y + b.y, a.z + b.z); }
static BTG_ALWAYS_INLINE BtgV3W btgW3Sub(BtgV3W a, BtgV3W b) { return btgW3(a.x - b.x, a.y - b.y, a.z - b.z); }
static BTG_ALWAYS_INLINE BtgV3W btgW3Neg(BtgV3W a) { return btgW3(-a.x, -a.y, -a.z); }
/* btgDot3, btgCross3, btgMat3MulVec */
static BTG_ALWAYS_INLINE BtgW btgW3Dot(BtgV3W a, BtgV3W b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static BTG_ALWAYS_INLINE BtgV3W btgW3Cross(BtgV3W a, BtgV3W b)
{
    return btgW3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static BTG_ALWAYS_INLINE BtgV3W btgW3MatMul(BtgM3W m, BtgV3W v) { return btgW3(btgW3Dot(m.r0, v), btgW3Dot(m.r1, v), btgW3Dot(m.r2, v)); }
static BTG_ALWAYS_INLINE BtgV3W btgW3Mul(BtgV3W a, BtgV3W b) { return btgW3(a.x * b.x, a.y * b.y, a.z * b.z); }
static BTG_ALWAYS_INLINE BtgV3W btgW3Select(BtgV3W no, BtgV3W yes, int8 pick)
{
    return btgW3(select(no.x, yes.x, pick), select(no.y, yes.y, pick), select(no.z, yes.z, pick));
}

/* A cache line read ahead (a CPU device's clang: prefetcht0), nothing elsewhere. */
#if defined(BTG_CPU_DEVICE) && defined(__clang__)
#define btgPrefetch(p) __builtin_prefetch((const __global void*)(p))
#else
#define btgPrefetch(p) ((void)0)
#endif

/* A body as the rows see it (BtgSolverBody, BtgBodyVel, BtgSoftDelta), eight lanes. */
typedef struct {
    BtgM3W invI;
    BtgV3W invMassLin, linFactor, angFactor;
    BtgW invMass;
} BtgBodyW;
typedef struct {
    BtgV3W lin, ang;
} BtgVelW;
typedef struct {
    BtgV3W pos;
    BtgM3W rot;
} BtgDeltaW;

/* Field f of a chunk's block of contact lanes (global memory: soft_wide_pack's), as vectors. */
static BTG_ALWAYS_INLINE BtgW btgWLoadG(__global const float* c, int f) { return vload8(0, c + f * BTG_SOFT_WIDE); }
static BTG_ALWAYS_INLINE BtgV3W btgW3LoadG(__global const float* c, int f)
{
    return btgW3(btgWLoadG(c, f), btgWLoadG(c, f + 1), btgWLoadG(c, f + 2));
}
static BTG_ALWAYS_INLINE void btgWStoreG(__global float* c, int f, BtgW x) { vstore8(x, 0, c + f * BTG_SOFT_WIDE); }

/* One float of lane l of field f in a block of lanes. Each its own store: a loop over the fields
 * becomes AVX-512 scatters, which cost a quarter of the sweep. */
#define BTG_W_PUT(lanes, f, l, x) (lanes)[(f) * BTG_SOFT_WIDE + (l)] = (x)

/* btgQuatToMat3, lane by lane */
static BTG_ALWAYS_INLINE BtgM3W btgWQuatToMat3(BtgW qx, BtgW qy, BtgW qz, BtgW qw)
{
    BtgW d = qx * qx + qy * qy + qz * qz + qw * qw;
    BtgW s = 2.0f / d;
    BtgW xs = qx * s, ys = qy * s, zs = qz * s;
    BtgW wx = qw * xs, wy = qw * ys, wz = qw * zs;
    BtgW xx = qx * xs, xy = qx * ys, xz = qx * zs;
    BtgW yy = qy * ys, yz = qy * zs, zz = qz * zs;
    BtgM3W m;
    m.r0 = btgW3(1.0f - (yy + zz), xy - wz, xz + wy);
    m.r1 = btgW3(xy + wz, 1.0f - (xx + zz), yz - wx);
    m.r2 = btgW3(xz - wy, yz + wx, 1.0f - (xx + yy));
    return m;
}

/* The lanes' bodies as soft_solver_body, btgMakeBodyVel and load_delta make them, from each
 * lane's eight rows (rows[8 l + r]: the solver record's four, then the velocity rows, w of the
 * first the kind, and the deltas; an empty lane's a fixed body at rest). Each field's vector is
 * built from the eight lanes in registers: put through memory lane by lane and read back as a
 * vector, every read waited for eight stores it could not forward. */
#define BTG_W_ROW(rows, r, c)                                                                         \
    ((BtgW)((rows)[(r)].c, (rows)[8 + (r)].c, (rows)[16 + (r)].c, (rows)[24 + (r)].c, (rows)[32 + (r)].c, \
            (rows)[40 + (r)].c, (rows)[48 + (r)].c, (rows)[56 + (r)].c))
/* The solver body and velocities alone, from rows 0-5 (the PGS sweeps' lanes, pgs_wide.h, have
 * no deltas). */
static BTG_ALWAYS_INLINE void btgWSolverBody(const BtgFloat4* rows, BtgBodyW* b, BtgVelW* v, BtgW* kind)
{
    b->invI.r0 = btgW3(BTG_W_ROW(rows, 0, x), BTG_W_ROW(rows, 0, y), BTG_W_ROW(rows, 0, z));
    b->invI.r1 = btgW3(BTG_W_ROW(rows, 1, x), BTG_W_ROW(rows, 1, y), BTG_W_ROW(rows, 1, z));
    b->invI.r2 = btgW3(BTG_W_ROW(rows, 2, x), BTG_W_ROW(rows, 2, y), BTG_W_ROW(rows, 2, z));
    b->invMass = BTG_W_ROW(rows, 0, w);
    b->linFactor = btgW3(BTG_W_ROW(rows, 1, w), BTG_W_ROW(rows, 2, w), BTG_W_ROW(rows, 3, w));
    b->angFactor = btgW3(BTG_W_ROW(rows, 3, x), BTG_W_ROW(rows, 3, y), BTG_W_ROW(rows, 3, z));
    b->invMassLin = btgW3(b->linFactor.x * b->invMass, b->linFactor.y * b->invMass, b->linFactor.z * b->invMass);
    *kind = BTG_W_ROW(rows, 4, w);
    const int8 moving = *kind == 1.0f || *kind == 3.0f;
    const BtgW zero = (BtgW)(0.0f);
    const BtgV3W z3 = btgW3(zero, zero, zero);
    v->lin = btgW3Select(z3, btgW3(BTG_W_ROW(rows, 4, x), BTG_W_ROW(rows, 4, y), BTG_W_ROW(rows, 4, z)), moving);
    v->ang = btgW3Select(z3, btgW3(BTG_W_ROW(rows, 5, x), BTG_W_ROW(rows, 5, y), BTG_W_ROW(rows, 5, z)), moving);
}
static BTG_ALWAYS_INLINE void btgWBody(const BtgFloat4* rows, BtgBodyW* b, BtgVelW* v, BtgDeltaW* d, BtgW* kind)
{
    btgWSolverBody(rows, b, v, kind);
    d->pos = btgW3(BTG_W_ROW(rows, 6, x), BTG_W_ROW(rows, 6, y), BTG_W_ROW(rows, 6, z));
    d->rot = btgWQuatToMat3(BTG_W_ROW(rows, 7, x), BTG_W_ROW(rows, 7, y), BTG_W_ROW(rows, 7, z), BTG_W_ROW(rows, 7, w));
}
/* An empty lane's rows: a fixed body at rest, nothing moved. */
static BTG_ALWAYS_INLINE void btgWEmptyRows(BtgFloat4* rows)
{
    for (int r = 0; r < 7; ++r) rows[r] = btgZero4();
    rows[7] = btgMake4(0.0f, 0.0f, 0.0f, 1.0f);
}

/* BtgJacobian, lanes */
typedef struct {
    BtgV3W linear, angularA, angularB, responseA, responseB;
} BtgJacobianW;
static BTG_ALWAYS_INLINE BtgJacobianW btgWPointJacobian(BtgV3W dir, BtgV3W rA, BtgV3W rB, const BtgBodyW* a, const BtgBodyW* b)
{
    BtgJacobianW j;
    j.linear = dir;
    j.angularA = btgW3Cross(rA, j.linear);
    j.angularB = btgW3Neg(btgW3Cross(rB, j.linear));
    j.responseA = btgW3Mul(btgW3MatMul(a->invI, j.angularA), a->angFactor);
    j.responseB = btgW3Mul(btgW3MatMul(b->invI, j.angularB), b->angFactor);
    return j;
}
static BTG_ALWAYS_INLINE BtgW btgWRowVelocity(const BtgJacobianW* j, const BtgVelW* va, const BtgVelW* vb)
{
    BtgW v1 = btgW3Dot(j->linear, va->lin) + btgW3Dot(j->angularA, va->ang);
    BtgW v2 = btgW3Dot(btgW3Neg(j->linear), vb->lin) + btgW3Dot(j->angularB, vb->ang);
    return v1 + v2;
}
/* btgRowApply on one body (l: the row's linear part on that side), each component as its float4
 * expression */
static BTG_ALWAYS_INLINE void btgWApplySide(BtgVelW* v, BtgV3W l, BtgV3W response, const BtgBodyW* body, BtgW impulse)
{
    v->lin.x = v->lin.x + (l.x * body->invMassLin.x) * impulse * body->linFactor.x;
    v->lin.y = v->lin.y + (l.y * body->invMassLin.y) * impulse * body->linFactor.y;
    v->lin.z = v->lin.z + (l.z * body->invMassLin.z) * impulse * body->linFactor.z;
    v->ang.x = v->ang.x + response.x * (body->angFactor.x * impulse);
    v->ang.y = v->ang.y + response.y * (body->angFactor.y * impulse);
    v->ang.z = v->ang.z + response.z * (body->angFactor.z * impulse);
}
static BTG_ALWAYS_INLINE void btgWRowApply(const BtgJacobianW* j, const BtgBodyW* a, const BtgBodyW* b, BtgVelW* va,
                                           BtgVelW* vb, BtgW impulse)
{
    btgWApplySide(va, j->linear, j->responseA, a, impulse);
    btgWApplySide(vb, btgW3Neg(j->linear), j->responseB, b, impulse);
}
/* The lanes' velocities and kinds spilled lane by lane for their stores: x[f * 8 + l], f 0-2
 * the linear velocity, 3-5 the angular, 6 the kind. */
static BTG_ALWAYS_INLINE void btgWVelLanes(const BtgVelW* v, BtgW kinds, float* x)
{
    vstore8(kinds, 6, x);
    vstore8(v->lin.x, 0, x);
    vstore8(v->lin.y, 1, x);
    vstore8(v->lin.z, 2, x);
    vstore8(v->ang.x, 3, x);
    vstore8(v->ang.y, 4, x);
    vstore8(v->ang.z, 5, x);
}
/* Lever arms rA, rB of lane l into fields f.. f + 5 (x, y, z of A's, then of B's). */
static BTG_ALWAYS_INLINE void btgWPutArms(__global float* c, int f, int l, BtgFloat4 rA, BtgFloat4 rB)
{
    BTG_W_PUT(c, f, l, rA.x);
    BTG_W_PUT(c, f + 1, l, rA.y);
    BTG_W_PUT(c, f + 2, l, rA.z);
    BTG_W_PUT(c, f + 3, l, rB.x);
    BTG_W_PUT(c, f + 4, l, rB.y);
    BTG_W_PUT(c, f + 5, l, rB.z);
}

/* A row's velocity change kept only in the lanes that solve it (the scalar rows return early). */
static BTG_ALWAYS_INLINE void btgWKeep(BtgVelW* v, BtgVelW before, int8 solved)
{
    v->lin = btgW3Select(before.lin, v->lin, solved);
    v->ang = btgW3Select(before.ang, v->ang, solved);
}

/* A contact's fields in lanes: per point k the anchors (w: the normal mass), base separation,
 * tangent masses, impulses and step totals. */
enum {
    BTG_WC_NX, BTG_WC_NY, BTG_WC_NZ, BTG_WC_FRICTION, BTG_WC_STIFFENING, BTG_WC_FIXED, BTG_WC_IMPACT,
    BTG_WC_POINT0, /* then per point: */
    BTG_WC_AX = 0, BTG_WC_AY, BTG_WC_AZ, BTG_WC_BX, BTG_WC_BY, BTG_WC_BZ, BTG_WC_MASS, BTG_WC_BASE,
    BTG_WC_T1MASS, BTG_WC_T2MASS, BTG_WC_NIMP, BTG_WC_TOTN, BTG_WC_T1IMP, BTG_WC_T2IMP, BTG_WC_TOT1, BTG_WC_TOT2,
    BTG_WC_PER_POINT
};
#define BTG_WC_FIELDS BTG_SOFT_WIDE_FIELDS /* BTG_WC_POINT0 + BTG_MAX_POINTS * BTG_WC_PER_POINT */
#define BTG_WC_AT(k, f) (BTG_WC_POINT0 + (k) * BTG_WC_PER_POINT + (f))
/* the host sizes the blocks by BTG_SOFT_WIDE_FIELDS: a field added here must be counted there */
typedef char BtgWideFieldsCounted[BTG_WC_POINT0 + BTG_MAX_POINTS * BTG_WC_PER_POINT == BTG_WC_FIELDS ? 1 : -1];

/* Lane l of a chunk's block from soft contact s as load_soft reads it for the solve and relax
 * (s 0: an empty lane, no points), and a point field of lane l back as the contact's float4. */
static BTG_ALWAYS_INLINE void btgWPutContact(__global float* c, int l, __global const BtgSoftContact* s)
{
    const BtgFloat4 z = btgZero4();
    const int live = s != 0;
    const BtgFloat4 n = live ? s->normal : z;
    const int points = live ? s->numPoints : 0;
    BTG_W_PUT(c, BTG_WC_NX, l, n.x);
    BTG_W_PUT(c, BTG_WC_NY, l, n.y);
    BTG_W_PUT(c, BTG_WC_NZ, l, n.z);
    BTG_W_PUT(c, BTG_WC_FRICTION, l, live ? s->friction : 0.0f);
    BTG_W_PUT(c, BTG_WC_STIFFENING, l, live ? s->stiffening.x : 0.0f);
    BTG_W_PUT(c, BTG_WC_FIXED, l, live && (s->flags & BTG_SOFT_FIXED) ? 1.0f : 0.0f);
    BTG_W_PUT(c, BTG_WC_IMPACT, l, live && (s->flags & BTG_SOFT_IMPACT) ? 1.0f : 0.0f);
    const BtgFloat4 normal = live ? s->normalImpulse : z, total = live ? s->totalNormal : z;
    const BtgFloat4 base = live ? s->baseSeparation : z;
    const BtgFloat4 m1 = live ? s->tangent1Mass : z, m2 = live ? s->tangent2Mass : z;
    const BtgFloat4 i1 = live ? s->tangent1Impulse : z, i2 = live ? s->tangent2Impulse : z;
    const BtgFloat4 t1 = live ? s->total1 : z, t2 = live ? s->total2 : z;
#pragma unroll
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        const BtgFloat4 rA = k < points ? s->rA[k] : z, rB = k < points ? s->rB[k] : z;
        btgWPutArms(c, BTG_WC_AT(k, BTG_WC_AX), l, rA, rB);
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_MASS), l, rA.w); /* the anchors' w: the normal mass (btgSoftPack) */
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_BASE), l, btgLane(base, k));
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_T1MASS), l, btgLane(m1, k));
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_T2MASS), l, btgLane(m2, k));
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_NIMP), l, btgLane(normal, k));
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_TOTN), l, btgLane(total, k));
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_T1IMP), l, btgLane(i1, k));
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_T2IMP), l, btgLane(i2, k));
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_TOT1), l, btgLane(t1, k));
        BTG_W_PUT(c, BTG_WC_AT(k, BTG_WC_TOT2), l, btgLane(t2, k));
    }
}
static BTG_ALWAYS_INLINE BtgFloat4 btgWPoints(__global const float* c, int l, int f)
{
    return btgMake4(c[BTG_WC_AT(0, f) * BTG_SOFT_WIDE + l], c[BTG_WC_AT(1, f) * BTG_SOFT_WIDE + l],
                    c[BTG_WC_AT(2, f) * BTG_SOFT_WIDE + l], c[BTG_WC_AT(3, f) * BTG_SOFT_WIDE + l]);
}

/* btgSoftStiffened / btgSoftSpringOf for the lanes (r: each contact's one factor). */
static BTG_ALWAYS_INLINE void btgWContactSpring(BtgW r, int8 fixed, BtgSoftParams p, BtgW* massScale, BtgW* impulseScale,
                                                BtgW* biasRate)
{
    const BtgW omega2 = select((BtgW)(p.omega2Contact), (BtgW)(p.omega2Fixed), fixed);
    const BtgW zeta = (BtgW)(p.zeta), h = (BtgW)(p.h);
    const BtgW omega = sqrt(omega2), hw = h * omega;
    const BtgW a1 = 2.0f * zeta * r * sqrt(r) + hw * r;
    const BtgW stiffness = hw * a1;
    const BtgW rate = omega * r / a1;
    const BtgW ms = stiffness / (1.0f + stiffness);
    const BtgW is = 1.0f / (1.0f + stiffness);
    const int8 stiffened = r > 1.0f;
    *massScale = select(select((BtgW)(p.contact.massScale), (BtgW)(p.fixed.massScale), fixed), ms, stiffened);
    *impulseScale = select(select((BtgW)(p.contact.impulseScale), (BtgW)(p.fixed.impulseScale), fixed), is, stiffened);
    *biasRate = select(select((BtgW)(p.contact.biasRate), (BtgW)(p.fixed.biasRate), fixed), rate, stiffened);
}

/* btgPlaneSpace of the lanes' normals */
static BTG_ALWAYS_INLINE void btgWPlaneSpace(BtgV3W n, BtgV3W* p, BtgV3W* q)
{
    const BtgW zero = (BtgW)(0.0f);
    const int8 zAxis = fabs(n.z) > 0.70710678f;
    const BtgW az = n.y * n.y + n.z * n.z;
    const BtgW kz = 1.0f / sqrt(az);
    const BtgV3W pz = btgW3(zero, -n.z * kz, n.y * kz);
    const BtgV3W qz = btgW3(az * kz, -n.x * pz.z, n.x * pz.y);
    const BtgW ax = n.x * n.x + n.y * n.y;
    const BtgW kx = 1.0f / sqrt(ax);
    const BtgV3W px = btgW3(-n.y * kx, n.x * kx, zero);
    const BtgV3W qx = btgW3(-n.z * px.y, n.z * px.x, ax * kx);
    *p = btgW3Select(px, pz, zAxis);
    *q = btgW3Select(qx, qz, zAxis);
}

/* Point k's normal row (btgSoftNormalRow with the soft step's own spring; normals 1) and its
 * two friction rows (btgSoftFrictionRows along the tangents), lanes. */
static BTG_ALWAYS_INLINE void btgWNormalRow(__global float* c, int k, BtgV3W n, const BtgBodyW* a, const BtgBodyW* b, BtgVelW* va,
                                            BtgVelW* vb, const BtgDeltaW* dA, const BtgDeltaW* dB, int useBias,
                                            BtgSoftParams p, BtgW springMassScale, BtgW springImpulseScale,
                                            BtgW springBiasRate, int8 take)
{
    const BtgW mass = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_MASS));
    const int8 solved = (mass != 0.0f) & take;
    if (!any(solved)) return;
    const BtgV3W rA = btgW3LoadG(c, BTG_WC_AT(k, BTG_WC_AX)), rB = btgW3LoadG(c, BTG_WC_AT(k, BTG_WC_BX));
    /* btgSoftSeparation */
    const BtgV3W pA = btgW3Add(dA->pos, btgW3MatMul(dA->rot, rA));
    const BtgV3W pB = btgW3Add(dB->pos, btgW3MatMul(dB->rot, rB));
    const BtgW sep = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_BASE)) + btgW3Dot(btgW3Sub(pA, pB), n);
    const BtgW old = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_NIMP));
    const int8 open = sep > 0.0f;
    BtgW bias = (BtgW)(0.0f), massScale = (BtgW)(1.0f), impulseScale = (BtgW)(0.0f);
    if (useBias) {
        massScale = springMassScale;
        impulseScale = springImpulseScale;
        bias = massScale * springBiasRate * sep;
        bias = select(bias, (BtgW)(-p.pushSpeed), bias < -p.pushSpeed);
        massScale = select(massScale, (BtgW)(1.0f), open);
        impulseScale = select(impulseScale, (BtgW)(0.0f), open);
    }
    bias = select(bias, sep * p.invH, open);
    const BtgJacobianW j = btgWPointJacobian(n, rA, rB, a, b);
    const BtgW vn = btgWRowVelocity(&j, va, vb);
    BtgW next = old - mass * (massScale * vn + bias) - impulseScale * old;
    next = select((BtgW)(0.0f), next, next > 0.0f);
    next = select(old, next, solved);
    btgWStoreG(c, BTG_WC_AT(k, BTG_WC_NIMP), next);
    const BtgW total = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_TOTN));
    btgWStoreG(c, BTG_WC_AT(k, BTG_WC_TOTN), select(total, total + (next - old), solved));
    const BtgVelW a0 = *va, b0 = *vb;
    btgWRowApply(&j, a, b, va, vb, next - old);
    btgWKeep(va, a0, solved);
    btgWKeep(vb, b0, solved);
}
/* btgRowSolve on the lanes' rows (btgMakeSolverRow's fields): returns the new impulse, the old
 * one where the lane solves no row (`solved` false: its velocities kept too). */
static BTG_ALWAYS_INLINE BtgW btgWRowSolve(const BtgJacobianW* j, BtgW mass, BtgW target, BtgW cfm, BtgW lower, BtgW upper,
                                           BtgW impulse, int8 solved, const BtgBodyW* a, const BtgBodyW* b, BtgVelW* va,
                                           BtgVelW* vb)
{
    BtgW delta = (target - btgWRowVelocity(j, va, vb)) * mass - impulse * cfm;
    const BtgW sum = impulse + delta;
    const int8 below = sum < lower, above = !below & (sum > upper);
    delta = select(select(delta, upper - impulse, above), lower - impulse, below);
    const BtgW next = select(select(sum, upper, above), lower, below);
    const BtgVelW a0 = *va, b0 = *vb;
    btgWRowApply(j, a, b, va, vb, delta);
    btgWKeep(va, a0, solved);
    btgWKeep(vb, b0, solved);
    return select(impulse, next, solved);
}
/* btgSoftFrictionRows (take: the lanes that run them): Gauss-Seidel where the pair stays within
 * the cone, else btgSoftFrictionSlip. */
static BTG_ALWAYS_INLINE void btgWFrictionRows(__global float* c, int k, BtgV3W t1, BtgV3W t2, BtgW friction, const BtgBodyW* a,
                                               const BtgBodyW* b, BtgVelW* va, BtgVelW* vb, int8 take)
{
    const int8 active = (btgWLoadG(c, BTG_WC_AT(k, BTG_WC_MASS)) != 0.0f) & take;
    if (!any(active)) return;
    const BtgW o1 = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_T1IMP)), o2 = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_T2IMP));
    const BtgW m1 = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_T1MASS)), m2 = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_T2MASS));
    const BtgV3W rA = btgW3LoadG(c, BTG_WC_AT(k, BTG_WC_AX)), rB = btgW3LoadG(c, BTG_WC_AT(k, BTG_WC_BX));
    const BtgJacobianW j1 = btgWPointJacobian(t1, rA, rB, a, b);
    const BtgJacobianW j2 = btgWPointJacobian(t2, rA, rB, a, b);
    const BtgW slip1 = btgWRowVelocity(&j1, va, vb), slip2 = btgWRowVelocity(&j2, va, vb);
    const BtgW zero = (BtgW)(0.0f), unbounded = (BtgW)(BTG_SOFT_FRICTION_FREE);
    const int8 row1 = active & (m1 != 0.0f), row2 = active & (m2 != 0.0f);
    BtgW n1 = any(row1) ? btgWRowSolve(&j1, m1, zero, zero, -unbounded, unbounded, o1, row1, a, b, va, vb) : o1;
    BtgW d2 = (0.0f - btgWRowVelocity(&j2, va, vb)) * m2 - o2 * 0.0f;
    d2 = select(zero, d2, row2);
    BtgW n2 = select(o2, o2 + d2, row2);
    /* btgSoftFrictionCone, btgSoftFrictionSlip */
    const BtgW lim = friction * btgWLoadG(c, BTG_WC_AT(k, BTG_WC_NIMP));
    const int8 slipping = (n1 * n1 + n2 * n2 > lim * lim) & row1;
    if (any(slipping)) {
        const int8 two = m2 != 0.0f;
        const BtgW m = select(m1, 2.0f * m1 * m2 / (m1 + m2), two);
        const BtgW s1 = o1 - m * slip1, s2 = select(o2, o2 - m * slip2, two);
        const int8 over = s1 * s1 + s2 * s2 > lim * lim;
        const BtgW scale = lim / sqrt(s1 * s1 + s2 * s2);
        const BtgW c1 = select(s1, s1 * scale, over), c2 = select(s2, s2 * scale, over);
        const BtgVelW a0 = *va, b0 = *vb;
        btgWRowApply(&j1, a, b, va, vb, c1 - n1);
        btgWKeep(va, a0, slipping);
        btgWKeep(vb, b0, slipping);
        d2 = select(d2, c2 - o2, slipping);
        n1 = select(n1, c1, slipping);
        n2 = select(n2, c2, slipping);
    }
    const int8 apply2 = active & ((m2 != 0.0f) | (d2 != 0.0f));
    if (any(apply2)) {
        const BtgVelW a0 = *va, b0 = *vb;
        btgWRowApply(&j2, a, b, va, vb, d2);
        btgWKeep(va, a0, apply2);
        btgWKeep(vb, b0, apply2);
    }
    btgWStoreG(c, BTG_WC_AT(k, BTG_WC_T1IMP), select(o1, n1, active));
    btgWStoreG(c, BTG_WC_AT(k, BTG_WC_T2IMP), select(o2, n2, active));
    const BtgW s1 = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_TOT1)), s2 = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_TOT2));
    btgWStoreG(c, BTG_WC_AT(k, BTG_WC_TOT1), select(s1, s1 + (n1 - o1), active));
    btgWStoreG(c, BTG_WC_AT(k, BTG_WC_TOT2), select(s2, s2 + (n2 - o2), active));
}

/* btgSoftCarriedTotals, lanes */
static BTG_ALWAYS_INLINE void btgWCarriedTotals(__global float* c, int normal, int friction)
{
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        const int8 active = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_MASS)) != 0.0f;
        if (normal) {
            const BtgW t = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_TOTN));
            btgWStoreG(c, BTG_WC_AT(k, BTG_WC_TOTN), select(t, t + btgWLoadG(c, BTG_WC_AT(k, BTG_WC_NIMP)), active));
        }
        if (!friction) continue;
        const BtgW t1 = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_TOT1)), t2 = btgWLoadG(c, BTG_WC_AT(k, BTG_WC_TOT2));
        btgWStoreG(c, BTG_WC_AT(k, BTG_WC_TOT1), select(t1, t1 + btgWLoadG(c, BTG_WC_AT(k, BTG_WC_T1IMP)), active));
        btgWStoreG(c, BTG_WC_AT(k, BTG_WC_TOT2), select(t2, t2 + btgWLoadG(c, BTG_WC_AT(k, BTG_WC_T2IMP)), active));
    }
}

/* btgSoftSolve for the lanes: the normal rows point by point (soft while biased; twice in the
 * relax where a lane has two or more solved points), then, in the relax (or with
 * frictionInSolve), the friction rows; in the relax, the impacts' lanes again for their other
 * rounds (btgSoftRelaxRounds), the other lanes kept. */
static BTG_ALWAYS_INLINE void btgWSoftSolve(__global float* c, const BtgBodyW* a, const BtgBodyW* b, BtgVelW* va, BtgVelW* vb,
                                            const BtgDeltaW* dA, const BtgDeltaW* dB, int useBias, BtgSoftParams p)
{
    const BtgV3W n = btgW3LoadG(c, BTG_WC_NX);
    const int8 fixed = btgWLoadG(c, BTG_WC_FIXED) != 0.0f;
    BtgW ms = (BtgW)(1.0f), is = (BtgW)(0.0f), rate = (BtgW)(0.0f);
    if (useBias) btgWContactSpring(btgWLoadG(c, BTG_WC_STIFFENING), fixed, p, &ms, &is, &rate);
    const int8 all = (int8)(-1);
    /* btgSoftNormalSweeps: the relax's second pass, in the lanes with two or more solved points */
    int8 solvedPoints = (int8)(0);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) solvedPoints -= btgWLoadG(c, BTG_WC_AT(k, BTG_WC_MASS)) != 0.0f;
    const int8 multi = solvedPoints > 1;
    const int8 impact = btgWLoadG(c, BTG_WC_IMPACT) != 0.0f;
    const int friction = !useBias || p.frictionInSolve;
    BtgV3W t1, t2;
    if (friction) btgWPlaneSpace(n, &t1, &t2);
    const BtgW frictionCoefficient = btgWLoadG(c, BTG_WC_FRICTION);
    for (int round = 0; round < (useBias ? 1 : BTG_SOFT_IMPACT_ROUNDS); ++round) {
        const int8 take = round == 0 ? all : impact;
        if (!any(take)) break;
        for (int k = 0; k < BTG_MAX_POINTS; ++k) btgWNormalRow(c, k, n, a, b, va, vb, dA, dB, useBias, p, ms, is, rate, take);
        if (!useBias && any(multi & take))
            for (int k = 0; k < BTG_MAX_POINTS; ++k)
                btgWNormalRow(c, k, n, a, b, va, vb, dA, dB, useBias, p, ms, is, rate, multi & take);
        if (!friction) continue;
        for (int k = 0; k < BTG_MAX_POINTS; ++k) btgWFrictionRows(c, k, t1, t2, frictionCoefficient, a, b, va, vb, take);
    }
}

#endif
