// convex_shapes_test.cpp — the convex shapes Bullet collides by GJK (capsules, cylinders, cones
// of each axis, a multi-sphere, a convex triangle mesh, a uniformly scaled capsule, locally
// scaled boxes and hulls) on stock Bullet and on btgpu in the same test: rest heights, a
// cylinder rolling down a ramp, a mixed pile within stock's own chaos. Every step must stay on
// the GPU path and run the GJK stage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scenes/convex_scenes.h"
#include "scenes/stock_chaos.h"
#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;
using scenes::ConvexKind;

namespace {

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

// Steps both worlds, asserting the GPU path (and the GJK stage) after every step.
void stepOnGpu(SideBySide& s, int steps, bool gjk = true)
{
    for (int i = 0; i < steps; ++i) {
        s.step();
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
        if (gjk) ASSERT_TRUE(has(s.gpu->report()->stages, "narrowphase_gjk")) << "step " << i;
    }
}

struct Landing {
    const char* name;
    ConvexKind kind;
    int axis;
    double tilt;
    bool gjk;  // the scene has a GJK pair (scaled boxes and hulls keep their own kinds)
};

void expectRestsAsStock(const Landing& c, int steps = 180)
{
    SCOPED_TRACE(c.name);
    SideBySide s([&](scenes::WorldKind k, const Config& cfg) { return scenes::convexLanding(k, c.kind, c.axis, c.tilt, 1.5, cfg); });
    ASSERT_NO_FATAL_FAILURE(stepOnGpu(s, steps, c.gjk));
    EXPECT_NEAR(s.gpuY(1), s.stockY(1), tol::kRestHeight) << c.name;
    // at rest, not still falling or rolling away
    EXPECT_LT(s.gpu->body(1)->getLinearVelocity().length(), 0.05) << c.name << " stock " << s.stock->body(1)->getLinearVelocity().length() << " y " << s.gpuY(1) << " " << s.stockY(1);
}

}  // namespace

TEST(ConvexShapes, CapsuleOnItsSideRestsAtStockHeight)
{
    expectRestsAsStock({"capsule y on its side", ConvexKind::Capsule, 1, M_PI / 2, true});
}

TEST(ConvexShapes, CylinderOnItsSideRestsAtStockHeight)
{
    expectRestsAsStock({"cylinder y on its side", ConvexKind::Cylinder, 1, M_PI / 2, true});
}

TEST(ConvexShapes, ConeRestsAtStockHeight)
{
    expectRestsAsStock({"cone y upright", ConvexKind::Cone, 1, 0.0, true});
}

TEST(ConvexShapes, EveryAxisRestsAtStockHeight)
{
    for (int axis = 0; axis < 3; ++axis) {
        expectRestsAsStock({"capsule upright", ConvexKind::Capsule, axis, 0.0, true});
        expectRestsAsStock({"cylinder upright", ConvexKind::Cylinder, axis, 0.0, true});
        expectRestsAsStock({"cone", ConvexKind::Cone, axis, 0.0, true});
    }
}

TEST(ConvexShapes, MultiSphereAndConvexMeshLandAsStock)
{
    expectRestsAsStock({"multi-sphere", ConvexKind::MultiSphere, 1, 0.0, true});
    expectRestsAsStock({"convex triangle mesh", ConvexKind::ConvexMesh, 1, 0.0, true});
    expectRestsAsStock({"uniformly scaled capsule", ConvexKind::UniformCapsule, 1, M_PI / 2, true});
}

TEST(ConvexShapes, ScaledBoxAndHullRestAsStock)
{
    expectRestsAsStock({"scaled box", ConvexKind::ScaledBox, 1, 0.0, false});
    expectRestsAsStock({"scaled hull", ConvexKind::ScaledHull, 1, 0.0, false});
}

