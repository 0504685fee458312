// sixdof_test.cpp — btGeneric6DofSpring2Constraint and btFixedConstraint on the GPU path against
// stock Bullet in the same process (the btgpu world asserted on the GPU path after every step):
// fixed boxes holding together under gravity and on landing, a 6-DoF joint's linear motor
// driving to its limit and angular motor reaching its speed in every rotation order, and the
// springs, servos and btHinge2Constraint that keep the CPU path naming why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scenes/joint_scenes.h"
#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

// Body b's centre in body a's frame.
btVector3 inFrameOf(const btRigidBody& a, const btRigidBody& b)
{
    return a.getWorldTransform().inverse() * b.getWorldTransform().getOrigin();
}

}  // namespace

TEST(SixDof, FixedBoxesHoldTogetherAsOnStock)
{
    SideBySide s([](WorldKind k, const Config& c) { return scenes::fixedBoxes(k, c); });
    const btVector3 arm0 = inFrameOf(*s.stock->body(1), *s.stock->body(2));
    const btVector3 pair0 = inFrameOf(*s.stock->body(3), *s.stock->body(4));
    double stockArm = 0, gpuArm = 0, stockPair = 0, gpuPair = 0;
    for (int i = 0; i < 180; ++i) {  // 3 s: the pair lands at about 0.3 s and settles
        s.step();
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
        stockArm = std::max<double>(stockArm, (inFrameOf(*s.stock->body(1), *s.stock->body(2)) - arm0).length());
        gpuArm = std::max<double>(gpuArm, (inFrameOf(*s.gpu->body(1), *s.gpu->body(2)) - arm0).length());
        stockPair = std::max<double>(stockPair, (inFrameOf(*s.stock->body(3), *s.stock->body(4)) - pair0).length());
        gpuPair = std::max<double>(gpuPair, (inFrameOf(*s.gpu->body(3), *s.gpu->body(4)) - pair0).length());
    }
    std::printf("fixed joints, largest relative drift over 3 s: cantilever stock %.5f m, btgpu %.5f m; landing pair "
                "stock %.5f m, btgpu %.5f m\n",
                stockArm, gpuArm, stockPair, gpuPair);
    const Report& r = *s.gpu->report();
    for (const char* stage : {"prepare_joints", "solve_constraints", "finish_joints", "narrowphase_sat"})
        EXPECT_NE(std::find(r.stages.begin(), r.stages.end(), stage), r.stages.end()) << stage;
    EXPECT_LE(gpuArm, stockArm + 1e-3);
    EXPECT_LE(gpuPair, stockPair + 1e-3);
    EXPECT_GT(stockArm, 0.0);  // gravity does pull the cantilever: the bound is not vacuous
    // Landed and at rest on the ground, as on stock.
    EXPECT_NEAR(s.gpuY(3), s.stockY(3), 1e-2);
    EXPECT_NEAR(s.gpuY(4), s.stockY(4), 1e-2);
    EXPECT_NEAR(s.gpuY(2), s.stockY(2), 1e-3);
}

TEST(SixDof, MotorsDriveToTheLimitAndSpinAsOnStock)
{
    for (int order = 0; order < 6; ++order) {
        SCOPED_TRACE(order);
        SideBySide s([order](WorldKind k, const Config& c) { return scenes::sixDofMotors(k, c, 2.0, order); });
        for (int i = 0; i < 60; ++i) {
            s.step();
            ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
        }
        const btRigidBody &st = *s.stock->body(0), &gp = *s.gpu->body(0);
        const double stockW = st.getAngularVelocity().z(), gpuW = gp.getAngularVelocity().z();
        const double stockX = st.getWorldTransform().getOrigin().x(), gpuX = gp.getWorldTransform().getOrigin().x();
        std::printf("6dof2 order %d after 1 s: spin stock %.4f, btgpu %.4f rad/s; x stock %.5f, btgpu %.5f m; "
                    "y stock %.5f, btgpu %.5f m\n",
                    order, stockW, gpuW, stockX, gpuX, s.stockY(0), s.gpuY(0));
        EXPECT_NEAR(gpuW, stockW, 0.02 * std::fabs(stockW));
        // The motors drive body B (the box) against body A (the fixed body): -target. In the
        // orders where z is the middle Euler angle (XZY, YZX) it is the one confined to
        // +-90 degrees and the spin runs through Euler's singularity, on stock as here.
        if (order != 1 && order != 3) EXPECT_NEAR(gpuW, -2.0, 0.04);
        EXPECT_NEAR(gpuX, stockX, 1e-3);
        EXPECT_NEAR(gpuX, -0.3, 2e-3);                // at its limit
        EXPECT_NEAR(s.gpuY(0), s.stockY(0), 1e-3);    // held against gravity by the locked axis
    }
}

TEST(SixDof, SpringsServosAndHinge2KeepTheCpuPathNamingWhy)
{
    {
        ScenePtr s = scenes::sixDofMotors(WorldKind::Gpu);
        auto* d = static_cast<btGeneric6DofSpring2Constraint*>(s->joint(0));
        d->enableSpring(1, true);
        s->step();
        EXPECT_FALSE(s->gpuWorld()->isGpuPath());
        EXPECT_NE(s->report()->cpuPathReason.find("spring on axis 1"), std::string::npos) << s->report()->cpuPathReason;
    }
    {
        ScenePtr s = scenes::sixDofMotors(WorldKind::Gpu);
        auto* d = static_cast<btGeneric6DofSpring2Constraint*>(s->joint(0));
        d->setServo(5, true);
        s->step();
        EXPECT_FALSE(s->gpuWorld()->isGpuPath());
        EXPECT_NE(s->report()->cpuPathReason.find("servo on axis 5"), std::string::npos) << s->report()->cpuPathReason;
    }
    {
        // Turned on between steps: the next step falls back (never a joint half uploaded).
        ScenePtr s = scenes::sixDofMotors(WorldKind::Gpu);
        for (int i = 0; i < 5; ++i) s->step();
        EXPECT_TRUE(s->gpuWorld()->isGpuPath()) << s->report()->cpuPathReason;
        static_cast<btGeneric6DofSpring2Constraint*>(s->joint(0))->enableSpring(3, true);
        s->step();
        EXPECT_FALSE(s->gpuWorld()->isGpuPath());
        EXPECT_NE(s->report()->cpuPathReason.find("spring on axis 3"), std::string::npos) << s->report()->cpuPathReason;
    }
    {
        ScenePtr s = scenes::fixedBoxes(WorldKind::Gpu);
        btVector3 anchor(-1.8f, 0.7f, 0), up(0, 1, 0), x(1, 0, 0);
        s->addJoint(new btHinge2Constraint(*s->body(3), *s->body(4), anchor, up, x));
        s->step();
        EXPECT_FALSE(s->gpuWorld()->isGpuPath());
        EXPECT_NE(s->report()->cpuPathReason.find("btHinge2Constraint"), std::string::npos) << s->report()->cpuPathReason;
        EXPECT_NE(s->report()->cpuPathReason.find("spring"), std::string::npos) << s->report()->cpuPathReason;
    }
}
