/* soft_flow_passes.h — solve_soft.cl's kernels for the resident launch's flow (soft_flow.h):
 * soft_flow_ranks and soft_flow_degrees. Not a header of its own: solve_soft.cl includes it
 * where contact_edges and list_side are defined. */
#ifndef BTG_SOFT_FLOW_PASSES_H
#define BTG_SOFT_FLOW_PASSES_H
/* The sweeps' order as each body sees it, for the resident launch's flow (soft_resident): for
 * each side of regular slot k (colours below the last), the edge's place among its body's
 * regular edges in colour order (rank) and their number (deg), packed deg << 16 | rank; no
 * wait (BTG_SOFT_FLOW_FREE) for a side that is not a listed dynamic body. One work-item per
 * slot, after the lists are filled (their order does not matter here). */
__kernel void soft_flow_ranks(__global const uint* restrict counters, int edgeCapacity, int numJoints, int numColors,
                              __global const uint* restrict colorStart, __global const int* restrict colorOrder,
                              __global const int* restrict edgeColor, __global const BtgEdge* restrict edges,
                              __global const BtgJoint* restrict joints, __global const BtgJointState* restrict jointState,
                              __global const BtgBodyProps* restrict props,
                              __global const uint* restrict listStart, __global const uint* restrict listEntries,
                              __global uint* flowRank)
{
    const int k = (int)get_global_id(0), last = numColors - 1;
    if (k >= (int)colorStart[last]) return;
    const int nc = contact_edges(counters, edgeCapacity, numJoints), e = colorOrder[k];
    int a, b;
    if (e < nc) {
        a = edges[e].bodyA;
        b = edges[e].bodyB;
    } else {
        a = joints[e - nc].bodyA;
        b = joints[e - nc].bodyB;
    }
    const int color = edgeColor[e];
    /* a joint without rows is in no body's list (list_edge) and touches no body */
    const int listed = e < nc || jointState[e - nc].numRows != 0;
    const int waitA = listed && list_side(props, a), waitB = listed && list_side(props, b) && b != a;
    flowRank[2 * k] = waitA ? flow_rank(a, color, last, nc, edgeColor, listStart, listEntries) : BTG_SOFT_FLOW_FREE;
    flowRank[2 * k + 1] = waitB ? flow_rank(b, color, last, nc, edgeColor, listStart, listEntries) : BTG_SOFT_FLOW_FREE;
    /* a moving body that is not dynamic (kinematic): its position pass moves the deltas that
     * its edges read, and its edges are not ordered on it, so that pass keeps its barriers
     * (flowRank[2 * edgeCapacity], zeroed by the host) */
    if (listed && ((a >= 0 && !waitA && btgIsSolverMoving(props[a].flags)) ||
                   (b >= 0 && b != a && !waitB && btgIsSolverMoving(props[b].flags))))
        flowRank[2 * edgeCapacity] = 1u;
}
/* Each body's regular edges (its count's step per flow sweep), for the flow's body passes. */
__kernel void soft_flow_degrees(int numBodies, int numJoints, int numColors, __global const uint* restrict counters,
                                int edgeCapacity, __global const int* restrict edgeColor,
                                __global const uint* restrict listStart, __global const uint* restrict listEntries,
                                __global uint* flowDeg)
{
    const int b = (int)get_global_id(0);
    if (b >= numBodies) return;
    const int nc = contact_edges(counters, edgeCapacity, numJoints);
    flowDeg[b] = flow_rank(b, 0, numColors - 1, nc, edgeColor, listStart, listEntries) >> 16;
}
#endif