TEST(ConvexShapes, LocallyScaledShapesRestAsStock)
{
    for (int axis = 0; axis < 3; ++axis) {
        expectRestsAsStock({"scaled capsule", ConvexKind::ScaledCapsule, axis, 0.0, true});
        expectRestsAsStock({"scaled cylinder", ConvexKind::ScaledCylinder, axis, 0.0, true});
        // On its side (axes x and z) a cone rolls about its apex until it falls asleep (2 s
        // slow): its landing on the rim is chaotic (the friction direction of a flat contact is
        // the normal's rounding, stock's as well), so 4 s let both worlds' cones come to rest.
        expectRestsAsStock({"scaled cone", ConvexKind::ScaledCone, axis, 0.0, true}, axis == 1 ? 180 : 240);
    }
    expectRestsAsStock({"scaled multi-sphere", ConvexKind::ScaledMultiSphere, 1, 0.0, true});
    expectRestsAsStock({"scaled sphere", ConvexKind::ScaledSphere, 1, 0.0, false});
}

TEST(ConvexShapes, PileIsDeterministic)
{
    // Same scene, same device, same binary: bitwise the same states, step by step.
    scenes::ScenePtr a = scenes::convexPile(scenes::WorldKind::Gpu), b = scenes::convexPile(scenes::WorldKind::Gpu);
    for (int i = 0; i < 120; ++i) {
        a->step();
        b->step();
        for (size_t k = 0; k < a->bodies().size(); ++k) {
            const btTransform &ta = a->body(int(k))->getWorldTransform(), &tb = b->body(int(k))->getWorldTransform();
            ASSERT_EQ(ta.getOrigin(), tb.getOrigin()) << "step " << i << " body " << k;
            ASSERT_EQ(ta.getRotation(), tb.getRotation()) << "step " << i << " body " << k;
        }
    }
    ASSERT_TRUE(a->gpuWorld()->isGpuPath());
}

TEST(ConvexShapes, SubstepsAsStock)
{
    // Four substeps a call (the GJK manifolds and the warm-start cache carried between them and
    // kept for a redo), a capsule and a cone landing: rest heights as stock's at the same calls.
    auto make = [](scenes::WorldKind k, const Config& c) {
        scenes::ScenePtr s = scenes::convexLanding(k, ConvexKind::Capsule, 0, 0.0, 1.5, c);
        btTransform t;
        t.setIdentity();
        t.setOrigin(btVector3(3, 1.2f, 0));
        s->addBody(s->ownShape(new btConeShapeZ(.4f, .9f)), 1, t);
        return s;
    };
    SideBySide s(make);
    for (int i = 0; i < 45; ++i) {
        s.step(1, btScalar(4) / btScalar(60), 4);
        ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
    }
    EXPECT_NEAR(s.gpuY(1), s.stockY(1), tol::kRestHeight);
    EXPECT_NEAR(s.gpuY(2), s.stockY(2), tol::kRestHeight);
}

TEST(ConvexShapes, CylinderRollsDownRampAsStock)
{
    SideBySide s(scenes::cylinderRamp);
    const btVector3 start = s.stock->body(1)->getWorldTransform().getOrigin();
    ASSERT_NO_FATAL_FAILURE(stepOnGpu(s, 180));
    const double stockDist = (s.stock->body(1)->getWorldTransform().getOrigin() - start).length();
    const double gpuDist = (s.gpu->body(1)->getWorldTransform().getOrigin() - start).length();
    ASSERT_GT(stockDist, 1.0) << "stock's cylinder did not roll: the scene is wrong";
    EXPECT_NEAR(gpuDist, stockDist, tol::kRollDistanceRel * stockDist);
}

