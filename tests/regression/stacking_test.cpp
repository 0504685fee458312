// stacking_test.cpp — many contacts at rest: a stack of 8 unit boxes that must not creep,
// Bullet's BasicDemo pile of 125 boxes and BenchmarkDemo's round tower against stock Bullet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scenes/demo_scenes.h"
#include "scenes/stock_chaos.h"
#include "side_by_side.h"
#include "tolerances.h"

using namespace btgpu;
using namespace btgpu::test;

TEST(Stacking, EightBoxStackHolds)
{
    SideBySide s([](WorldKind k, const Config& c) { return scenes::boxStack(k, c, 8); });
    const btVector3 start = s.stock->body(8)->getWorldTransform().getOrigin();
    s.step(300);  // 5 s
    for (Scene* scene : {s.stock.get(), s.gpu.get()}) {
        const double drift = (scene->body(8)->getWorldTransform().getOrigin() - start).length();
        EXPECT_LT(drift, tol::kStackDrift) << scenes::toString(scene->kind());
    }
    EXPECT_TRUE(s.onGpu());
}

TEST(Stacking, BasicDemoSettlesLikeStock)
{
    // 8 s: the pile has landed, settled and fallen asleep on both. Its collapse is chaotic, so
    // the GPU pile is judged against stock's own chaos, not one stock run.
    const int steps = 480;
    auto measure = [](const Scene& scene) {
        scenes::Aggregates a = scenes::aggregates(scene);
        return std::vector<double>{a.meanHeight, a.spread, a.kineticEnergy};
    };
    std::vector<scenes::ChaosBand> bands = scenes::stockChaos(
        [](WorldKind kind) { return scenes::basicDemo(kind); }, steps, measure, {"mean height", "spread", "kinetic energy"},
        {tol::kChaosHeightFloor, tol::kChaosSpreadFloor, tol::kChaosEnergyFloor});
    scenes::ScenePtr gpu = scenes::basicDemo(WorldKind::Gpu);
    for (int i = 0; i < steps; ++i) {
        gpu->step();
        ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << gpu->report()->cpuPathReason;
    }
    const std::vector<double> got = measure(*gpu);
    for (size_t k = 0; k < bands.size(); ++k) {
        std::printf("BasicDemo %s: btgpu %.4f, stock %.4f +- %.4f\n", bands[k].name.c_str(), got[k], bands[k].stockMean,
                    bands[k].bound());
        EXPECT_TRUE(bands[k].admits(got[k])) << bands[k].name << ": btgpu " << got[k] << ", stock mean "
                                             << bands[k].stockMean << " +- " << bands[k].bound();
    }
    // Box half extent 0.1: a centre lower than 0.1 - kSinkDepth has sunk into the ground.
    EXPECT_GE(scenes::lowestHeight(*gpu), 0.1 - tol::kSinkDepth);
    EXPECT_TRUE(scenes::allFinite(*gpu));
}

namespace {

// BenchmarkDemo test 2's round tower: each box's drift from the circle it started on (radius
// 1.3 * 24 / pi about x = 25, z = 0), mean over all boxes and over the top ring.
std::vector<double> towerDrift(const Scene& scene, int rings)
{
    const double start = 1.3 * 24.0 / 3.14159265358979;
    double all = 0, top = 0;
    for (int i = 1; i <= rings * 24; ++i) {
        const btVector3 p = scene.body(i)->getWorldTransform().getOrigin();
        const double drift = std::sqrt(double(p.x() - 25) * double(p.x() - 25) + double(p.z()) * double(p.z())) - start;
        all += drift;
        if (i > (rings - 1) * 24) top += drift;
    }
    return {all / (rings * 24), top / 24};
}

}  // namespace

