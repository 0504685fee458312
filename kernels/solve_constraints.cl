/* solve_constraints.cl — Stage: solve (batched projected Gauss-Seidel over the colored
 * constraint graph, color by color; edge e below the contact count is contact e, edge
 * contacts + j is joint j). Each velocity iteration solves, as Bullet's solveSingleIteration,
 * every joint row first (joint j while the iteration is below its own iteration count), then
 * the contacts (while it is below m_numIterations) in two sweeps: every contact's normal rows,
 * then every friction row; joints take no warm-start or push pass.
 * Launch: color_count / color_fill: one work-item per edge slot, sorting edge indices into
 * per-color ranges; solve_color_range: one work-item per slot of one color's range (no
 * dynamic body twice in a color, so no races); solve_resident: every pass and color in one
 * launch (resident groups on GPUs, one group for small scenes on CPUs);
 * solve_color_serial: one work-item that walks, in index order, the edges whose color is the
 * last one or higher (so a caller launching fewer colors than were assigned still solves all).
 * mode 0: apply warm-start impulses; 1: velocity iteration (both sweeps at once, unused by
 * the host); 2: split-impulse iteration; 3, 4: a velocity iteration's normal sweep, then its
 * friction sweep over every contact (counters.h); 5: its rolling sweep (rolling friction);
 * rows: BTG_ROWS_* (contact_rows.h), which optional row fields exist (second friction rows,
 * contact cfm, rolling rows). seed: SOLVER_RANDMIZE_ORDER's stream of this substep (0: off),
 * which permutes each sweep's colours and each contact's points (btgPassKey, btgPermute).
 * Reads counters[kEdgeCount, kContactCount, kColorsUsed, kLeftovers], edgeColor, props,
 * invInertiaWorld, contacts (a pass reads the fields of its rows only, see BtgContact),
 * rolling (rows & BTG_ROWS_ROLLING; else a placeholder), frictionDirs (rows & BTG_ROWS_ANISOTROPIC;
 * else a placeholder), anchors (rows & BTG_ROWS_ANCHORS; else a placeholder), joints, jointState
 * (rows built).
 * Writes contacts, rolling and jointRows (accumulated impulses),
 * linVel, angVel (modes 0, 1) or pushLin, pushAng (mode 2), dynamic bodies only. */
#include "shared/types.h"
#include "shared/math.h"
#include "shared/contact_rows.h"
#include "shared/material_rows.h"
#include "shared/joint_rows.h"
#include "shared/counters.h"
#include "shared/grid_barrier.h"

/* The joint buffers every solve kernel takes (one-element placeholders without joints). */
#define JOINT_ARGS __global const BtgJoint* restrict joints, __global const BtgJointState* restrict jointState, \
                   __global BtgJointRow* jointRows, int numJoints
#define JOINT_PASS joints, jointState, jointRows, numJoints


static BtgSolverBody load_body(__global const BtgBodyProps* restrict props,
                               __global const BtgFloat4* restrict invInertiaWorld, int i)
{
    return btgMakeSolverBody(props[i], invInertiaWorld[3 * i], invInertiaWorld[3 * i + 1], invInertiaWorld[3 * i + 2]);
}

static int edge_count(__global const uint* restrict counters, int edgeCapacity)
{
    return (int)min(counters[BTG_COUNTER_EDGES], (uint)edgeCapacity);
}

/* Edges below this are contacts; the joints' follow (the contact slots are the edge slots
 * less one per joint). */
static int contact_edges(__global const uint* restrict counters, int edgeCapacity, int numJoints)
{
    return (int)min(counters[BTG_COUNTER_CONTACTS], (uint)(edgeCapacity - numJoints));
}

/* The edges' rows against the bodies' velocities (pgs_edges.h), twice: through BTG_SHARED global
 * pointers (every kernel but solve_local; volatile on GPUs, where solve_resident shares them
 * between work-groups across its grid barriers and a non-coherent cache must not serve a stale
 * copy), and through local ones (solve_local's one work-group). The arithmetic is the same. */
