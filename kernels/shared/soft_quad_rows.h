/* soft_quad_rows.h — one contact's solve and relax rows on four work-items (NVIDIA's GPUs).
 *
 * A soft sweep's colour has a few hundred to a few thousand contacts, one work-item each, and a
 * grid barrier after it: the colour takes as long as one contact's chain of dependent
 * instructions. On the H100 (2026-12-06, cubes 1,000) a relax's twelve rows took about 3 us of
 * a 7.5 us colour and a solve's four about 1 us. Each point's separation, bias and Jacobians do
 * not depend on the velocities the rows change; only the Gauss-Seidel updates do. So four
 * work-items of a warp (a quad) take one contact: work-item q makes point q's separation, bias
 * and Jacobians alongside the others, and then every work-item of the quad runs the points' rows
 * in order, each row's Jacobian and bias fetched from its point's work-item with shfl.sync. The
 * quad's four copies of the velocities and impulses stay equal (the same values in the same
 * order); work-item 0 stores them. The rows are btgSoftNormalRow's and btgSoftFrictionRows'
 * expressions: on the H100 the state hashes of cubes 1,000, 32,768 and 112,500 are those of the
 * one-work-item rows, and SolveSoftLaunch's launch shapes agree bit for bit. The solve stage:
 * 1.71 -> 1.51 ms at cubes 1,000, 4.22 -> 3.78 at 32,768, 3.63 -> 3.48 at 112,500.
 *
 * Only for contacts in order (no SOLVER_RANDMIZE_ORDER, no interleaving), without held pairs or
 * Bullet's friction directions: solve_soft.cl takes the scalar rows for the others. */
#ifndef BTG_SOFT_QUAD_ROWS_H
#define BTG_SOFT_QUAD_ROWS_H
#include "soft_rows.h"

#if defined(BTG_NVIDIA)
/* v of the quad's work-item src (0..3); mask: the quad's four lanes of the warp */
static inline float btgQuadGet(float v, int src, uint mask)
{
    float r;
    __asm__ __volatile__("shfl.sync.idx.b32 %0, %1, %2, 0x1c1f, %3;" : "=f"(r) : "f"(v), "r"(src), "r"(mask));
    return r;
}
static inline BtgFloat4 btgQuadGet3(BtgFloat4 v, int src, uint mask)
{
    return btgMake4(btgQuadGet(v.x, src, mask), btgQuadGet(v.y, src, mask), btgQuadGet(v.z, src, mask), 0.0f);
}
/* point k's Jacobian from its work-item (the linear part, the contact's direction, is every one's) */
static inline BtgJacobian btgQuadJacobian(BtgJacobian j, int k, uint mask)
{
    BtgJacobian r;
    r.linear = j.linear;
    r.angularA = btgQuadGet3(j.angularA, k, mask);
    r.angularB = btgQuadGet3(j.angularB, k, mask);
    r.responseA = btgQuadGet3(j.responseA, k, mask);
    r.responseB = btgQuadGet3(j.responseB, k, mask);
    return r;
}
/* Lane q of v, q known only at run time: by integer masks, not an indexed element (which the
 * compiler would keep in local memory, as btgLane's comment says). */
static inline float btgQuadLane(BtgFloat4 v, int q)
{
    const uint m0 = 0u - (uint)(q == 0), m1 = 0u - (uint)(q == 1), m2 = 0u - (uint)(q == 2), m3 = 0u - (uint)(q == 3);
    return as_float((as_uint(v.x) & m0) | (as_uint(v.y) & m1) | (as_uint(v.z) & m2) | (as_uint(v.w) & m3));
}
static inline BtgFloat4 btgQuadPick4(const BtgFloat4* a, int q)
{
    const uint m0 = 0u - (uint)(q == 0), m1 = 0u - (uint)(q == 1), m2 = 0u - (uint)(q == 2), m3 = 0u - (uint)(q == 3);
    return as_float4((as_uint4(a[0]) & m0) | (as_uint4(a[1]) & m1) | (as_uint4(a[2]) & m2) | (as_uint4(a[3]) & m3));
}

/* btgSoftSolve's rows for a contact in order with normals 1 and the contact's tangents, work-item
 * q of the quad (mask) taking point q's parallel part. */
