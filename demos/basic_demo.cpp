// basic_demo.cpp — Bullet's BasicDemo (125 boxes on a ground box) stepped headless on stock
// btDiscreteDynamicsWorld and on btGpuDynamicsWorld side by side; prints the device, the median
// ms per step of each, and how far apart the two end up.
// Usage: btgpu_basic_demo [--steps N] [--device gpu|cpu|<name substring>] [--scene NAME] [--bullet-mode]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "btgpu/btGpuDynamicsWorld.h"
#include "scenes/scenes.h"

using namespace btgpu;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v)
{
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double stepMs(scenes::Scene& scene)
{
    const auto t0 = Clock::now();
    scene.step();
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

void usage()
{
    std::printf("usage: btgpu_basic_demo [--steps N] [--device gpu|cpu|<name substring>] [--scene NAME] [--bullet-mode]\n"
                "  --steps N    steps of 1/60 s on each world (default 300)\n"
                "  --device D   OpenCL device (Config::device; BTGPU_DEVICE overrides it)\n"
                "  --scene S    another scene of the library (e.g. cubes:10x10x10); default basic_demo\n"
                "  --bullet-mode  the bullet mode's solver (Config::bulletMode()), whose answers follow\n"
                "               stock's; the default (SolverKind::Auto) runs the soft step\n");
}

}  // namespace

int main(int argc, char** argv)
{
    int steps = 300;
    std::string sceneName = "basic_demo";
    Config config;  // the library's default: what the one-line swap gives an app
    for (int i = 1; i < argc; ++i) {
        const bool hasValue = i + 1 < argc;
        if (!std::strcmp(argv[i], "--steps") && hasValue) {
            steps = std::max(1, std::atoi(argv[++i]));
        } else if (!std::strcmp(argv[i], "--device") && hasValue) {
            config.device = argv[++i];
        } else if (!std::strcmp(argv[i], "--scene") && hasValue) {
            sceneName = argv[++i];
        } else if (!std::strcmp(argv[i], "--bullet-mode")) {
            config.solver = SolverKind::BatchedPgs;
        } else {
            usage();
            return std::strcmp(argv[i], "--help") && std::strcmp(argv[i], "-h") ? 2 : 0;
        }
    }

    scenes::ScenePtr stock = scenes::makeScene(sceneName, scenes::WorldKind::Stock, config);
    scenes::ScenePtr gpu = scenes::makeScene(sceneName, scenes::WorldKind::Gpu, config);
    if (!stock || !gpu) {
        std::fprintf(stderr, "unknown scene '%s'\n", sceneName.c_str());
        usage();
        return 2;
    }

    // The first GPU step compiles the OpenCL programs (slow under PoCL): it is printed apart and
    // left out of btgpu's median.
    std::vector<double> stockMs, gpuMs;
    stockMs.reserve(steps);
    gpuMs.reserve(steps);
    double firstGpuMs = 0.0;
    for (int i = 0; i < steps; ++i) {
        stockMs.push_back(stepMs(*stock));
        const double ms = stepMs(*gpu);
        if (i == 0) firstGpuMs = ms;
        gpuMs.push_back(ms);
    }

    const Report& report = *gpu->report();
    const scenes::StateDifference diff = scenes::positionDifference(*stock, *gpu);
    std::printf("scene        %s, %d bodies, %d steps of 1/60 s\n", sceneName.c_str(),
                static_cast<int>(stock->bodies().size()), steps);
    std::printf("device       %s\n", report.device.empty() ? "(none)" : report.device.c_str());
    std::printf("path         %s%s%s\n", report.gpuPath ? "GPU" : "CPU fallback",
                report.gpuPath ? "" : ": ", report.gpuPath ? "" : report.cpuPathReason.c_str());
    std::printf("solver       %s%s%s\n", scenes::solverName(report.solver),
                report.solverReason.empty() ? "" : ": ", report.solverReason.c_str());
    std::printf("stock        %8.3f ms/step (median)\n", median(stockMs));
    std::printf("btgpu        %8.3f ms/step (median); first step %.1f ms, program builds %.2f s\n",
                median(std::vector<double>(gpuMs.begin() + (steps > 1 ? 1 : 0), gpuMs.end())), firstGpuMs,
                report.buildSeconds);
    std::printf("difference   max %.4f m, mean %.4f m over %d dynamic bodies\n", diff.maxPosition,
                diff.meanPosition, diff.bodies);
    std::printf("mean height  stock %.4f m, btgpu %.4f m\n", scenes::meanHeight(*stock), scenes::meanHeight(*gpu));
    // Bitwise fingerprint of btgpu's final state: same scene, device and binary give the same.
    std::printf("state hash   %016llx\n", static_cast<unsigned long long>(gpu->gpuWorld()->stateHash()));
    for (const Issue& issue : report.issues) std::printf("issue        %s\n", issue.message.c_str());
    return 0;
}
