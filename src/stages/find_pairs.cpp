// find_pairs.cpp — host launcher of kernels/find_pairs.cl: the small bodies' pass (grid hash,
// radix sort of (hash, row), cell ranges, grid pairs; or stages/sort_sweep), the large and
// plane passes, then a radix sort of the appended pairs by (kind, a, b): the (a, b) digits, the
// gather into w.pairs, the kind digit into w.pairOrder and the kind ranges. The pair count stays
// on the device: the sort runs over pairCapacity slots and its kernels read the count (no
// readback).
#include "stages/find_pairs.h"

#include "cl/program.h"
#include "stages/prims/radix_sort.h"
#include "stages/sort_sweep.h"

#include <algorithm>

namespace btgpu {
namespace {

// Hash table size: a power of two at least twice the bodies, so buckets hold ~0.5 cells.
cl_uint gridTableSize(size_t numBodies)
{
    cl_uint t = 2;
    while (t < 2 * numBodies) t *= 2;
    return t;
}

int log2Exact(cl_uint pow2)
{
    int b = 0;
    while ((cl_uint(1) << b) < pow2) ++b;
    return b;
}

void appendGridPairs(DeviceWorld& w, cl::Program& prog, cl_uint capacity, float cellSize)
{
    cl::Context& ctx = w.ctx;
    BroadphaseScratch& s = w.broadphase;
    const size_t n = size_t(w.numBodies);
    const cl_int numBodies = cl_int(n);
    const float invCellSize = 1.0f / cellSize;
    const cl_uint table = gridTableSize(n);
    const cl_uint tableMask = table - 1;
    s.cellKeys.reserve(ctx, n);
    s.cellRows.reserve(ctx, n);
    cl::Launch(ctx, prog.kernel("grid_hash"), &w.profiler)
        .arg(w.aabbMin).arg(w.aabbMax).arg(w.props).arg(w.shapes).arg(s.cellKeys).arg(s.cellRows)
        .arg(numBodies).arg(invCellSize).arg(tableMask)
        .run(n);
    // One bit above the hash so the 0xffffffff of ungridded rows sorts after every bucket.
    radixSort(ctx, &w.profiler, s.cellKeys, s.cellRows, n, log2Exact(table) + 1, s.sort);
    s.cellRange.zero(ctx, 2 * size_t(table));
    cl::Launch(ctx, prog.kernel("grid_cell_ranges"), &w.profiler).arg(s.cellKeys).arg(s.cellRange).arg(numBodies).run(n);
    cl::Launch(ctx, prog.kernel("grid_pairs"), &w.profiler)
        .arg(w.aabbMin).arg(w.aabbMax).arg(w.props).arg(s.cellKeys).arg(s.cellRows).arg(s.cellRange)
        .arg(s.rawPairs).arg(w.counters).arg(capacity).arg(numBodies).arg(invCellSize).arg(tableMask)
        .run(n);
}

// Never write past the pair buffer, whatever pairCapacity claims.
cl_uint pairSlots(DeviceWorld& w)
{
    const cl_uint capacity = cl_uint(std::min(w.pairCapacity, w.pairs.capacity()));
    w.broadphase.rawPairs.reserve(w.ctx, std::max<size_t>(capacity, 1));
    return capacity;
}

}  // namespace

void smallBodyPairs(DeviceWorld& w, Broadphase broadphase, float cellSize)
{
    cl::Context& ctx = w.ctx;
    cl::Program& prog = ctx.program("find_pairs");
    const cl_uint capacity = pairSlots(w);
    cl::Launch(ctx, prog.kernel("pairs_reset"), &w.profiler).arg(w.counters).run(1, 1);
    if (w.numBodies <= 0) return;
    if (broadphase == Broadphase::SortAndSweep) sortSweepPairs(w, capacity);
    else appendGridPairs(w, prog, capacity, cellSize);
}

void groupPairsByKind(DeviceWorld& w, const PairKinds& kinds)
{
    cl::Context& ctx = w.ctx;
    BroadphaseScratch& s = w.broadphase;
    cl::Program& prog = ctx.program("find_pairs");
    const cl_uint capacity = cl_uint(std::min(w.pairCapacity, w.pairs.capacity()));
    w.pairKindRanges.reserve(ctx, BTG_KIND_RANGES_SIZE);
    // One kind: the pairs are its range as they stand, nothing to sort.
    w.pairKindsIndirect = kinds.count() > 1;
    cl_int singleKind = -1;
    for (int k = 0; k < BTG_NUM_PAIR_KINDS && !w.pairKindsIndirect; ++k)
        if (kinds.has(k)) singleKind = k;
    if (w.pairKindsIndirect && capacity > 0) {
        s.pairKeys.reserve(ctx, capacity);
        w.pairOrder.reserve(ctx, capacity);
        cl::Launch(ctx, prog.kernel("pair_kind_keys"), &w.profiler)
            .arg(w.pairs).arg(w.props).arg(w.shapes).arg(w.children).arg(w.counters).arg(s.pairKeys).arg(w.pairOrder)
            .arg(capacity)
            .run(capacity);
        // The most significant digit of (kind, a, b): stable, so each kind keeps (a, b) order. Every
        // kind id fits (padding keys are all ones and sort last).
        radixSort(ctx, &w.profiler, s.pairKeys, w.pairOrder, capacity, radixBitsFor(BTG_NUM_PAIR_KINDS - 1), s.sort);
    } else {
        s.pairKeys.reserve(ctx, 1);
        w.pairOrder.reserve(ctx, 1);
    }
    cl::Launch(ctx, prog.kernel("pair_kind_ranges"), &w.profiler)
        .arg(s.pairKeys).arg(w.counters).arg(capacity).arg(w.pairKindsIndirect ? cl_int(-1) : singleKind)
        .arg(w.pairKindRanges)
        .run(BTG_NUM_PAIR_KINDS, BTG_NUM_PAIR_KINDS);
}

void finishPairs(DeviceWorld& w, const PairKinds& kinds, bool group)
{
    cl::Context& ctx = w.ctx;
    BroadphaseScratch& s = w.broadphase;
    cl::Program& prog = ctx.program("find_pairs");
    const size_t n = w.numBodies > 0 ? size_t(w.numBodies) : 0;
    const cl_int numBodies = cl_int(n);
    const cl_uint capacity = pairSlots(w);

    if (n > 0) {
        if (w.numLarge > 0)
            cl::Launch(ctx, prog.kernel("large_pairs"), &w.profiler)
                .arg(w.aabbMin).arg(w.aabbMax).arg(w.props).arg(w.shapes).arg(w.largeBodies).arg(cl_int(w.numLarge))
                .arg(s.rawPairs).arg(w.counters).arg(capacity).arg(numBodies)
                .run(n);
        if (w.numPlanes > 0)
            cl::Launch(ctx, prog.kernel("plane_pairs"), &w.profiler)
                .arg(w.aabbMin).arg(w.aabbMax).arg(w.props).arg(w.shapes).arg(w.pos).arg(w.rot).arg(w.planeBodies)
                .arg(cl_int(w.numPlanes)).arg(s.rawPairs).arg(w.counters).arg(capacity).arg(numBodies)
                .run(n);
    }

    if (capacity > 0) {
        s.pairKeys.reserve(ctx, capacity);
        w.pairOrder.reserve(ctx, capacity);
        const cl_uint rowBits = cl_uint(radixBitsFor(n > 1 ? cl_uint(n - 1) : 0u));
        auto keys = [&](cl_int mode) {
            cl::Launch(ctx, prog.kernel("pair_sort_keys"), &w.profiler)
                .arg(s.rawPairs).arg(w.pairOrder).arg(s.pairKeys).arg(w.counters).arg(capacity)
                .arg(mode).arg(rowBits)
                .run(capacity);
        };
        if (2 * rowBits <= 32) {
            keys(BTG_PAIR_KEY_PACKED);  // (a, b) packed in one key: a single sort
            radixSort(ctx, &w.profiler, s.pairKeys, w.pairOrder, capacity, int(2 * rowBits), s.sort);
        } else {
            // Two stable passes, minor key first. Padding keys are all ones in rowBits; a real b
            // can tie with them, but padding starts after every real slot and the sort is stable.
            keys(BTG_PAIR_KEY_MINOR);
            radixSort(ctx, &w.profiler, s.pairKeys, w.pairOrder, capacity, int(rowBits), s.sort);
            keys(BTG_PAIR_KEY_MAJOR);
            radixSort(ctx, &w.profiler, s.pairKeys, w.pairOrder, capacity, int(rowBits), s.sort);
        }
    } else {
        w.pairOrder.reserve(ctx, 1);
    }
    w.pairManifolds.reserveExact(ctx, std::max<size_t>(w.pairCapacity, 1));
    cl::Launch(ctx, prog.kernel("pairs_write"), &w.profiler)
        .arg(s.rawPairs).arg(w.pairOrder).arg(w.pairs.mem() ? w.pairs : s.rawPairs).arg(w.pairManifolds)
        .arg(w.counters).arg(capacity)
        .run(std::max<size_t>(capacity, 1));
    if (group && kinds.any()) groupPairsByKind(w, kinds);
}

void findPairs(DeviceWorld& w, const PairKinds& kinds, Broadphase broadphase, float cellSize)
{
    smallBodyPairs(w, broadphase, cellSize);
    finishPairs(w, kinds);
}

}  // namespace btgpu
