// broadphase_scratch.h — temporaries find_pairs keeps between steps so nothing is reallocated
// per step: the grid's sorted (hash, row) list and cell ranges, the unsorted pairs and the
// arrays and scratch of their sort. Only src/stages/find_pairs.cpp looks inside.
#pragma once
#include "stages/prims/radix_sort.h"
#include "shared/types.h"

namespace btgpu {

struct BroadphaseScratch {
    cl::DeviceArray<uint> cellKeys;    // N: cell hash per gridded body (0xffffffff: not gridded)
    cl::DeviceArray<uint> cellRows;    // N: body row, sorted with cellKeys
    cl::DeviceArray<uint> cellRange;   // 2 per hash: [start, end) in the sorted list
    cl::DeviceArray<BtgPair> rawPairs; // pairCapacity: as appended, unsorted
    cl::DeviceArray<uint> pairKeys;    // pairCapacity: sort keys
    cl::DeviceArray<uint> pairOrder;   // pairCapacity: slots of rawPairs in sorted order
    RadixScratch sort;
};

}  // namespace btgpu
