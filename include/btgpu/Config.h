// Config.h — every option of a btGpuDynamicsWorld: device choice, what to keep in step with
// the CPU side, contact and solver settings the btContactSolverInfo does not carry.
// No global variable changes behaviour: everything lives here (BTGPU_DEVICE, the one
// environment override, picks the device).
#pragma once
#include <cstddef>
#include <functional>
#include <string>

namespace btgpu {

struct Issue;

// How the contacts are solved. BatchedPgs: projected Gauss-Seidel as btSequentialImpulse-
// ConstraintSolver, batched by graph coloring (contacts of one color in parallel).
// JacobiMassSplitting: every contact in parallel against copies of its bodies holding 1/n of
// their mass, averaged after each iteration (Tonge et al. 2012): no coloring, two launches per
// iteration whatever the scene, but slower to converge per iteration.
enum class SolverKind { BatchedPgs, JacobiMassSplitting };

struct Config {
    // "" (first GPU, else a CPU device), "gpu", "cpu", or a substring of the platform or device
    // name. The environment variable BTGPU_DEVICE overrides it.
    std::string device;
    // Run on the base class's CPU path regardless (for comparisons and debugging).
    bool forceCpu = false;
    // Keep the CPU broadphase's AABBs current after each step so rayTest, convexSweepTest and
    // contactTest see the bodies where they are. Apps that never query may turn it off.
    bool syncBroadphaseAabbs = true;
    // Keep the app's dispatcher holding the contact manifolds stock Bullet would
    // (getNumManifolds, getManifoldByIndexInternal: points, impulses, lifetimes) after each
    // step. Apps that never read contacts may turn it off: the dispatcher then holds none.
    bool fillDispatcherManifolds = true;
    // Per-stage device times from OpenCL profiling events (Report::stageMs), taken on one
    // stepSimulation call in profileEvery (events cost host time on every launch).
    bool profile = false;
    int profileEvery = 1;
    // m: points closer than this become contacts (Bullet's gContactBreakingThreshold).
    float contactThreshold = 0.02f;
    SolverKind solver = SolverKind::BatchedPgs;
    // Device substeps per fixed step (stepSimulation's own substeps are not touched: the app
    // sees the same steps, motion states and interpolation). Stiff scenes (mass ratios, tall
    // stacks) converge much better from more, shorter steps than from more iterations; each
    // costs a full pipeline pass on the device and nothing on the host.
    int internalSubsteps = 1;
    // Upper bound on the solver's batches (graph colors) per iteration; contacts the coloring
    // cannot place within it run serially. The number actually launched follows the scene
    // (BatchedPgs only).
    int maxColors = 64;
    // A body whose bounding size exceeds this multiple of the median body size is paired by
    // brute force against all bodies instead of through the uniform grid.
    float largeBodyFactor = 4.0f;
    // Device memory this world may hold in buffers, bytes (0: as much as the device gives).
    // Running out, at this limit or the device's own, is an OpenCL failure: reported, and the
    // world continues on the CPU path from where it was.
    std::size_t deviceMemoryLimit = 0;
    // Called for each problem the world reports (bad body input, OpenCL failure, fallback).
    std::function<void(const Issue&)> onIssue;
};

}  // namespace btgpu
