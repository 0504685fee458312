// ccd_test.cpp — Bullet's continuous collision detection on the GPU path, against stock in the
// same test: a CCD pile that never moves fast stays on the GPU path with the very results it has
// without CCD; a fast ball in free flight stays on the GPU path as stock's; a fast ball shot at a
// thin wall is stopped by it as on stock, the steps CCD acts in run on the CPU path (named), and
// the world comes back to the GPU path after; the same beside Bullet's character controller
// (an action on a ghost object).
#include "scenes/ccd_scenes.h"
#include "scenes/ghost_scenes.h"
#include "side_by_side.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <cstdio>

using namespace btgpu;
using namespace btgpu::test;

// The 4x4x4 pile with a CCD threshold on every box (a quarter of its size): no box moves that far
// in a step, so stock's sweeps never run; the GPU path stays, bitwise as without CCD.
TEST(Ccd, PileThatNeverMovesFastIsUnchanged)
{
    auto make = [](bool ccd) {
        ScenePtr s = scenes::cubes(WorldKind::Gpu, 4, 4, 4, Config::bulletMode());
        if (ccd)
            for (btRigidBody* b : s->bodies())
                if (b->getInvMass() > 0) {
                    b->setCcdMotionThreshold(btScalar(0.25));
                    b->setCcdSweptSphereRadius(btScalar(0.2));
                }
        return s;
    };
    ScenePtr with = make(true), without = make(false);
    for (int step = 0; step < 120; ++step) {
        with->step();
        without->step();
        ASSERT_TRUE(with->gpuWorld()->isGpuPath()) << step << " " << with->report()->cpuPathReason;
    }
    EXPECT_EQ(with->gpuWorld()->stateHash(), without->gpuWorld()->stateHash());
}

// A ball at 120 m/s with nothing in its way: its sweep runs every step and hits nothing, so the
// GPU path keeps it, where stock's is.
TEST(Ccd, FastBallInFreeFlightStaysOnTheGpu)
{
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::ballAtWall(k, c, 120, false); });
    for (int step = 0; step < 30; ++step) {
        sb.step();
        ASSERT_TRUE(sb.onGpu()) << step << " " << sb.gpu->report()->cpuPathReason;
        EXPECT_LT(sb.distance(2), 1e-3) << step;
    }
    EXPECT_GT(sb.gpu->body(2)->getWorldTransform().getOrigin().x(), 50);
}

// The ball shot at the 4 cm wall (2 m a step: without CCD it passes through between two steps):
// stock's CCD stops it at the wall; so does btgpu's, the step(s) it acts in on the CPU path with
// a reason naming the body and the wall, and once the ball is slow the GPU path again.
TEST(Ccd, FastBallStopsAtAThinWallAsStock)
{
    {  // the test can fail: without CCD the ball goes through
        ScenePtr s = scenes::ballAtWall(WorldKind::Stock);
        s->body(2)->setCcdMotionThreshold(0);
        for (int step = 0; step < 10; ++step) s->step();
        ASSERT_GT(s->body(2)->getWorldTransform().getOrigin().x(), 5.5);
    }
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::ballAtWall(k, c); });
    int cpuSteps = 0;
    bool named = false;
    for (int step = 0; step < 90; ++step) {
        sb.step();
        if (!sb.onGpu()) {
            ++cpuSteps;
            const std::string& why = sb.gpu->report()->cpuPathReason;
            named |= why.find("continuous collision detection acts: body 2") != std::string::npos &&
                     why.find("hit body 1") != std::string::npos;
        }
        EXPECT_LT(sb.gpu->body(2)->getWorldTransform().getOrigin().x(), 5.0) << step;  // never through the wall
        EXPECT_LT(sb.stock->body(2)->getWorldTransform().getOrigin().x(), 5.0) << step;
    }
    std::printf("ball at the wall: %d steps on the CPU path; x stock %.4f, btgpu %.4f\n", cpuSteps,
                sb.stock->body(2)->getWorldTransform().getOrigin().x(), sb.gpu->body(2)->getWorldTransform().getOrigin().x());
    EXPECT_GE(cpuSteps, 1);
    EXPECT_LE(cpuSteps, 5);
    EXPECT_TRUE(named);
    EXPECT_TRUE(sb.onGpu());  // back once CCD no longer acts
    EXPECT_LT(sb.distance(2), 0.05);
}

