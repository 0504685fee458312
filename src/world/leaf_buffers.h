// leaf_buffers.h — the device state of stage broadphase_leaves (stock's Dbvt leaf per row, kept
// across calls) and its work lists: the leaves' sweep order, the overlapping leaf pairs found,
// this call's and the last call's sorted lists, and what changed between them (read back).
// Allocated only while the plan has the stage. Only src/stages/broadphase_leaves.cpp looks inside.
#pragma once
#include "shared/types.h"
#include "stages/prims/radix_sort.h"

namespace btgpu {

struct LeafBuffers {
    cl::DeviceArray<BtgFloat4> leafMin;  // N: m, each row's leaf volume
    cl::DeviceArray<BtgFloat4> leafMax;
    cl::DeviceArray<BtgFloat4> oldMin;   // N: each row's leaf before the last substep's update
    cl::DeviceArray<BtgFloat4> oldMax;
    cl::DeviceArray<uint> moved;         // N: 1 when the row's leaf moved in this call
    cl::DeviceArray<uint> sweepKeys;     // 4N: entries' (cell hash, leaf min x) keys (BTG_LEAF_NO_ENTRY: none)
    cl::DeviceArray<uint> sweepRows;     // 4N: 4 row + which of its cells, sorted with sweepKeys
    cl::DeviceArray<int> large;          // N: rows too big for the cells (BTG_LEAF_LARGE of them)
    cl::DeviceArray<uint> isLarge;       // N: 1 for those
    float cell = 1.0f;                   // m: the cells' side
    RadixScratch sort;
    cl::DeviceArray<BtgPair> raw;        // capacity: overlapping leaf pairs as appended (a < b)
    cl::DeviceArray<BtgPair> transient;  // capacity: pairs stock's pass met whose leaves part by its end
    cl::DeviceArray<uint> keys;          // capacity: their sort keys
    cl::DeviceArray<uint> order;         // capacity: raw slots in (a, b) order
    cl::DeviceArray<BtgPair> lists[2];   // capacity each: sorted by (a, b); lists[current] the last call's
    int current = 0;
    cl::DeviceArray<BtgPair> changes;    // 2 x capacity: added pairs (childA 1) from 0, removed ones (childA 0) from capacity
    cl::DeviceArray<uint> counts;        // BTG_LEAF_NUM_COUNTS
    size_t capacity = 0;                 // pairs each list holds
    bool reset = true;                   // the next update starts every leaf afresh (rows re-uploaded)
    bool continuous = true;              // btDispatcherInfo::m_useContinuous
    float threshold = 0.02f;             // m: gContactBreakingThreshold, stock's AABB growth
};

}  // namespace btgpu
