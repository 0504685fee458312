// fuzz_test.cpp — the fuzz label: seeded random scenes with bad and extreme input, each run on
// stock Bullet (for contrast, without what stock cannot survive) and on btGpuDynamicsWorld.
// Environment: BTGPU_FUZZ_SCENES (scenes per case), BTGPU_FUZZ_SEED (first seed),
// BTGPU_FUZZ_SKIP (generator choices left out, comma-separated), BTGPU_FUZZ_TIMEOUT (s per
// scene), BTGPU_FUZZ_VERBOSE=1 (keep the library's stderr), BTGPU_FUZZ_STOCK_ALL=1 (give stock
// every op too: for finding what crashes it, one seed per process), BTGPU_FUZZ_ONLY=stock|gpu
// (run one engine; the verdict then needs btgpu's trace, so stock-only checks nothing).
#include <gtest/gtest.h>

#include "fuzz_guard.h"
#include "fuzz_recipe.h"
#include "fuzz_verdict.h"
#include "fuzz_world.h"

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <unistd.h>

using namespace btgpu::fuzz;

namespace {

struct FuzzEnv {
    int scenes = 0;
    std::uint64_t firstSeed = 1;
    std::string skipText;
    Skip skip;
    bool stockEverything = false;
    bool verbose = false;
    std::string only;  // "", "stock" or "gpu"
    double timeout = 120.0;
};

FuzzEnv readEnv(int defaultScenes)
{
    FuzzEnv e;
    e.scenes = defaultScenes;
    if (const char* s = std::getenv("BTGPU_FUZZ_SCENES")) e.scenes = std::max(0, std::atoi(s));
    if (const char* s = std::getenv("BTGPU_FUZZ_SEED")) e.firstSeed = std::strtoull(s, nullptr, 10);
    if (const char* s = std::getenv("BTGPU_FUZZ_SKIP")) {
        e.skipText = s;
        std::stringstream ss(e.skipText);
        for (std::string item; std::getline(ss, item, ',');) e.skip.names.push_back(item);
    }
    if (const char* s = std::getenv("BTGPU_FUZZ_TIMEOUT")) e.timeout = std::atof(s);
    if (const char* s = std::getenv("BTGPU_FUZZ_ONLY")) e.only = s;
    e.stockEverything = std::getenv("BTGPU_FUZZ_STOCK_ALL") && std::atoi(std::getenv("BTGPU_FUZZ_STOCK_ALL"));
    e.verbose = e.scenes == 1 || (std::getenv("BTGPU_FUZZ_VERBOSE") && std::atoi(std::getenv("BTGPU_FUZZ_VERBOSE")));
    return e;
}

std::string selfPath()
{
    char buf[4096];
    ssize_t n = ::readlink("/proc/self/exe", buf, sizeof(buf) - 1);
    return n > 0 ? std::string(buf, size_t(n)) : "btgpu_fuzz_tests";
}

std::string reproduce(const FuzzEnv& e, Profile p, std::uint64_t seed)
{
    std::string line = "BTGPU_FUZZ_SEED=" + std::to_string(seed) + " BTGPU_FUZZ_SCENES=1 ";
    if (!e.skipText.empty()) line += "BTGPU_FUZZ_SKIP=" + e.skipText + " ";
    return line + selfPath() + " --gtest_filter=Fuzz." + toString(p);
}

struct ClassStats {
    int scenes = 0;
    std::uint64_t lastSeed = ~std::uint64_t(0);
    std::vector<std::uint64_t> seeds;  // the first few
    std::string example;
};

void note(std::map<std::string, ClassStats>& m, const std::string& kind, std::uint64_t seed, const std::string& example)
{
    ClassStats& c = m[kind];
    if (c.lastSeed == seed) return;  // once per scene
    c.lastSeed = seed;
    ++c.scenes;
    if (c.seeds.size() < 6) c.seeds.push_back(seed);
    if (c.example.empty()) c.example = example;
}

std::string table(const std::map<std::string, ClassStats>& m)
{
    std::ostringstream os;
    for (const auto& [kind, c] : m) {
        os << "  " << kind << ": " << c.scenes << " scene(s), seeds";
        for (std::uint64_t s : c.seeds) os << " " << s;
        os << "\n      e.g. " << c.example << "\n";
    }
    return os.str();
}

void runProfile(Profile profile, int defaultScenes)
{
    const FuzzEnv e = readEnv(defaultScenes);
    installGuards(e.timeout);
    const int kPrintedScenes = 8;  // full reports; the rest are in the summary table
    std::map<std::string, ClassStats> failures, stockSide;
    int failedScenes = 0, cpuPathScenes = 0;
    const auto t0 = std::chrono::steady_clock::now();
    RunOptions options;
    options.stockEverything = e.stockEverything;
    for (int i = 0; i < e.scenes; ++i) {
        const std::uint64_t seed = e.firstSeed + std::uint64_t(i);
        const Recipe recipe = makeRecipe(seed, profile, e.skip);
        const std::string line = describe(recipe);
        const std::string repro = reproduce(e, profile, seed);
        if (e.verbose) std::cout << "[fuzz] " << line << "\n" << std::flush;
        else if (sanitized()) printToStderr("[fuzz] Fuzz." + std::string(toString(profile)) + " seed " + std::to_string(seed) + "\n");
        Trace stock, gpu;
        guardScene("  scene: " + line + "\n  reproduce: " + repro + "\n  stage: stock Bullet");
        if (e.only != "gpu") {
            QuietStderr quiet(!e.verbose);
            stock = run(recipe, Engine::Stock, options);
        }
        guardScene("  scene: " + line + "\n  reproduce: " + repro + "\n  stage: btGpuDynamicsWorld");
        if (e.only != "stock") {
            QuietStderr quiet(!e.verbose);
            gpu = run(recipe, Engine::Gpu, options);
        }
        sceneDone();
        if (!e.only.empty()) continue;
        if (e.scenes == 1) std::cout << "  stock:\n" << dump(recipe, stock) << "  btgpu:\n" << dump(recipe, gpu) << std::flush;
        if (!gpu.cpuReason.empty()) ++cpuPathScenes;
        for (const std::string& n : stockNotes(recipe, stock)) note(stockSide, n.substr(0, n.find(' ')), seed, n);
        std::vector<Failure> notes;
        const std::vector<Failure> found = judge(recipe, gpu, &stock, &notes);
        for (const Failure& n : notes) note(stockSide, n.kind, seed, n.detail);
        if (found.empty()) continue;
        ++failedScenes;
        std::ostringstream os;
        os << "Fuzz." << toString(profile) << " seed " << seed << ": " << found.size() << " failure(s)\n";
        for (const Failure& f : found) {
            os << "  " << f.kind << ": " << f.detail << "\n";
            note(failures, f.kind, seed, f.detail);
        }
        if (!gpu.cpuReason.empty()) os << "  (CPU path: " << gpu.cpuReason << ")\n";
        os << "  scene: " << line << "\n  reproduce: " << repro;
        if (failedScenes <= kPrintedScenes) ADD_FAILURE() << os.str();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::ostringstream summary;
    summary << "[fuzz] Fuzz." << toString(profile) << ": " << e.scenes << " scenes (seeds " << e.firstSeed << ".."
            << e.firstSeed + std::uint64_t(std::max(e.scenes, 1)) - 1 << "), " << cpuPathScenes << " on the CPU path, "
            << failedScenes << " failed, " << seconds << " s\n";
    if (!failures.empty()) summary << "failure classes:\n" << table(failures);
    if (!stockSide.empty()) summary << "for the record, not failures (stock Bullet on the same seeds; NaN btgpu shares with it):\n" << table(stockSide);
    if (failedScenes == 0) std::cout << summary.str() << std::flush;
    EXPECT_EQ(failedScenes, 0) << summary.str();
}

}  // namespace

// Scenes per case in CI: a few hundred in all, within two minutes on two cores (Release).
TEST(Fuzz, BadBodies) { runProfile(Profile::BadBodies, 70); }
TEST(Fuzz, CpuPath) { runProfile(Profile::CpuPath, 100); }
TEST(Fuzz, StepArguments) { runProfile(Profile::StepArguments, 50); }
TEST(Fuzz, Extreme) { runProfile(Profile::Extreme, 50); }
// Last: a NaN hull point crashes today's library, and a crash ends the process.
TEST(Fuzz, BadShapes) { runProfile(Profile::BadShapes, 40); }
