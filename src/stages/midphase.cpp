// midphase.cpp — host launcher of kernels/midphase.cl: count per mesh pair, exclusive scan of
// the counts (pairCapacity + 1 slots: the last holds the total), the total into the counters
// with the overflow bit, then the write pass. Nothing is read back.
#include "stages/midphase.h"

#include "cl/program.h"

#include <algorithm>

namespace btgpu {

void midphase(DeviceWorld& w)
{
    cl::Context& ctx = w.ctx;
    if (w.pairCapacity == 0) return;
    // First use: one sub-pair per two pair slots (a body on a mesh meets a few triangles, and
    // most pairs are not mesh pairs); an overflow grows it to what the midphase counted.
    w.subPairCapacity = std::max<size_t>(w.subPairCapacity, std::max<size_t>(256, w.pairCapacity / 2));
    const size_t slots = w.pairCapacity + 1;
    w.subPairOffsets.reserve(ctx, slots);
    w.subPairs.reserveExact(ctx, w.subPairCapacity);
    // Before any narrowphase of this substep writes a manifold: growing does not keep contents.
    w.manifolds.reserveExact(ctx, w.pairCapacity + w.subPairCapacity);
    const size_t items = std::min(slots, size_t(std::max<cl_uint>(ctx.device().computeUnits, 1)) * 1024);
    const cl_int indirect = w.pairKindsIndirect ? 1 : 0;
    const cl_uint countSlots = cl_uint(slots), capacity = cl_uint(w.subPairCapacity);
    // The bullet mode's manifolds persist as stock's: its box is stock's (no threshold).
    const cl_int persistent = w.speculativeContacts ? 0 : 1;
    cl::Program& prog = ctx.program("midphase");
    cl::Launch(ctx, prog.kernel("midphase_count"), &w.profiler)
        .arg(w.pairs).arg(w.pairOrder).arg(w.pairKindRanges).arg(indirect).arg(w.pos).arg(w.rot).arg(w.props)
        .arg(w.shapes).arg(w.children).arg(w.meshes).arg(w.meshNodes).arg(w.meshParts).arg(w.meshTriangles).arg(w.meshVertices)
        .arg(w.heightfields).arg(w.heightfieldHeights).arg(w.subPairOffsets).arg(countSlots).arg(persistent)
        .run(items);
    exclusiveScan(ctx, &w.profiler, w.subPairOffsets, slots, w.subPairScan);
    cl::Launch(ctx, prog.kernel("midphase_total"), &w.profiler)
        .arg(w.subPairOffsets).arg(countSlots).arg(w.counters).arg(capacity).run(1, 1);
    cl::Launch(ctx, prog.kernel("midphase_write"), &w.profiler)
        .arg(w.pairs).arg(w.pairOrder).arg(w.pairKindRanges).arg(indirect).arg(w.pos).arg(w.rot).arg(w.props)
        .arg(w.shapes).arg(w.children).arg(w.meshes).arg(w.meshNodes).arg(w.meshParts).arg(w.meshTriangles).arg(w.meshVertices)
        .arg(w.heightfields).arg(w.heightfieldHeights).arg(w.subPairOffsets).arg(countSlots)
        .arg(w.subPairs).arg(capacity).arg(persistent)
        .run(items);
}

}  // namespace btgpu
