/* sort_sweep.cl — broadphase of the small bodies by sort-and-sweep, in place of the uniform
 * grid when their sizes differ a lot (one cell size fits them badly): choose the axis along
 * which the AABB centres spread most, sort the rows by AABB min on it (prims/radix_sort,
 * launched from the host between these kernels), and sweep each row forward over the rows
 * whose min lies within its extent. Pairs go to the same unsorted list as find_pairs' passes.
 * Stage: broadphase. Launch: per kernel below (one work-group, body rows or sorted entries).
 * Reads: aabbMin, aabbMax, props, shapes.
 * Writes: raw pairs and counters[BTG_COUNTER_PAIRS] (all pairs found, even past capacity), and the
 * sort-and-sweep scratch of BroadphaseScratch (axis, keys, rows, sorted AABBs). */
#include "shared/broadphase.h"
#include "shared/sort_sweep.h"

/* Launch: one work-group of BTG_SAP_LANES work-items. Sums the centres of the swept rows in a
 * fixed order (deterministic, no atomics) and writes the chosen axis to axisOut[0]. */
__kernel void sap_axis(__global const BtgFloat4* restrict aabbMin, __global const BtgFloat4* restrict aabbMax,
                       __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                       int numBodies, __global uint* restrict axisOut)
{
    __local BtgFloat4 sum[BTG_SAP_LANES];
    __local BtgFloat4 sumSq[BTG_SAP_LANES];
    int lane = (int)get_local_id(0);
    BtgFloat4 s = btgZero4(), q = btgZero4();
    for (int i = lane; i < numBodies; i += BTG_SAP_LANES) {
        if (!btgGridded(props[i], shapes)) continue;
        BtgFloat4 c = btgSapCentre(aabbMin[i], aabbMax[i]);
        s = s + c;
        q = q + btgSapSquare(c);
    }
    sum[lane] = s;
    sumSq[lane] = q;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int span = BTG_SAP_LANES / 2; span > 0; span >>= 1) {
        if (lane < span) {
            sum[lane] = sum[lane] + sum[lane + span];
            sumSq[lane] = sumSq[lane] + sumSq[lane + span];
        }
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (lane == 0) axisOut[0] = btgSapAxis(sum[0], sumSq[0]);
}

/* Launch: one work-item per body row. Key: the AABB min on the axis, or BTG_SAP_NO_KEY for
 * rows outside the sweep (they sort last). */
__kernel void sap_keys(__global const BtgFloat4* restrict aabbMin, __global const BtgBodyProps* restrict props,
                       __global const BtgShape* restrict shapes, __global const uint* restrict axisIn,
                       __global uint* restrict keys, __global uint* restrict rows, int numBodies)
{
    int i = (int)get_global_id(0);
    if (i >= numBodies) return;
    uint axis = axisIn[0];
    keys[i] = btgGridded(props[i], shapes) ? btgSapKey(btgAxisValue(aabbMin[i], axis)) : BTG_SAP_NO_KEY;
    rows[i] = (uint)i;
}

/* Launch: one work-item per sorted entry. The AABBs in sorted order, so the sweep reads
 * consecutive memory. */
__kernel void sap_gather(__global const BtgFloat4* restrict aabbMin, __global const BtgFloat4* restrict aabbMax,
                         __global const uint* restrict keys, __global const uint* restrict rows,
                         __global BtgFloat4* restrict sortedMin, __global BtgFloat4* restrict sortedMax, int numBodies)
{
    int k = (int)get_global_id(0);
    if (k >= numBodies || keys[k] == BTG_SAP_NO_KEY) return;
    uint r = rows[k];
    sortedMin[k] = aabbMin[r];
    sortedMax[k] = aabbMax[r];
}

/* Launch: one work-item per sorted entry. Walks the later entries while their min on the axis
 * is within this row's max (touching counts, as in btgAabbOverlap); each pair is found once,
 * from its entry earlier in the sorted order. The full 3D test and the filter decide. */
__kernel void sap_pairs(__global const BtgBodyProps* restrict props, __global const uint* restrict axisIn,
                        __global const uint* restrict keys, __global const uint* restrict rows,
                        __global const BtgFloat4* restrict sortedMin, __global const BtgFloat4* restrict sortedMax,
                        __global BtgPair* restrict raw, volatile __global uint* counters,
                        uint capacity, int numBodies)
{
    int k = (int)get_global_id(0);
    if (k >= numBodies || keys[k] == BTG_SAP_NO_KEY) return;
    uint axis = axisIn[0];
    int i = (int)rows[k];
    BtgFloat4 iMin = sortedMin[k], iMax = sortedMax[k];
    float reach = btgAxisValue(iMax, axis);
    BtgBodyProps pi = props[i];
    for (int m = k + 1; m < numBodies && keys[m] != BTG_SAP_NO_KEY; ++m) {
        BtgFloat4 jMin = sortedMin[m];
        if (!(btgAxisValue(jMin, axis) <= reach)) break;  /* a NaN reach stops at once too */
        if (!btgAabbOverlap(iMin, iMax, jMin, sortedMax[m])) continue;
        int j = (int)rows[m];
        if (!btgPairAllowed(pi, props[j])) continue;
        btgAppendPair(raw, counters, capacity, i, j);
    }
}
