// contact_threshold_test.cpp — which points become contacts, as Bullet's dispatcher decides:
// with CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD (its default) a pair keeps points closer than
// the smaller of its shapes' getContactBreakingThreshold (0.0035 m for a sphere of radius 0.1),
// without it closer than gContactBreakingThreshold (0.02 m). A small sphere coasting down onto
// the ground from 15 mm shows the difference: a contact 15 mm early stops it at the surface, none
// lets it sink in.
#include <gtest/gtest.h>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

ScenePtr coastingSphere(WorldKind kind, const Config& config, bool relative)
{
    auto scene = std::make_unique<Scene>(kind, config);
    if (!relative) {
        auto* dispatcher = static_cast<btCollisionDispatcher*>(scene->world().getDispatcher());
        dispatcher->setDispatcherFlags(dispatcher->getDispatcherFlags() &
                                       ~btCollisionDispatcher::CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD);
    }
    scene->world().setGravity(btVector3(0, 0, 0));
    scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
    btRigidBody* ball = scene->addBody(scene->sphereShape(0.1f), 1, btVector3(0, 0.115f, 0));
    ball->setLinearVelocity(btVector3(0, -3, 0));  // 5 cm a step
    return scene;
}

}  // namespace

TEST(ContactThreshold, RelativeAndAbsoluteAsStock)
{
    for (bool relative : {true, false}) {
        SCOPED_TRACE(relative ? "relative thresholds (Bullet's default)" : "one absolute threshold");
        SideBySide s([&](WorldKind kind, const Config& config) { return coastingSphere(kind, config, relative); });
        s.step();
        ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        // Relative: no contact yet, the sphere sinks 35 mm in; absolute: held at the surface.
        if (relative) EXPECT_LT(s.stockY(1), 0.08);
        else EXPECT_GT(s.stockY(1), 0.095);
        EXPECT_NEAR(s.gpuY(1), s.stockY(1), 2e-3) << "btgpu " << s.gpuY(1) << ", stock " << s.stockY(1);
        s.step(30);
        ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        EXPECT_NEAR(s.gpuY(1), s.stockY(1), 5e-3) << "btgpu " << s.gpuY(1) << ", stock " << s.stockY(1);
    }
}

// An app that changes gContactBreakingThreshold (Config::contactThreshold left at its default)
// keeps the GPU path, which follows it as stock does: with one absolute threshold of 10 mm the
// sphere 15 mm up gets no contact this step and sinks in on both; with 50 mm it is held. Set to
// differ from Config::contactThreshold, it falls back naming both.
TEST(ContactThreshold, FollowsGContactBreakingThresholdAsStock)
{
    const btScalar saved = gContactBreakingThreshold;
    for (float threshold : {0.01f, 0.05f}) {
        SCOPED_TRACE(threshold);
        gContactBreakingThreshold = threshold;
        SideBySide s([&](WorldKind kind, const Config& config) { return coastingSphere(kind, config, false); });
        s.step();
        ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        if (threshold < 0.015f) EXPECT_LT(s.stockY(1), 0.08);
        else EXPECT_GT(s.stockY(1), 0.095);
        EXPECT_NEAR(s.gpuY(1), s.stockY(1), 2e-3) << "btgpu " << s.gpuY(1) << ", stock " << s.stockY(1);
        s.step(30);
        ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        EXPECT_NEAR(s.gpuY(1), s.stockY(1), 5e-3) << "btgpu " << s.gpuY(1) << ", stock " << s.stockY(1);
    }
    {
        gContactBreakingThreshold = 0.05f;
        Config config = Config::bulletMode();
        config.contactThreshold = 0.03f;
        ScenePtr scene = coastingSphere(WorldKind::Gpu, config, false);
        scene->step();
        EXPECT_FALSE(scene->report()->gpuPath);
        EXPECT_NE(scene->report()->cpuPathReason.find("gContactBreakingThreshold"), std::string::npos);
    }
    gContactBreakingThreshold = saved;
}
