/* soft_wide_passes.h — solve_soft.cl's wide sweeps for CPU devices (soft_wide.h's rows): the
 * kernels soft_wide_offsets, soft_wide_pack, soft_wide_unpack and soft_color_wide, and the chunk
 * and slot functions soft_resident shares with them. Not a header of its own: solve_soft.cl
 * includes it where SOFT_ARGS, soft_edge and the body loads are defined, under BTG_CPU_DEVICE
 * (a GPU's build never sees it). */
#ifndef BTG_SOFT_WIDE_PASSES_H
#define BTG_SOFT_WIDE_PASSES_H
#include "wide_chunks.h"
/* ---- CPU devices: the solve and relax sweeps eight contacts at a time (soft_wide.h) ----
 * The regular colours' slots in chunks of eight (colour c's chunk m: slots colorStart[c] + 8m..,
 * at wideStart[c] + m); soft_wide_pack puts each contact the wide rows serve into its chunk's
 * block of lanes once a step (after the first substep's warm-start gather, which reads and
 * writes the soft contacts), the sweeps then work on the blocks, and soft_wide_unpack puts the
 * impulses and totals back before restitution. Every other edge of a chunk (a joint, a contact
 * with its own spring or Bullet's directions) stays with soft_edge, lane mode 0. */
__kernel void soft_wide_offsets(__global const uint* restrict colorStart, __global uint* wideStart, int numColors)
{
    if (get_global_id(0) == 0) btgWideOffsets(colorStart, wideStart, numColors);
}
static void wide_pack_slot(int k, __global const uint* restrict colorStart, __global const int* restrict colorOrder,
                           int nc, WIDE_ARGS, __global const BtgSoftContact* softContacts)
{
    const int2 at = btgWideChunkOf(k, colorStart, wideStart);
    const int e = colorOrder[k];
    __global const BtgSoftContact* s = softContacts + k;
    const int wide = e < nc && !(s->springStiffness > 0.0f) && !(s->flags & BTG_SOFT_BULLET_DIRECTIONS);
    __global float* block = wideBlock + at.x * BTG_WC_FIELDS * BTG_SOFT_WIDE;
    __global int* info = wideLanes + at.x * WIDE_INFO * BTG_SOFT_WIDE;
    info[at.y] = wide;
    info[BTG_SOFT_WIDE + at.y] = wide ? s->bodyA : 0;
    info[2 * BTG_SOFT_WIDE + at.y] = wide ? s->bodyB : 0;
    btgWPutContact(block, at.y, wide ? s : 0);
    /* the colour's last slot empties the rest of its chunk */
    if (!btgWideLastOfColor(k, colorStart)) return;
    for (int l = at.y + 1; l < BTG_SOFT_WIDE; ++l) {
        info[l] = 0;
        btgWPutContact(block, l, 0);
    }
}
static void wide_unpack_slot(int k, __global const uint* restrict colorStart, WIDE_ARGS,
                             __global BtgSoftContact* softContacts)
{
    const int2 at = btgWideChunkOf(k, colorStart, wideStart);
    if (!wideLanes[at.x * WIDE_INFO * BTG_SOFT_WIDE + at.y]) return;
    __global const float* block = wideBlock + at.x * BTG_WC_FIELDS * BTG_SOFT_WIDE;
    softContacts[k].normalImpulse = btgWPoints(block, at.y, BTG_WC_NIMP);
    softContacts[k].totalNormal = btgWPoints(block, at.y, BTG_WC_TOTN);
    softContacts[k].tangent1Impulse = btgWPoints(block, at.y, BTG_WC_T1IMP);
    softContacts[k].tangent2Impulse = btgWPoints(block, at.y, BTG_WC_T2IMP);
    softContacts[k].total1 = btgWPoints(block, at.y, BTG_WC_TOT1);
    softContacts[k].total2 = btgWPoints(block, at.y, BTG_WC_TOT2);
}
__kernel void soft_wide_pack(__global const uint* restrict colorStart, __global const int* restrict colorOrder,
                             WIDE_ARGS, int edgeCapacity, int numJoints, int numColors, SOFT_ARGS)
{
    const int k = (int)get_global_id(0);
    if (k >= (int)colorStart[numColors - 1]) return; /* the regular colours' slots only */
    wide_pack_slot(k, colorStart, colorOrder, contact_edges(counters, edgeCapacity, numJoints), WIDE_PASS, softContacts);
}
__kernel void soft_wide_unpack(__global const uint* restrict colorStart, WIDE_ARGS, int numColors,
                               __global BtgSoftContact* softContacts)
{
    const int k = (int)get_global_id(0);
    if (k >= (int)colorStart[numColors - 1]) return;
    wide_unpack_slot(k, colorStart, WIDE_PASS, softContacts);
}
/* The eight rows of body i a lane takes (the solver record, then velocity and deltas), read
 * for all the chunk's lanes before any is put into lanes: their cache misses then overlap. */
