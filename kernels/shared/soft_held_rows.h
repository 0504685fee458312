/* soft_held_rows.h — the soft step's opt-in cure for a light body under a heavy one
 * (SoftStepConfig::heldMassRatio, 0 by default): the light body held, its load passed to its
 * support. Split from soft_rows.h, whose contacts and rows it builds on. Shared by
 * kernels/solve_soft.cl and its CPU reference. */
#ifndef BTG_SOFT_HELD_ROWS_H
#define BTG_SOFT_HELD_ROWS_H
#include "soft_rows.h"

/* The support a held pair reads and writes: another work-group's soft contact, volatile where
 * BTG_SHARED is (solve_soft.cl keeps it volatile on NVIDIA's GPUs, where it reads the rest of
 * its shared data with btgLoadShared4 instead). */
#ifndef BTG_HELD_GLOBAL
#define BTG_HELD_GLOBAL BTG_SHARED_GLOBAL
#endif

/* ---- a light body under a heavy one (SoftStepConfig::heldMassRatio) ---- */

/* A body as a held contact's rows see it: its velocity read, nothing applied to it. */
static inline BtgSolverBody btgSoftHeldBody(BtgSolverBody b)
{
    b.invMass = 0.0f;
    b.invMassLin = btgZero4();
    b.invI.r0 = btgZero4();
    b.invI.r1 = btgZero4();
    b.invI.r2 = btgZero4();
    return b;
}

/* 1: A is the light body of a pair of dynamic bodies whose inverse masses differ by more than
 * heldMassRatio, 2: B, 0: neither. */
static inline int btgSoftLightSide(BtgSolverBody a, BtgSolverBody b, BtgSoftParams p)
{
    if (!(p.heldMassRatio > 0.0f) || !a.dynamic || !b.dynamic) return 0;
    if (a.invMass > p.heldMassRatio * b.invMass) return 1;
    if (b.invMass > p.heldMassRatio * a.invMass) return 2;
    return 0;
}

/* Prepare's note in a body's BTG_SOFT_SUPPORT row (one edge at a time: prepare runs color by
 * color while heldMassRatio is on): edge e is a contact of this body with a fixed one (fixed),
 * or holds it (held: it is the light side of a pair above heldMassRatio). */
static inline BtgFloat4 btgSoftNoteSupport(BtgFloat4 row, int fixed, int held, int e)
{
    return btgMake4(row.x + (fixed ? 1.0f : 0.0f), fixed ? (float)e : row.y, held ? 1.0f : row.z, 0.0f);
}

/* Where a held body's support (its one contact with a fixed body, on the side opposite the
 * held contact) takes the loads handed to it: per point the lever of its push on the light
 * body about the two tangents, and the three sums' Gram matrix inverted (least norm). Valid
 * (returns 1) with at least three points spanning a torque and the support pushing against
 * the held contact's normal. */
typedef struct {
    float arm1[BTG_MAX_POINTS];
    float arm2[BTG_MAX_POINTS];
    float inv[6]; /* the Gram matrix's adjugate over its determinant: 00 01 02 11 12 22 */
    BtgFloat4 dg; /* the support's push on the light body */
    BtgFloat4 e1, e2;
    int points;
} BtgSoftShare;

