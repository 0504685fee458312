// broadphase_scratch.h — temporaries find_pairs keeps between steps so nothing is reallocated
// per step: the grid's sorted (hash, row) list and cell ranges, or the sort-and-sweep's
// sorted (key, row) list and AABBs (each allocated on first use, so only the broadphase the
// plan names holds memory), the unsorted pairs and the keys and scratch of their sort (its
// values, the pair order, are DeviceWorld::pairOrder: the narrowphase reads them).
// Only src/stages/find_pairs.cpp and src/stages/sort_sweep.cpp look inside.
#pragma once
#include "stages/prims/radix_sort.h"
#include "shared/types.h"

namespace btgpu {

struct BroadphaseScratch {
    cl::DeviceArray<uint> cellKeys;    // N: cell hash per gridded body (0xffffffff: not gridded)
    cl::DeviceArray<uint> cellRows;    // N: body row, sorted with cellKeys
    cl::DeviceArray<uint> cellRange;   // 2 per hash: [start, end) in the sorted list
    cl::DeviceArray<uint> sapAxis;     // 1: the sweep axis (0 x, 1 y, 2 z), chosen on the device
    cl::DeviceArray<uint> sapKeys;     // N: AABB min on the axis as an ordered uint (0xffffffff: not swept)
    cl::DeviceArray<uint> sapRows;     // N: body row, sorted with sapKeys
    cl::DeviceArray<BtgFloat4> sapMin; // N: m, AABBs in sorted order
    cl::DeviceArray<BtgFloat4> sapMax;
    cl::DeviceArray<BtgPair> rawPairs; // pairCapacity: as appended, unsorted
    cl::DeviceArray<uint> pairKeys;    // pairCapacity: sort keys
    RadixScratch sort;
};

}  // namespace btgpu
