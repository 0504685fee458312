// color_constraints.cpp — host launcher of the batching stage: maxColors - 1 claim/assign
// rounds on the device (3 launches each), then the leftovers take the last color. The host
// never reads the count: every launch covers the contact capacity and early-outs.
#include "stages/color_constraints.h"

#include "cl/program.h"

#include <algorithm>

namespace btgpu {

void colorConstraints(DeviceWorld& w, int maxColors)
{
    cl::Context& ctx = w.ctx;
    w.profiler.stage = "batching";
    if (maxColors < 1) maxColors = 1;
    w.numColors = maxColors;
    cl::Program& prog = ctx.program("color_constraints");
    size_t slots = std::min(w.contactCapacity, w.contacts.capacity());
    int contactCapacity = int(slots);
    if (slots == 0) return;
    size_t bodies = size_t(std::max(w.numBodies, 1));
    w.solverScratch.bodyClaim.reserve(ctx, bodies);
    cl_kernel reset = prog.kernel("claim_reset");
    cl_kernel claim = prog.kernel("color_claim");
    cl_kernel assign = prog.kernel("color_assign");

    cl::Launch(ctx, prog.kernel("color_init"), &w.profiler).arg(w.contacts).arg(w.counters).arg(contactCapacity).run(slots);
    for (int round = 0; round < maxColors - 1; ++round) {
        cl::Launch(ctx, reset, &w.profiler).arg(w.solverScratch.bodyClaim).arg(w.numBodies).run(bodies);
        cl::Launch(ctx, claim, &w.profiler).arg(w.contacts).arg(w.counters).arg(contactCapacity).arg(w.props)
            .arg(w.solverScratch.bodyClaim).run(slots);
        cl::Launch(ctx, assign, &w.profiler).arg(w.contacts).arg(w.counters).arg(contactCapacity).arg(w.props)
            .arg(w.solverScratch.bodyClaim).arg(round).run(slots);
    }
    cl::Launch(ctx, prog.kernel("color_finish"), &w.profiler).arg(w.contacts).arg(w.counters).arg(contactCapacity)
        .arg(maxColors - 1).run(slots);
}

}  // namespace btgpu
