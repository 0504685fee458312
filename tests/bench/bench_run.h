// bench_run.h — runs one backend on a scene for F frames and condenses what it saw: frame
// time percentiles (frame 0, with its kernel builds, apart), per-stage medians, counts, and
// physics sanity (deepest ground penetration, NaNs, bodies below the ground).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "bench_backend.h"

namespace btgpu::bench {

struct Percentiles {
    double median = -1, p90 = -1, max = -1;  // -1: not measured
};

struct RunResult {
    std::string backend, device, notes;
    bool ran = false;
    std::string skipped;             // why it did not run (or stopped after frame 0)
    int framesRun = 0;               // timed frames (1..F), fewer than asked when over budget
    bool cutShort = false;
    double setUpS = 0;               // the app's part: the scene's Bullet objects made and added (stock's own cost)
    double firstStepS = 0;           // frame 0's stepSimulation alone: the backend's one-time work, kernel builds included
    Percentiles stepMs, writebackMs, totalMs;
    std::map<std::string, double> stageMedianMs;
    FrameInfo last;                  // counts after the last frame
    float minLowestY = 0;            // lowest point of any dynamic body over the run (ground top is 0)
    int minLowestFrame = -1;
    float finalLowestY = 0;          // the same after the last frame only (resting penetration)
    int nanBodies = 0;               // non-finite poses after the last frame
    int belowGround = 0;             // dynamic bodies with centre y < 0 after the last frame
};

RunResult runBackend(Backend& backend, const Scene& scene, const Options& options, int frames, double budgetS);

}  // namespace btgpu::bench
