// robustness_test.cpp — btGpuDynamicsWorld on its own: it stays on the GPU path for every scene,
// is deterministic step by step, survives and names bad bodies, and falls back to the CPU
// path for an unserved constraint and comes back when it is removed.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

TEST(Robustness, EverySceneRunsOnGpuPath)
{
    for (const scenes::SceneEntry& entry : scenes::catalog()) {
        SCOPED_TRACE(entry.name);
        ScenePtr scene = entry.make(WorldKind::Gpu, Config::bulletMode());
        for (int i = 0; i < 3; ++i) scene->step();
        const Report& report = *scene->report();
        EXPECT_TRUE(report.gpuPath) << report.cpuPathReason;
        EXPECT_TRUE(report.cpuPathReason.empty()) << report.cpuPathReason;
        EXPECT_FALSE(report.device.empty());
        EXPECT_FALSE(report.stages.empty());
        EXPECT_TRUE(scenes::allFinite(*scene));
    }
}

TEST(Robustness, SameSceneTwiceGivesSameHashes)
{
    ScenePtr a = scenes::basicDemo(WorldKind::Gpu);
    ScenePtr b = scenes::basicDemo(WorldKind::Gpu);
    ASSERT_EQ(a->gpuWorld()->stateHash(), b->gpuWorld()->stateHash());
    for (int i = 0; i < 120; ++i) {
        a->step();
        b->step();
        ASSERT_EQ(a->gpuWorld()->stateHash(), b->gpuWorld()->stateHash()) << "step " << i;
    }
}

TEST(Robustness, BadBodiesAreNamedAndOthersKeepSimulating)
{
    int callbacks = 0;
    Config config = Config::bulletMode();
    config.onIssue = [&callbacks](const Issue&) { ++callbacks; };
    ScenePtr gpu = scenes::dropRow(WorldKind::Gpu, config);
    ScenePtr clean = scenes::dropRow(WorldKind::Stock);
    for (int i = 0; i < 5; ++i) {
        gpu->step();
        clean->step();
    }
    btRigidBody* nanBody = gpu->body(1);
    btRigidBody* massless = gpu->body(3);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    nanBody->setLinearVelocity(btVector3(nan, 0, 0));
    // setMassProps(0, ...) marks the body static itself; clearing the flag leaves what a buggy
    // app can produce: inverse mass 0 on a body that is neither static nor kinematic.
    massless->setMassProps(0, btVector3(0, 0, 0));
    massless->setCollisionFlags(massless->getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT);
    const int nanIndex = gpu->worldIndex(nanBody);
    const int masslessIndex = gpu->worldIndex(massless);

    for (int i = 0; i < 55; ++i) {
        EXPECT_NO_THROW(gpu->step());
        clean->step();
    }
    bool namedNan = false, namedMassless = false;
    for (const Issue& issue : gpu->report()->issues) {
        if (issue.kind != Issue::Kind::BadBody) continue;
        namedNan |= issue.bodyIndex == nanIndex;
        namedMassless |= issue.bodyIndex == masslessIndex;
    }
    EXPECT_TRUE(namedNan) << "no BadBody issue names body " << nanIndex << " (NaN velocity)";
    EXPECT_TRUE(namedMassless) << "no BadBody issue names body " << masslessIndex << " (inverse mass 0, dynamic)";
    EXPECT_GE(callbacks, 2);
    // The middle box, 1.5 m from either, fell and landed as in a clean stock run.
    const btVector3 good = gpu->body(2)->getWorldTransform().getOrigin();
    EXPECT_LT((good - clean->body(2)->getWorldTransform().getOrigin()).length(), tol::kRestHeight);
    EXPECT_TRUE(std::isfinite(good.y()));
}

namespace {
// A joint type the GPU path does not serve (joints are served by exact type).
struct AppJoint : btPoint2PointConstraint {
    using btPoint2PointConstraint::btPoint2PointConstraint;
};
}  // namespace

TEST(Robustness, ConstraintFallsBackAndComesBack)
{
    SideBySide s(scenes::restingBox);
    s.step(5);
    EXPECT_TRUE(s.onGpu());
    std::unique_ptr<btPoint2PointConstraint> stockJoint, gpuJoint;
    s.both([&](Scene& scene) {
        auto joint = std::make_unique<AppJoint>(*scene.body(1), btVector3(0, .5, 0));
        scene.world().addConstraint(joint.get());
        (scene.kind() == WorldKind::Stock ? stockJoint : gpuJoint) = std::move(joint);
    });
    s.step(5);
    EXPECT_FALSE(s.onGpu());
    EXPECT_FALSE(s.gpu->report()->cpuPathReason.empty());
    s.stock->world().removeConstraint(stockJoint.get());
    s.gpu->world().removeConstraint(gpuJoint.get());
    s.step(5);
    EXPECT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
    EXPECT_TRUE(s.gpu->report()->cpuPathReason.empty());
    EXPECT_LT(s.distance(1), tol::kRestHeight);
}
