// compare_run.h — btgpu_compare's measurement: a saved scene on btgpu, on stock Bullet, and on
// stock again tol::kChaosRuns times with every dynamic body's start nudged (the scene's own
// chaos, tests/scenes/stock_chaos.h), sampled every step; btgpu judged against stock's bands.
#pragma once
#include <string>
#include <vector>

#include "btgpu/Config.h"
#include "compare/imported_world.h"
#include "scenes/stock_chaos.h"

namespace btgpu::compare {

enum ExitCode { kWithinChaos = 0, kOutsideChaos = 1, kBadInput = 2, kCpuPath = 3 };

struct CompareOptions {
    std::string path;
    int steps = 300;
    double dt = 0.0;  // 0: the file's own fixed step (solver info), else 1/60
    Config config = Config::bulletMode();
    bool verbose = false;  // progress on stderr
    // Judge the aggregates after every step, not only at the end (the regression tests judge the
    // end state; a landing absorbed a step later is a transient outside the band).
    bool everyStep = false;
};

struct BodyResult {
    int index = 0;
    std::string name;
    bool dynamic = false;
    btVector3 gpu, stock, stockMean;  // final centres: btgpu, unnudged stock, mean of the nudged runs
    double distance = 0.0;            // |gpu - stockMean|, m
    double chaos = 0.0;               // largest distance between two nudged stock runs, m
    double bound = 0.0;               // kChaosFactor * chaos + kChaosPositionFloor
    double gpuSpeed = 0.0, stockMeanSpeed = 0.0;  // m/s
    bool gpuAtRest = false;
    double stockAtRest = 0.0;         // fraction of the nudged runs in which it is at rest
    bool within() const { return distance <= bound; }
};

struct CompareResult {
    int exitCode = kBadInput;
    std::string error;  // for kBadInput
    std::string path;
    FileCheck file;     // header facts (bytes dropped)
    Restoration restoration;
    int bodies = 0, dynamicBodies = 0, constraints = 0;
    double dt = 0.0;
    int steps = 0;
    btVector3 up{0, 1, 0};
    std::string device;
    std::string solver;  // the solver btgpu's last step ran (CompareOptions::config.solver, Auto resolved)
    // GPU path: every step, or the first step that was not and the world's reason.
    bool gpuPathEveryStep = false;
    int cpuPathSteps = 0, firstCpuPathStep = -1;
    std::string cpuPathReason;
    double stockMsPerStep = 0.0, gpuMsPerStep = 0.0;  // medians
    // The btgpu world's plan after the last step: the stages it launched, the programs it built.
    std::vector<std::string> gpuStages, gpuPrograms;
    // Aggregates: names, and per step (index s = after step s+1) btgpu's value, unnudged stock's,
    // and the band of the nudged runs.
    std::vector<std::string> measures;
    std::vector<bool> judged;  // per measure: part of the verdict (contacts are shown, not judged)
    bool everyStep = false;
    std::vector<int> stepsOutside;  // per measure: steps at which btgpu was outside the band
    std::vector<std::vector<double>> gpu, stock;       // [measure][step]
    std::vector<std::vector<scenes::ChaosBand>> bands;  // [measure][step]
    std::vector<double> worstBody;                      // [step]: max over bodies of distance / bound (sampled steps)
    std::vector<int> bodySampleSteps;                   // steps (1-based) where worstBody is measured
    std::vector<BodyResult> finalBodies;
    int bodiesOutside = 0;
    bool aggregatesWithin = false;     // the judged aggregates, at the end (or every step: everyStep)
    std::vector<std::string> outside;  // first step each aggregate left its band, in words
    double ratio(size_t measure, size_t step) const;  // |gpu - stock mean| / bound
};

CompareResult runCompare(const CompareOptions& options);

}  // namespace btgpu::compare