#define BTG_PGS_VEL BTG_SHARED __global BtgFloat4*
#define BTG_PGS_LOAD(p) btgLoadShared4(p)
#define BTG_PGS_FN(name) name
#include "shared/pgs_edges.h"
#undef BTG_PGS_VEL
#undef BTG_PGS_LOAD
#undef BTG_PGS_FN
#define BTG_PGS_VEL __local BtgFloat4*
#define BTG_PGS_LOAD(p) (*(p))
#define BTG_PGS_FN(name) name##_local
#include "shared/pgs_edges.h"
#undef BTG_PGS_VEL
#undef BTG_PGS_LOAD
#undef BTG_PGS_FN

#ifdef BTG_CPU_DEVICE
#include "shared/pgs_wide_passes.h" /* the wide velocity sweeps: CPU devices only (a GPU's build never sees them) */
#endif

/* Whether edge e has a split-impulse row (only contacts do: Bullet pushes contacts only). */
static int edge_has_push(__global const BtgContact* restrict contacts, int e)
{
    return btgContactHasPush(contacts, e);
}

__kernel void solve_color_serial(__global const int* restrict edgeColor, __global BtgContact* contacts,
                                 __global BtgRollingContact* rolling, __global const BtgFrictionDirs* restrict frictionDirs, __global const BtgFrictionAnchor* restrict anchors,
                                 __global const uint* restrict counters, int edgeCapacity,
                                 __global const BtgBodyProps* restrict props,
                                 __global const BtgFloat4* restrict invInertiaWorld, __global BtgFloat4* lin,
                                 __global BtgFloat4* ang, int color, int mode, int rows, JOINT_ARGS, int phase,
                                 int iteration, uint seed)
{
    if (get_global_id(0) != 0) return;
    const uint key = btgPassKey(seed, mode, phase, iteration);
    /* No leftovers from the batching and no color at or past this one (the usual case):
     * nothing to walk, and a GPU thread walking every edge is slow. */
    if (counters[BTG_COUNTER_LEFTOVERS] == 0u && counters[BTG_COUNTER_COLORS_USED] <= (uint)color) return;
    int n = edge_count(counters, edgeCapacity);
    const int nc = contact_edges(counters, edgeCapacity, numJoints);
    for (int i = phase ? nc : 0; i < (phase ? n : min(n, nc)); ++i)
        if (edgeColor[i] >= color)
            solve_phase_edge(i, i, phase, nc, iteration, mode, rows, contacts, rolling, frictionDirs, anchors, JOINT_PASS, props,
                             invInertiaWorld, lin, ang, key);
}

/* Color ranges, so a color's launch touches only its own edges instead of reading every
 * edge's color: count per color, exclusive offsets (one work-item: there are few colors),
 * then each edge writes its index into its color's range. The order inside a range is the
 * atomics' order, which does not matter: edges of one color share no dynamic body, so
 * solving them in any order gives the same result. Two lists: list 0 holds every edge,
 * list 1 only the contacts with a split-impulse (push) target on some point — the push passes
 * skip the rest, which they would leave unchanged (as Bullet skips rows without
 * m_rhsPenetration). List l's counts and starts are at l * (numColors + 1), its indices at
 * l * orderStride. */

__kernel void color_count(__global const int* restrict edgeColor, __global const BtgContact* restrict contacts,
                          __global const uint* restrict counters, int edgeCapacity, __global uint* colorCount,
                          int numColors, int numJoints)
{
    int i = (int)get_global_id(0);
    if (i >= edge_count(counters, edgeCapacity)) return;
    int c = edgeColor[i];
    if (c < 0 || c >= numColors - 1) return;
    if (i >= contact_edges(counters, edgeCapacity, numJoints)) {
        atomic_inc(&colorCount[2 * (numColors + 1) + c]); /* list 2: the joints */
        return;
    }
    atomic_inc(&colorCount[c]);
    if (edge_has_push(contacts, i)) atomic_inc(&colorCount[numColors + 1 + c]);
}

