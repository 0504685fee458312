// bench_backend.h — what the benchmark runner needs from each simulator (btgpu, stock
// Bullet, Bullet3's GPU pipeline): build a scene, step one frame with timings, hand back
// every body's pose in scene order, and report counts, stage times and memory.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "scenes/scene_specs.h"

namespace btgpu::bench {

// The scene data is the shared scene library's (tests/scenes/scene_specs.h).
using scenes::spec::BodySpec;
using scenes::spec::HullSpec;
using scenes::spec::Scene;
using scenes::spec::ShapeKind;
using scenes::spec::dimsForCount;
using scenes::spec::makeLandscape;
using scenes::spec::makeMixed;
using scenes::spec::makeStack;
using scenes::spec::makeVoronoi;
using scenes::spec::makeRagdolls;
using scenes::spec::makeCompounds;

struct Options {
    bool noSleep = false;           // disable Bullet's deactivation on every dynamic body
    bool noManifolds = false;       // btgpu: Config::fillDispatcherManifolds off (apps that never read contacts)
    bool emptyManifolds = false;    // btgpu: Config::stockEmptyManifolds (stock's empty manifolds too)
    bool noEmptyManifolds = false;  // btgpu: Config::deviceEmptyManifolds off (manifolds with points only)
    // btgpu: the app's contact callbacks' cost: "ground" (gContactAddedCallback, the first static
    // body CF_CUSTOM_MATERIAL_CALLBACK), "all" (every body flagged), "processed"
    // (gContactProcessedCallback); empty: none.
    std::string contactCallback;
    bool noAabbSync = false;        // btgpu: Config::syncBroadphaseAabbs off (apps that never query)
    bool jacobi = false;            // btgpu: Config::solver = JacobiMassSplitting
    bool soft = false;              // btgpu: Config::solver = SoftStep
    bool autoSolver = false;        // btgpu: Config::solver = Auto (the library's default)
    bool bulletMode = false;        // btgpu: Config::solver = BatchedPgs (Config::bulletMode())
    int softSubsteps = 0;           // btgpu: SoftStepConfig::substeps (0: m_numIterations')
    bool requireGpuPath = false;    // btgpu: skip (not fail) when the world is not on the GPU path
    bool b3NativeInertia = false;   // b3gpu: keep Bullet3's own (inflated) box inertia
    // Bullet worlds: one absolute contact breaking threshold (CD_USE_RELATIVE_CONTACT_BREAKING_
    // THRESHOLD off), to compare with builds from before btgpu followed the relative one.
    bool absoluteThresholds = false;
};

struct Pose {
    float p[3];
    float q[4];  // x, y, z, w
};

// One frame. writebackMs < 0: this backend has no separate host write-back (or we cannot
// separate it through its API).
struct FrameTime {
    double stepMs = 0;
    double writebackMs = -1;
};

// Filled after a frame, outside the timed region.
struct FrameInfo {
    std::map<std::string, double> stageMs;  // this frame's per-stage ms (device or host zones)
    long pairs = -1;
    long manifolds = -1;      // contact manifolds (pairs with points)
    long points = -1;         // contact points
    long long deviceBytes = -1;
    std::string overflow;     // non-empty once a fixed capacity overflowed (what and when)
};

class Backend {
public:
    virtual ~Backend() = default;
    virtual std::string name() const = 0;
    // Builds the world. False (with *why) when this backend cannot run here: the runner
    // reports it and goes on with the others.
    virtual bool setUp(const Scene& scene, const Options& options, std::string* why) = 0;
    virtual FrameTime step() = 0;
    virtual void poses(std::vector<Pose>& out) = 0;
    // detailed: also the costlier counts (contact points); the runner asks on the last frame.
    virtual void info(FrameInfo& out, bool detailed) = 0;
    // After the first frame: empty to go on, else why this backend stops (e.g. btgpu off its
    // GPU path under Options::requireGpuPath).
    virtual std::string checkAfterFirstFrame() { return {}; }
    virtual std::string device() const = 0;
    // Settings worth printing with the numbers (limits set, iterations, broadphase...).
    virtual std::string notes() const { return {}; }
};

std::unique_ptr<Backend> makeBulletBackend();
std::unique_ptr<Backend> makeBtgpuBackend();
std::unique_ptr<Backend> makeB3gpuBackend();

}  // namespace btgpu::bench
