// update_activation.cpp — host launcher of the deactivation stage.
#include "stages/update_activation.h"

#include <algorithm>
#include <utility>

namespace btgpu {

void updateActivation(DeviceWorld& w, float dt, float deactivationTime, int rounds)
{
    cl::Program& prog = w.ctx.program("update_activation");
    const int n = w.numBodies;
    cl::Launch(w.ctx, prog.kernel("own_timers"), &w.profiler)
        .arg(n).arg(w.linVel).arg(w.angVel).arg(w.props).arg(w.sleepTime).arg(w.islandTime).arg(w.wake).arg(dt)
        .arg(w.counters).arg(w.islandLabel).arg(w.islandWake).run(n);
    const int capacity = int(std::min(w.edgeCapacity, w.edges.capacity()));
    // With deactivation off only apply_sleep runs, to report the sleep state the app set.
    if (deactivationTime <= 0.0f) rounds = 0;
    for (int r = 0; r < rounds; ++r) {
        w.islandScratch.copyFrom(w.ctx, w.islandTime, size_t(n));
        w.islandLabelScratch.copyFrom(w.ctx, w.islandLabel, size_t(n));
        cl::Launch(w.ctx, prog.kernel("island_min"), &w.profiler)
            .arg(w.edges).arg(w.counters).arg(capacity).arg(w.props).arg(w.sleepTime).arg(w.islandTime)
            .arg(w.islandScratch).arg(w.wake).arg(w.numJoints).arg(w.islandLabel).arg(w.islandLabelScratch)
            .run(size_t(capacity));
        std::swap(w.islandTime, w.islandScratch);
        std::swap(w.islandLabel, w.islandLabelScratch);
    }
    cl::Launch(w.ctx, prog.kernel("apply_sleep"), &w.profiler)
        .arg(n).arg(w.islandTime).arg(w.wake).arg(w.sleepTime).arg(w.props).arg(w.linVel).arg(w.angVel)
        .arg(w.sleepState).arg(deactivationTime).arg(w.counters)
        .run(n);
    // Stock's islands are its broadphase pairs: a sleeping island a moving body's pair reaches
    // wakes whole now, so that the next step collides its own pairs (wake_paired).
    const int pairCapacity = int(std::min(w.pairCapacity, w.pairs.capacity()));
    if (deactivationTime > 0.0f && pairCapacity > 0) {
        cl::Launch(w.ctx, prog.kernel("wake_paired"), &w.profiler)
            .arg(w.pairs).arg(w.counters).arg(pairCapacity).arg(n).arg(w.props).arg(w.sleepTime).arg(w.islandLabel)
            .arg(w.islandWake).run(size_t(pairCapacity));
        cl::Launch(w.ctx, prog.kernel("wake_paired_apply"), &w.profiler)
            .arg(n).arg(w.props).arg(w.sleepTime).arg(w.sleepState).arg(w.islandLabel).arg(w.islandWake).arg(w.counters)
            .run(n);
    }
}

void wakeTouched(DeviceWorld& w)
{
    cl::Program& prog = w.ctx.program("update_activation");
    const int n = w.numBodies;
    // The marks of the last step's island_min stay after apply_sleep woke their bodies; an app
    // may have put such a body to sleep since.
    w.wake.fill(w.ctx, 0u, 0, size_t(n));
    const int capacity = int(std::min(w.contactCapacity, w.contacts.capacity()));
    if (capacity > 0)
        cl::Launch(w.ctx, prog.kernel("wake_touched"), &w.profiler)
            .arg(w.contacts).arg(w.counters).arg(capacity).arg(w.props).arg(w.sleepTime).arg(w.wake)
            .run(size_t(capacity));
    if (w.numJoints > 0) {
        // One work-group: the joints' closure takes rounds with a group barrier between them.
        cl_kernel k = prog.kernel("wake_jointed");
        const size_t group = std::max<size_t>(
            1, std::min({cl::kernelWorkGroupSize(w.ctx, k), w.ctx.device().maxWorkGroupSize, size_t(256)}));
        cl::Launch(w.ctx, k, &w.profiler)
            .arg(w.joints).arg(w.numJoints).arg(w.props).arg(w.wake)
            .run(group, group);
    }
    cl::Launch(w.ctx, prog.kernel("wake_island_mark"), &w.profiler)
        .arg(n).arg(w.wake).arg(w.props).arg(w.islandLabel).arg(w.islandWake).run(n);
    cl::Launch(w.ctx, prog.kernel("wake_island_spread"), &w.profiler)
        .arg(n).arg(w.wake).arg(w.props).arg(w.islandLabel).arg(w.islandWake).run(n);
    cl::Launch(w.ctx, prog.kernel("wake_apply"), &w.profiler)
        .arg(n).arg(w.wake).arg(w.props).arg(w.sleepTime).arg(w.sleepState)
        .run(n);
}

}  // namespace btgpu
