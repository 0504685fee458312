// world_api_test.cpp — what an app sees of btGpuDynamicsWorld besides the motion: the plan
// builds only what the scene needs and grows when a new shape kind arrives, picks sort-and-sweep
// for bodies of widely different sizes and the grid for alike ones, queries on the
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

TEST(WorldApi, PlanLeavesOutSatUntilABoxPairExists)
{
    // Spheres over a static plane: no hull at all, so no SAT/clipping program and no stage; the
    // GJK program takes two spheres (stock's sphere–sphere algorithm, its point only while they touch).
    btStaticPlaneShape plane(btVector3(0, 1, 0), 0);  // outlives the scene that uses it
    Scene scene(WorldKind::Gpu);
    scene.addBody(&plane, 0, btVector3(0, 0, 0));
    for (int i = 0; i < 4; ++i) scene.addBody(scene.sphereShape(.5), 1, btVector3(btScalar(1.1 * i), 2, 0));
    for (int i = 0; i < 30; ++i) scene.step();
    const Report* r = scene.report();
    ASSERT_TRUE(r->gpuPath) << r->cpuPathReason;
    EXPECT_FALSE(has(r->builtPrograms, "narrowphase_sat"));
    EXPECT_FALSE(has(r->stages, "narrowphase_sat"));
    EXPECT_TRUE(has(r->builtPrograms, "narrowphase_gjk"));
    EXPECT_TRUE(has(r->stages, "narrowphase_gjk"));
    EXPECT_TRUE(has(r->builtPrograms, "narrowphase"));
    // Two boxes arrive: a box–box pair kind now exists, and the program comes in; the lower box
    // meets the plane as stock's convex–plane algorithm does, one point a step (the GJK program).
    btBoxShape* box = scene.boxShape(btVector3(.5, .5, .5));
    scene.addBody(box, 1, btVector3(10, .5, 0));
    scene.addBody(box, 1, btVector3(10, 1.6, 0));
    for (int i = 0; i < 30; ++i) scene.step();
    EXPECT_TRUE(has(r->stages, "narrowphase_sat"));
    EXPECT_TRUE(has(r->builtPrograms, "narrowphase_sat"));
    EXPECT_TRUE(has(r->builtPrograms, "narrowphase_gjk"));
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
    Config config = Config::bulletMode();
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

TEST(WorldApi, PlanSweepsMixedSizesAndGridsAlikeOnes)
{
    // Debris boxes of half extents 0.1-0.2 m with a crate of 0.6 m (within the large limit, so
    // it sets the grid's cell): mostly empty cells, sort-and-sweep.
    Scene mixed(WorldKind::Gpu);
    mixed.addBody(mixed.boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
    unsigned seed = 7;
    auto uniform = [&](float lo, float hi) {
        seed = seed * 1664525u + 1013904223u;
        return lo + (hi - lo) * float(seed >> 8) * (1.0f / 16777216.0f);
    };
    for (int i = 0; i < 64; ++i) {
        btVector3 half(uniform(0.1f, 0.2f), uniform(0.1f, 0.2f), uniform(0.1f, 0.2f));
        if (i == 0) half = btVector3(0.6, 0.6, 0.6);  // the crate
        btVector3 at(btScalar((i % 4) * 6 - 9), btScalar(4 + (i / 16) * 6), btScalar(((i / 4) % 4) * 6 - 9));
        mixed.addBody(mixed.boxShape(half), half.x() * half.y() * half.z(), at);
    }
    for (int i = 0; i < 150; ++i) mixed.step();
    const Report* r = mixed.report();
    ASSERT_TRUE(r->gpuPath) << r->cpuPathReason;
    EXPECT_TRUE(has(r->stages, "sort_sweep"));
    EXPECT_FALSE(has(r->stages, "uniform_grid"));
    EXPECT_TRUE(has(r->builtPrograms, "sort_sweep"));
    EXPECT_GT(r->pairs, 30) << "the boxes landed and touch each other";
    EXPECT_TRUE(scenes::allFinite(mixed));
    EXPECT_GT(scenes::lowestHeight(mixed), 0.05) << "a box fell into the ground";

    // Cubes of one size: the uniform grid, and no sort-and-sweep program.
    ScenePtr cubes = scenes::cubes(WorldKind::Gpu, 3, 3, 3);
    for (int i = 0; i < 5; ++i) cubes->step();
    const Report* c = cubes->report();
    ASSERT_TRUE(c->gpuPath) << c->cpuPathReason;
    EXPECT_TRUE(has(c->stages, "uniform_grid"));
    EXPECT_FALSE(has(c->stages, "sort_sweep"));
}

namespace {
// An app's own motion state: records what the world hands it.
struct RecordingMotionState : btMotionState {
    btTransform start, last;
    int calls = 0;
    explicit RecordingMotionState(const btTransform& t) : start(t), last(t) {}
    void getWorldTransform(btTransform& t) const override { t = start; }
    void setWorldTransform(const btTransform& t) override
    {
        last = t;
        ++calls;
    }
};
}  // namespace

TEST(WorldApi, MotionStatesAndForcesAsStock)
{
    // Two falling boxes per world, one with Bullet's motion state and one with the app's own;
    // a force is applied before every call. After each call both motion states hold what stock
    // gives them, the app's own is called as often, and the forces are cleared.
    auto run = [](WorldKind kind, RecordingMotionState* own, int steps) {
        Scene scene(kind);
        btBoxShape* box = scene.boxShape(btVector3(.5, .5, .5));
        btRigidBody* a = scene.addBody(box, 1, btVector3(0, 5, 0));
        btRigidBody* b = scene.addBody(box, 1, btVector3(3, 5, 0));
        btMotionState* scenes = b->getMotionState();
        b->setMotionState(own);
        std::vector<btTransform> out;
        for (int i = 0; i < steps; ++i) {
            a->applyCentralForce(btVector3(1, 0, 0));
            b->applyCentralForce(btVector3(0, 0, 1));
            scene.step();
            EXPECT_EQ(a->getTotalForce(), btVector3(0, 0, 0)) << toString(kind) << " step " << i;
            EXPECT_EQ(b->getTotalForce(), btVector3(0, 0, 0)) << toString(kind) << " step " << i;
            btTransform t;
            a->getMotionState()->getWorldTransform(t);
            out.push_back(t);
            out.push_back(own->last);
        }
        b->setMotionState(scenes);  // the recording state belongs to the test, the other to the scene
        return out;
    };
    const int steps = 20;
    btTransform start(btQuaternion::getIdentity(), btVector3(3, 5, 0));
    RecordingMotionState stockOwn(start), gpuOwn(start);
    std::vector<btTransform> stock = run(WorldKind::Stock, &stockOwn, steps);
    std::vector<btTransform> gpu = run(WorldKind::Gpu, &gpuOwn, steps);
    EXPECT_EQ(gpuOwn.calls, stockOwn.calls);
    ASSERT_EQ(stock.size(), gpu.size());
    for (size_t i = 0; i < stock.size(); ++i)
        EXPECT_LT((stock[i].getOrigin() - gpu[i].getOrigin()).length(), tol::kFreeFallPosition) << "transform " << i;
}