/* Each list's colour starts from its counts (the last colour, the leftovers', gets none), the
 * counts zeroed to serve as the fill's cursors. */
static void color_offsets_of(__global uint* colorCount, __global uint* colorStart, int numColors, int numLists)
{
    for (int list = 0; list < numLists; ++list) {
        const int base = list * (numColors + 1);
        uint sum = 0u;
        for (int c = 0; c < numColors; ++c) {
            colorStart[base + c] = sum;
            sum += c < numColors - 1 ? colorCount[base + c] : 0u;
            colorCount[base + c] = 0u; /* reused as the fill cursor */
        }
        colorStart[base + numColors] = sum;
    }
}
__kernel void color_offsets(__global uint* colorCount, __global uint* colorStart, int numColors, int numLists)
{
    if (get_global_id(0) == 0) color_offsets_of(colorCount, colorStart, numColors, numLists);
}

__kernel void color_fill(__global const int* restrict edgeColor, __global const BtgContact* restrict contacts,
                         __global const uint* restrict counters, int edgeCapacity,
                         __global const uint* restrict colorStart, __global uint* colorCursor,
                         __global int* colorOrder, int numColors, int orderStride, int numJoints)
{
    int i = (int)get_global_id(0);
    if (i >= edge_count(counters, edgeCapacity)) return;
    int c = edgeColor[i];
    if (c < 0 || c >= numColors - 1) return;
    if (i >= contact_edges(counters, edgeCapacity, numJoints)) {
        const int q = 2 * (numColors + 1) + c;
        colorOrder[2 * orderStride + colorStart[q] + atomic_inc(&colorCursor[q])] = i;
        return;
    }
    colorOrder[colorStart[c] + atomic_inc(&colorCursor[c])] = i;
    if (edge_has_push(contacts, i)) {
        const int p = numColors + 1 + c;
        colorOrder[orderStride + colorStart[p] + atomic_inc(&colorCursor[p])] = i;
    }
}

/* The contacts' list 0 (every contact of a regular colour) copied in colour order, so that a sweep
 * reads its colour's rows one after another instead of at the contacts' scattered places: slot k
 * of list 0 is contact colorOrder[k]. The velocity sweeps solve the copy (the push sweeps read the
 * list's own rows, which hold the same values: the velocity sweeps change impulses only, never
 * a push row's fields), and contacts_scatter puts the impulses they changed back. The
 * leftovers (colours past the last regular one) are not in list 0: solved in place. */
static int list0_count(__global const uint* restrict colorStart, int numColors)
{
    return (int)colorStart[numColors];
}
__kernel void contacts_gather(__global const BtgContact* restrict contacts, __global const uint* restrict colorStart,
                              __global const int* restrict colorOrder, int numColors, __global BtgContact* sorted)
{
    const int k = (int)get_global_id(0);
    if (k >= list0_count(colorStart, numColors)) return;
    sorted[k] = contacts[colorOrder[k]];
}
__kernel void contacts_scatter(__global BtgContact* contacts, __global const uint* restrict colorStart,
                               __global const int* restrict colorOrder, int numColors,
                               __global const BtgContact* restrict sorted)
{
    const int k = (int)get_global_id(0);
    if (k >= list0_count(colorStart, numColors)) return;
    const int e = colorOrder[k];
    contacts[e].normalImpulse = sorted[k].normalImpulse;
    contacts[e].friction1Impulse = sorted[k].friction1Impulse;
    contacts[e].friction2Impulse = sorted[k].friction2Impulse;
}

/* color_count, color_offsets and color_fill in one work-item, the edges in index order (a CPU
 * device: the fill's atomics on a dozen colour cursors in one cache line kept it moving between
 * the cores, 1.7 ms of a PoCL frame of cubes 8,000 for 30,000 edges; one core walks them in
 * 0.2). Each colour's range then lists its edges in index order, which the solve does not care
 * about (a colour's edges share no dynamic body). */