static BTG_ALWAYS_INLINE void wide_load_body(__global const BtgFloat4* restrict softSolver,
                                             BTG_SHARED __global BtgFloat4* softBodies, int i, BtgFloat4* rows)
{
    const int r = BTG_SOFT_BODY_ROWS * i, s = BTG_SOFT_SOLVER_ROWS * i;
    rows[0] = softSolver[s];
    rows[1] = softSolver[s + 1];
    rows[2] = softSolver[s + 2];
    rows[3] = softSolver[s + 3];
    rows[4] = btgLoadShared4(&softBodies[r + BTG_SOFT_VEL_LIN]);
    rows[5] = btgLoadShared4(&softBodies[r + BTG_SOFT_VEL_ANG]);
    rows[6] = btgLoadShared4(&softBodies[r + BTG_SOFT_DELTA_POS]);
    rows[7] = btgLoadShared4(&softBodies[r + BTG_SOFT_DELTA_ROT]);
}
/* The lanes' velocities back to the dynamic bodies' rows (store_vel's; w of VEL_LIN the kind). */
static void wide_store_vels(const BtgVelW* v, BtgW kinds, __global const int* body, const int* wide,
                            BTG_SHARED __global BtgFloat4* softBodies)
{
    float x[7 * BTG_SOFT_WIDE];
    btgWVelLanes(v, kinds, x);
    for (int l = 0; l < BTG_SOFT_WIDE; ++l) {
        const float kind = x[6 * BTG_SOFT_WIDE + l];
        if (!wide[l] || !(kind >= 2.0f)) continue;
        const int r = BTG_SOFT_BODY_ROWS * body[l];
        softBodies[r + BTG_SOFT_VEL_LIN] = btgMake4(x[l], x[BTG_SOFT_WIDE + l], x[2 * BTG_SOFT_WIDE + l], kind);
        softBodies[r + BTG_SOFT_VEL_ANG] =
            btgMake4(x[3 * BTG_SOFT_WIDE + l], x[4 * BTG_SOFT_WIDE + l], x[5 * BTG_SOFT_WIDE + l], 0.0f);
    }
}

/* Chunk m of colour `color` (slots begin.., end its colour's end) in a solve or relax sweep: its
 * scalar edges through soft_edge (one colour's edges share no dynamic body: the order within it
 * changes nothing), its wide lanes through soft_wide.h's rows on the chunk's block. next: the
 * work-item's next chunk of the colour (-1: none), whose bodies are read ahead. */