TEST(Stacking, BenchTowerStaysLikeStock)
{
    // BenchmarkDemo test 2's tower alone (8 rings of 24 unit boxes, 5 iterations), 5 s. Each box
    // rests on two below it; solving each contact's friction right after its own normal rows
    // (not after every contact's, as Bullet) pushed the rings outward, 35 mm on average.
    const int rings = 8, steps = 300;
    auto measure = [&](const Scene& scene) { return towerDrift(scene, rings); };
    std::vector<scenes::ChaosBand> bands = scenes::stockChaos(
        [&](WorldKind kind) { return scenes::benchTower(kind, Config::bulletMode(), rings); }, steps, measure,
        {"mean radial drift", "top ring's radial drift"}, {tol::kChaosRadialFloor, tol::kChaosRadialFloor});
    scenes::ScenePtr gpu = scenes::benchTower(WorldKind::Gpu, Config::bulletMode(), rings);
    for (int i = 0; i < steps; ++i) {
        gpu->step();
        ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << gpu->report()->cpuPathReason;
    }
    const std::vector<double> got = measure(*gpu);
    for (size_t k = 0; k < bands.size(); ++k) {
        std::printf("Bench tower %s: btgpu %.2f mm, stock %.2f +- %.2f mm\n", bands[k].name.c_str(), 1e3 * got[k],
                    1e3 * bands[k].stockMean, 1e3 * bands[k].bound());
        EXPECT_TRUE(bands[k].admits(got[k])) << bands[k].name << ": btgpu " << got[k] << ", stock mean "
                                             << bands[k].stockMean << " +- " << bands[k].bound();
    }
    EXPECT_TRUE(scenes::allFinite(*gpu));
}

namespace {

// BenchmarkDemo test 1's pile on btgpu with `config` after `steps` steps: mean height and spread
// within stock's own chaos (8 nudged stock runs), the GPU path asserted every step.
void expectBenchPileWithinStocksChaos(const Config& config, int steps, const char* label)
{
    auto measure = [](const Scene& s) {
        const scenes::Aggregates a = scenes::aggregates(s);
        return std::vector<double>{a.meanHeight, a.spread};
    };
    const std::vector<scenes::ChaosBand> bands = scenes::stockChaos(
        [](WorldKind kind) { return scenes::benchPile(kind, Config::bulletMode()); }, steps, measure, {"mean height", "spread"},
        {tol::kChaosHeightFloor, tol::kChaosSpreadFloor});
    scenes::ScenePtr gpu = scenes::benchPile(WorldKind::Gpu, config);
    for (int i = 0; i < steps; ++i) {
        gpu->step();
        ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << gpu->report()->cpuPathReason;
    }
    EXPECT_EQ(gpu->report()->solver, config.solver == SolverKind::Auto ? SolverKind::SoftStep : config.solver);
    const std::vector<double> got = measure(*gpu);
    for (size_t k = 0; k < bands.size(); ++k) {
        std::printf("bench pile (%s) %s: btgpu %.3f, stock %.3f +- %.3f\n", label, bands[k].name.c_str(), got[k],
                    bands[k].stockMean, bands[k].bound());
        EXPECT_TRUE(bands[k].admits(got[k])) << bands[k].name << ": btgpu " << got[k] << ", stock " << bands[k].stockMean
                                             << " +- " << bands[k].bound();
    }
}

}  // namespace

// BenchmarkDemo test 1's pile (3,008 boxes: a 47-layer stack that collapses into a heap), 4 s:
// mean height and spread within stock's own chaos (issue 13's yardstick for a default solver).
// Measured on PoCL: bullet mode 18.44 m / 15.82 m against stock's 18.33 +- 0.22 / 16.14 +- 0.40;
// the soft step (not asserted here: mid-collapse it is outside) 26.28 m / 13.48 m, its stiffer
// stack still standing where stock's has fallen, as refined stock's does (README, solver modes).
TEST(Stacking, BenchPileWithinStocksChaos)
{
    expectBenchPileWithinStocksChaos(Config::bulletMode(), 240, "bullet mode");
}

