// demo_run.cpp — the side-by-side run and its printout (demo_run.h).
#include "demo_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "btgpu/btGpuDynamicsWorld.h"
#include "scenes/stock_chaos.h"

namespace btgpu::demos {

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v)
{
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

template <class F>
double timeMs(F&& f)
{
    const auto t0 = Clock::now();
    f();
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

DemoResult runDemo(const Demo& demo, const RunOptions& options, const StepHook& hook)
{
    DemoResult r;
    r.name = demo.name;
    r.steps = options.steps > 0 ? options.steps : demo.steps;
    DemoWorld stock = demo.make(scenes::WorldKind::Stock, options.config);
    DemoWorld gpu = demo.make(scenes::WorldKind::Gpu, options.config);
    DemoWorld nudged;
    if (options.chaos) {
        nudged = demo.make(scenes::WorldKind::Stock, options.config);
        scenes::nudge(*nudged.scene, 1u, 1e-4);
    }
    if (options.noSleep)
        for (DemoWorld* world : {&stock, &gpu, &nudged})
            if (world->scene)
                for (btRigidBody* b : world->scene->bodies())
                    if (!b->isStaticOrKinematicObject()) b->setActivationState(DISABLE_DEACTIVATION);
    r.bodies = int(stock.scene->bodies().size());
    for (const btRigidBody* b : stock.scene->bodies()) r.dynamicBodies += !b->isStaticOrKinematicObject();

    scenes::RayFan stockRays, gpuRays;
    std::vector<double> stockHits, gpuHits, nudgedHits;
    std::vector<double> stockRayMs, gpuRayMs;
    if (demo.rays) stockRays = gpuRays = scenes::benchmarkRays();
    if (hook) hook(0, gpu, RayView{demo.rays ? &gpuRays : nullptr, nullptr});

    std::vector<double> stockMs, gpuMs;
    r.gpuEveryStep = true;
    for (int i = 0; i < r.steps; ++i) {
        stockMs.push_back(timeMs([&] { stock.scene->step(); }));
        gpuMs.push_back(timeMs([&] { gpu.scene->step(); }));
        if (nudged.scene) nudged.scene->step();
        if (i == 0) r.firstGpuMs = gpuMs.back();
        if (!gpu.scene->gpuWorld()->isGpuPath() && r.firstCpuStep < 0) {
            r.gpuEveryStep = false;
            r.firstCpuStep = i + 1;
            r.cpuReason = gpu.scene->report()->cpuPathReason;
        }
        if (demo.rays) {
            const double dt = 1.0 / 60.0;
            stockRays.move(dt), gpuRays.move(dt);
            stockRayMs.push_back(timeMs([&] { stockHits = scenes::castRays(stock.scene->world(), stockRays); }));
            gpuRayMs.push_back(timeMs([&] { gpuHits = scenes::castRays(gpu.scene->world(), gpuRays); }));
            if (nudged.scene && i + 1 == r.steps) nudgedHits = scenes::castRays(nudged.scene->world(), stockRays);
        }
        if (hook) hook(i + 1, gpu, RayView{demo.rays ? &gpuRays : nullptr, demo.rays ? &gpuHits : nullptr});
    }

    const Report& report = *gpu.scene->report();
    r.device = report.device;
    r.solver = scenes::solverName(report.solver);
    r.buildSeconds = report.buildSeconds;
    r.stockMs = median(stockMs);
    r.gpuMs = median(std::vector<double>(gpuMs.begin() + (gpuMs.size() > 1 ? 1 : 0), gpuMs.end()));
    const scenes::StateDifference d = scenes::positionDifference(*stock.scene, *gpu.scene);
    r.meanDiff = d.meanPosition, r.maxDiff = d.maxPosition;
    r.chaosMean = r.chaosMax = -1;
    if (nudged.scene) {
        const scenes::StateDifference c = scenes::positionDifference(*stock.scene, *nudged.scene);
        r.chaosMean = c.meanPosition, r.chaosMax = c.maxPosition;
    }
    if (options.worst > 0) {
        for (size_t i = 0; i < stock.scene->bodies().size() && i < gpu.scene->bodies().size(); ++i) {
            const btRigidBody* a = stock.scene->bodies()[i];
            const btRigidBody* b = gpu.scene->bodies()[i];
            if (a->isStaticOrKinematicObject()) continue;
            const btVector3 pa = a->getWorldTransform().getOrigin(), pb = b->getWorldTransform().getOrigin();
            r.worst.push_back({int(i), pa, pb, double((pa - pb).length())});
        }
        std::sort(r.worst.begin(), r.worst.end(), [](const BodyGap& x, const BodyGap& y) {
            return x.distance != y.distance ? x.distance > y.distance : x.index < y.index;
        });
        if (int(r.worst.size()) > options.worst) r.worst.resize(size_t(options.worst));
    }
    r.stockHeight = scenes::meanHeight(*stock.scene), r.gpuHeight = scenes::meanHeight(*gpu.scene);
    r.finite = scenes::allFinite(*gpu.scene);
    r.stateHash = gpu.scene->gpuWorld()->stateHash();
    if (demo.rays) {
        r.raysCast = int(stockHits.size());
        for (size_t i = 0; i < stockHits.size() && i < gpuHits.size(); ++i) {
            const double diff = std::fabs(stockHits[i] - gpuHits[i]);
            r.rayMaxDiff = std::max(r.rayMaxDiff, diff);
            r.raysDiffering += diff > 1e-3;
        }
        r.stockRayMs = median(stockRayMs), r.gpuRayMs = median(gpuRayMs);
        if (!nudgedHits.empty()) {
            r.chaosRaysDiffering = 0;
            for (size_t i = 0; i < stockHits.size() && i < nudgedHits.size(); ++i)
                r.chaosRaysDiffering += std::fabs(stockHits[i] - nudgedHits[i]) > 1e-3;
        }
    }
    return r;
}

void printResult(const DemoResult& r)
{
    std::printf("demo         %s: %d bodies (%d dynamic), %d steps of 1/60 s\n", r.name.c_str(), r.bodies, r.dynamicBodies,
                r.steps);
    std::printf("device       %s\n", r.device.empty() ? "(none)" : r.device.c_str());
    std::printf("solver       %s\n", r.solver.c_str());
    if (r.gpuEveryStep)
        std::printf("path         GPU on every step\n");
    else
        std::printf("path         CPU from step %d: %s\n", r.firstCpuStep, r.cpuReason.c_str());
    std::printf("stock        %9.3f ms/step (median)\n", r.stockMs);
    std::printf("btgpu        %9.3f ms/step (median); first step %.1f ms, program builds %.2f s\n", r.gpuMs, r.firstGpuMs,
                r.buildSeconds);
    std::printf("difference   btgpu vs stock: mean %.4f m, max %.4f m per dynamic body\n", r.meanDiff, r.maxDiff);
    if (r.chaosMean >= 0) {
        std::printf("chaos        stock vs stock nudged 0.1 mm: mean %.4f m, max %.4f m\n", r.chaosMean, r.chaosMax);
        std::printf("divergence   %.2f (btgpu's mean difference / stock's own; about 1 or less: within stock's chaos)\n",
                    r.meanDiff / std::max(r.chaosMean, 1e-6));
    }
    std::printf("mean height  stock %.3f m, btgpu %.3f m%s\n", r.stockHeight, r.gpuHeight, r.finite ? "" : " (NON-FINITE)");
    if (r.raysCast) {
        std::printf("rays         %d a step: at the end %d hit more than 0.1%% of the ray apart on btgpu and stock (max %.4f)",
                    r.raysCast, r.raysDiffering, r.rayMaxDiff);
        if (r.chaosRaysDiffering >= 0) std::printf(", %d on stock and nudged stock", r.chaosRaysDiffering);
        std::printf("\nray ms       stock %.3f, btgpu %.3f per fan (closest hit)\n", r.stockRayMs, r.gpuRayMs);
    }
    for (const BodyGap& g : r.worst)
        std::printf("body %-7d stock (%.3f, %.3f, %.3f)  btgpu (%.3f, %.3f, %.3f)  %.4f m apart\n", g.index, g.stock.x(),
                    g.stock.y(), g.stock.z(), g.gpu.x(), g.gpu.y(), g.gpu.z(), g.distance);
    std::printf("state hash   %016llx\n", static_cast<unsigned long long>(r.stateHash));
}

std::string markdownHeader()
{
    return "| demo | bodies | steps | path | stock ms/step | btgpu ms/step | mean diff (m) | max diff (m) | stock chaos mean (m) | divergence |\n"
           "| --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
}

std::string markdownRow(const DemoResult& r)
{
    char buf[1024], chaos[64] = "—", divergence[64] = "—";
    const std::string path = r.gpuEveryStep ? "GPU" : "CPU: " + r.cpuReason;
    if (r.chaosMean >= 0) {
        std::snprintf(chaos, sizeof chaos, "%.4f", r.chaosMean);
        std::snprintf(divergence, sizeof divergence, "%.2f", r.meanDiff / std::max(r.chaosMean, 1e-6));
    }
    std::snprintf(buf, sizeof buf, "| %s | %d | %d | %s | %.2f | %.2f | %.4f | %.4f | %s | %s |\n", r.name.c_str(), r.bodies,
                  r.steps, path.c_str(), r.stockMs, r.gpuMs, r.meanDiff, r.maxDiff, chaos, divergence);
    return buf;
}

}  // namespace btgpu::demos
