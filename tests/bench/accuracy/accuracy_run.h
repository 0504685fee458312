// accuracy_run.h — one point of the sweep: a case run on one engine with one setting
// (solver kind, iterations, substeps), timed per simulated second and measured by its probe.
#pragma once
#include <string>

#include "accuracy_cases.h"

namespace btgpu::accuracy {

struct Setting {
    std::string solver = "pgs";  // solver kind; see solverKindSupported
    int iterations = 10;
    int substeps = 1;  // stepSimulation(1/60, n, 1/(60 n))
};

struct RunResult {
    std::string scene, engine, device;
    Setting setting;
    int copies = 0, bodies = 0;
    double simSeconds = 0;   // simulated, timed frames only (frame 1, with kernel builds, is not)
    double wallMs = 0;       // stepSimulation calls of the timed frames
    double msPerSimS = 0;    // median timed frame x 60 (a frame is 1/60 s)
    Measurement measurement;
    bool ran = false, finite = true;
    std::string skipped;     // why it did not run
};

// Solver kinds each engine has: "pgs" (Bullet's sequential impulse; btgpu's batched PGS).
// Kinds: "pgs" (both engines), "jacobi" (btgpu's Jacobi with mass splitting), "soft" (btgpu's
// soft step, SolverKind::SoftStep: m_numIterations = the iterations swept is its substep count).
bool solverKindSupported(const std::string& engine, const std::string& kind);

RunResult runCase(const Case& c, const std::string& engine, const Setting& s, int copies, const Config& config);

}  // namespace btgpu::accuracy
