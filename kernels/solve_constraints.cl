/* solve_constraints.cl — Stage: solve (batched projected Gauss-Seidel over the colored
 * constraint graph, color by color; edge e below the contact count is contact e).
 * Launch: color_count / color_fill: one work-item per edge slot, sorting edge indices into
 * per-color ranges; solve_color_range: one work-item per slot of one color's range (no
 * dynamic body twice in a color, so no races); solve_resident: every pass and color in one
 * launch (resident groups on GPUs, one group for small scenes on CPUs);
 * solve_color_serial: one work-item that walks, in index order, the edges whose color is the
 * last one or higher (so a caller launching fewer colors than were assigned still solves all).
 * mode 0: apply warm-start impulses; 1: velocity iteration; 2: split-impulse iteration;
 * twoFriction: SOLVER_USE_2_FRICTION_DIRECTIONS (else the second friction rows are not read).
 * Reads counters[kEdgeCount, kColorsUsed, kLeftovers], edgeColor, props, invInertiaWorld,
 * contacts (a pass reads the fields of its rows only, see BtgContact). Writes contacts
 * (accumulated impulses), linVel, angVel (modes 0, 1) or pushLin, pushAng (mode 2), dynamic
 * bodies only. */
#include "shared/types.h"
#include "shared/math.h"
#include "shared/contact_rows.h"
#include "shared/counters.h"
#include "shared/grid_barrier.h"


static BtgSolverBody load_body(__global const BtgBodyProps* restrict props,
                               __global const BtgFloat4* restrict invInertiaWorld, int i)
{
    return btgMakeSolverBody(props[i], invInertiaWorld[3 * i], invInertiaWorld[3 * i + 1], invInertiaWorld[3 * i + 2]);
}

/* Body velocities go through BTG_SHARED (volatile on GPUs) pointers: solve_resident shares
 * them between work-groups across its grid barriers, where a non-coherent cache must not
 * serve a stale copy. The arithmetic is the same for every caller. */
static void solve_contact(int i, int mode, int twoFriction, __global BtgContact* contacts,
                      __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld,
                      BTG_SHARED __global BtgFloat4* lin, BTG_SHARED __global BtgFloat4* ang)
{
    BtgContact c = btgLoadContactRows(contacts, i, mode, twoFriction);
    BtgSolverBody a = load_body(props, invInertiaWorld, c.bodyA);
    BtgSolverBody b = load_body(props, invInertiaWorld, c.bodyB);
    /* Push velocities of infinite-mass bodies are zero, as Bullet's solver bodies start them. */
    int movingA = mode == BTG_PASS_PUSH ? a.dynamic : a.moving, movingB = mode == BTG_PASS_PUSH ? b.dynamic : b.moving;
    BtgFloat4 linA = lin[c.bodyA], angA = ang[c.bodyA], linB = lin[c.bodyB], angB = ang[c.bodyB];
    BtgBodyVel va = btgMakeBodyVel(movingA, linA, angA);
    BtgBodyVel vb = btgMakeBodyVel(movingB, linB, angB);
    if (mode == BTG_PASS_WARM_START) btgContactWarmStart(&c, a, b, &va, &vb, twoFriction);
    else if (mode == BTG_PASS_VELOCITY) btgContactSolveVelocity(&c, a, b, &va, &vb, twoFriction);
    else btgContactSolvePush(&c, a, b, &va, &vb);
    /* w of the velocity columns is not the solver's: keep it. */
    if (a.dynamic) {
        lin[c.bodyA] = btgMake4(va.lin.x, va.lin.y, va.lin.z, linA.w);
        ang[c.bodyA] = btgMake4(va.ang.x, va.ang.y, va.ang.z, angA.w);
    }
    if (b.dynamic) {
        lin[c.bodyB] = btgMake4(vb.lin.x, vb.lin.y, vb.lin.z, linB.w);
        ang[c.bodyB] = btgMake4(vb.ang.x, vb.ang.y, vb.ang.z, angB.w);
    }
    btgStoreContactImpulses(contacts, i, &c, mode, twoFriction);
}

/* One edge of the graph: the contacts are the edges [0, contacts); a constraint kind with
 * edges after them is solved here by its own rows. */
static void solve_edge(int e, int mode, int twoFriction, __global BtgContact* contacts,
                       __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld,
                       BTG_SHARED __global BtgFloat4* lin, BTG_SHARED __global BtgFloat4* ang)
{
    solve_contact(e, mode, twoFriction, contacts, props, invInertiaWorld, lin, ang);
}

static int edge_count(__global const uint* restrict counters, int edgeCapacity)
{
    return (int)min(counters[BTG_COUNTER_EDGES], (uint)edgeCapacity);
}

/* Whether edge e has a split-impulse row (only contacts do: Bullet pushes contacts only). */
static int edge_has_push(__global const BtgContact* restrict contacts, int e)
{
    return btgContactHasPush(contacts, e);
}

__kernel void solve_color_serial(__global const int* restrict edgeColor, __global BtgContact* contacts,
                                 __global const uint* restrict counters, int edgeCapacity,
                                 __global const BtgBodyProps* restrict props,
                                 __global const BtgFloat4* restrict invInertiaWorld, __global BtgFloat4* lin,
                                 __global BtgFloat4* ang, int color, int mode, int twoFriction)
{
    if (get_global_id(0) != 0) return;
    /* No leftovers from the batching and no color at or past this one (the usual case):
     * nothing to walk, and a GPU thread walking every edge is slow. */
    if (counters[BTG_COUNTER_LEFTOVERS] == 0u && counters[BTG_COUNTER_COLORS_USED] <= (uint)color) return;
    int n = edge_count(counters, edgeCapacity);
    for (int i = 0; i < n; ++i)
        if (edgeColor[i] >= color) solve_edge(i, mode, twoFriction, contacts, props, invInertiaWorld, lin, ang);
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
                          int numColors)
{
    int i = (int)get_global_id(0);
    if (i >= edge_count(counters, edgeCapacity)) return;
    int c = edgeColor[i];
    if (c < 0 || c >= numColors - 1) return;
    atomic_inc(&colorCount[c]);
    if (edge_has_push(contacts, i)) atomic_inc(&colorCount[numColors + 1 + c]);
}

