// pipeline.h — the whole step on the device: the substeps of one stepSimulation call,
// enqueued back to back with no host round trip, plus the snapshot that lets the caller redo
// the call after a buffer overflowed.
#pragma once
#include "world/device_world.h"
#include "world/plan.h"

#include <btgpu/Config.h>

namespace btgpu {

struct StepSettings {
    BtgStepParams params;  // dt is the fixed substep
    int substeps = 1;
    int iterations = 10;   // btContactSolverInfo::m_numIterations
    int maxColors = 24;    // BatchedPgs only
    SolverKind solver = SolverKind::BatchedPgs;  // must match the plan's
};

// Enqueues `s.substeps` substeps of the plan (the caller reads back once afterwards).
void runSubsteps(DeviceWorld& w, const Plan& plan, const StepSettings& s);

// What a redo needs: the body state and the counters as they were before the call. The
// warm-start cache needs nothing here: a substep that overflows leaves it untouched
// (store_contact_cache checks the status), and when a call runs several substeps runSubsteps
// keeps a copy of it (DeviceWorld::contactCacheAtCall) that restoreSnapshot puts back.
struct Snapshot {
    cl::DeviceArray<BtgFloat4> pos, rot, linVel, angVel;
    cl::DeviceArray<uint> counters;
};
void takeSnapshot(DeviceWorld& w, Snapshot& s);
void restoreSnapshot(DeviceWorld& w, Snapshot& s);

// Clears the status word and the NaN marker at the start of a call.
void resetStatus(DeviceWorld& w);

}  // namespace btgpu