// Bullet's character walking (an action on its ghost) while a CCD ball is shot at the wall in
// front of it (0.5 m thick, 2.5 m a step): the ball stops at the wall on both; the character
// walks as stock's every step; the step CCD acts in is Bullet's own, the others the GPU path's.
TEST(Ccd, BesideACharacterControllerAsStock)
{
    auto make = [](WorldKind k) {
        auto g = scenes::characterWalk(k, Config::bulletMode());
        btRigidBody* ball = g->scene->addBody(g->scene->sphereShape(btScalar(0.1)), 1, btVector3(btScalar(1.5), 2, 2));
        ball->setLinearVelocity(btVector3(0, 0, 150));
        ball->setCcdMotionThreshold(btScalar(0.1));
        ball->setCcdSweptSphereRadius(btScalar(0.08));
        return g;
    };
    auto stock = make(WorldKind::Stock), gpu = make(WorldKind::Gpu);
    btRigidBody* ballS = stock->scene->bodies().back();
    btRigidBody* ballG = gpu->scene->bodies().back();
    int gpuSteps = 0, cpuSteps = 0;
    for (int i = 0; i < 90; ++i) {
        stock->character->setWalkDirection(btVector3(0, 0, btScalar(0.05)));
        gpu->character->setWalkDirection(btVector3(0, 0, btScalar(0.05)));
        stock->scene->step();
        gpu->scene->step();
        (gpu->scene->gpuWorld()->isGpuPath() ? gpuSteps : cpuSteps)++;
        EXPECT_LT(ballS->getWorldTransform().getOrigin().z(), 7.75) << i;
        EXPECT_LT(ballG->getWorldTransform().getOrigin().z(), 7.75) << i;  // never into the wall
        const btVector3 s = stock->ghost()->getWorldTransform().getOrigin(), g = gpu->ghost()->getWorldTransform().getOrigin();
        ASSERT_LT((s - g).length(), 0.01) << "step " << i;
    }
    std::printf("beside the character: %d steps on the GPU path, %d on the CPU path; ball z stock %.3f, btgpu %.3f\n",
                gpuSteps, cpuSteps, ballS->getWorldTransform().getOrigin().z(), ballG->getWorldTransform().getOrigin().z());
    EXPECT_GE(cpuSteps, 1);
    EXPECT_GE(gpuSteps, 80);
    EXPECT_TRUE(gpu->scene->gpuWorld()->isGpuPath());
}

// With an app's pre-tick callback (called once at the start of each internal step): the steps
// CCD acts in are started on the GPU path and handed to Bullet's, which must not call it again.
// The callback is called as often as on stock (once a step), and the ball stops at the wall.
TEST(Ccd, PreTickCallbackOncePerStepAsStock)
{
    static long calls[2];
    calls[0] = calls[1] = 0;
    auto tick = [](btDynamicsWorld* w, btScalar) { ++calls[w->getWorldUserInfo() ? 1 : 0]; };
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::ballAtWall(k, c); });
    sb.stock->world().setInternalTickCallback(tick, nullptr, true);
    sb.gpu->world().setInternalTickCallback(tick, reinterpret_cast<void*>(1), true);
    int cpuSteps = 0;
    for (int step = 0; step < 60; ++step) {
        sb.step();
        cpuSteps += !sb.onGpu();
        EXPECT_EQ(calls[1], calls[0]) << step;
        EXPECT_LT(sb.gpu->body(2)->getWorldTransform().getOrigin().x(), 5.0) << step;
    }
    EXPECT_EQ(calls[0], 60);
    EXPECT_GE(cpuSteps, 1);
    EXPECT_TRUE(sb.onGpu());
}
