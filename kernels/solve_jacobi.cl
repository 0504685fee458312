/* solve_jacobi.cl — Stage: solve by Jacobi iterations with mass splitting (the alternative to
 * color_constraints + solve_constraints). Each contact solves against its own copies of its
 * bodies (1/n of the mass each), writing the copies' changes; each body then averages them.
 * Launch: jacobi_count, jacobi_fill, jacobi_solve: one work-item per contact slot (early-out
 * past counters[kContactCount]); jacobi_sort_lists, jacobi_gather: one work-item per body row.
 * List build: jacobi_count counts each dynamic body's solvable contacts (integer atomics), the
 * host scans the counts into `start` (N + 1 entries), jacobi_fill appends entries 2 * contact +
 * side, jacobi_sort_lists sorts each body's entries (the append order is a race), so every sum
 * below is taken in contact order: deterministic.
 * Reads counters, props, invInertiaWorld, contacts. Writes contacts (accumulated impulses),
 * cursor, entries, deltas, and linVel/angVel (modes 0, 1) or pushLin/pushAng (mode 2) of
 * dynamic rows with contacts (w kept). */
#include "shared/counters.h"
#include "shared/types.h"
#include "shared/math.h"
#include "shared/jacobi_rows.h"


static int num_contacts(__global const uint* restrict counters, int contactCapacity)
{
    return (int)min(counters[BTG_COUNTER_CONTACTS], (uint)contactCapacity);
}

/* A side enters the lists when its body is dynamic and the contact is solved at all. */
static int side_listed(__global const BtgBodyProps* restrict props, int bodyA, int bodyB, int side)
{
    uint fa = props[bodyA].flags, fb = props[bodyB].flags;
    return btgContactSolvable(fa, fb) && btgIsSolverDynamic(side == 0 ? fa : fb);
}

__kernel void jacobi_count(__global const BtgContact* restrict contacts, __global const uint* restrict counters,
                           int contactCapacity, __global const BtgBodyProps* restrict props, __global uint* cursor)
{
    int i = (int)get_global_id(0);
    if (i >= num_contacts(counters, contactCapacity)) return;
    const int a = contacts[i].bodyA, b = contacts[i].bodyB;
    if (side_listed(props, a, b, 0)) atomic_inc(&cursor[a]);
    if (side_listed(props, a, b, 1)) atomic_inc(&cursor[b]);
}

__kernel void jacobi_fill(__global const BtgContact* restrict contacts, __global const uint* restrict counters,
                          int contactCapacity, __global const BtgBodyProps* restrict props,
                          __global const uint* restrict start, __global uint* cursor, __global uint* entries)
{
    int i = (int)get_global_id(0);
    if (i >= num_contacts(counters, contactCapacity)) return;
    const int a = contacts[i].bodyA, b = contacts[i].bodyB;
    if (side_listed(props, a, b, 0)) entries[start[a] + atomic_inc(&cursor[a])] = 2u * (uint)i;
    if (side_listed(props, a, b, 1)) entries[start[b] + atomic_inc(&cursor[b])] = 2u * (uint)i + 1u;
}

/* Insertion sort of one body's entries: lists are short (the contacts touching one body). */
__kernel void jacobi_sort_lists(__global const uint* restrict start, int numBodies, __global uint* entries)
{
    int b = (int)get_global_id(0);
    if (b >= numBodies) return;
    uint lo = start[b], hi = start[b + 1];
    for (uint i = lo + 1u; i < hi; ++i) {
        uint e = entries[i];
        uint j = i;
        while (j > lo && entries[j - 1u] > e) {
            entries[j] = entries[j - 1u];
            --j;
        }
        entries[j] = e;
    }
}

static uint body_count(__global const uint* restrict start, int b)
{
    return start[b + 1] - start[b];
}

__kernel void jacobi_solve(__global BtgContact* contacts, __global const uint* restrict counters, int contactCapacity,
                           __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld,
                           __global const uint* restrict start, __global const BtgFloat4* restrict lin,
                           __global const BtgFloat4* restrict ang, __global BtgFloat4* deltas, int mode)
{
    int i = (int)get_global_id(0);
    if (i >= num_contacts(counters, contactCapacity)) return;
    /* Every row is visited (second friction rows too: see btgJacobiContact). */
    BtgContact c = btgLoadContactRows(contacts, i, mode, 1);
    int ia = c.bodyA, ib = c.bodyB;
    BtgSolverBody a = btgMakeSolverBody(props[ia], invInertiaWorld[3 * ia], invInertiaWorld[3 * ia + 1], invInertiaWorld[3 * ia + 2]);
    BtgSolverBody b = btgMakeSolverBody(props[ib], invInertiaWorld[3 * ib], invInertiaWorld[3 * ib + 1], invInertiaWorld[3 * ib + 2]);
    if (a.dynamic) a = btgSplitBody(a, body_count(start, ia));
    if (b.dynamic) b = btgSplitBody(b, body_count(start, ib));
    /* Push velocities of infinite-mass bodies are zero, as Bullet's solver bodies start them. */
    int movingA = mode == BTG_PASS_PUSH ? a.dynamic : a.moving, movingB = mode == BTG_PASS_PUSH ? b.dynamic : b.moving;
    BtgBodyVel dA, dB;
    btgJacobiContact(&c, a, b, btgMakeBodyVel(movingA, lin[ia], ang[ia]), btgMakeBodyVel(movingB, lin[ib], ang[ib]), mode,
                     &dA, &dB);
    deltas[4 * i] = dA.lin;
    deltas[4 * i + 1] = dA.ang;
    deltas[4 * i + 2] = dB.lin;
    deltas[4 * i + 3] = dB.ang;
    btgStoreContactImpulses(contacts, i, &c, mode, 1);
}

__kernel void jacobi_gather(int numBodies, __global const uint* restrict start, __global const uint* restrict entries,
                            __global const BtgFloat4* restrict deltas, __global BtgFloat4* lin, __global BtgFloat4* ang)
{
    int b = (int)get_global_id(0);
    if (b >= numBodies) return;
    uint lo = start[b], hi = start[b + 1];
    if (hi == lo) return;
    BtgFloat4 sl = btgZero4(), sa = btgZero4();
    for (uint k = lo; k < hi; ++k) {
        uint e = entries[k];
        sl = sl + deltas[2u * e];
        sa = sa + deltas[2u * e + 1u];
    }
    lin[b] = btgJacobiAverage(lin[b], sl, hi - lo);
    ang[b] = btgJacobiAverage(ang[b], sa, hi - lo);
}
