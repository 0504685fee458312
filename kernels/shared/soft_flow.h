/* soft_flow.h — the soft step's flow (solve_soft.cl's soft_resident with flow != 0): the ranks
 * soft_flow_ranks gives each edge side and the waits and signals on the bodies' counts. Device
 * code only. */
#ifndef BTG_SOFT_FLOW_H
#define BTG_SOFT_FLOW_H
#include "grid_barrier.h"
#include "soft_rows.h"
#include "types.h"

#ifdef __OPENCL_C_VERSION__
/* The flow (flow != 0): within a solve, relax or restitution sweep in colour order, an edge waits
 * only for its own bodies' earlier edges, not for every edge of the colour before: each dynamic
 * body counts the edges done on it (flowDone, zeroed at the step's begin pass), and edge slot k
 * of flow sweep s (the launch's s-th such sweep) runs when its bodies' counts are s * deg + rank
 * (soft_flow_ranks). Each body sees its edges in the same order as with a barrier per colour, so
 * the results are the same bit for bit; only the colours' barriers go. Deadlock-free where all
 * groups are resident (as the grid barrier needs) and a group's work-items progress apart (GPUs;
 * a CPU device runs a group's work-items one after another: groups of one there): an edge waits
 * only for edges of lower colours, which their work-items reach first. A wait past spinLimit
 * polls gives up as the grid barrier does (the host redoes the step launch by launch). */

/* no wait: the side is not a listed dynamic body */
#define BTG_SOFT_FLOW_FREE 0xffffffffu
static int entry_edge(uint entry, int nc)
{
    return (entry & BTG_SOFT_ENTRY_JOINT) ? nc + (int)((entry & ~BTG_SOFT_ENTRY_JOINT) >> 2) : (int)(entry >> 2);
}
static uint flow_rank(int body, int color, int last, int nc, __global const int* restrict edgeColor,
                      __global const uint* restrict listStart, __global const uint* restrict listEntries)
{
    uint rank = 0u, deg = 0u;
    for (uint q = listStart[body]; q < listStart[body + 1]; ++q) {
        const int c = edgeColor[entry_edge(listEntries[q], nc)];
        if (c < 0 || c >= last) continue; /* a leftover: walked after the sweep, outside the flow */
        ++deg;
        if (c < color) ++rank;
    }
    return deg << 16 | rank;
}
/* Edge side `pack` waits for its body's count: s * deg + the flow's body passes so far + rank. */
static uint flow_want(uint pack, uint sweep, uint passes)
{
    return sweep * (pack >> 16) + passes + (pack & 0xffffu);
}
static int flow_wait(volatile __global uint* flowDone, int body, uint pack, uint sweep, uint passes,
                     volatile __global BtgGridBarrier* bar, int spinLimit)
{
    if (pack == BTG_SOFT_FLOW_FREE) return 0;
    return btgWaitForCount(&flowDone[body], flow_want(pack, sweep, passes), bar, spinLimit);
}
static void flow_signal(volatile __global uint* flowDone, int body, uint pack, uint sweep, uint passes)
{
    if (pack == BTG_SOFT_FLOW_FREE) return;
    flowDone[body] = flow_want(pack, sweep, passes) + 1u;
}
/* The bodies of edge slot k (soft_flow_ranks' sides): a contact's from its soft rows, a joint's. */
static int2 flow_bodies(int e, int slot, int nc, __global const BtgSoftContact* softContacts,
                        __global const BtgJoint* restrict joints)
{
    if (e < nc) return (int2)(softContacts[slot].bodyA, softContacts[slot].bodyB);
    return (int2)(joints[e - nc].bodyA, joints[e - nc].bodyB);
}

#endif

#endif
