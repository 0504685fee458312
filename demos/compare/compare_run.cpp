// compare_run.cpp — loads the file into each world, steps them, samples the aggregates every
// step and body centres on up to ~60 steps, then bands the nudged stock runs (chaosBands, the
// same definition the regression tests use) and places btgpu and unnudged stock in them.
#include "compare/compare_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "btgpu/btGpuDynamicsWorld.h"
#include "tolerances.h"

namespace btgpu::compare {
namespace {

struct Run {
    std::vector<std::vector<double>> measures;  // [step][measure]
    std::vector<std::vector<btVector3>> centres;  // [sample][body]
    std::vector<double> finalSpeed;               // [body], m/s, after the last step
    std::vector<bool> finalAtRest;                // [body]
    std::vector<double> stepMs;
};

// Asleep, or slower than its own sleeping thresholds (Bullet's test for starting the clock that
// puts a body to sleep).
bool atRest(const btRigidBody* b)
{
    const bool still = b->getLinearVelocity().length2() < b->getLinearSleepingThreshold() * b->getLinearSleepingThreshold() &&
                       b->getAngularVelocity().length2() < b->getAngularSleepingThreshold() * b->getAngularSleepingThreshold();
    return b->getActivationState() == ISLAND_SLEEPING || still;
}

double atRestFraction(const std::vector<btRigidBody*>& bodies)
{
    int n = 0, rest = 0;
    for (const btRigidBody* b : bodies) {
        if (b->getInvMass() == 0) continue;
        ++n;
        rest += atRest(b) ? 1 : 0;
    }
    return n ? double(rest) / n : 0.0;
}

std::vector<double> measure(const ImportedWorld& w, const btVector3& up)
{
    const scenes::Aggregates a = scenes::aggregates(w.bodies(), 0.0, up);
    return {a.meanHeight, a.spread, a.kineticEnergy, double(w.contacts()), atRestFraction(w.bodies())};
}

double median(std::vector<double> v)
{
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

double CompareResult::ratio(size_t m, size_t s) const
{
    const scenes::ChaosBand& b = bands[m][s];
    const double d = std::fabs(gpu[m][s] - b.stockMean);
    return b.bound() > 0 ? d / b.bound() : (d == 0 ? 0.0 : HUGE_VAL);
}

CompareResult runCompare(const CompareOptions& o)
{
    CompareResult res;
    res.path = o.path;
    res.steps = o.steps;
    if (o.steps < 1) {
        res.error = "--steps must be at least 1";
        return res;
    }
    FileCheck file = checkBulletFile(o.path);
    if (!file.ok) {
        res.error = file.error;
        return res;
    }
    const std::string probe = probeImport(file);
    if (!probe.empty()) {
        res.error = o.path + ": " + probe;
        return res;
    }
    res.file = file;
    res.file.bytes.clear();

    std::string error;
    auto load = [&](Engine e) {
        std::unique_ptr<ImportedWorld> w = ImportedWorld::load(file, e, o.config, error);
        if (!w) error = o.path + ": " + error;
        return w;
    };
    std::unique_ptr<ImportedWorld> first = load(Engine::Stock);
    if (!first) {
        res.error = error;
        return res;
    }
    res.restoration = first->restoration();
    res.bodies = int(first->bodies().size());
    for (const btRigidBody* b : first->bodies()) res.dynamicBodies += b->getInvMass() != 0 ? 1 : 0;
    res.constraints = first->constraints();
    res.dt = o.dt > 0 ? o.dt : (first->fileTimeStep() > 0 && first->fileTimeStep() <= 1 ? first->fileTimeStep() : 1.0 / 60.0);
    const btVector3 g = first->world().getGravity();
    res.up = g.length2() > 0 ? -g.normalized() : btVector3(0, 1, 0);
    res.measures = {"mean height", "spread", "kinetic energy", "contacts", "at rest"};
    // btgpu's Report::contacts counts its own manifolds, which are not stock's: it keeps none for
    // pairs that sleep (stock keeps theirs) and makes points for boxes touching only at an edge or
    // a corner (stock's box-box detector makes none: BasicDemo's lattice, 1,036 against 302 at
    // the first step). Shown with its band, not judged.
    res.judged = {true, true, true, false, true};
    res.everyStep = o.everyStep;
    res.stepsOutside.assign(res.measures.size(), 0);
    const std::vector<double> floors = {tol::kChaosHeightFloor, tol::kChaosSpreadFloor, tol::kChaosEnergyFloor,
                                        tol::kChaosContactsFloor, tol::kChaosAtRestFloor};
    const int every = std::max(1, o.steps / 60);
    for (int s = every; s <= o.steps; s += every) res.bodySampleSteps.push_back(s);
    if (res.bodySampleSteps.empty() || res.bodySampleSteps.back() != o.steps) res.bodySampleSteps.push_back(o.steps);

    const btScalar dt = btScalar(res.dt);
    auto run = [&](ImportedWorld& w, const std::function<void(int)>& afterStep) {
        Run r;
        size_t nextSample = 0;
        for (int s = 1; s <= o.steps; ++s) {
            const auto t0 = std::chrono::steady_clock::now();
            w.world().stepSimulation(dt, 1, dt);
            r.stepMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
            if (afterStep) afterStep(s);
            r.measures.push_back(measure(w, res.up));
            if (nextSample < res.bodySampleSteps.size() && res.bodySampleSteps[nextSample] == s) {
                std::vector<btVector3> c;
                for (const btRigidBody* b : w.bodies()) c.push_back(b->getWorldTransform().getOrigin());
                r.centres.push_back(std::move(c));
                ++nextSample;
            }
        }
        for (const btRigidBody* b : w.bodies()) {
            r.finalSpeed.push_back(b->getLinearVelocity().length());
            r.finalAtRest.push_back(atRest(b));
        }
        return r;
    };

    if (o.verbose) std::fprintf(stderr, "btgpu_compare: stock Bullet, %d steps of %g s\n", o.steps, res.dt);
    Run stock = run(*first, nullptr);
    res.stockMsPerStep = median(stock.stepMs);
    first.reset();

    std::unique_ptr<ImportedWorld> gw = load(Engine::Gpu);
    if (!gw) {
        res.error = error;
        return res;
    }
    if (o.verbose) std::fprintf(stderr, "btgpu_compare: btgpu\n");
    btGpuDynamicsWorld* gpuWorld = gw->gpuWorld();
    Run gpu = run(*gw, [&](int s) {
        if (!gpuWorld->isGpuPath()) {
            if (res.cpuPathSteps++ == 0) {
                res.firstCpuPathStep = s;
                res.cpuPathReason = gpuWorld->report().cpuPathReason;
            }
        }
    });
    res.gpuPathEveryStep = res.cpuPathSteps == 0;
    res.device = gpuWorld->report().device;
    res.solver = scenes::solverName(gpuWorld->report().solver);
    res.gpuStages = gpuWorld->report().stages;
    res.gpuPrograms = gpuWorld->report().builtPrograms;
    res.gpuMsPerStep = median(gpu.stepMs);
    gw.reset();

    std::vector<Run> nudged;
    for (int k = 0; k < tol::kChaosRuns; ++k) {
        if (o.verbose) std::fprintf(stderr, "btgpu_compare: stock Bullet nudged, run %d of %d\n", k + 1, tol::kChaosRuns);
        std::unique_ptr<ImportedWorld> w = load(Engine::Stock);
        if (!w) {
            res.error = error;
            return res;
        }
        scenes::nudge(w->bodies(), unsigned(k + 1), tol::kChaosNudge);
        nudged.push_back(run(*w, nullptr));
    }

    const size_t nm = res.measures.size(), ns = size_t(o.steps);
    res.gpu.assign(nm, std::vector<double>(ns));
    res.stock.assign(nm, std::vector<double>(ns));
    res.bands.assign(nm, std::vector<scenes::ChaosBand>(ns));
    res.aggregatesWithin = true;
    std::vector<bool> reported(nm, false);
    for (size_t s = 0; s < ns; ++s) {
        std::vector<std::vector<double>> runs;
        for (const Run& r : nudged) runs.push_back(r.measures[s]);
        const std::vector<scenes::ChaosBand> b = scenes::chaosBands(runs, res.measures, floors);
        for (size_t m = 0; m < nm; ++m) {
            res.bands[m][s] = b[m];
            res.gpu[m][s] = gpu.measures[s][m];
            res.stock[m][s] = stock.measures[s][m];
            if (!b[m].admits(res.gpu[m][s])) {
                ++res.stepsOutside[m];
                if (res.judged[m] && (o.everyStep || s + 1 == ns)) res.aggregatesWithin = false;
                if (!reported[m]) {
                    reported[m] = true;
                    char line[256];
                    std::snprintf(line, sizeof line, "%s left stock's band at step %zu: btgpu %.6g, stock %.6g +- %.6g",
                                  res.measures[m].c_str(), s + 1, res.gpu[m][s], b[m].stockMean, b[m].bound());
                    res.outside.push_back(line);
                }
            }
        }
    }

    // Per body, on the sampled steps: distance from the nudged runs' mean centre against the
    // largest distance between two nudged runs.
    const size_t nb = size_t(res.bodies);
    for (size_t k = 0; k < res.bodySampleSteps.size(); ++k) {
        double worst = 0.0;
        for (size_t j = 0; j < nb; ++j) {
            btVector3 mean(0, 0, 0);
            for (const Run& r : nudged) mean += r.centres[k][j];
            mean /= btScalar(nudged.size());
            double chaos = 0.0;
            for (size_t a = 0; a < nudged.size(); ++a)
                for (size_t c = a + 1; c < nudged.size(); ++c)
                    chaos = std::max(chaos, double((nudged[a].centres[k][j] - nudged[c].centres[k][j]).length()));
            const double bound = tol::kChaosFactor * chaos + tol::kChaosPositionFloor;
            const double distance = (gpu.centres[k][j] - mean).length();
            worst = std::max(worst, distance / bound);
            if (k + 1 == res.bodySampleSteps.size()) {
                BodyResult br;
                br.index = int(j);
                br.dynamic = false;
                br.gpu = gpu.centres[k][j];
                br.stock = stock.centres[k][j];
                br.stockMean = mean;
                br.distance = distance;
                br.gpuSpeed = gpu.finalSpeed[j];
                br.gpuAtRest = gpu.finalAtRest[j];
                for (const Run& r : nudged) {
                    br.stockMeanSpeed += r.finalSpeed[j] / double(nudged.size());
                    br.stockAtRest += (r.finalAtRest[j] ? 1.0 : 0.0) / double(nudged.size());
                }
                br.chaos = chaos;
                br.bound = bound;
                res.finalBodies.push_back(br);
            }
        }
        res.worstBody.push_back(worst);
    }
    {
        std::unique_ptr<ImportedWorld> w = load(Engine::Stock);  // names and dynamic flags, as loaded
        for (size_t j = 0; w && j < nb; ++j) {
            res.finalBodies[j].name = w->names()[j];
            res.finalBodies[j].dynamic = w->bodies()[j]->getInvMass() != 0;
            if (res.finalBodies[j].dynamic && !res.finalBodies[j].within()) ++res.bodiesOutside;
        }
    }

    if (!res.gpuPathEveryStep) res.exitCode = kCpuPath;
    else res.exitCode = res.aggregatesWithin && res.bodiesOutside == 0 ? kWithinChaos : kOutsideChaos;
    return res;
}

}  // namespace btgpu::compare
