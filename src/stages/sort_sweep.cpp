// sort_sweep.cpp — host launcher of kernels/sort_sweep.cl: the axis (one work-group, result
// left on the device), keys, a 32-bit radix sort of (key, row), the gather of the sorted
// AABBs and the sweep. No count is read back: every launch covers all rows.
#include "stages/sort_sweep.h"

#include "cl/program.h"
#include "shared/sort_sweep.h"
#include "stages/prims/radix_sort.h"

namespace btgpu {

void sortSweepPairs(DeviceWorld& w, cl_uint capacity)
{
    const size_t n = w.numBodies > 0 ? size_t(w.numBodies) : 0;
    if (n == 0) return;
    cl::Context& ctx = w.ctx;
    BroadphaseScratch& s = w.broadphase;
    cl::Program& prog = ctx.program("sort_sweep");
    const cl_int numBodies = cl_int(n);
    // The reduction's order is fixed by its lane count; a smaller group would change it.
    if (ctx.device().maxWorkGroupSize < BTG_SAP_LANES)
        cl::fail("sap_axis needs a work-group of BTG_SAP_LANES", CL_INVALID_WORK_GROUP_SIZE, __FILE__, __LINE__);
    s.sapAxis.reserve(ctx, 1);
    s.sapKeys.reserve(ctx, n);
    s.sapRows.reserve(ctx, n);
    s.sapMin.reserve(ctx, n);
    s.sapMax.reserve(ctx, n);

    cl::Launch(ctx, prog.kernel("sap_axis"), &w.profiler)
        .arg(w.aabbMin).arg(w.aabbMax).arg(w.props).arg(w.shapes).arg(numBodies).arg(s.sapAxis)
        .run(BTG_SAP_LANES, BTG_SAP_LANES);
    cl::Launch(ctx, prog.kernel("sap_keys"), &w.profiler)
        .arg(w.aabbMin).arg(w.props).arg(w.shapes).arg(s.sapAxis).arg(s.sapKeys).arg(s.sapRows).arg(numBodies)
        .run(n);
    // Full 32-bit keys: the float order needs every bit. Stable, so equal mins keep row order.
    radixSort(ctx, &w.profiler, s.sapKeys, s.sapRows, n, 32, s.sort);
    cl::Launch(ctx, prog.kernel("sap_gather"), &w.profiler)
        .arg(w.aabbMin).arg(w.aabbMax).arg(s.sapKeys).arg(s.sapRows).arg(s.sapMin).arg(s.sapMax).arg(numBodies)
        .run(n);
    cl::Launch(ctx, prog.kernel("sap_pairs"), &w.profiler)
        .arg(w.props).arg(s.sapAxis).arg(s.sapKeys).arg(s.sapRows).arg(s.sapMin).arg(s.sapMax)
        .arg(s.rawPairs).arg(w.counters).arg(capacity).arg(numBodies)
        .run(n);
}

}  // namespace btgpu
