// Report.h — what a btGpuDynamicsWorld tells its app: the device, whether the GPU path runs
// (and why not), the plan (stages, built programs), per-stage times, counts, memory, and
// problems found (bad bodies, OpenCL failures, overflows).
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "btgpu/Config.h"

namespace btgpu {

struct Issue {
    // BadArgument: a stepSimulation argument (the call simulated nothing) or a world setting
    // such as a non-finite gravity. Difference: the GPU path gives the app less than stock would
    // by a Config choice (once, when it starts to; e.g. no empty manifolds past
    // Config::deviceEmptyManifoldsUpTo collision objects).
    enum class Kind { BadBody, OpenCL, Fallback, Overflow, Device, BadArgument, Difference };
    Kind kind;
    std::string message;
    int bodyIndex = -1;  // index in getCollisionObjectArray(), for BadBody
    int userIndex = -1;  // the body's getUserIndex()
    int shapeType = -1;  // the body's shape type (BroadphaseNativeTypes)
};

struct Report {
    std::string device;               // the OpenCL device in use, "" when none
    bool gpuPath = false;             // the last step ran on the OpenCL pipeline
    std::string cpuPathReason;        // why the base class's CPU path runs, when it does
    std::vector<std::string> stages;  // the plan: stages the step launches, in order
    std::vector<std::string> builtPrograms;  // OpenCL programs compiled so far
    double buildSeconds = 0.0;        // time spent compiling them
    std::map<std::string, double> stageMs;   // device ms per stage, last step (Config::profile)
    int launches = 0;                 // kernel launches in the last stepSimulation call
    // Host wall times of the last stepSimulation call on the GPU path, ms: finding what the app
    // changed and uploading it; the device substeps with their one readback (enqueue, wait,
    // copy); writing the results into the btRigidBody objects and their motion states (and
    // clearing forces); keeping Bullet's own broadphase AABBs current (Config::syncBroadphaseAabbs).
    double checkMs = 0.0;             // the checks before it: CPU-path rules, shape changes, rows followed
    double syncInMs = 0.0;
    double deviceMs = 0.0;
    double writeBackMs = 0.0;
    double manifoldFillMs = 0.0;      // the app's dispatcher manifolds filled (Config::fillDispatcherManifolds): in writeBackMs (with actions, in deviceMs)
    double aabbSyncMs = 0.0;          // what the sync added to the call (run beside the manifold fill in big worlds)
    double ghostBroadphaseMs = 0.0;   // with ghosts, an overlap filter or Config::stockEmptyManifolds: Bullet's broadphase pair update on the host (in syncInMs)
    // While the app's contact callbacks (gContactAddedCallback on CF_CUSTOM_MATERIAL_CALLBACK
    // bodies, gContactProcessedCallback, custom combiners) or an overlap filter need the host
    // between a step's contacts and its solve: that part's time (gather, callbacks, the changes
    // sent back), in deviceMs; and the added and processed callbacks' calls in this call.
    double callbackMs = 0.0;
    long contactCallbacks = 0;
    std::size_t deviceBytes = 0;      // device memory held by this world
    int pairs = 0;                    // broadphase pairs, last substep
    int contacts = 0;                 // manifolds with points, last substep
    int redoneSteps = 0;              // steps redone after a buffer grew (since creation)
    // The solver the last step ran on the GPU path (Config::solver, Auto resolved; never Auto),
    // and with Config::solver = Auto why it was not the soft step ("" when it was).
    SolverKind solver = SolverKind::BatchedPgs;
    std::string solverReason;
    int colors = 0;                   // graph colors (solver batches) the last step's constraints needed
    int softSubsteps = 0;             // SolverKind::SoftStep: substeps of the last step (SoftStepConfig::substepsPerRootMassRatio)
    std::vector<Issue> issues;        // every issue so far (also passed to Config::onIssue)
};

}  // namespace btgpu
