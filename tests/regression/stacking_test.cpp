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
    // The block's collapse is chaotic: stock Bullet's own resting mean height moves by 15 %
    // between 8, 10 and 12 iterations. The GPU pile must rest within that spread of stock
    // (widened by kPileMeanHeightRel), not on one chance outcome of it.
    double lo = scenes::meanHeight(*s.stock), hi = lo;
    for (int iterations : {8, 12}) {
        scenes::ScenePtr other = scenes::basicDemo(WorldKind::Stock);
        other->world().getSolverInfo().m_numIterations = iterations;
        for (int i = 0; i < 480; ++i) other->step();
        lo = std::min(lo, scenes::meanHeight(*other));
        hi = std::max(hi, scenes::meanHeight(*other));
    }
    const double gpuMean = scenes::meanHeight(*s.gpu);
    EXPECT_GE(gpuMean, lo * (1.0 - tol::kPileMeanHeightRel)) << "stock spread " << lo << ".." << hi;
    EXPECT_LE(gpuMean, hi * (1.0 + tol::kPileMeanHeightRel)) << "stock spread " << lo << ".." << hi;
    // Box half extent 0.1: a centre lower than 0.1 - kSinkDepth has sunk into the ground.
    EXPECT_GE(scenes::lowestHeight(*s.gpu), 0.1 - tol::kSinkDepth);
    EXPECT_GE(scenes::lowestHeight(*s.stock), 0.1 - tol::kSinkDepth);
    EXPECT_TRUE(scenes::allFinite(*s.gpu));
    EXPECT_TRUE(s.onGpu());
}
