// demo_run.h — runs one demo on stock btDiscreteDynamicsWorld and on btGpuDynamicsWorld side by
// side (and on stock again with every start nudged by 0.1 mm: the scene's own chaos), timing
// each step, following btgpu's path every step, comparing the two worlds at the end.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "demo_catalog.h"
#include "scenes/demo_scenes.h"

namespace btgpu::demos {

struct RunOptions {
    int steps = 0;       // 0: the demo's default
    Config config = Config::bulletMode();
    bool chaos = true;   // also run the nudged stock world
    int worst = 0;       // list this many bodies that end farthest from stock
    bool noSleep = false; // every dynamic body DISABLE_DEACTIVATION, in every world
};

struct BodyGap {
    int index = 0;                 // scene body index (Scene::bodies())
    btVector3 stock, gpu;          // final centres
    double distance = 0;           // m
};

struct DemoResult {
    std::string name, device, solver;  // solver: the one btgpu's world ran at the end
    int bodies = 0, dynamicBodies = 0, steps = 0;
    bool gpuEveryStep = false;     // btgpu's world was on the GPU path after every step
    int firstCpuStep = -1;         // the first step it was not, -1 if none
    std::string cpuReason;         // why (the world's own reason)
    double stockMs = 0, gpuMs = 0; // median ms per step (btgpu's first step left out)
    double firstGpuMs = 0, buildSeconds = 0;
    double meanDiff = 0, maxDiff = 0;    // m, btgpu against stock, per dynamic body at the end
    double chaosMean = 0, chaosMax = 0;  // m, nudged stock against stock (-1: not run)
    double stockHeight = 0, gpuHeight = 0;
    // Ray fan (raycast demo): rays whose hit fraction differs by more than 1e-3 (of the ray)
    // between the worlds at the last step, the largest difference, and ms per fan on each.
    int raysCast = 0, raysDiffering = 0, chaosRaysDiffering = -1;  // the last: stock vs nudged stock
    double rayMaxDiff = 0, stockRayMs = 0, gpuRayMs = 0;
    std::vector<BodyGap> worst;    // RunOptions::worst bodies, farthest first
    std::uint64_t stateHash = 0;
    bool finite = true;
};

// The ray fan as btgpu's world saw it this step (raycast demo), for drawing.
struct RayView {
    const scenes::RayFan* fan = nullptr;
    const std::vector<double>* fractions = nullptr;
};
// Called at the start (step 0) and after each step with btgpu's world: the pictures hook.
using StepHook = std::function<void(int step, DemoWorld& gpu, const RayView& rays)>;

DemoResult runDemo(const Demo& demo, const RunOptions& options, const StepHook& hook = nullptr);
void printResult(const DemoResult& r);
// One Markdown row (and its header) for `--demo all`.
std::string markdownHeader();
std::string markdownRow(const DemoResult& r);

}  // namespace btgpu::demos
