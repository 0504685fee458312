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

namespace {
// Unit boxes (0.5 m half extents) dropped flat from 0.1, 1.5 and 3 m (their bottoms) onto a
// ground box, 4 m apart, each 0.1 m off its column's axis.
scenes::ScenePtr flatDrops(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<scenes::Scene>(kind, config, "flat_drops");
    scene->addBody(scene->boxShape(btVector3(50, 1, 50)), 0, btVector3(0, -1, 0));
    btCollisionShape* box = scene->boxShape(btVector3(0.5f, 0.5f, 0.5f));
    const btScalar heights[3] = {0.1f, 1.5f, 3.0f};
    for (int i = 0; i < 3; ++i) scene->addBody(box, 1, btVector3(btScalar(4 * i) + 0.1f, 0.5f + heights[i], 0));
    return scene;
}
}  // namespace

// A box landing flat stays where it lands, unturned, on the default solver (the soft step) as on
// stock: nothing in a flat landing turns it. The soft step's relax ran a contact's normal rows
// once, leaving the four corners' impulses in the order they were solved: the box dropped from
// 3 m spun up to 0.59 rad/s and slid 13 mm (0.1 m: 3 mm), where stock's stays within 0.003 rad/s
// and 0.3 mm. With two passes of the normal rows in the relax (btgSoftNormalSweeps): 0.056 rad/s
// at most (a transient of the 0.1 m drop; the 3 m one 0.014) and 0.4 mm (PoCL).
TEST(Landing, BoxLandingFlatStaysPutOnTheDefaultSolver)
{
    scenes::ScenePtr stock = flatDrops(WorldKind::Stock, Config());
    scenes::ScenePtr gpu = flatDrops(WorldKind::Gpu, Config());
    double spin[2] = {0, 0}, slide[2] = {0, 0};
    for (int step = 0; step < 150; ++step) {
        stock->step();
        gpu->step();
        ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << step;
        ASSERT_EQ(gpu->report()->solver, SolverKind::SoftStep) << step;
        for (int w = 0; w < 2; ++w) {
            scenes::Scene& s = w == 0 ? *stock : *gpu;
            for (int i = 1; i <= 3; ++i) {
                const btRigidBody* b = s.body(i);
                const btVector3 p = b->getWorldTransform().getOrigin();
                spin[w] = std::max(spin[w], double(b->getAngularVelocity().length()));
                slide[w] = std::max(slide[w], double(btVector3(p.x() - (4 * (i - 1) + 0.1f), 0, p.z()).length()));
            }
        }
    }
    EXPECT_LT(spin[0], 0.01) << "stock's own (measured 0.003)";
    EXPECT_LT(slide[0], 0.001) << "stock's own (measured 0.00025)";
    EXPECT_LT(spin[1], 0.1) << "rad/s (measured 0.056, the 0.1 m drop's; one pass 0.59)";
    EXPECT_LT(slide[1], 0.001) << "m (measured 0.0004; one pass 0.013)";
    for (int i = 1; i <= 3; ++i) EXPECT_NEAR(gpu->body(i)->getWorldTransform().getOrigin().y(), 0.5, 0.002) << i;
}