// The same pile at rest (20 s) on the default (the soft step): issue 13 found btgpu's pile
// resting 8% taller than stock's; at rest it lies within stock's own chaos, the spread near the
// band's edge. Measured on PoCL, 2026-12-08: mean height 1.628 m against stock's 1.586 +- 0.284
// (8 nudged runs 1.54-1.64), spread 55.57 m against 52.39 +- 3.34 (51.7-52.8; nudged default runs
// 55.0-55.6; refined stock, 1/240 s and 20 iterations, 57.8-61.0 and still moving: stock's boxes
// scatter least, as its ragdolls do in bench 3). 133 s on PoCL's 2 cores (eight 20 s stock runs),
// so kept out of CI: --gtest_also_run_disabled_tests --gtest_filter=Stacking.DISABLED_BenchPile*.
TEST(Stacking, DISABLED_BenchPileAtRestOnTheDefaultWithinStocksChaos)
{
    expectBenchPileWithinStocksChaos(Config(), 1200, "default, at rest");
}

namespace {

// Mean height at `early` steps and spread at `late` steps of BenchmarkDemo test 1's pile of
// `layers` layers, nudged by `seed` (0: not), each 1/60 s step cut into `refine` fixed steps at
// `iterations` iterations (0: the scene's). A btgpu world is asserted on the GPU path every step.
std::pair<double, double> benchPileCourse(WorldKind kind, const Config& config, int layers, unsigned seed, int early,
                                          int late, int refine, int iterations)
{
    scenes::ScenePtr s = scenes::benchPile(kind, config, layers);
    if (seed) scenes::nudge(*s, seed, tol::kChaosNudge);
    if (iterations) s->world().getSolverInfo().m_numIterations = iterations;
    double height = 0;
    for (int i = 1; i <= late; ++i) {
        s->step(btScalar(1) / 60, refine, btScalar(1) / btScalar(60 * refine));
        if (kind == WorldKind::Gpu && !s->gpuWorld()->isGpuPath()) {
            ADD_FAILURE() << "step " << i << ": " << s->report()->cpuPathReason;
            return {0, 0};
        }
        if (i == early) height = scenes::aggregates(*s).meanHeight;
    }
    return {height, scenes::aggregates(*s).spread};
}

}  // namespace

// The pile of 16 layers (1,024 boxes) on the default against stock and refined stock (1/240 s,
// 20 iterations): stock at its own settings lets the leaning columns collapse early (mean height
// 8.2-8.5 m at 3 s) and scatters the boxes least at rest (spread 23.6-24.1 m at 12 s); refined,
// stock holds them up (13.5 m) and scatters them farthest (34-35.5 m, 33.8 at 1/600 s and 50
// iterations); the default lies between, nearer refined stock on the collapse (13.8-13.9 m;
// 27.2-28.2 m). So here, as on bench 3's ragdolls, stock's own chaos band measures stock's
// dissipation: the default is outside it on spread (PoCL, 2026-12-08). Fails if the default
// collapses as early as stock's or scatters beyond refined stock.
TEST(Stacking, BenchPileOnTheDefaultLiesBetweenStockAndRefinedStock)
{
    const int layers = 16, early = 180, late = 720;
    double stockHeight = 0, refinedHeight = 0, stockSpreadMax = 0, refinedSpreadMin = 1e9;
    for (unsigned seed : {1u, 2u}) {
        const auto a = benchPileCourse(WorldKind::Stock, Config::bulletMode(), layers, seed, early, late, 1, 0);
        const auto b = benchPileCourse(WorldKind::Stock, Config::bulletMode(), layers, seed, early, late, 4, 20);
        std::printf("bench pile (%d layers), seed %u: stock height %.3f m at 3 s, spread %.3f m at 12 s; refined %.3f, %.3f\n",
                    layers, seed, a.first, a.second, b.first, b.second);
        stockHeight += a.first / 2;
        refinedHeight += b.first / 2;
        stockSpreadMax = std::max(stockSpreadMax, a.second);
        refinedSpreadMin = std::min(refinedSpreadMin, b.second);
    }
    ASSERT_GT(refinedHeight, stockHeight + 2.0);  // the premise: refined, the columns stand longer
    ASSERT_GT(refinedSpreadMin, stockSpreadMax);  // and scatter farther
    for (unsigned seed : {0u, 1u}) {
        const auto got = benchPileCourse(WorldKind::Gpu, Config(), layers, seed, early, late, 1, 0);
        std::printf("bench pile (%d layers), seed %u: the default's height %.3f m at 3 s, spread %.3f m at 12 s\n", layers,
                    seed, got.first, got.second);
        EXPECT_LT(std::fabs(got.first - refinedHeight), std::fabs(stockHeight - refinedHeight));
        EXPECT_GT(got.second, stockSpreadMax);
        EXPECT_LT(got.second, refinedSpreadMin);
    }
}

