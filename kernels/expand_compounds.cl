/* expand_compounds.cl — Stage: expand_compounds. Each broadphase pair with a compound side
 * becomes the pairs of the compound's leaves that stock btCompoundCollisionAlgorithm processes
 * (btgExpandPair in shared/compound.h: its tree's query, then the leaf's world AABB against the
 * other body's); every other pair stays itself. Count, exclusive scan (prims/scan, from the
 * host), write: the list stays sorted by (a, b), each pair's leaves in child order, with no
 * sort and no atomics; the total replaces the pair count.
 * Launch: expand_count / expand_write any number of work-items striding over the count slots
 * (pairCapacity + 1: the last, always 0, ends up holding the total); expand_total one
 * work-item; expand_copy one work-item per pair slot.
 * speculative (the soft step): the culling tests grown by the pair's threshold (compound.h).
 * Reads pairs, pos, rot, props, shapes, children, counters[BTG_COUNTER_PAIRS]. Writes offsets,
 * expanded, then pairs and pairManifolds (empty), counters[BTG_COUNTER_PAIRS] (every leaf pair
 * found, even past capacity) and BTG_STATUS_PAIR_OVERFLOW, on which the host grows the pair
 * buffers and redoes the step. */
#include "shared/counters.h"
#include "shared/compound.h"

__kernel void expand_count(__global const BtgPair* restrict pairs, __global const uint* restrict counters,
                           __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                           __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                           __global const BtgChild* restrict children, __global uint* restrict counts,
                           uint countSlots, int speculative)
{
    const uint n = min(counters[BTG_COUNTER_PAIRS], countSlots - 1u);
    for (uint i = (uint)get_global_id(0); i < countSlots; i += (uint)get_global_size(0))
        counts[i] = i < n ? btgExpandPair(pairs[i], pos, rot, props, shapes, children, 0, 0u, 0u, speculative) : 0u;
}

/* When the broadphase itself overflowed, only the pairs that fit were expanded: the total is
 * scaled by found / stored, so the growth is sized for all of them in one redo. */
__kernel void expand_total(__global const uint* restrict offsets, uint countSlots, __global uint* restrict counters)
{
    if (get_global_id(0) != 0) return;
    const uint capacity = countSlots - 1u, found = counters[BTG_COUNTER_PAIRS];
    ulong total = (ulong)offsets[countSlots - 1u];
    if (found > capacity && capacity > 0u) total = total * (ulong)found / (ulong)capacity;
    counters[BTG_COUNTER_PAIRS] = (uint)min(total, (ulong)0xffffffffu);
    if (total > (ulong)capacity) counters[BTG_COUNTER_STATUS] |= BTG_STATUS_PAIR_OVERFLOW;
}

/* Runs before expand_total: reads the broadphase's count, which expand_total then replaces. */
__kernel void expand_write(__global const BtgPair* restrict pairs, __global const uint* restrict counters,
                           __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                           __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                           __global const BtgChild* restrict children, __global const uint* restrict offsets,
                           uint countSlots, __global BtgPair* restrict expanded, int speculative)
{
    const uint capacity = countSlots - 1u;
    const uint n = min(counters[BTG_COUNTER_PAIRS], capacity);
    for (uint i = (uint)get_global_id(0); i < n; i += (uint)get_global_size(0)) {
        const uint first = offsets[i];
        if (offsets[i + 1u] == first || first >= capacity) continue;
        btgExpandPair(pairs[i], pos, rot, props, shapes, children, expanded, first, capacity, speculative);
    }
}

__kernel void expand_copy(__global const BtgPair* restrict expanded, __global const uint* restrict counters,
                          uint capacity, __global BtgPair* restrict pairs, __global BtgManifoldRange* restrict pairManifolds)
{
    const uint k = (uint)get_global_id(0);
    if (k >= min(counters[BTG_COUNTER_PAIRS], capacity)) return;
    pairs[k] = expanded[k];
    BtgManifoldRange none;
    none.start = (int)k;
    none.count = 0;
    pairManifolds[k] = none;
}
