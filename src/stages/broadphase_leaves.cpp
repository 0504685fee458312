// broadphase_leaves.cpp — host launcher of kernels/broadphase_leaves.cl: the leaves' update each
// substep; in the last, the sweep (the leaves' (y, z) cell entries sorted by cell and lower x
// bound with prims/radix_sort, each cell swept; the large rows against every row), the
// found pairs sorted by (a, b) as find_pairs sorts its own, and the difference with the last
// list appended (few), put in order by the host. Counts stay on the device until readLeafChanges.
#include "stages/broadphase_leaves.h"

#include "cl/program.h"
#include "shared/broadphase_leaves.h"
#include "shared/counters.h"

#include <algorithm>

namespace btgpu {

void reserveLeafPairs(DeviceWorld& w, size_t capacity)
{
    LeafBuffers& l = w.leaves;
    l.capacity = capacity;
    l.raw.reserveExact(w.ctx, capacity);
    l.transient.reserveExact(w.ctx, capacity);
    l.keys.reserveExact(w.ctx, capacity);
    l.order.reserveExact(w.ctx, capacity);
    l.lists[0].reserveExact(w.ctx, capacity, true);  // the last list is compared with the next one
    l.lists[1].reserveExact(w.ctx, capacity, true);
    l.changes.reserveExact(w.ctx, 2 * capacity);
}

void startLeafCall(DeviceWorld& w)
{
    LeafBuffers& l = w.leaves;
    const size_t n = size_t(std::max(w.numBodies, 1));
    l.counts.reserve(w.ctx, BTG_LEAF_NUM_COUNTS, true);
    if (l.leafMin.capacity() < n || l.reset) {
        l.leafMin.reserve(w.ctx, n);
        l.leafMax.reserve(w.ctx, n);
        l.oldMin.reserve(w.ctx, n);
        l.oldMax.reserve(w.ctx, n);
        l.moved.reserve(w.ctx, n);
        l.reset = true;
    }
    if (l.reset) l.counts.fill(w.ctx, 0u, 0, BTG_LEAF_NUM_COUNTS);  // no last list
    else l.counts.fill(w.ctx, 0u, BTG_LEAF_ADDED, BTG_LEAF_NUM_COUNTS - BTG_LEAF_ADDED);
    l.moved.fill(w.ctx, 0u, 0, n);
    if (l.capacity == 0) reserveLeafPairs(w, std::max<size_t>(256, 4 * n));  // as the pair list starts
}

void updateLeaves(DeviceWorld& w, float threshold, float dt)
{
    LeafBuffers& l = w.leaves;
    if (w.numBodies <= 0) return;
    cl::Launch(w.ctx, w.ctx.program("broadphase_leaves").kernel("leaves_update"), &w.profiler)
        .arg(cl_int(w.numBodies)).arg(w.pos).arg(w.rot).arg(w.linVel).arg(w.angVel).arg(w.props).arg(w.shapes)
        .arg(l.leafMin).arg(l.leafMax).arg(l.oldMin).arg(l.oldMax).arg(l.moved).arg(l.counts).arg(threshold).arg(dt)
        .arg(cl_int(l.continuous ? 1 : 0)).arg(cl_int(l.reset ? 1 : 0))
        .run(size_t(w.numBodies));
    l.reset = false;
}

void leafPairs(DeviceWorld& w, float cellSize)
{
    LeafBuffers& l = w.leaves;
    cl::Context& ctx = w.ctx;
    cl::Program& prog = ctx.program("broadphase_leaves");
    const size_t n = size_t(std::max(w.numBodies, 0));
    const cl_uint capacity = cl_uint(l.capacity);
    l.counts.fill(ctx, 0u, BTG_LEAF_FOUND, 1);
    l.counts.fill(ctx, 0u, BTG_LEAF_NEWPAIRS, 1);
    l.cell = cellSize;
    const float invCell = 1.0f / cellSize;
    l.counts.fill(ctx, 0u, BTG_LEAF_LARGE, 2);  // and the transient pairs
    if (n > 0) {
        l.sweepKeys.reserve(ctx, 4 * n);
        l.sweepRows.reserve(ctx, 4 * n);
        l.large.reserve(ctx, n);
        l.isLarge.reserve(ctx, n);
        cl::Launch(ctx, prog.kernel("leaves_entries"), &w.profiler)
            .arg(cl_int(n)).arg(w.props).arg(w.shapes).arg(l.leafMin).arg(l.leafMax).arg(l.oldMin).arg(l.oldMax)
            .arg(l.sweepKeys).arg(l.sweepRows)
            .arg(l.large).arg(l.isLarge).arg(l.counts).arg(invCell)
            .run(n);
        radixSort(ctx, &w.profiler, l.sweepKeys, l.sweepRows, 4 * n, BTG_LEAF_CELL_BITS + BTG_LEAF_SWEEP_BITS, l.sort);
        cl::Launch(ctx, prog.kernel("leaves_sweep"), &w.profiler)
            .arg(cl_int(4 * n)).arg(l.sweepKeys).arg(l.sweepRows).arg(w.props).arg(l.leafMin).arg(l.leafMax)
            .arg(l.oldMin).arg(l.oldMax).arg(l.moved).arg(l.raw).arg(l.transient).arg(l.counts).arg(capacity).arg(invCell)
            .run(4 * n);
        cl::Launch(ctx, prog.kernel("leaves_large"), &w.profiler)
            .arg(cl_int(n)).arg(l.large).arg(l.isLarge).arg(w.props).arg(l.leafMin).arg(l.leafMax).arg(l.oldMin)
            .arg(l.oldMax).arg(l.moved).arg(l.raw).arg(l.transient).arg(l.counts).arg(capacity)
            .run(n);
    }
    const cl_uint rowBits = cl_uint(radixBitsFor(n > 1 ? cl_uint(n - 1) : 0u));
    auto keys = [&](cl_int mode) {
        cl::Launch(ctx, prog.kernel("leaves_pair_keys"), &w.profiler)
            .arg(l.raw).arg(l.counts).arg(l.keys).arg(l.order).arg(capacity).arg(mode).arg(cl_int(rowBits))
            .run(capacity);
    };
    if (2 * rowBits <= 32) {
        keys(BTG_PAIR_KEY_PACKED);
        radixSort(ctx, &w.profiler, l.keys, l.order, capacity, int(2 * rowBits), l.sort);
    } else {
        // Minor key first; padding ties a real b only after every real slot (the sort is stable).
        keys(BTG_PAIR_KEY_MINOR);
        radixSort(ctx, &w.profiler, l.keys, l.order, capacity, int(rowBits), l.sort);
        keys(BTG_PAIR_KEY_MAJOR);
        radixSort(ctx, &w.profiler, l.keys, l.order, capacity, int(rowBits), l.sort);
    }
    cl::DeviceArray<BtgPair>& next = l.lists[1 - l.current];
    const cl::DeviceArray<BtgPair>& prev = l.lists[l.current];
    cl::Launch(ctx, prog.kernel("leaves_pairs_write"), &w.profiler)
        .arg(l.raw).arg(l.order).arg(l.counts).arg(next).arg(capacity)
        .run(capacity);
    l.counts.fill(ctx, 0u, BTG_LEAF_ADDED, 2);
    // A CPU device walks runs of 64 pairs (a bisection for each pair was 3 ms of a PoCL frame of
    // cubes 8,000); a GPU takes a pair a work-item.
    const int span = ctx.device().isGpu ? 1 : 64;
    const size_t half = (size_t(capacity) + size_t(span) - 1) / size_t(span);
    cl::Launch(ctx, prog.kernel("leaves_diff"), &w.profiler)
        .arg(next).arg(prev).arg(l.counts).arg(l.changes).arg(capacity).arg(span)
        .run(2 * half);
}

LeafChanges readLeafChanges(DeviceWorld& w)
{
    LeafBuffers& l = w.leaves;
    LeafChanges c;
    uint counts[BTG_LEAF_NUM_COUNTS];
    l.counts.download(w.ctx, counts, BTG_LEAF_NUM_COUNTS);
    if (counts[BTG_LEAF_MOVED] == 0) {
        // Nothing moved: no list was made; the last one stays.
        c.pairs = counts[BTG_LEAF_PREV];
        return c;
    }
    if (counts[BTG_LEAF_FOUND] > l.capacity || counts[BTG_LEAF_TRANSIENT] > l.capacity) {
        // The leaves stay as the call left them: only the list is made again, in a bigger buffer.
        const size_t found = std::max(counts[BTG_LEAF_FOUND], counts[BTG_LEAF_TRANSIENT]);
        reserveLeafPairs(w, std::max(l.capacity + l.capacity / 4, found + found / 4 + 64));
        // its own label: profiles had counted it under the step's last stage (update_activation)
        w.profiler.stage = "broadphase_leaves (list redone)";
        leafPairs(w, l.cell);
        l.counts.download(w.ctx, counts, BTG_LEAF_NUM_COUNTS);
        c.redone = true;
    }
    c.pairs = counts[BTG_LEAF_FOUND];
    c.newPairs = counts[BTG_LEAF_NEWPAIRS];
    c.moved = counts[BTG_LEAF_MOVED];
    const size_t added = counts[BTG_LEAF_ADDED], removed = counts[BTG_LEAF_REMOVED];
    // Appended in any order on the device: put in (a, b) order, as the lists hold them.
    auto less = [](const BtgPair& x, const BtgPair& y) { return x.a < y.a || (x.a == y.a && x.b < y.b); };
    c.added.resize(added);
    c.removed.resize(removed);
    if (added > 0) l.changes.download(w.ctx, c.added.data(), added);
    if (removed > 0) l.changes.download(w.ctx, c.removed.data(), removed, l.capacity);
    std::sort(c.added.begin(), c.added.end(), less);
    std::sort(c.removed.begin(), c.removed.end(), less);
    c.transient.resize(counts[BTG_LEAF_TRANSIENT]);
    if (!c.transient.empty()) l.transient.download(w.ctx, c.transient.data(), c.transient.size());
    std::sort(c.transient.begin(), c.transient.end(), less);
    l.current = 1 - l.current;
    l.counts.fill(w.ctx, c.pairs, BTG_LEAF_PREV, 1);
    return c;
}

}  // namespace btgpu