static inline int btgSoftMakeShare(BtgSoftShare* h, BTG_HELD_GLOBAL const BtgSoftContact* support, int light,
                                   BtgFloat4 dt)
{
    const int supportA = support->bodyA == light;
    h->dg = supportA ? support->normal : -support->normal;
    h->e1 = support->tangent1;
    h->e2 = support->tangent2;
    if (btgDot3(h->dg, dt) > -0.5f) return 0;
    float g00 = 0.0f, g01 = 0.0f, g02 = 0.0f, g11 = 0.0f, g12 = 0.0f, g22 = 0.0f;
    h->points = 0;
    for (int j = 0; j < BTG_MAX_POINTS; ++j) {
        h->arm1[j] = 0.0f;
        h->arm2[j] = 0.0f;
        if (j >= support->numPoints || btgLane(support->normalMass, j) == 0.0f) continue;
        BtgFloat4 c = btgCross3(supportA ? support->rA[j] : support->rB[j], h->dg);
        h->arm1[j] = btgDot3(c, h->e1);
        h->arm2[j] = btgDot3(c, h->e2);
        g00 += 1.0f;
        g01 += h->arm1[j];
        g02 += h->arm2[j];
        g11 += h->arm1[j] * h->arm1[j];
        g12 += h->arm1[j] * h->arm2[j];
        g22 += h->arm2[j] * h->arm2[j];
        ++h->points;
    }
    const float c00 = g11 * g22 - g12 * g12, c01 = g02 * g12 - g01 * g22, c02 = g01 * g12 - g02 * g11;
    const float det = g00 * c00 + g01 * c01 + g02 * c02, lever = g11 + g22;
    if (h->points < 3 || !(det > 1e-6f * lever * lever)) return 0;
    h->inv[0] = c00 / det;
    h->inv[1] = c01 / det;
    h->inv[2] = c02 / det;
    h->inv[3] = (g00 * g22 - g02 * g02) / det;
    h->inv[4] = (g01 * g02 - g00 * g12) / det;
    h->inv[5] = (g00 * g11 - g01 * g01) / det;
    return 1;
}

/* The support's point impulse changes d_j that push the light body back with force along dg
 * and torque (about its centre) as the held contact's changes force (along dt) and torque push
 * it: least norm, and of four points the free share (the null vector of the three sums) taken
 * nearest zero that keeps every point's impulse (from `base`) at or above zero, so that no
 * clamp breaks the balance (a lone loaded corner above would otherwise ask one below to pull). */
static inline void btgSoftShareOut(const BtgSoftShare* h, BTG_HELD_GLOBAL const BtgSoftContact* support, BtgFloat4 base,
                                   float force, BtgFloat4 dt, BtgFloat4 torque, float* delta)
{
    const float b0 = -force * btgDot3(dt, h->dg), b1 = -btgDot3(torque, h->e1), b2 = -btgDot3(torque, h->e2);
    const float y0 = h->inv[0] * b0 + h->inv[1] * b1 + h->inv[2] * b2;
    const float y1 = h->inv[1] * b0 + h->inv[3] * b1 + h->inv[4] * b2;
    const float y2 = h->inv[2] * b0 + h->inv[4] * b1 + h->inv[5] * b2;
    for (int j = 0; j < BTG_MAX_POINTS; ++j)
        delta[j] = j < support->numPoints && btgLane(support->normalMass, j) != 0.0f ? y0 + y1 * h->arm1[j] + y2 * h->arm2[j]
                                                                                    : 0.0f;
    if (h->points != 4 || support->numPoints != 4) return;
    float u[4];
    for (int j = 0; j < 4; ++j) {
        /* u_j: (-1)^j times the 3x3 minor of the columns (1, arm1, arm2) without column j */
        const int c0 = j == 0 ? 1 : 0, c1 = j <= 1 ? 2 : 1, c2 = j <= 2 ? 3 : 2;
        float m = (h->arm1[c1] * h->arm2[c2] - h->arm2[c1] * h->arm1[c2]) -
                  (h->arm1[c0] * h->arm2[c2] - h->arm2[c0] * h->arm1[c2]) +
                  (h->arm1[c0] * h->arm2[c1] - h->arm2[c0] * h->arm1[c1]);
        u[j] = (j & 1) ? -m : m;
    }
    float lo = -3.0e38f, hi = 3.0e38f;
    for (int j = 0; j < 4; ++j) {
        float room = btgLane(base, j) + delta[j];
        if (u[j] > 0.0f) lo = -room / u[j] > lo ? -room / u[j] : lo;
        else if (u[j] < 0.0f) hi = room / -u[j] < hi ? room / -u[j] : hi;
    }
    float t = lo > hi ? 0.5f * (lo + hi) : (0.0f < lo ? lo : (0.0f > hi ? hi : 0.0f));
    for (int j = 0; j < 4; ++j) delta[j] += t * u[j];
}