__kernel void color_lists_serial(__global const int* restrict edgeColor, __global const BtgContact* restrict contacts,
                                 __global const uint* restrict counters, int edgeCapacity, __global uint* colorCount,
                                 __global uint* colorStart, __global int* colorOrder, int numColors, int orderStride,
                                 int numJoints, int numLists)
{
    if (get_global_id(0) != 0) return;
    const int n = edge_count(counters, edgeCapacity), nc = contact_edges(counters, edgeCapacity, numJoints);
    for (int q = 0; q < numLists * (numColors + 1); ++q) colorCount[q] = 0u;
    for (int i = 0; i < n; ++i) {
        const int c = edgeColor[i];
        if (c < 0 || c >= numColors - 1) continue;
        if (i >= nc) {
            ++colorCount[2 * (numColors + 1) + c];
        } else {
            ++colorCount[c];
            if (edge_has_push(contacts, i)) ++colorCount[numColors + 1 + c];
        }
    }
    color_offsets_of(colorCount, colorStart, numColors, numLists);
    for (int i = 0; i < n; ++i) {
        const int c = edgeColor[i];
        if (c < 0 || c >= numColors - 1) continue;
        if (i >= nc) {
            const int q = 2 * (numColors + 1) + c;
            colorOrder[2 * orderStride + colorStart[q] + colorCount[q]++] = i;
            continue;
        }
        colorOrder[colorStart[c] + colorCount[c]++] = i;
        if (edge_has_push(contacts, i)) {
            const int p = numColors + 1 + c;
            colorOrder[orderStride + colorStart[p] + colorCount[p]++] = i;
        }
    }
}

/* solve_color_range: the color's range in list (phase 1: 2, the joints; else mode == 2 ? 1 : 0), strided over however many
 * work-items the host launched (it does not know the range's length; a launch over every
 * edge slot cost a CPU device hundreds of empty work-groups per color). List 0's rows from the
 * colour-ordered copy `sorted` (contacts_gather) where `useSorted`, else in place. */
__kernel void solve_color_range(__global BtgContact* contacts, __global BtgContact* sorted, int useSorted,
                                __global BtgRollingContact* rolling,
                                __global const BtgFrictionDirs* restrict frictionDirs, __global const BtgFrictionAnchor* restrict anchors,
                                __global const uint* restrict colorStart,
                                __global const int* restrict colorOrder, __global const BtgBodyProps* restrict props,
                                __global const BtgFloat4* restrict invInertiaWorld, __global BtgFloat4* lin,
                                __global BtgFloat4* ang, int color, int mode, int rows, int numColors,
                                int orderStride, __global const uint* restrict counters, int edgeCapacity, JOINT_ARGS,
                                int phase, int iteration, uint seed)
{
    const uint key = btgPassKey(seed, mode, phase, iteration);
    const int list = phase ? 2 : (mode == 2 ? 1 : 0);
    const int begin = (int)colorStart[list * (numColors + 1) + color];
    const int end = (int)colorStart[list * (numColors + 1) + color + 1];
    const int nc = phase ? contact_edges(counters, edgeCapacity, numJoints) : 0;
    const int copied = useSorted && list == 0;
    __global BtgContact* rowsAt = copied ? sorted : contacts;
    for (int k = begin + (int)get_global_id(0); k < end; k += (int)get_global_size(0)) {
        const int e = colorOrder[list * orderStride + k];
        solve_phase_edge(e, copied ? k : e, phase, nc, iteration, mode, rows, rowsAt, rolling, frictionDirs, anchors,
                         JOINT_PASS, props, invInertiaWorld, lin, ang, key);
    }
}