// 300 marbles (radius 0.1 m, restitution 0.3) poured from random heights into a 2.2 m box: two
// spheres make their points as btSphereSphereCollisionAlgorithm does (only while they touch,
// none kept: Bullet 3.24 clears that manifold each step), so the heap settles within stock's own chaos (PoCL,
// 2026-12-07: mean height 0.2332 m against stock's 0.2313 +- 0.0217, spread 0.872 against
// 0.869 +- 0.040). A pour from a grid (marbles in exact columns) is a knife edge where stock's
// columns topple sooner; see README, Known differences.
TEST(Stacking, MarblesPouredSettleLikeStock)
{
    const int steps = 180;
    auto make = [](WorldKind kind) {
        auto s = std::make_unique<Scene>(kind, Config::bulletMode(), "marbles");
        s->addBody(s->boxShape(btVector3(50, 1, 50)), 0, btVector3(0, -1, 0));
        btBoxShape* wallX = s->boxShape(btVector3(btScalar(1.1), 1, btScalar(.1)));
        btBoxShape* wallZ = s->boxShape(btVector3(btScalar(.1), 1, btScalar(1.1)));
        s->addBody(wallX, 0, btVector3(0, 1, btScalar(1.2)));
        s->addBody(wallX, 0, btVector3(0, 1, btScalar(-1.2)));
        s->addBody(wallZ, 0, btVector3(btScalar(1.2), 1, 0));
        s->addBody(wallZ, 0, btVector3(btScalar(-1.2), 1, 0));
        btSphereShape* marble = s->sphereShape(btScalar(.1));
        uint32_t seed = 11u;
        auto rnd = [&seed](double lo, double hi) {
            seed = seed * 1664525u + 1013904223u;
            return btScalar(lo + (hi - lo) * double(seed >> 8) / double(1u << 24));
        };
        for (int i = 0; i < 300; ++i) {
            const btScalar x = rnd(-.85, .85), z = rnd(-.85, .85), y = rnd(.3, 5.0);
            s->addBody(marble, btScalar(.05), btVector3(x, y, z))->setRestitution(btScalar(.3));
        }
        return s;
    };
    auto measure = [](const Scene& scene) {
        scenes::Aggregates a = scenes::aggregates(scene);
        return std::vector<double>{a.meanHeight, a.spread};
    };
    const std::vector<scenes::ChaosBand> bands = scenes::stockChaos(make, steps, measure, {"mean height", "spread"},
                                                                    {tol::kChaosHeightFloor, tol::kChaosSpreadFloor});
    scenes::ScenePtr gpu = make(WorldKind::Gpu);
    for (int i = 0; i < steps; ++i) {
        gpu->step();
        ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << gpu->report()->cpuPathReason;
    }
    const std::vector<double> got = measure(*gpu);
    for (size_t k = 0; k < bands.size(); ++k) {
        std::printf("marbles %s: btgpu %.4f, stock %.4f +- %.4f\n", bands[k].name.c_str(), got[k], bands[k].stockMean,
                    bands[k].bound());
        EXPECT_TRUE(bands[k].admits(got[k])) << bands[k].name << ": btgpu " << got[k] << ", stock mean "
                                             << bands[k].stockMean << " +- " << bands[k].bound();
    }
    EXPECT_TRUE(scenes::allFinite(*gpu));
}