TEST(ConvexShapes, MixedPileWithinStockChaos)
{
    const int steps = 240;
    auto measure = [](const scenes::Scene& sc) {
        scenes::Aggregates a = scenes::aggregates(sc);
        return std::vector<double>{a.meanHeight, a.spread};
    };
    const std::vector<scenes::ChaosBand> bands =
        scenes::stockChaos([](scenes::WorldKind k) { return scenes::convexPile(k); }, steps, measure,
                           {"mean height", "spread"}, {tol::kChaosHeightFloor, tol::kChaosSpreadFloor});
    scenes::ScenePtr gpu = scenes::convexPile(scenes::WorldKind::Gpu);
    for (int i = 0; i < steps; ++i) {
        gpu->step();
        ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << "step " << i << ": " << gpu->report()->cpuPathReason;
        ASSERT_TRUE(has(gpu->report()->stages, "narrowphase_gjk"));
    }
    ASSERT_TRUE(scenes::allFinite(*gpu));
    const std::vector<double> values = measure(*gpu);
    for (size_t k = 0; k < bands.size(); ++k)
        EXPECT_TRUE(bands[k].admits(values[k])) << bands[k].name << ": btgpu " << values[k] << ", stock "
                                                << bands[k].stockMean << " +- " << bands[k].bound();
}

// btEmptyShape (game code's bodies without collision: anchors, particles, placeholders): such a
// body moves and takes joints but collides with nothing, as on stock, where its concave type
// gets no contact from any algorithm. A free one falls through the ground box; one hung from a
// box by a point-to-point joint swings below it; a box dropped onto a static empty-shape body
// falls through its spot onto the ground. No point with one of them on either world.
TEST(ConvexShapes, EmptyShapeBodiesCollideWithNothingAsStock)
{
    auto make = [](WorldKind k, const Config& c) {
        auto s = std::make_unique<Scene>(k, c, "empty_shapes");
        s->addBody(s->boxShape(btVector3(10, 0.5f, 10)), 0, btVector3(0, -0.5f, 0));     // 0: ground
        btEmptyShape* empty = s->ownShape(new btEmptyShape());
        btRigidBody* free = s->addBody(empty, 1, btVector3(-3, 2, 0));                   // 1
        btRigidBody* bob = s->addBody(empty, 1, btVector3(0, 3, 1.0f));                  // 2
        btRigidBody* box = s->addBody(s->boxShape(btVector3(0.5f, 0.5f, 0.5f)), 1, btVector3(0, 3, 0));  // 3
        s->addBody(empty, 0, btVector3(3, 0.5f, 0));                                     // 4: static
        s->addBody(s->boxShape(btVector3(0.3f, 0.3f, 0.3f)), 1, btVector3(3, 2, 0));      // 5: falls onto 4
        for (btRigidBody* b : {free, bob}) b->setMassProps(1, btVector3(0.1f, 0.1f, 0.1f));
        s->addJoint(new btPoint2PointConstraint(*box, *bob, btVector3(0, 0, 0.5f), btVector3(0, 0, -0.5f)));
        box->setActivationState(DISABLE_DEACTIVATION);
        return ScenePtr(std::move(s));
    };
    SideBySide s(make);
    int stockPoints = 0, gpuPoints = 0;
    auto points = [](Scene& sc) {
        int n = 0;
        btDispatcher* d = sc.world().getDispatcher();
        for (int i = 0; i < d->getNumManifolds(); ++i) {
            const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
            const bool withEmpty = m->getBody0()->getCollisionShape()->getShapeType() == EMPTY_SHAPE_PROXYTYPE ||
                                   m->getBody1()->getCollisionShape()->getShapeType() == EMPTY_SHAPE_PROXYTYPE;
            if (withEmpty) n += m->getNumContacts();
        }
        return n;
    };
    for (int step = 0; step < 120; ++step) {
        s.step();
        ASSERT_TRUE(s.onGpu()) << step << " " << s.gpu->report()->cpuPathReason;
        stockPoints += points(*s.stock);
        gpuPoints += points(*s.gpu);
        for (int b : {1, 2, 3, 5}) ASSERT_LT(s.distance(b), 1e-3) << "body " << b << " step " << step;
    }
    EXPECT_EQ(stockPoints, 0);
    EXPECT_EQ(gpuPoints, 0);
    EXPECT_LT(s.gpuY(1), -10.0);  // fell through the ground
    EXPECT_NEAR(s.gpuY(5), 0.3, 0.01);  // through the static empty shape's spot, onto the ground
    EXPECT_LT(s.gpuY(2), 0.5);          // the bob hangs below its pivot, through the ground
}