/* The flow (solve_resident's flow != 0, every sweep in colour order): an edge waits only for its
 * own dynamic bodies' earlier edges, not for every edge of the colour before. Each body keeps
 * one bit per colour and list (flowMasks[4 b + list]: list 0 every contact, 1 the push
 * contacts, 2 the joints, as colorOrder's lists) where it is a dynamic side, and counts the edges
 * done on it (flowDone[2 b]: the velocity sweeps', whose lists 2 and 0 share the velocities;
 * flowDone[2 b + 1]: the push sweeps'). Edge slot k of a list-L sweep at colour c runs when the
 * count is the sweeps done so far times the body's bits in their lists, plus its bits below c
 * in L. Each body sees its edges in the same order as with a barrier per colour: the same
 * results bit for bit. As the grid barrier, valid where all groups are resident and a group's
 * work-items progress apart (GPUs; groups of one work-item on a CPU device). One work-item per
 * slot of the lists (list = id / orderStride), after color_fill; the host zeroes the masks
 * and counts. */
static void flow_mask(volatile __global uint* flowMasks, __global const BtgBodyProps* restrict props, int body, int list,
                      int color)
{
    if (body >= 0 && btgIsSolverDynamic(props[body].flags)) atomic_or(&flowMasks[4 * body + list], 1u << color);
}
static int2 flow_edge_bodies(int e, int list, int nc, __global const BtgContact* restrict contacts,
                             __global const BtgJoint* restrict joints)
{
    if (list == 2) return (int2)(joints[e - nc].bodyA, joints[e - nc].bodyB);
    return (int2)(contacts[e].bodyA, contacts[e].bodyB);
}
__kernel void solve_flow_masks(__global const uint* restrict counters, int edgeCapacity, int numJoints, int numColors,
                               int numLists, __global const uint* restrict colorStart, __global const int* restrict colorOrder,
                               int orderStride, __global const int* restrict edgeColor,
                               __global const BtgContact* restrict contacts, __global const BtgJoint* restrict joints,
                               __global const BtgBodyProps* restrict props, volatile __global uint* flowMasks)
{
    const int id = (int)get_global_id(0), list = id / max(orderStride, 1), k = id - list * max(orderStride, 1);
    if (list >= numLists || k >= (int)colorStart[list * (numColors + 1) + numColors - 1]) return;
    const int e = colorOrder[list * orderStride + k], nc = contact_edges(counters, edgeCapacity, numJoints);
    const int2 ab = flow_edge_bodies(e, list, nc, contacts, joints);
    const int color = edgeColor[e];
    flow_mask(flowMasks, props, ab.x, list, color);
    if (ab.y != ab.x) flow_mask(flowMasks, props, ab.y, list, color);
}
/* What side `body` of a list-`list` edge at `color` waits for (its count before it), or -1 (no
 * wait: not a dynamic side). sweeps: the flow sweeps done so far per list. */
static long flow_want(__global const uint* restrict flowMasks, int body, int list, int color, int last, int4 sweeps)
{
    if (body < 0) return -1;
    const uint4 m = vload4(body, flowMasks);
    const uint mine = list == 0 ? m.x : (list == 1 ? m.y : m.z);
    if (!((mine >> color) & 1u)) return -1;
    const uint regular = last >= 32 ? 0xffffffffu : (1u << last) - 1u;
    const uint before = popcount(mine & ((1u << color) - 1u));
    if (list == 1) return (long)((uint)sweeps.y * popcount(m.y & regular) + before);
    return (long)((uint)sweeps.x * popcount(m.x & regular) + (uint)sweeps.z * popcount(m.z & regular) + before);
}
static int flow_wait(volatile __global uint* done, long want, volatile __global BtgGridBarrier* bar, int spinLimit)
{
    return want >= 0 && btgWaitForCount(done, (uint)want, bar, spinLimit);
}

/* Velocity iterations: the contacts' count, or more when a joint asks for more
 * (setOverrideNumSolverIterations: Bullet iterates to the largest). */
static int velocity_passes(int iterations, int numJoints, int jointIterations)
{
    return max(iterations, numJoints > 0 ? jointIterations : 0);
}
/* Whether the sweeps walk the batching's leftovers (edges at or past the last colour) serially. */
static int walk_leftovers(__global const uint* restrict counters, int last)
{
    return counters[BTG_COUNTER_LEFTOVERS] != 0u || counters[BTG_COUNTER_COLORS_USED] > (uint)last;
}

