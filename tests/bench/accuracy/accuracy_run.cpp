// accuracy_run.cpp — builds the case's scene on stock Bullet or btgpu, applies the setting,
// steps it frame by frame (timing only stepSimulation) and lets the probe measure it.
#include "accuracy_run.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "btgpu/btGpuDynamicsWorld.h"

namespace btgpu::accuracy {

bool solverKindSupported(const std::string& engine, const std::string& kind)
{
    if (kind == "pgs") return engine == "stock" || engine == "btgpu";
    // Jacobi with mass splitting and the soft step: btgpu only
    return (kind == "jacobi" || kind == "soft") && engine == "btgpu";
}

RunResult runCase(const Case& c, const std::string& engine, const Setting& s, int copies, const Config& config)
{
    RunResult r;
    r.scene = c.name;
    r.engine = engine;
    r.setting = s;
    if (!solverKindSupported(engine, s.solver)) {
        r.skipped = "solver kind " + s.solver + " not available on " + engine;
        return r;
    }
    const scenes::WorldKind kind = engine == "btgpu" ? scenes::WorldKind::Gpu : scenes::WorldKind::Stock;
    Config chosen = config;
    // Each kind names its solver, whatever Config's default is.
    if (s.solver == "pgs") chosen.solver = SolverKind::BatchedPgs;
    if (s.solver == "jacobi") chosen.solver = SolverKind::JacobiMassSplitting;
    if (s.solver == "soft") chosen.solver = SolverKind::SoftStep;  // substeps = the iterations swept
    scenes::AccuracyScene a = c.make(kind, chosen, copies);
    r.copies = a.copies;
    r.bodies = a.copies * a.bodiesPerCopy;
    a.scene->world().getSolverInfo().m_numIterations = s.iterations;
    std::unique_ptr<Probe> probe = c.probe();

    const int frames = int(c.seconds * 60 + 0.5);
    const btScalar frame = btScalar(1) / btScalar(60);
    const btScalar fixed = btScalar(1) / btScalar(60 * s.substeps);
    double t = 0, timedSeconds = 0, timedMs = 0;
    std::vector<double> frameMs;
    probe->sample(a, 0, 0);
    for (int f = 1; f <= frames; ++f) {
        const auto t0 = std::chrono::steady_clock::now();
        const int done = a.scene->step(frame, s.substeps, fixed);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        // Bullet's float clock may run n-1 or n+1 substeps in a frame: the analytic time is
        // the substeps actually taken.
        const double dt = double(done) * double(fixed);
        t += dt;
        if (f > 1) {
            timedMs += ms;
            timedSeconds += dt;
            frameMs.push_back(ms);
        }
        probe->sample(a, f, t);
    }
    r.simSeconds = timedSeconds;
    r.wallMs = timedMs;
    // The median frame, not the mean: helpers and other jobs share this machine's cores, and a
    // frame that lost its core for 50 ms says nothing about the setting.
    if (!frameMs.empty()) {
        std::nth_element(frameMs.begin(), frameMs.begin() + frameMs.size() / 2, frameMs.end());
        r.msPerSimS = frameMs[frameMs.size() / 2] * 60.0;
    }
    r.measurement = probe->finish(a);
    r.finite = scenes::allFinite(*a.scene);
    if (const Report* rep = a.scene->report()) {
        r.device = rep->device;
        if (!rep->gpuPath) r.measurement.notes += "cpu_path:" + rep->cpuPathReason + ";";
    } else r.device = "cpu";
    r.ran = true;
    return r;
}

}  // namespace btgpu::accuracy