static BTG_ALWAYS_INLINE void btgSoftSolveQuad(BtgSoftContact* s, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va,
                                               BtgBodyVel* vb, BtgSoftDelta dA, BtgSoftDelta dB, int useBias,
                                               BtgSoftParams p, int q, uint mask)
{
    const int n = s->numPoints;
    const int friction = !useBias || p.frictionInSolve;
    BtgSoftness spring = (s->flags & BTG_SOFT_FIXED) ? p.fixed : p.contact;
    if (useBias && !(s->springStiffness > 0.0f)) spring = btgSoftContactSpring(s, p);
    const BtgFloat4 rA = btgQuadPick4(s->rA, q), rB = btgQuadPick4(s->rB, q);
    /* point q's bias and scales (btgSoftNormalRow's, before its Gauss-Seidel update) */
    const float mass = btgQuadLane(s->normalMass, q);
    const BtgFloat4 pA = btgXyz(dA.pos) + btgMat3MulVec(dA.rot, rA);
    const BtgFloat4 pB = btgXyz(dB.pos) + btgMat3MulVec(dB.rot, rB);
    const float sep = btgQuadLane(s->baseSeparation, q) + btgDot3(pA - pB, s->normal);
    float bias = 0.0f, massScale = 1.0f, impulseScale = 0.0f;
    if (sep > 0.0f) bias = sep * p.invH;
    else if (useBias && s->springStiffness > 0.0f) bias = btgSoftPairSpringBias(s, mass, sep, p, &massScale, &impulseScale);
    else if (useBias) bias = btgSoftSpringBias(spring, sep, p, &massScale, &impulseScale);
    const BtgJacobian jn = btgPointJacobian(s->normal, rA, rB, a, b);
    const int sweeps = btgSoftNormalSweeps(s, useBias);
    /* btgSoftSolve's rounds (an impact's relax) */
    const int rounds = btgSoftRelaxRounds(s, useBias, 1);
    for (int round = 0; round < rounds; ++round) {
        for (int pass = 0; pass < sweeps; ++pass) {
            BTG_FOR_POINTS(k, n) {
                const float mk = btgLane(s->normalMass, k);
                if (mk == 0.0f) continue;
                const BtgJacobian j = btgQuadJacobian(jn, k, mask);
                const float bk = btgQuadGet(bias, k, mask), msk = btgQuadGet(massScale, k, mask);
                const float isk = btgQuadGet(impulseScale, k, mask);
                const float old = btgLane(s->normalImpulse, k);
                const float vn = btgRowVelocity(j, *va, *vb);
                float next = old - mk * (msk * vn + bk) - isk * old;
                if (!(next > 0.0f)) next = 0.0f;
                btgSetLane(&s->normalImpulse, k, next);
                btgSetLane(&s->totalNormal, k, btgLane(s->totalNormal, k) + (next - old));
                btgRowApply(j, a, b, va, vb, next - old);
            }
        }
        if (!friction) continue;
        const BtgJacobian j1 = btgPointJacobian(s->tangent1, rA, rB, a, b);
        const BtgJacobian j2 = btgPointJacobian(s->tangent2, rA, rB, a, b);
        BTG_FOR_POINTS(k, n) {
            if (btgLane(s->normalMass, k) == 0.0f) continue;
            /* btgSoftFrictionRows' rows on the fetched Jacobians */
            const float o1 = btgLane(s->tangent1Impulse, k), o2 = btgLane(s->tangent2Impulse, k);
            const BtgJacobian k1 = btgQuadJacobian(j1, k, mask);
            const BtgJacobian k2 = btgQuadJacobian(j2, k, mask);
            float n1, n2;
            btgSoftFrictionPair(k1, k2, btgLane(s->tangent1Mass, k), btgLane(s->tangent2Mass, k), o1, o2,
                                s->friction * btgLane(s->normalImpulse, k), a, b, va, vb, &n1, &n2);
            btgSetLane(&s->tangent1Impulse, k, n1);
            btgSetLane(&s->tangent2Impulse, k, n2);
            btgSetLane(&s->total1, k, btgLane(s->total1, k) + (n1 - o1));
            btgSetLane(&s->total2, k, btgLane(s->total2, k) + (n2 - o2));
        }
    }
}
#endif

#endif