/* The one-launch solves' schedule (solve_resident, solve_local): pass 0 warm-starts, the next
 * `velocity` passes iterate velocities, the rest (split impulse) push. */
static int pass_mode(int pass, int velocity)
{
    return pass == 0 ? BTG_PASS_WARM_START : (pass <= velocity ? BTG_PASS_VELOCITY : BTG_PASS_PUSH);
}
/* A phase's sweeps: the contacts' velocity pass is normals then friction (interleaved: both in
 * one), then rolling; every other phase one sweep of its pass's mode. */
static int phase_sweeps(int mode, int phase, int rows)
{
    if (phase != 0 || mode != BTG_PASS_VELOCITY) return 1;
    return ((rows & BTG_ROWS_INTERLEAVE) ? 1 : 2) + ((rows & BTG_ROWS_ROLLING) ? 1 : 0);
}
/* The list a phase's edges come from: the joints (phase 1), the contacts with a push target
 * (push passes), or every contact. */
static int phase_list(int mode, int phase)
{
    return phase ? 2 : (mode == BTG_PASS_PUSH ? 1 : 0);
}
/* The phases of a pass, from this one down to 0: the joints first where velocity passes have
 * joints to solve. */
static int first_phase(int mode, int numJoints)
{
    return (mode == BTG_PASS_VELOCITY && numJoints > 0) ? 1 : 0;
}
/* ... down to this one: a velocity pass past the contacts' iterations (a joint asked for more)
 * solves the joints only. */
static int last_phase(int mode, int iteration, int iterations)
{
    return (mode == BTG_PASS_VELOCITY && iteration >= iterations) ? 1 : 0;
}
/* Colour `color`'s slots [x, y) in `list`'s part of colorOrder. */
static int2 color_range(__global const uint* restrict colorStart, int list, int numColors, int color)
{
    return (int2)((int)colorStart[list * (numColors + 1) + color], (int)colorStart[list * (numColors + 1) + color + 1]);
}
static int sweep_mode(int mode, int phase, int rows, int sweep, int sweeps)
{
    if (phase != 0 || mode != BTG_PASS_VELOCITY) return mode;
    if (sweep == sweeps - 1 && (rows & BTG_ROWS_ROLLING)) return BTG_PASS_ROLLING;
    if (rows & BTG_ROWS_INTERLEAVE) return BTG_PASS_VELOCITY;
    return sweep == 0 ? BTG_PASS_NORMALS : BTG_PASS_FRICTION;
}

#define BTG_RESIDENT_KERNEL solve_resident
#define BTG_RESIDENT_WIDE 0
#include "shared/pgs_resident.h"
#undef BTG_RESIDENT_KERNEL
#undef BTG_RESIDENT_WIDE
#ifdef BTG_CPU_DEVICE
#define BTG_RESIDENT_KERNEL solve_resident_wide
#define BTG_RESIDENT_WIDE 1
#include "shared/pgs_resident.h"
#undef BTG_RESIDENT_KERNEL
#undef BTG_RESIDENT_WIDE
#endif

/* solve_local: solve_resident's passes, sweeps and colours on ONE work-group whose bodies'
 * velocities live in local memory (slin, sang: a float4 each a body, every body of the world)
 * for the whole launch: a small scene on a GPU, where each of the step's hundreds of colour
 * phases is a chain of dependent loads and a barrier, and here the velocities are local loads
 * and the barrier a work-group's. The velocity passes run on linVel/angVel's values, then (split
 * impulse) the push passes on pushLin/pushAng's (zeroed by the host), each written back after
 * its passes. Edges go to work-items as in solve_resident (slot k of a colour's range to work-item
 * k mod the group), the rows and the colour order are its: the results are the same bit for
 * bit (SolveConstraints.LocalSolveIsTheResidentSolveBitForBit). */
