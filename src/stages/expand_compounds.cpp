// expand_compounds.cpp — host launcher of kernels/expand_compounds.cl: count per pair, exclusive
// scan of the counts (pairCapacity + 1 slots: the last holds the total), the write pass, the
// total into the counters with the overflow bit, the copy back over `pairs`, then the kind
// grouping the narrowphase kernels walk. Nothing is read back.
#include "stages/expand_compounds.h"

#include "cl/program.h"
#include "stages/find_pairs.h"

#include <algorithm>

namespace btgpu {

void expandCompounds(DeviceWorld& w, const PairKinds& kinds)
{
    cl::Context& ctx = w.ctx;
    const size_t capacity = std::min(w.pairCapacity, w.pairs.capacity());
    if (capacity > 0) {
        const size_t slots = capacity + 1;
        w.compoundOffsets.reserve(ctx, slots);
        w.compoundPairs.reserve(ctx, capacity);
        const size_t items = std::min(slots, size_t(std::max<cl_uint>(ctx.device().computeUnits, 1)) * 1024);
        const cl_uint countSlots = cl_uint(slots);
        cl::Program& prog = ctx.program("expand_compounds");
        cl::Launch(ctx, prog.kernel("expand_count"), &w.profiler)
            .arg(w.pairs).arg(w.counters).arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes).arg(w.children)
            .arg(w.compoundOffsets).arg(countSlots).arg(w.speculativeContacts ? 1 : 0)
            .run(items);
        exclusiveScan(ctx, &w.profiler, w.compoundOffsets, slots, w.compoundScan);
        cl::Launch(ctx, prog.kernel("expand_write"), &w.profiler)
            .arg(w.pairs).arg(w.counters).arg(w.pos).arg(w.rot).arg(w.props).arg(w.shapes).arg(w.children)
            .arg(w.compoundOffsets).arg(countSlots).arg(w.compoundPairs).arg(w.speculativeContacts ? 1 : 0)
            .run(items);
        // After the write pass, which reads the broadphase's count that this replaces.
        cl::Launch(ctx, prog.kernel("expand_total"), &w.profiler).arg(w.compoundOffsets).arg(countSlots).arg(w.counters).run(1, 1);
        cl::Launch(ctx, prog.kernel("expand_copy"), &w.profiler)
            .arg(w.compoundPairs).arg(w.counters).arg(cl_uint(capacity)).arg(w.pairs).arg(w.pairManifolds)
            .run(capacity);
    }
    if (kinds.any()) groupPairsByKind(w, kinds);
}

}  // namespace btgpu
