// stacking_test.cpp — many contacts at rest: a stack of 8 unit boxes that must not creep, and
// Bullet's BasicDemo pile of 125 boxes against stock Bullet.
#include <gtest/gtest.h>

#include <cstdio>

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
