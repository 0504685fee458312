/* pgs_wide_passes.h — solve_constraints.cl's wide velocity sweeps for CPU devices (pgs_wide.h's
 * rows): the kernels pgs_wide_offsets, pgs_wide_pack, pgs_wide_unpack and solve_color_wide. Not
 * a header of its own: solve_constraints.cl includes it under BTG_CPU_DEVICE (a GPU's build never
 * sees it), where load_body is defined. pgs_wide_bodies makes each body's record once a step.
 * The regular colours' slots of list 0 (every contact) go in chunks of eight (wide_chunks.h);
 * pgs_wide_pack puts each contact into its chunk's block of lanes once a step, the warm-start,
 * normal and friction sweeps then work on the blocks, and pgs_wide_unpack puts the impulses back
 * into the contacts after the step's last velocity sweep. The push sweeps (list 1) read the
 * contacts themselves, whose push rows the velocity sweeps never change; the leftovers and the
 * joints are solved in place as before. */
#ifndef BTG_PGS_WIDE_PASSES_H
#define BTG_PGS_WIDE_PASSES_H
#include "pgs_wide.h"
#include "wide_chunks.h"

/* ints a lane of a chunk: live (1) or empty, body A, body B (each eight a chunk) */
#define PGS_WIDE_INFO 3
#define PGS_WIDE_ARGS __global const uint* restrict wideStart, __global float* wideBlock, __global int* wideLanes
#define PGS_WIDE_PASS wideStart, wideBlock, wideLanes

__kernel void pgs_wide_offsets(__global const uint* restrict colorStart, __global uint* wideStart, int numColors)
{
    if (get_global_id(0) == 0) btgWideOffsets(colorStart, wideStart, numColors);
}
__kernel void pgs_wide_pack(__global const BtgContact* restrict contacts, __global const uint* restrict colorStart,
                            __global const int* restrict colorOrder, int numColors, PGS_WIDE_ARGS)
{
    const int k = (int)get_global_id(0);
    if (k >= (int)colorStart[numColors - 1]) return; /* list 0's regular colours */
    const int2 at = btgWideChunkOf(k, colorStart, wideStart);
    __global const BtgContact* c = contacts + colorOrder[k];
    __global float* block = wideBlock + at.x * BTG_PW_FIELDS * BTG_SOFT_WIDE;
    __global int* info = wideLanes + at.x * PGS_WIDE_INFO * BTG_SOFT_WIDE;
    info[at.y] = 1;
    info[BTG_SOFT_WIDE + at.y] = c->bodyA;
    info[2 * BTG_SOFT_WIDE + at.y] = c->bodyB;
    btgPwPutContact(block, at.y, c);
    if (!btgWideLastOfColor(k, colorStart)) return;
    for (int l = at.y + 1; l < BTG_SOFT_WIDE; ++l) {
        info[l] = 0;
        info[BTG_SOFT_WIDE + l] = 0;
        info[2 * BTG_SOFT_WIDE + l] = 0;
        btgPwPutContact(block, l, 0);
    }
}
__kernel void pgs_wide_unpack(__global BtgContact* contacts, __global const uint* restrict colorStart,
                              __global const int* restrict colorOrder, int numColors, PGS_WIDE_ARGS)
{
    const int k = (int)get_global_id(0);
    if (k >= (int)colorStart[numColors - 1]) return;
    const int2 at = btgWideChunkOf(k, colorStart, wideStart);
    __global const float* block = wideBlock + at.x * BTG_PW_FIELDS * BTG_SOFT_WIDE;
    __global BtgContact* c = contacts + colorOrder[k];
    const int points = c->numPoints;
    c->normalImpulse = btgPwPoints(block, at.y, BTG_PW_NIMP, points, c->normalImpulse);
    c->friction1Impulse = btgPwPoints(block, at.y, BTG_PW_F1IMP, points, c->friction1Impulse);
    c->friction2Impulse = btgPwPoints(block, at.y, BTG_PW_F2IMP, points, c->friction2Impulse);
}

/* Each body's solver record for the step's wide sweeps, four rows as btgWSolverBody reads them
 * (load_body's fields: the inverse inertia rows with w the inverse mass and the linear factor,
 * the angular factor), and its kind (3 dynamic, 1 moving, 0 fixed): one 64-byte line a body where
 * load_body reads two lines of its props and the inertia rows (one work-item a body, once a
 * step: the sweeps change none of it). */
__kernel void pgs_wide_bodies(int numBodies, __global const BtgBodyProps* restrict props,
                              __global const BtgFloat4* restrict invInertiaWorld, __global BtgFloat4* record,
                              __global int* kinds)
{
    const int i = (int)get_global_id(0);
    if (i >= numBodies) return;
    const BtgSolverBody b = load_body(props, invInertiaWorld, i);
    record[4 * i] = btgMake4(b.invI.r0.x, b.invI.r0.y, b.invI.r0.z, b.invMass);
    record[4 * i + 1] = btgMake4(b.invI.r1.x, b.invI.r1.y, b.invI.r1.z, b.linFactor.x);
    record[4 * i + 2] = btgMake4(b.invI.r2.x, b.invI.r2.y, b.invI.r2.z, b.linFactor.y);
    record[4 * i + 3] = btgMake4(b.angFactor.x, b.angFactor.y, b.angFactor.z, b.linFactor.z);
    kinds[i] = b.dynamic ? 3 : (b.moving ? 1 : 0);
}
/* Body i's rows (its record, then its velocities with w the kind); an empty lane's are a fixed
 * body at rest. */
