// stability.h — the stability suite's harness: runs one scene on stock Bullet and on btgpu,
// measures what the issue asks (NaN, speeds, settling, penetration, drift, energy), judges
// each engine against the same criteria, and records a results row per engine (GoogleTest
// properties and, when BTGPU_STABILITY_TABLE names a file, a Markdown row appended to it).
#pragma once
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "btgpu/btGpuDynamicsWorld.h"
#include "scenes/scenes.h"
#include "scenes/stability_scenes.h"
#include "tolerances.h"

namespace btgpu::stability {

using scenes::Scene;
using scenes::ScenePtr;
using scenes::WorldKind;
using Builder = std::function<ScenePtr(WorldKind, const Config&)>;

// BTGPU_STABILITY_FULL=1 runs the long versions (bigger towers and pyramids, more steps).
bool fullMode();

struct Criteria {
    double seconds = 3;                         // simulated time
    btScalar timeStep = btScalar(1) / btScalar(60);
    double settleBy = -1;                       // s: from then on KE/M stays under the bound; < 0: not asked
    double penetration = -1;                    // m: most allowed penetration at rest; < 0: not asked
    double measureFrom = -1;                    // s: penetration measured from then on (default settleBy, else the end)
    int driftBody = -1;                         // scene index of the body whose sideways drift is bounded
    double drift = 0;                           // m
    // m: how far driftBody may end below where it started (each contact under it may sink by
    // the penetration bound); < 0: not asked. Catches a stack that collapsed in place.
    double drop = -1;
    double speed = -1;                          // m/s: bound on every body's speed; < 0: from the scene's heights
    bool energyNeverGrows = false;
    bool noSleep = false;                       // DISABLE_DEACTIVATION on every body (tests the solver, not sleep)
    // m: how far any dynamic body may be from where it started (3-D, sampled every 0.5 s and
    // at the end); < 0: not asked.
    double move = -1;
};

struct Outcome {
    WorldKind kind = WorldKind::Stock;
    bool finite = true;
    double maxSpeed = 0;        // m/s, any dynamic body, any step
    double speedBound = 0;      // m/s, the bound applied
    double finalKePerMass = 0;  // J/kg at the end
    double settleTime = 0;      // s: end of the last step with KE/M above the bound
    double penetration = 0;     // m, deepest over the measured window (ground or body pair)
    double drift = 0;           // m, sideways (x-z) motion of Criteria::driftBody
    double drop = 0;            // m, how far Criteria::driftBody ended below its start
    double energyRise = 0;      // J, max over steps of E(t) - E(0) (kinetic + potential)
    double wallSeconds = 0;
    double maxMove = 0;         // m, the farthest any dynamic body got from its start (Criteria::move)
    bool gpuPath = false;       // btgpu only: the last step ran on the OpenCL pipeline
    bool gpuEveryStep = false;  // btgpu only: every step ran on it
    std::vector<std::string> stages;  // btgpu only: the plan's stages at the end (Report::stages)
    int issues = 0;             // btgpu only: report().issues.size()
    std::string firstIssue;
    bool pass = false;
    std::string why;            // the criteria it failed, "" when it passed
};

// Steps the scene under the criteria and judges it.
Outcome run(Scene& scene, const Criteria& criteria);
Outcome run(const Builder& make, WorldKind kind, const Criteria& criteria, const Config& config = Config::bulletMode());

// Deepest penetration now: a dynamic body's lowest point below the ground top (y = groundY),
// and between two dynamic bodies the deepest contact Bullet's own narrowphase finds
// (contactPairTest), which for stacked boxes is the overlap along the stack axis.
double penetration(Scene& scene, double groundY = 0);
double kePerMass(const Scene& scene);
double totalEnergy(const Scene& scene);  // kinetic + potential (g = 10), J

// "1.2 mm" style.
std::string figure(const Outcome& o);
// Records both engines' rows (RecordProperty, BTGPU_STABILITY_TABLE) and asserts honestly:
// btgpu must pass whatever stock passes; when stock fails too, btgpu's result is recorded but
// does not fail the test (the case is marked "both fail" in the table and on stdout).
void judge(const std::string& caseName, const Outcome& stock, const Outcome& gpu, bool requireGpuPath = true);
// One table row for one engine, with a free-form figure.
void record(const std::string& caseName, const Outcome& o, const std::string& figureText);

// A row for a case an engine does not run (and why).
void appendRowNotRun(const std::string& caseName, const std::string& engine, const std::string& why);

// The same judgement for one more btgpu run under its own label (the default solver beside
// the bullet mode): it must pass whatever stock passes; stock's row is not recorded again.
void judgeAs(const std::string& caseName, const std::string& engine, const Outcome& stock, const Outcome& gpu);
// The usual case: build on stock and on btgpu in both solver modes (the bullet mode,
// Config::bulletMode(), recorded as "btgpu"; the default, Config(), as "btgpu default"), run,
// judge each btgpu run against stock.
void runEngines(const std::string& caseName, const Builder& make, const Criteria& criteria);
// The stiff cases as btgpu earns them: Config::internalSubsteps device substeps per step. The
// test fails when btgpu does not pass with them.
void runEarned(const std::string& caseName, const Builder& make, const Criteria& criteria, int internalSubsteps);
// record() under another engine label.
void recordAs(const std::string& caseName, const std::string& engine, const Outcome& o, const std::string& figureText);

}  // namespace btgpu::stability