static void soft_wide_chunk(int color, int m, int next, int begin, int end, __global const int* restrict colorOrder,
                            WIDE_ARGS, int nc, int mode, uint key, SOFT_FN_ARGS)
{
    SOFT_FN_PARAMS
    const int base = btgSoftBaseMode(mode);
    const int k0 = begin + m * BTG_SOFT_WIDE, chunk = (int)wideStart[color] + m;
    __global const int* info = wideLanes + chunk * WIDE_INFO * BTG_SOFT_WIDE;
    __global float* block = wideBlock + chunk * BTG_WC_FIELDS * BTG_SOFT_WIDE;
    int wide[BTG_SOFT_WIDE], any = 0;
    for (int l = 0; l < BTG_SOFT_WIDE; ++l) {
        wide[l] = k0 + l < end && info[l];
        any |= wide[l];
        if (k0 + l < end && !wide[l]) soft_edge(colorOrder[k0 + l], k0 + l, nc, mode, key, SOFT_FN_PASS);
    }
    if (!any) return;
    /* the work-item's next chunk's bodies read ahead: their rows sit anywhere in memory, and
     * waiting for them was a fifth of the sweep */
    if (next >= 0) {
        __global const int* nextInfo = wideLanes + ((int)wideStart[color] + next) * WIDE_INFO * BTG_SOFT_WIDE;
        for (int l = 0; l < BTG_SOFT_WIDE; ++l) {
            const int ia = nextInfo[BTG_SOFT_WIDE + l], ib = nextInfo[2 * BTG_SOFT_WIDE + l];
            btgPrefetch(softBodies + BTG_SOFT_BODY_ROWS * ia);
            btgPrefetch(softSolver + BTG_SOFT_SOLVER_ROWS * ia);
            btgPrefetch(softBodies + BTG_SOFT_BODY_ROWS * ib);
            btgPrefetch(softSolver + BTG_SOFT_SOLVER_ROWS * ib);
        }
    }
    BtgFloat4 rowsA[BTG_SOFT_WIDE * 8], rowsB[BTG_SOFT_WIDE * 8];
    for (int l = 0; l < BTG_SOFT_WIDE; ++l) {
        if (!wide[l]) {
            btgWEmptyRows(rowsA + 8 * l);
            btgWEmptyRows(rowsB + 8 * l);
            continue;
        }
        wide_load_body(softSolver, softBodies, info[BTG_SOFT_WIDE + l], rowsA + 8 * l);
        wide_load_body(softSolver, softBodies, info[2 * BTG_SOFT_WIDE + l], rowsB + 8 * l);
    }
    BtgBodyW a, b;
    BtgVelW va, vb;
    BtgDeltaW dA, dB;
    BtgW kindA, kindB;
    btgWBody(rowsA, &a, &va, &dA, &kindA);
    btgWBody(rowsB, &b, &vb, &dB, &kindB);
    if (mode & BTG_SOFT_WARM_TOTALS)
        btgWCarriedTotals(block, base == BTG_SOFT_SOLVE, params.frictionInSolve ? base == BTG_SOFT_SOLVE : base == BTG_SOFT_RELAX);
    btgWSoftSolve(block, &a, &b, &va, &vb, &dA, &dB, base == BTG_SOFT_SOLVE, params);
    wide_store_vels(&va, kindA, info + BTG_SOFT_WIDE, wide, softBodies);
    wide_store_vels(&vb, kindB, info + 2 * BTG_SOFT_WIDE, wide, softBodies);
}
/* A colour's solve or relax sweep, each work-item a run of consecutive chunks (their blocks
 * stream through memory in order). */
__kernel void soft_color_wide(__global const uint* restrict colorStart, __global const int* restrict colorOrder,
                              WIDE_ARGS, int edgeCapacity, int numJoints, int color, int mode, uint key, SOFT_ARGS)
{
    const int begin = (int)colorStart[color], end = (int)colorStart[color + 1];
    const int chunks = (end - begin + BTG_SOFT_WIDE - 1) / BTG_SOFT_WIDE;
    const int nc = contact_edges(counters, edgeCapacity, numJoints);
    const int2 run = btgWideRun(chunks, (int)get_global_id(0), (int)get_global_size(0));
    const int stop = run.y;
    for (int m = run.x; m < stop; ++m)
        soft_wide_chunk(color, m, m + 1 < stop ? m + 1 : -1, begin, end, colorOrder, WIDE_PASS, nc, mode, key, SOFT_PASS);
}

#endif