static BTG_ALWAYS_INLINE void pgs_wide_body(__global const BtgFloat4* restrict record, __global const int* restrict kinds,
                                            __global const BtgFloat4* lin, __global const BtgFloat4* ang, int i,
                                            int live, BtgFloat4* rows)
{
    if (!live) {
        for (int r = 0; r < 6; ++r) rows[r] = btgZero4();
        return;
    }
    for (int r = 0; r < 4; ++r) rows[r] = record[4 * i + r];
    const BtgFloat4 v = lin[i];
    rows[4] = btgMake4(v.x, v.y, v.z, (float)kinds[i]);
    rows[5] = ang[i];
}
/* The lanes' velocities back to their dynamic bodies (store_velocity's: w kept). */
static void pgs_wide_store(const BtgVelW* v, BtgW kinds, __global const int* body, const int* live,
                           __global BtgFloat4* lin, __global BtgFloat4* ang)
{
    float x[7 * BTG_SOFT_WIDE];
    btgWVelLanes(v, kinds, x);
    for (int l = 0; l < BTG_SOFT_WIDE; ++l) {
        if (!live[l] || !(x[6 * BTG_SOFT_WIDE + l] >= 2.0f)) continue;
        const int i = body[l];
        lin[i] = btgMake4(x[l], x[BTG_SOFT_WIDE + l], x[2 * BTG_SOFT_WIDE + l], lin[i].w);
        ang[i] = btgMake4(x[3 * BTG_SOFT_WIDE + l], x[4 * BTG_SOFT_WIDE + l], x[5 * BTG_SOFT_WIDE + l], ang[i].w);
    }
}

/* Chunk `chunk`'s lanes through one velocity sweep (mode: warm start, normals or friction). next:
 * the work-item's next chunk (-1: none), whose bodies are read ahead. */
static void pgs_wide_chunk(int chunk, int next, int mode, int twoFriction, PGS_WIDE_ARGS,
                           __global const BtgFloat4* restrict record, __global const int* restrict kinds,
                           __global BtgFloat4* lin, __global BtgFloat4* ang)
{
    __global const int* info = wideLanes + chunk * PGS_WIDE_INFO * BTG_SOFT_WIDE;
    __global float* block = wideBlock + chunk * BTG_PW_FIELDS * BTG_SOFT_WIDE;
    int live[BTG_SOFT_WIDE], any = 0;
    for (int l = 0; l < BTG_SOFT_WIDE; ++l) {
        live[l] = info[l];
        any |= live[l];
    }
    if (!any) return;
    /* the next chunk's bodies read ahead: their rows sit anywhere in memory */
    if (next >= 0) {
        __global const int* nextInfo = wideLanes + next * PGS_WIDE_INFO * BTG_SOFT_WIDE;
        for (int l = 0; l < BTG_SOFT_WIDE; ++l) {
            for (int s = 1; s <= 2; ++s) {
                const int i = nextInfo[s * BTG_SOFT_WIDE + l];
                btgPrefetch(record + 4 * i);
                btgPrefetch(lin + i);
                btgPrefetch(ang + i);
            }
        }
    }
    BtgFloat4 rowsA[BTG_SOFT_WIDE * 8], rowsB[BTG_SOFT_WIDE * 8];
    for (int l = 0; l < BTG_SOFT_WIDE; ++l) {
        pgs_wide_body(record, kinds, lin, ang, info[BTG_SOFT_WIDE + l], live[l], rowsA + 8 * l);
        pgs_wide_body(record, kinds, lin, ang, info[2 * BTG_SOFT_WIDE + l], live[l], rowsB + 8 * l);
    }
    BtgBodyW a, b;
    BtgVelW va, vb;
    BtgW kindA, kindB;
    btgWSolverBody(rowsA, &a, &va, &kindA);
    btgWSolverBody(rowsB, &b, &vb, &kindB);
    if (mode == BTG_PASS_WARM_START) btgPwWarmStart(block, &a, &b, &va, &vb, twoFriction);
    else if (mode == BTG_PASS_NORMALS) btgPwNormals(block, &a, &b, &va, &vb);
    else btgPwFriction(block, &a, &b, &va, &vb, twoFriction);
    pgs_wide_store(&va, kindA, info + BTG_SOFT_WIDE, live, lin, ang);
    pgs_wide_store(&vb, kindB, info + 2 * BTG_SOFT_WIDE, live, lin, ang);
}
/* A colour's velocity sweep, each work-item a run of consecutive chunks (their blocks stream
 * through memory in order). */
__kernel void solve_color_wide(__global const uint* restrict colorStart, PGS_WIDE_ARGS, int color, int mode,
                               int twoFriction, __global const BtgFloat4* restrict record,
                               __global const int* restrict kinds, __global BtgFloat4* lin, __global BtgFloat4* ang)
{
    const int chunks = (int)(wideStart[color + 1] - wideStart[color]);
    const int2 run = btgWideRun(chunks, (int)get_global_id(0), (int)get_global_size(0));
    for (int m = run.x; m < run.y; ++m)
        pgs_wide_chunk((int)wideStart[color] + m, m + 1 < run.y ? (int)wideStart[color] + m + 1 : -1, mode, twoFriction,
                       PGS_WIDE_PASS, record, kinds, lin, ang);
}

#endif