__kernel void color_offsets(__global uint* colorCount, __global uint* colorStart, int numColors)
{
    if (get_global_id(0) != 0) return;
    for (int list = 0; list < 2; ++list) {
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

__kernel void color_fill(__global const int* restrict edgeColor, __global const BtgContact* restrict contacts,
                         __global const uint* restrict counters, int edgeCapacity,
                         __global const uint* restrict colorStart, __global uint* colorCursor,
                         __global int* colorOrder, int numColors, int orderStride)
{
    int i = (int)get_global_id(0);
    if (i >= edge_count(counters, edgeCapacity)) return;
    int c = edgeColor[i];
    if (c < 0 || c >= numColors - 1) return;
    colorOrder[colorStart[c] + atomic_inc(&colorCursor[c])] = i;
    if (edge_has_push(contacts, i)) {
        const int p = numColors + 1 + c;
        colorOrder[orderStride + colorStart[p] + atomic_inc(&colorCursor[p])] = i;
    }
}

/* solve_color_range: the color's range in list (mode == 2 ? 1 : 0), strided over however many
 * work-items the host launched (it does not know the range's length; a launch over every
 * edge slot cost a CPU device hundreds of empty work-groups per color). */
__kernel void solve_color_range(__global BtgContact* contacts, __global const uint* restrict colorStart,
                                __global const int* restrict colorOrder, __global const BtgBodyProps* restrict props,
                                __global const BtgFloat4* restrict invInertiaWorld, __global BtgFloat4* lin,
                                __global BtgFloat4* ang, int color, int mode, int twoFriction, int numColors,
                                int orderStride)
{
    const int list = mode == 2 ? 1 : 0;
    const int begin = (int)colorStart[list * (numColors + 1) + color];
    const int end = (int)colorStart[list * (numColors + 1) + color + 1];
    for (int k = begin + (int)get_global_id(0); k < end; k += (int)get_global_size(0))
        solve_edge(colorOrder[list * orderStride + k], mode, twoFriction, contacts, props, invInertiaWorld, lin, ang);
}

/* solve_resident: every pass and color in ONE launch over resident work-groups (GPUs), with a
 * grid barrier (shared/grid_barrier.h) where the per-color path has a kernel boundary: a step
 * has (colors + 1) x (1 + 2 x iterations) of those. Body velocities go through BTG_SHARED
 * pointers (see solve_contact); an edge's impulses are touched by the same work-item in every
 * pass (the assignment is fixed for the launch), so plain accesses suffice there. The
 * arithmetic and color order are the per-color launches' ones: the results are the same bit
 * for bit. A batching that timed out at its own barrier leaves nothing to solve: the step is redone. */

__kernel void solve_resident(__global const int* restrict edgeColor, __global BtgContact* contacts,
                             __global uint* counters, int edgeCapacity,
                             __global const uint* restrict colorStart, __global const int* restrict colorOrder,
                             __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld,
                             BTG_SHARED __global BtgFloat4* linVel, BTG_SHARED __global BtgFloat4* angVel,
                             BTG_SHARED __global BtgFloat4* pushLin, BTG_SHARED __global BtgFloat4* pushAng,
                             volatile __global BtgGridBarrier* bar, int numColors, int orderStride, int iterations,
                             int splitImpulse, int twoFriction, int spinLimit)
{
    __local int quit;
    if (counters[BTG_COUNTER_STATUS] & BTG_STATUS_GRID_BARRIER_TIMEOUT) return;
    const int gid = (int)get_global_id(0), gsize = (int)get_global_size(0);
    const int n = edge_count(counters, edgeCapacity);
    const int last = numColors - 1;
    const int walkLast = counters[BTG_COUNTER_LEFTOVERS] != 0u || counters[BTG_COUNTER_COLORS_USED] > (uint)last;
    const int passes = 1 + iterations + (splitImpulse ? iterations : 0);
    for (int pass = 0; pass < passes; ++pass) {
        const int mode = pass == 0 ? BTG_PASS_WARM_START : (pass <= iterations ? BTG_PASS_VELOCITY : BTG_PASS_PUSH);
        BTG_SHARED __global BtgFloat4* lin = mode == 2 ? pushLin : linVel;
        BTG_SHARED __global BtgFloat4* ang = mode == 2 ? pushAng : angVel;
        const int list = mode == 2 ? 1 : 0; /* push passes: only contacts with a push target */
        for (int color = 0; color < last; ++color) {
            const int begin = (int)colorStart[list * (numColors + 1) + color];
            const int end = (int)colorStart[list * (numColors + 1) + color + 1];
            for (int k = begin + gid; k < end; k += gsize)
                solve_edge(colorOrder[list * orderStride + k], mode, twoFriction, contacts, props, invInertiaWorld, lin,
                           ang);
            if (btgGridBarrier(bar, spinLimit, &quit)) {
                if (gid == 0) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
                return;
            }
        }
        if (walkLast) {
            if (gid == 0)
                for (int i = 0; i < n; ++i)
                    if (edgeColor[i] >= last)
                        solve_edge(i, mode, twoFriction, contacts, props, invInertiaWorld, lin, ang);
            if (btgGridBarrier(bar, spinLimit, &quit)) {
                if (gid == 0) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
                return;
            }
        }
    }
}
