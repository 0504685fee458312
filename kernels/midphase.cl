/* midphase.cl — Stage: midphase. Each convex–concave pair of the broadphase is split into
 * (convex, triangle) sub-pairs by walking the mesh's quantized BVH, or the heightfield's cells,
 * with the convex's box (btgMidphasePair in shared/concave.h). Deterministic without
 * sorting: a count pass, an exclusive scan of the counts (prims/scan, from the host), and a write pass that puts each pair's
 * triangles at its offset in walk order, so the sub-pairs come out grouped by pair in the
 * kind-grouped pair order.
 * Launch: midphase_count / midphase_write any number of work-items striding over the count
 * slots (pairCapacity + 1: the last one, always 0, ends up holding the total); midphase_total
 * one work-item.
 * Reads pairs, kindOrder, kindRanges (the mesh kinds' range), pos, rot, props, shapes, children, meshes,
 * meshNodes, meshParts, heightfields, heightfieldHeights. Writes subPairCounts (counts, then offsets after the scan), subPairs,
 * counters[BTG_COUNTER_SUB_PAIRS] (every sub-pair found, even past capacity) and the status
 * bit BTG_STATUS_SUB_PAIR_OVERFLOW, on which the host grows subPairs and redoes the step. */
#include "shared/counters.h"
#include "shared/concave.h"

static uint midphase_slot(uint i, uint start, __global const uint* restrict kindOrder, int indirect)
{
    return indirect ? kindOrder[start + i] : start + i;
}

__kernel void midphase_count(__global const BtgPair* restrict pairs, __global const uint* restrict kindOrder,
                             __global const uint* restrict kindRanges, int indirect,
                             __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                             __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                             __global const BtgChild* restrict children,
                             __global const BtgMesh* restrict meshes, __global const BtgBvhNode* restrict nodes,
                             __global const int* restrict parts, __global const BtgTriangle* restrict triangles,
                             __global const BtgFloat4* restrict meshVerts,
                             __global const BtgHeightfield* restrict heightfields, __global const float* restrict heights,
                             __global uint* restrict counts, uint countSlots, int persistent)
{
    uint start, end;
    btgMeshPairRange(kindRanges, &start, &end);
    for (uint i = (uint)get_global_id(0); i < countSlots; i += (uint)get_global_size(0)) {
        uint c = 0u;
        if (start + i < end) {
            uint slot = midphase_slot(i, start, kindOrder, indirect);
            c = btgMidphasePair(pairs[slot], (int)slot, pos, rot, props, shapes, children, BTG_CONCAVE_TABLE_ARGS, 0, 0u,
                                0u, persistent);
        }
        counts[i] = c;
    }
}

__kernel void midphase_total(__global const uint* restrict offsets, uint countSlots, __global uint* restrict counters,
                             uint capacity)
{
    if (get_global_id(0) != 0) return;
    uint total = offsets[countSlots - 1u];
    counters[BTG_COUNTER_SUB_PAIRS] = total;
    if (total > capacity) counters[BTG_COUNTER_STATUS] |= BTG_STATUS_SUB_PAIR_OVERFLOW;
}

__kernel void midphase_write(__global const BtgPair* restrict pairs, __global const uint* restrict kindOrder,
                             __global const uint* restrict kindRanges, int indirect,
                             __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                             __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                             __global const BtgChild* restrict children,
                             __global const BtgMesh* restrict meshes, __global const BtgBvhNode* restrict nodes,
                             __global const int* restrict parts, __global const BtgTriangle* restrict triangles,
                             __global const BtgFloat4* restrict meshVerts,
                             __global const BtgHeightfield* restrict heightfields, __global const float* restrict heights,
                             __global const uint* restrict offsets,
                             uint countSlots, __global BtgSubPair* restrict subPairs, uint capacity, int persistent)
{
    uint start, end;
    btgMeshPairRange(kindRanges, &start, &end);
    for (uint i = (uint)get_global_id(0); i + 1u < countSlots && start + i < end; i += (uint)get_global_size(0)) {
        uint first = offsets[i];
        if (offsets[i + 1u] == first || first >= capacity) continue;
        uint slot = midphase_slot(i, start, kindOrder, indirect);
        btgMidphasePair(pairs[slot], (int)slot, pos, rot, props, shapes, children, BTG_CONCAVE_TABLE_ARGS, subPairs,
                        first, capacity, persistent);
    }
}
