// stacking_test.cpp — many contacts at rest: a stack of 8 unit boxes that must not creep,
// Bullet's BasicDemo pile of 125 boxes and BenchmarkDemo's round tower against stock Bullet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scenes/demo_scenes.h"
#include "scenes/stock_chaos.h"
#include "side_by_side.h"

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
