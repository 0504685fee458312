// color_constraints.cpp — host launcher of the batching stage: w.colorRounds colors (set from
// the last readback: the colors the scene needed plus slack), each filled in kSubRounds
// claim/assign passes on the device, then the leftovers take the last color (solved serially;
// counted so the next step runs more rounds). The host reads no count inside the step. On GPUs
// all of it is one launch (color_resident, stages/resident.h); on CPUs one work-item's
// (color_serial) where it has a few cores.
#include "stages/color_constraints.h"

#include "cl/program.h"
#include "stages/resident.h"
#include "shared/coloring.h"

#include <algorithm>

namespace btgpu {

namespace {
// Claim/assign passes per color: the first takes the local minima, the next fill the color up
// to nearly a maximal matching, which keeps the number of colors near the bodies' degree.
constexpr int kSubRounds = BTG_COLOR_SUB_ROUNDS;
// Small scenes (as of the last readback) color in one launch on one work-group on a CPU device of
// many cores and on a GPU that went over to per-round launches (counted in contacts, the edges'
// bulk).
constexpr int kOneGroupMaxContacts = 4096;
constexpr int kOneGroupMaxBodies = 16384;
}  // namespace

void colorConstraints(DeviceWorld& w, int maxColors, bool orderJoints)
{
    cl::Context& ctx = w.ctx;
    if (maxColors < 1) maxColors = 1;
    // Joints in stock's order (the host's levels; none where no two joints share a body): each
    // level a colour of its own, so the rounds reach the last level (beyond maxColors the rest
    // are leftovers, solved serially in joint order).
    const int ordered = orderJoints && w.numJoints > 0 && w.maxJointLevel > 0 ? 1 : 0;
    const int rounds = std::clamp(ordered ? std::max(w.colorRounds, w.maxJointLevel + 1) : w.colorRounds, 0, maxColors - 1);
    w.jointLevels.reserve(ctx, 1);  // bound even when unordered
    w.numColors = rounds + 1;  // the last one is the serial pass for leftovers
    cl::Program& prog = ctx.program("color_constraints");
    size_t slots = std::min({w.edgeCapacity, w.edges.capacity(), w.edgeColor.capacity()});
    int edgeCapacity = int(slots);
    if (slots == 0) return;
    size_t bodies = size_t(std::max(w.numBodies, 1));
    // color_resident's claims: two halves taken in turn, then a word per sub-round (its comment)
    w.solverScratch.bodyClaim.reserve(ctx, 2 * bodies + size_t(rounds) * kSubRounds);
    w.solverScratch.bodyColor.reserve(ctx, bodies);
    w.counters.fill(ctx, 0u, BTG_COUNTER_COLORS_USED, 2);  // colors used and leftovers
    // The whole batching in one launch: on a GPU over resident groups sized for one round's
    // work; on a CPU over one group for small scenes, where launch overhead would dominate.
    const bool resident = useResident(w);
    if (!resident && ctx.device().fewCpuCores()) {
        // A CPU device of a few cores: one work-item, the same coloring (color_serial's comment).
        w.solverScratch.colorActive.reserve(ctx, 8 * slots);  // two lists, four ints an edge
        cl::Launch(ctx, prog.kernel("color_serial"), &w.profiler).arg(w.edges).arg(w.edgeColor).arg(w.counters)
            .arg(edgeCapacity).arg(w.props).arg(w.solverScratch.bodyClaim).arg(w.solverScratch.bodyColor)
            .arg(w.numBodies).arg(rounds).arg(w.solverScratch.colorActive).arg(w.jointLevels).arg(w.numJoints)
            .arg(ordered).run(1);
        return;
    }
    if (resident || (w.lastContactCount <= kOneGroupMaxContacts && w.numBodies <= kOneGroupMaxBodies)) {
        cl_kernel k = prog.kernel("color_resident");
        size_t group = std::min<size_t>(256, cl::kernelGroupLimit(ctx, k));
        size_t items = std::min(slots, size_t(std::max(w.lastContactCount, 1)));
        size_t groups = resident ? residentGroups(w, std::max(items, size_t(w.numBodies)), group) : 1;
        cl::Launch(ctx, k, &w.profiler).arg(w.edges).arg(w.edgeColor).arg(w.counters).arg(edgeCapacity).arg(w.props)
            .arg(w.solverScratch.bodyClaim).arg(w.solverScratch.bodyColor).arg(w.numBodies).arg(rounds)
            .arg(gridBarrier(w)).arg(gridBarrierSpins(w)).arg(w.jointLevels).arg(w.numJoints).arg(ordered)
            .run(groups * group, group);
        return;
    }
    cl_kernel reset = prog.kernel("claim_reset");
    cl_kernel claim = prog.kernel("color_claim");
    cl_kernel assign = prog.kernel("color_assign");

    cl::Launch(ctx, prog.kernel("color_init"), &w.profiler).arg(w.edgeColor).arg(w.counters).arg(edgeCapacity).run(slots);
    cl::Launch(ctx, prog.kernel("body_color_reset"), &w.profiler).arg(w.solverScratch.bodyColor).arg(w.props).arg(w.numBodies).run(bodies);
    for (int color = 0; color < rounds; ++color) {
        if (ordered)
            cl::Launch(ctx, prog.kernel("color_joints"), &w.profiler).arg(w.edges).arg(w.edgeColor).arg(w.counters)
                .arg(edgeCapacity).arg(w.solverScratch.bodyColor).arg(color).arg(w.jointLevels).arg(w.numJoints)
                .arg(ordered).run(size_t(w.numJoints));
        for (int sub = 0; sub < kSubRounds; ++sub) {
            cl::Launch(ctx, reset, &w.profiler).arg(w.solverScratch.bodyClaim).arg(w.numBodies).run(bodies);
            cl::Launch(ctx, claim, &w.profiler).arg(w.edges).arg(w.edgeColor).arg(w.counters).arg(edgeCapacity)
                .arg(w.solverScratch.bodyClaim).arg(w.solverScratch.bodyColor).arg(color).arg(w.jointLevels)
                .arg(w.numJoints).arg(ordered).run(slots);
            cl::Launch(ctx, assign, &w.profiler).arg(w.edges).arg(w.edgeColor).arg(w.counters).arg(edgeCapacity)
                .arg(w.solverScratch.bodyClaim).arg(w.solverScratch.bodyColor).arg(color).arg(w.jointLevels)
                .arg(w.numJoints).arg(ordered).run(slots);
        }
    }
    cl::Launch(ctx, prog.kernel("color_finish"), &w.profiler).arg(w.edgeColor).arg(w.counters).arg(edgeCapacity)
        .arg(rounds).run(slots);
}

}  // namespace btgpu
