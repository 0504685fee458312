// solve_jacobi.cpp — host launcher of the Jacobi solve: per-body contact lists (count, scan,
// fill, sort), then per pass one launch over contacts and one over bodies. The host never
// reads the contact count: contact launches cover the capacity and early-out.
#include "stages/solve_jacobi.h"

#include "cl/program.h"

#include <algorithm>

namespace btgpu {

namespace {
}

void solveJacobi(DeviceWorld& w, const BtgStepParams& params, int iterations)
{
    cl::Context& ctx = w.ctx;
    size_t slots = std::min(w.contactCapacity, w.contacts.capacity());
    int contactCapacity = int(slots);
    int numBodies = std::max(w.numBodies, 0);
    size_t bodies = size_t(numBodies);
    if (params.splitImpulse && bodies > 0) {
        w.pushLin.zero(ctx, bodies);
        w.pushAng.zero(ctx, bodies);
    } else {  // bound, not read
        w.pushLin.reserve(ctx, 1);
        w.pushAng.reserve(ctx, 1);
    }
    if (slots == 0 || bodies == 0) return;
    SolverScratch& s = w.solverScratch;
    cl::Program& prog = ctx.program("solve_jacobi");

    s.jacobiCursor.zero(ctx, bodies);
    s.jacobiStart.zero(ctx, bodies + 1);  // the last entry stays 0 and scans to the total
    s.jacobiEntries.reserve(ctx, 2 * slots);
    s.jacobiDeltas.reserve(ctx, 4 * slots);
    cl::Launch(ctx, prog.kernel("jacobi_count"), &w.profiler).arg(w.contacts).arg(w.counters).arg(contactCapacity)
        .arg(w.props).arg(s.jacobiCursor).run(slots);
    s.jacobiStart.copyRangeFrom(ctx, s.jacobiCursor, bodies);
    exclusiveScan(ctx, &w.profiler, s.jacobiStart, bodies + 1, s.jacobiScan);
    s.jacobiCursor.zero(ctx, bodies);
    cl::Launch(ctx, prog.kernel("jacobi_fill"), &w.profiler).arg(w.contacts).arg(w.counters).arg(contactCapacity)
        .arg(w.props).arg(s.jacobiStart).arg(s.jacobiCursor).arg(s.jacobiEntries).run(slots);
    cl::Launch(ctx, prog.kernel("jacobi_sort_lists"), &w.profiler).arg(s.jacobiStart).arg(numBodies)
        .arg(s.jacobiEntries).run(bodies);

    cl_kernel solve = prog.kernel("jacobi_solve");
    cl_kernel gather = prog.kernel("jacobi_gather");
    auto pass = [&](int mode, cl::DeviceArray<BtgFloat4>& lin, cl::DeviceArray<BtgFloat4>& ang) {
        cl::Launch(ctx, solve, &w.profiler).arg(w.contacts).arg(w.counters).arg(contactCapacity).arg(w.props)
            .arg(w.invInertiaWorld).arg(s.jacobiStart).arg(lin).arg(ang).arg(s.jacobiDeltas).arg(mode).run(slots);
        cl::Launch(ctx, gather, &w.profiler).arg(numBodies).arg(s.jacobiStart).arg(s.jacobiEntries).arg(s.jacobiDeltas)
            .arg(lin).arg(ang).run(bodies);
    };
    pass(BTG_PASS_WARM_START, w.linVel, w.angVel);
    for (int it = 0; it < iterations; ++it) pass(BTG_PASS_VELOCITY, w.linVel, w.angVel);
    if (params.splitImpulse)
        for (int it = 0; it < iterations; ++it) pass(BTG_PASS_PUSH, w.pushLin, w.pushAng);
}

}  // namespace btgpu
