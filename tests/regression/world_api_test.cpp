// world_api_test.cpp — what an app sees of btGpuDynamicsWorld besides the motion: the plan
// builds only what the scene needs and grows when a new shape kind arrives, queries on the
// base class see bodies where the GPU put them, and an unusable device means the CPU path,
// said in the report, not an exception.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {
bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }
}  // namespace

TEST(WorldApi, PlanLeavesOutSatUntilAHullPairExists)
{
    // Spheres over a static plane: no hull at all, so no SAT/clipping program and no stage.
    btStaticPlaneShape plane(btVector3(0, 1, 0), 0);  // outlives the scene that uses it
    Scene scene(WorldKind::Gpu);
    scene.addBody(&plane, 0, btVector3(0, 0, 0));
    for (int i = 0; i < 4; ++i) scene.addBody(scene.sphereShape(.5), 1, btVector3(btScalar(1.1 * i), 2, 0));
    for (int i = 0; i < 30; ++i) scene.step();
    const Report* r = scene.report();
    ASSERT_TRUE(r->gpuPath) << r->cpuPathReason;
    EXPECT_FALSE(has(r->builtPrograms, "narrowphase_sat"));
    EXPECT_FALSE(has(r->stages, "narrowphase_sat"));
    EXPECT_TRUE(has(r->builtPrograms, "narrowphase"));
    // Two boxes arrive: a hull–hull pair kind now exists, and the program comes in.
    btBoxShape* box = scene.boxShape(btVector3(.5, .5, .5));
    scene.addBody(box, 1, btVector3(10, .5, 0));
    scene.addBody(box, 1, btVector3(10, 1.6, 0));
    for (int i = 0; i < 30; ++i) scene.step();
    EXPECT_TRUE(has(r->stages, "narrowphase_sat"));
    EXPECT_TRUE(has(r->builtPrograms, "narrowphase_sat"));
    EXPECT_GT(scene.body(6)->getWorldTransform().getOrigin().y(), 1.4) << "the upper box fell through";
}

TEST(WorldApi, RayTestSeesBodiesWhereTheGpuMovedThem)
{
    ScenePtr scene = scenes::freeFall(WorldKind::Gpu);
    for (int i = 0; i < 30; ++i) scene->step();
    ASSERT_TRUE(scene->report()->gpuPath);
    btRigidBody* body = scene->body(scene->bodies().size() > 1 ? 1 : 0);
    btVector3 at = body->getWorldTransform().getOrigin();
    btVector3 from = at + btVector3(0, 50, 0), to = at - btVector3(0, 50, 0);
    btCollisionWorld::ClosestRayResultCallback hit(from, to);
    scene->world().rayTest(from, to, hit);
    ASSERT_TRUE(hit.hasHit());
    EXPECT_EQ(hit.m_collisionObject, body);
}

TEST(WorldApi, NoSuchDeviceRunsTheCpuPathAndSaysSo)
{
    Config config;
    config.device = "no-such-opencl-device";
    if (std::getenv("BTGPU_DEVICE")) GTEST_SKIP() << "BTGPU_DEVICE overrides Config::device";
    ScenePtr scene = scenes::restingBox(WorldKind::Gpu, config);
    EXPECT_NO_THROW(scene->step());
    const Report* r = scene->report();
    EXPECT_FALSE(r->gpuPath);
    EXPECT_NE(r->cpuPathReason.find("no usable OpenCL device"), std::string::npos) << r->cpuPathReason;
    ASSERT_FALSE(r->issues.empty());
    EXPECT_EQ(r->issues.front().kind, Issue::Kind::Device);
    for (int i = 0; i < 60; ++i) scene->step();
    EXPECT_NEAR(scene->body(1)->getWorldTransform().getOrigin().y(), 0.5, 0.01) << "the CPU path simulates";
}
