// stacking_test.cpp — many contacts at rest: a stack of 8 unit boxes that must not creep, and
// Bullet's BasicDemo pile of 125 boxes against stock Bullet.
#include <gtest/gtest.h>

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
    SideBySide s(scenes::basicDemo);
    s.step(480);  // 8 s: the pile has landed, settled and fallen asleep on both
    const double stockMean = scenes::meanHeight(*s.stock);
    const double gpuMean = scenes::meanHeight(*s.gpu);
    EXPECT_NEAR(gpuMean, stockMean, tol::kPileMeanHeightRel * stockMean);
    // Box half extent 0.1: a centre lower than 0.1 - kSinkDepth has sunk into the ground.
    EXPECT_GE(scenes::lowestHeight(*s.gpu), 0.1 - tol::kSinkDepth);
    EXPECT_GE(scenes::lowestHeight(*s.stock), 0.1 - tol::kSinkDepth);
    EXPECT_TRUE(scenes::allFinite(*s.gpu));
    EXPECT_TRUE(s.onGpu());
}
