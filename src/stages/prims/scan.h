// scan.h — exclusive prefix sum of a uint device array, in place (wrapping arithmetic).
// Work-group scans in local memory, then the block totals are scanned recursively and added
// back. ScanScratch owns the per-level block-sum arrays so repeated scans allocate nothing.
#pragma once
#include "cl/buffer.h"
#include "cl/launch.h"
#include "shared/prelude.h"  // uint

#include <deque>

namespace btgpu {

struct ScanScratch {
    // Block totals, one array per recursion level; a deque so growing it never moves the
    // arrays a caller up the recursion still holds.
    std::deque<cl::DeviceArray<uint>> levels;
};

// Replaces data[0, n) by its exclusive prefix sum. n is a host-side count (or an upper bound
// whose tail the caller has filled with zeros).
void exclusiveScan(cl::Context& ctx, cl::Profiler* profiler, cl::DeviceArray<uint>& data, size_t n,
                   ScanScratch& scratch);

}  // namespace btgpu
