// main.cpp — btgpu_bench: one scene, up to three simulators (btgpu, stock Bullet, Bullet3's
// GPU pipeline) in the same run; a Markdown table on stdout, a CSV with --csv, progress on
// stderr. --smoke is the short ctest run (label bench): cubes, then 100 compound tables and dumbbells.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "bench_report.h"
#include "scenes/benchmark_specs.h"
#include "bench_run.h"

using namespace btgpu::bench;

namespace {

const char* kUsage =
    "usage: btgpu_bench [--scene cubes|spheres|mixed|voronoi|landscape|ragdolls|pile|stacks|hulls|compounds] [--n 1000|8000|32768|112500|1000000 | --dims NX NY NZ]\n"
    "                   [--bodies N] [--quads Q]   (landscape: N bodies on a Q x Q-quad mesh; 1000, 100;\n"
    "                                               compounds: N tables and dumbbells, default 1000)\n"
    "                   [--cells C]   (voronoi: C cells, default 90 as BenchmarkDemo's test 8)\n"
    "                   [--ragdolls COUNT (ragdolls of 11 capsules and 10 joints; default 100)]\n"
    "                   pile, stacks, hulls: BenchmarkDemo's tests 1, 2 and 4 (3,008 boxes, 1,076 boxes, 960 barrels)\n"
    "                   [--frames F] [--backends btgpu,bullet,b3gpu] [--csv PATH] [--budget-s S]\n"
    "                   [--no-sleep] [--no-aabb-sync] [--no-manifolds] [--empty-manifolds] [--no-empty-manifolds] [--contact-callback ground|all|processed] [--jacobi] [--soft] [--soft-substeps N] [--auto-solver] [--bullet-mode] [--b3-native-inertia] [--absolute-thresholds] [--smoke]\n"
    "  BTGPU_DEVICE=gpu|cpu|<name substring> picks the OpenCL device (btgpu and b3gpu alike).\n";

[[noreturn]] void usage(const char* why)
{
    std::fprintf(stderr, "btgpu_bench: %s\n%s", why, kUsage);
    std::exit(2);
}

// Runs one scene on each backend in the list; a Markdown table on stdout, the CSV when a path
// is given. Returns the failures: NaNs from a backend that ran, stock Bullet not running.
int runScene(const Scene& scene, const std::string& backends, const Options& options, int frames, double budgetS,
             const std::string& csvPath)
{
    std::vector<RunResult> results;
    std::stringstream list(backends);
    for (std::string name; std::getline(list, name, ',');) {
        std::unique_ptr<Backend> b = name == "btgpu" ? makeBtgpuBackend()
                                     : name == "bullet" ? makeBulletBackend()
                                     : name == "b3gpu"  ? makeB3gpuBackend()
                                                        : nullptr;
        if (!b) usage(("unknown backend " + name).c_str());
        std::fprintf(stderr, "btgpu_bench: %s on %s, %d frames...\n", name.c_str(), scene.name.c_str(), frames);
        results.push_back(runBackend(*b, scene, options, frames, budgetS));
        const RunResult& r = results.back();
        if (r.ran)
            std::fprintf(stderr, "  %s: %d frames, median %.3f ms, set-up %.2f s, first step %.2f s\n", name.c_str(),
                         r.framesRun, r.totalMs.median, r.setUpS, r.firstStepS);
        else
            std::fprintf(stderr, "  %s: skipped: %s\n", name.c_str(), r.skipped.c_str());
    }
    writeMarkdown(std::cout, scene, frames, results);
    if (!csvPath.empty()) {
        std::ofstream csv(csvPath);
        writeCsv(csv, scene, results);
        if (!csv) {
            std::fprintf(stderr, "btgpu_bench: cannot write %s\n", csvPath.c_str());
            return 1;
        }
    }
    // A backend that cannot run here (no device, btgpu off its GPU path) is skipped, not a
    // failure; one that ran must not have produced NaNs, and stock Bullet must always run.
    int failures = 0;
    for (const RunResult& r : results) {
        if (r.ran && r.nanBodies > 0) ++failures;
        if (r.backend == "bullet" && !r.ran) ++failures;
    }
    return failures;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string sceneName = "cubes", backends = "btgpu,bullet,b3gpu", csvPath;
    int dims[3] = {20, 20, 20};
    int frames = 300;
    int nCells = 90;
    int landscapeCount = 1000, landscapeQuads = 100;  // --bodies is also the compounds' count
    int ragdolls = 100;  // --scene ragdolls
    double budgetS = 600;  // per backend: a slow backend stops early and says so
    bool smoke = false;
    Options options;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto next = [&]() -> const char* {
            if (i + 1 >= argc) usage(("missing value after " + a).c_str());
            return argv[++i];
        };
        if (a == "--scene") sceneName = next();
        else if (a == "--n") {
            long n = std::atol(next());
            if (!dimsForCount(n, dims)) usage("--n must be 1000, 8000, 32768, 112500 or 1000000 (or use --dims)");
        } else if (a == "--dims") {
            for (int& d : dims) d = std::atoi(next());
            if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0) usage("--dims needs three positive counts");
        } else if (a == "--ragdolls") ragdolls = std::atoi(next());
        else if (a == "--frames") frames = std::atoi(next());
        else if (a == "--bodies") landscapeCount = std::max(1, std::atoi(next()));
        else if (a == "--quads") landscapeQuads = std::max(1, std::atoi(next()));
        else if (a == "--backends") backends = next();
        else if (a == "--csv") csvPath = next();
        else if (a == "--budget-s") budgetS = std::atof(next());
        else if (a == "--no-sleep") options.noSleep = true;
        else if (a == "--no-aabb-sync") options.noAabbSync = true;
        else if (a == "--no-manifolds") options.noManifolds = true;
        else if (a == "--empty-manifolds") options.emptyManifolds = true;
        else if (a == "--no-empty-manifolds") options.noEmptyManifolds = true;
        else if (a == "--contact-callback" && i + 1 < argc) options.contactCallback = argv[++i];
        else if (a == "--jacobi") options.jacobi = true;
        else if (a == "--soft") options.soft = true;
        else if (a == "--auto-solver") options.autoSolver = true;
        else if (a == "--bullet-mode") options.bulletMode = true;
        else if (a == "--soft-substeps") {
            options.soft = true;
            options.softSubsteps = std::max(1, std::atoi(next()));
        }
        else if (a == "--b3-native-inertia") options.b3NativeInertia = true;
        else if (a == "--absolute-thresholds") options.absoluteThresholds = true;
        else if (a == "--smoke") smoke = true;
        else if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else usage(("unknown argument " + a).c_str());
    }
    if (smoke) {
        sceneName = "cubes";
        dims[0] = dims[1] = dims[2] = 10;
        frames = 20;
        backends = "bullet,b3gpu,btgpu";
        options.requireGpuPath = true;
    }
    if (frames < 1) usage("--frames must be at least 1");

    Scene scene;
    if (sceneName == "cubes") scene = makeStack(dims[0], dims[1], dims[2], ShapeKind::Box);
    else if (sceneName == "spheres") scene = makeStack(dims[0], dims[1], dims[2], ShapeKind::Sphere);
    else if (sceneName == "mixed") scene = makeMixed();
    else if (sceneName == "voronoi") scene = makeVoronoi(nCells);
    else if (sceneName == "landscape") scene = makeLandscape(landscapeCount, landscapeQuads);
    else if (sceneName == "ragdolls") scene = makeRagdolls(ragdolls);
    else if (sceneName == "pile") scene = btgpu::scenes::spec::makeBenchPile();
    else if (sceneName == "stacks") scene = btgpu::scenes::spec::makeBenchStacks();
    else if (sceneName == "hulls") scene = btgpu::scenes::spec::makeBenchHulls();
    else if (sceneName == "compounds") scene = makeCompounds(landscapeCount);
    else usage("--scene must be cubes, spheres, mixed, voronoi, landscape, ragdolls, pile, stacks, hulls or compounds");

    // The smoke run also drops 100 compound tables and dumbbells (in this process: its
    // programs are built once).
    int failures = runScene(scene, backends, options, frames, budgetS, csvPath);
    if (smoke) failures += runScene(makeCompounds(100), backends, options, frames, budgetS, "");
    return failures ? 1 : 0;
}