/* The normal rows of a light body under a heavy one in the solve and the relax, the light body
 * held (shock propagation). Gauss-Seidel moves the heavy body by only the light one's share of
 * each correction (1,000:1: a thousandth): the load builds over many substeps and the pair, its
 * springs stiffened to maxSag, rings on the support until it falls (README, solver modes; the
 * 1-D model tests/stability/soft_mass_ratio_model.py shows it). Here the heavy body takes each
 * correction whole (a soft row of the contact's spring on its own effective mass, stiffened
 * from the impulse it carries now), and the light body's reaction goes straight into its
 * support, shared out (btgSoftShareOut) so that force and torque on the light body balance when
 * the next substep warm-starts both: the light body is never kicked, so nothing has to catch
 * it. Returns 0 (rows left to btgSoftSolve) where btgSoftMakeShare finds no valid support. */
static inline int btgSoftHeldNormals(BtgSoftContact* s, int lightIsA, BTG_HELD_GLOBAL BtgSoftContact* support,
                                     BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb, BtgSoftDelta dA,
                                     BtgSoftDelta dB, int useBias, BtgSoftParams p)
{
    const BtgSoftness soft = p.contact;
    const BtgFloat4 dt = lightIsA ? s->normal : -s->normal; /* this contact's push on the light body */
    BtgSoftShare share;
    if (!btgSoftMakeShare(&share, support, lightIsA ? s->bodyA : s->bodyB, dt)) return 0;
    const BtgSolverBody ha = lightIsA ? btgSoftHeldBody(a) : a, hb = lightIsA ? b : btgSoftHeldBody(b);
    float force = 0.0f;
    BtgFloat4 torque = btgZero4();
    for (int k = 0; k < s->numPoints; ++k) {
        if (btgLane(s->normalMass, k) == 0.0f) continue;
        float sep = btgSoftSeparation(s, k, dA, dB);
        float old = btgLane(s->normalImpulse, k);
        BtgJacobian j = btgPointJacobian(s->normal, btgSoftArmA(s, k), btgSoftArmB(s, k), ha, hb);
        float mass = btgPointRowMass(j, btgSoftArmA(s, k), btgSoftArmB(s, k), ha, hb);
        float bias = 0.0f, massScale = 1.0f, impulseScale = 0.0f;
        if (sep > 0.0f) {
            bias = sep * p.invH;
        } else if (useBias) {
            massScale = soft.massScale;
            impulseScale = soft.impulseScale;
            float r = p.maxSag > 0.0f ? old / (mass * p.h * p.omega2Contact * p.maxSag) : 1.0f;
            if (r > 1.0f) {
                float a2 = r * soft.stiffness;
                btgSoftScales(a2, &massScale, &impulseScale);
            }
            bias = massScale * soft.biasRate * sep;
            if (bias < -p.pushSpeed) bias = -p.pushSpeed;
        }
        float next = old - mass * (massScale * btgRowVelocity(j, *va, *vb) + bias) - impulseScale * old;
        if (!(next > 0.0f)) next = 0.0f;
        btgSetLane(&s->normalImpulse, k, next);
        btgSetLane(&s->totalNormal, k, btgLane(s->totalNormal, k) + (next - old));
        btgRowApply(j, ha, hb, va, vb, next - old);
        force += next - old;
        torque = torque + btgCross3(lightIsA ? btgSoftArmA(s, k) : btgSoftArmB(s, k), dt) * (next - old);
    }
    BtgFloat4 impulse = support->normalImpulse, total = support->totalNormal;
    float delta[BTG_MAX_POINTS];
    btgSoftShareOut(&share, support, impulse, force, dt, torque, delta);
    BTG_UNROLL
    for (int j = 0; j < BTG_MAX_POINTS; ++j) {
        if (j >= support->numPoints || btgLane(support->normalMass, j) == 0.0f) continue;
        float old = btgLane(impulse, j), next = old + delta[j];
        if (!(next > 0.0f)) next = 0.0f;
        btgSetLane(&impulse, j, next);
        btgSetLane(&total, j, btgLane(total, j) + (next - old));
    }
    support->normalImpulse = impulse;
    support->totalNormal = total;
    return 1;
}

#endif