__kernel void solve_local(__global const int* restrict edgeColor, __global BtgContact* contacts,
                          __global BtgRollingContact* rolling, __global const BtgFrictionDirs* restrict frictionDirs,
                          __global const BtgFrictionAnchor* restrict anchors, __global uint* counters, int edgeCapacity,
                          __global const uint* restrict colorStart, __global const int* restrict colorOrder,
                          __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld,
                          __global BtgFloat4* linVel, __global BtgFloat4* angVel, __global BtgFloat4* pushLin,
                          __global BtgFloat4* pushAng, int numColors, int orderStride, int iterations,
                          int splitImpulse, int rows, JOINT_ARGS, int jointIterations, uint seed, int numBodies,
                          __local BtgFloat4* slin, __local BtgFloat4* sang)
{
    if (counters[BTG_COUNTER_STATUS] & BTG_STATUS_GRID_BARRIER_TIMEOUT) return;
    const int lid = (int)get_local_id(0), lsize = (int)get_local_size(0);
    for (int b = lid; b < numBodies; b += lsize) {
        slin[b] = linVel[b];
        sang[b] = angVel[b];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    const int velocity = velocity_passes(iterations, numJoints, jointIterations);
    const int passes = 1 + velocity + (splitImpulse ? iterations : 0);
    const int n = edge_count(counters, edgeCapacity), nc = contact_edges(counters, edgeCapacity, numJoints);
    const int last = numColors - 1, walkLast = walk_leftovers(counters, last);
    int pushing = 0; /* the push passes have begun: the local velocities are the push ones */
    for (int pass = 0; pass < passes; ++pass) {
        const int mode = pass_mode(pass, velocity);
        const int iteration = pass - 1;
        if (mode == BTG_PASS_PUSH && !pushing) {
            /* the velocities are final: back to global memory, the push velocities in their place */
            for (int b = lid; b < numBodies; b += lsize) {
                linVel[b] = slin[b];
                angVel[b] = sang[b];
                slin[b] = pushLin[b];
                sang[b] = pushAng[b];
            }
            barrier(CLK_LOCAL_MEM_FENCE);
            pushing = 1;
        }
        for (int phase = first_phase(mode, numJoints); phase >= last_phase(mode, iteration, iterations); --phase) {
            const int list = phase_list(mode, phase), sweeps = phase_sweeps(mode, phase, rows);
            for (int sweep = 0; sweep < sweeps; ++sweep) {
                const int m = sweep_mode(mode, phase, rows, sweep, sweeps);
                const uint key = btgPassKey(seed, m, phase, iteration);
                for (int ci = 0; ci < last; ++ci) {
                    const int2 range = color_range(colorStart, list, numColors, btgPermute(key, last, ci));
                    if (range.x == range.y) continue; /* the same for every work-item */
                    for (int k = range.x + lid; k < range.y; k += lsize)
                        solve_phase_edge_local(colorOrder[list * orderStride + k], colorOrder[list * orderStride + k], phase, nc, iteration, m, rows, contacts,
                                               rolling, frictionDirs, anchors, JOINT_PASS, props, invInertiaWorld, slin,
                                               sang, key);
                    barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
                }
                if (walkLast) {
                    if (lid == 0)
                        for (int i = phase ? nc : 0; i < (phase ? n : min(n, nc)); ++i)
                            if (edgeColor[i] >= last)
                                solve_phase_edge_local(i, i, phase, nc, iteration, m, rows, contacts, rolling, frictionDirs,
                                                       anchors, JOINT_PASS, props, invInertiaWorld, slin, sang, key);
                    barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
                }
            }
        }
    }
    for (int b = lid; b < numBodies; b += lsize) {
        if (pushing) {
            pushLin[b] = slin[b];
            pushAng[b] = sang[b];
        } else {
            linVel[b] = slin[b];
            angVel[b] = sang[b];
        }
    }
}
