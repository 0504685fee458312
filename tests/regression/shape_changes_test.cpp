// shape_changes_test.cpp — the app's shapes as the world sees them: read, never changed (no
// polyhedral features left on a hull, so a world on the CPU path is stock bitwise), and
// followed when the app changes one in place between steps (setLocalScaling, setMargin).
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btMinkowskiSumShape.h>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

std::vector<btVector3> cubePoints(float h)
{
    std::vector<btVector3> p;
    for (int i = 0; i < 8; ++i) p.emplace_back((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h);
    return p;
}

// Two hull cubes falling onto each other on a ground box; `capsule` adds a compound holding a
// Minkowski sum of a capsule and a sphere (a shape the GPU path does not take), sending the
// world to the CPU path.
ScenePtr hulls(WorldKind kind, const Config& config, bool capsule)
{
    auto scene = std::make_unique<Scene>(kind, config);
    scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
    btConvexHullShape* hull = scene->hullShape(cubePoints(0.5f));
    scene->addBody(hull, 1, btVector3(0, 0.6f, 0));
    btTransform t(btQuaternion(btVector3(1, 1, 0).normalized(), 0.4f), btVector3(0.2f, 2.0f, 0.1f));
    scene->addBody(hull, 1, t);
    if (capsule) {
        btCompoundShape* compound = scene->ownShape(new btCompoundShape());
        btCollisionShape* sum = scene->ownShape(new btMinkowskiSumShape(
            scene->ownShape(new btCapsuleShape(0.3f, 1.0f)), scene->ownShape(new btSphereShape(0.1f))));
        compound->addChildShape(btTransform::getIdentity(), sum);
        scene->addBody(compound, 1, btVector3(5, 1, 0));
    }
    return scene;
}

}  // namespace

TEST(ShapeChanges, HullsAreReadNotChanged)
{
    ScenePtr gpu = hulls(WorldKind::Gpu, Config::bulletMode(), false);
    gpu->step();
    ASSERT_TRUE(gpu->gpuWorld()->isGpuPath());
    auto* hull = static_cast<const btConvexHullShape*>(gpu->body(1)->getCollisionShape());
    EXPECT_EQ(hull->getConvexPolyhedron(), nullptr) << "the world computed polyhedral features on the app's hull";
}

// On the CPU path the world is stock Bullet: bitwise, with hulls in it.
TEST(ShapeChanges, CpuPathWithHullsIsStockBitwise)
{
    SideBySide s([](WorldKind kind, const Config& config) { return hulls(kind, config, true); });
    for (int i = 0; i < 90; ++i) {
        s.step();
        ASSERT_FALSE(s.onGpu());
    }
    for (int i = 0; i < 4; ++i) EXPECT_EQ(s.distance(i), 0.0) << "body " << i;
}

TEST(ShapeChanges, ScalingAndMarginChangedBetweenStepsAreFollowed)
{
    SideBySide s(scenes::restingBox);
    s.step(10);
    // The box doubles: on stock it now overlaps the ground and is pushed up to rest at 1.0.
    s.both([](Scene& scene) {
        scene.body(1)->getCollisionShape()->setLocalScaling(btVector3(2, 2, 2));
        scene.body(1)->activate();
    });
    s.step(60);
    EXPECT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
    EXPECT_GT(s.stockY(1), 0.9);
    EXPECT_LT(std::fabs(s.gpuY(1) - s.stockY(1)), 0.01) << "btgpu " << s.gpuY(1) << ", stock " << s.stockY(1);

    // A hull's margin rounds it outwards: resting height rises by the margin change.
    SideBySide h([](WorldKind kind, const Config& config) {
        auto scene = std::make_unique<Scene>(kind, config);
        scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
        scene->addBody(scene->hullShape(cubePoints(0.5f)), 1, btVector3(0, 0.54f, 0));
        return scene;
    });
    h.step(30);
    h.both([](Scene& scene) {
        scene.body(1)->getCollisionShape()->setMargin(0.2f);
        scene.body(1)->activate();
    });
    h.step(60);
    EXPECT_TRUE(h.onGpu()) << h.gpu->report()->cpuPathReason;
    EXPECT_GT(h.stockY(1), 0.65);
    EXPECT_LT(std::fabs(h.gpuY(1) - h.stockY(1)), 0.01) << "btgpu " << h.gpuY(1) << ", stock " << h.stockY(1);
}

// A body given another shape between steps (setCollisionShape), the old one deleted by the
// app: the tables follow, as stock does, and nothing reads the deleted shape.
TEST(ShapeChanges, SwappedShapeIsFollowed)
{
    for (int bodies : {3, 9000}) {  // 9,000: the row passes run on several threads
        SCOPED_TRACE(bodies);
        SideBySide s([&](WorldKind kind, const Config& config) {
            auto scene = std::make_unique<Scene>(kind, config);
            scene->addBody(scene->boxShape(btVector3(500, 50, 500)), 0, btVector3(0, -50, 0));
            btBoxShape* small = scene->boxShape(btVector3(0.5f, 0.5f, 0.5f));
            for (int i = 1; i < bodies; ++i)
                scene->addBody(small, 1, btVector3(float(i % 95) * 3 - 140, 0.5f, float(i / 95) * 3 - 140));
            return scene;
        });
        s.step(5);
        std::unique_ptr<btBoxShape> stockBig(new btBoxShape(btVector3(1, 1, 1)));
        std::unique_ptr<btBoxShape> gpuBig(new btBoxShape(btVector3(1, 1, 1)));
        s.stock->body(1)->setCollisionShape(stockBig.get());
        s.gpu->body(1)->setCollisionShape(gpuBig.get());
        s.both([](Scene& scene) { scene.body(1)->activate(); });
        s.step(60);
        EXPECT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        EXPECT_GT(s.stockY(1), 0.9);
        EXPECT_LT(std::fabs(s.gpuY(1) - s.stockY(1)), 0.01) << "btgpu " << s.gpuY(1) << ", stock " << s.stockY(1);
        // Swapped again, and the big one deleted at once, as an app may; its stale contact
        // points dropped as Bullet asks after setCollisionShape (else stock keeps the body
        // standing on them).
        btBoxShape* small = static_cast<btBoxShape*>(s.gpu->body(2)->getCollisionShape());
        s.stock->body(1)->setCollisionShape(static_cast<btBoxShape*>(s.stock->body(2)->getCollisionShape()));
        s.gpu->body(1)->setCollisionShape(small);
        s.both([](Scene& scene) {
            btBroadphaseProxy* proxy = scene.body(1)->getBroadphaseHandle();
            scene.world().getPairCache()->cleanProxyFromPairs(proxy, scene.world().getDispatcher());
            scene.body(1)->activate();
        });
        stockBig.reset();
        gpuBig.reset();
        s.step(60);
        EXPECT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        EXPECT_LT(std::fabs(s.gpuY(1) - s.stockY(1)), 0.01) << "btgpu " << s.gpuY(1) << ", stock " << s.stockY(1);
        for (const Issue& issue : s.gpu->report()->issues) EXPECT_NE(issue.kind, Issue::Kind::OpenCL) << issue.message;
    }
}
