// landing_test.cpp — single bodies against stock Bullet: free fall, a box at rest, a sphere
// and a convex hull landing, a sphere bouncing with restitution 0.5.
#include <gtest/gtest.h>

#include <algorithm>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

TEST(Landing, FreeFallMatchesStock)
{
    SideBySide s(scenes::freeFall);
    for (int i = 0; i < 120; ++i) {
        s.step();
        ASSERT_LT(s.distance(1), tol::kFreeFallPosition) << "step " << i;
    }
    EXPECT_TRUE(s.onGpu());
    // Still in the air after 2 s (30 m up, 20 m fallen): this test saw no contact.
    EXPECT_GT(s.stockY(1), 5.0);
}

TEST(Landing, RestingBoxStaysWithStock)
{
    SideBySide s(scenes::restingBox);
    s.step(120);
    EXPECT_LT(s.distance(1), tol::kRestHeight);
    EXPECT_NEAR(s.gpuY(1), s.stockY(1), tol::kRestHeight);
}

TEST(Landing, SphereRestsAtStockHeight)
{
    SideBySide s(scenes::sphereLanding);
    s.step(120);
    EXPECT_NEAR(s.gpuY(1), s.stockY(1), tol::kRestHeight);
    EXPECT_LT(s.distance(1), tol::kRestHeight);
}

TEST(Landing, ConvexHullRestsAtStockHeight)
{
    SideBySide s(scenes::hullLanding);
    s.step(150);
    EXPECT_NEAR(s.gpuY(1), s.stockY(1), tol::kRestHeight);
    EXPECT_LT(s.distance(1), tol::kRestHeight);
}

namespace {
// Height of the sphere's bottom above the ground at the top of its first rebound.
double firstApex(Scene& scene, int maxSteps)
{
    btRigidBody* ball = scene.body(1);
    bool bounced = false;
    double apex = 0.0;
    for (int i = 0; i < maxSteps; ++i) {
        scene.step();
        const double vy = ball->getLinearVelocity().y();
        const double y = ball->getWorldTransform().getOrigin().y() - 0.5;
        if (!bounced && vy > 0) bounced = true;
        if (bounced) {
            apex = std::max(apex, y);
            if (vy < 0) break;
        }
    }
    return apex;
}
}  // namespace

TEST(Landing, BounceApexMatchesStock)
{
    scenes::ScenePtr stock = scenes::bouncingSphere(WorldKind::Stock);
    scenes::ScenePtr gpu = scenes::bouncingSphere(WorldKind::Gpu);
    // 4.5 m drop (~57 steps) and a ~0.5 s rise: 150 steps see the first apex.
    const double stockApex = firstApex(*stock, 150);
    const double gpuApex = firstApex(*gpu, 150);
    ASSERT_GT(stockApex, 0.5) << "stock did not bounce: the scene is wrong";
    EXPECT_NEAR(gpuApex, stockApex, tol::kBounceApexRel * stockApex);
}
