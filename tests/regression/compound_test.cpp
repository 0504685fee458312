// compound_test.cpp — btCompoundShape bodies on stock Bullet and on btgpu in the same test, the
// GPU path asserted after every step and expand_compounds seen to run: a table standing on a box
// ground and three stacked (rest heights within 1 mm of stock, tilt tiny), a dumbbell rolling, a
// table on a triangle mesh, child changes between steps (updateChildTransform, addChildShape,
// removeChildShape) taking effect on the next step; and what keeps the CPU path, with its reason.
#include "btgpu/btGpuDynamicsWorld.h"
#include "scenes/compound_scenes.h"
#include "side_by_side.h"
#include "tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace btgpu;
using namespace btgpu::test;

namespace {

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

// Steps both worlds, the btgpu one on the GPU path every step with expand_compounds in its plan.
void stepOnGpu(SideBySide& run, int steps)
{
    int contacts = 0;
    for (int i = 0; i < steps; ++i) {
        run.step();
        ASSERT_TRUE(run.onGpu()) << "step " << i << ": " << run.gpu->report()->cpuPathReason;
        contacts = std::max(contacts, run.gpu->report()->contacts);
    }
    const Report& r = *run.gpu->report();
    EXPECT_TRUE(has(r.stages, "expand_compounds"));
    EXPECT_TRUE(has(r.builtPrograms, "expand_compounds"));
    EXPECT_GT(contacts, 0);
}

// Angle between the body's up axis and the world's, rad.
double tilt(const scenes::Scene& s, int i)
{
    const btVector3 up = s.body(i)->getWorldTransform().getBasis().getColumn(1);
    return std::acos(std::min<btScalar>(1, up.y()));
}

void expectRestLikeStock(const SideBySide& run, int first, int last)
{
    for (int i = first; i <= last; ++i) {
        EXPECT_NEAR(run.gpuY(i), run.stockY(i), tol::kRestHeight) << "body " << i;
        std::printf("body %d: rest height btgpu %.4f stock %.4f, tilt btgpu %.5f stock %.5f rad\n", i, run.gpuY(i),
                    run.stockY(i), tilt(*run.gpu, i), tilt(*run.stock, i));
        EXPECT_LT(tilt(*run.gpu, i), tol::kRestTilt) << "body " << i;
        EXPECT_LT(run.distance(i), tol::kRestPlace) << "body " << i;
    }
}

}  // namespace

TEST(Compound, TableStandsOnABoxGroundAsOnStock)
{
    SideBySide run([](WorldKind k, const Config& c) { return scenes::tableStack(k, c, 1); });
    stepOnGpu(run, 120);
    EXPECT_NEAR(run.stockY(1), scenes::kTableFootDepth, 0.01);
    expectRestLikeStock(run, 1, 1);
}

TEST(Compound, ThreeTablesStackedAsOnStock)
{
    SideBySide run([](WorldKind k, const Config& c) { return scenes::tableStack(k, c, 3); });
    stepOnGpu(run, 150);
    for (int i = 1; i <= 3; ++i)
        EXPECT_NEAR(run.stockY(i), scenes::kTableFootDepth + scenes::kTableHeight * (i - 1), 0.02) << "body " << i;
    expectRestLikeStock(run, 1, 3);
}

// Tables without dynamic AABB trees (btCompoundShape(false)): two of them meet by stock's nested
// compound algorithms (compound.h), each table resting on the one below as on stock.
TEST(Compound, ThreeTablesWithoutTreesStackedAsOnStock)
{
    SideBySide run([](WorldKind k, const Config& c) { return scenes::tableStack(k, c, 3, false); });
    stepOnGpu(run, 150);
    for (int i = 1; i <= 3; ++i)
        EXPECT_NEAR(run.stockY(i), scenes::kTableFootDepth + scenes::kTableHeight * (i - 1), 0.02) << "body " << i;
    expectRestLikeStock(run, 1, 3);
}

// Game engines wrap each body in a btCompoundShape(false) of one child to put its centre of mass
// at its origin: a stack of such boxes lands and rests as on stock.
TEST(Compound, WrappedBoxStackAsOnStock)
{
    SideBySide run([](WorldKind k, const Config& c) { return scenes::wrappedBoxStack(k, c, 4); });
    stepOnGpu(run, 150);
    for (int i = 1; i <= 4; ++i) EXPECT_NEAR(run.stockY(i), 0.7 + 1.0 * (i - 1), 0.02) << "body " << i;
    expectRestLikeStock(run, 1, 4);
}

TEST(Compound, DumbbellRollsAsOnStock)
{
    SideBySide run(scenes::dumbbellRolling);
    stepOnGpu(run, 120);
    const double stock = run.stock->body(1)->getWorldTransform().getOrigin().z();
    const double gpu = run.gpu->body(1)->getWorldTransform().getOrigin().z();
    std::printf("dumbbell rolled btgpu %.4f m, stock %.4f m\n", gpu, stock);
    EXPECT_GT(stock, 0.3);  // it really rolls
    EXPECT_NEAR(gpu, stock, tol::kRollDistanceRel * stock);
    EXPECT_NEAR(run.gpuY(1), run.stockY(1), tol::kRestHeight);
}

TEST(Compound, TableStandsOnAMeshGroundAsOnStock)
{
    SideBySide run(scenes::tableOnMesh);
    stepOnGpu(run, 120);
    EXPECT_TRUE(has(run.gpu->report()->stages, "midphase"));
    expectRestLikeStock(run, 1, 1);
}

TEST(Compound, TableStandsOnAHeightfieldAsOnStock)
{
    SideBySide run(scenes::tableOnHeightfield);
    stepOnGpu(run, 120);
    EXPECT_TRUE(has(run.gpu->report()->stages, "midphase"));
    expectRestLikeStock(run, 1, 1);
}

// Cylinder wheels, a capsule axle and a cone: each leaf pair a GJK pair with its own persistent
// manifold, gathering its points over steps as stock's child algorithms do.
TEST(Compound, CartOfSupportShapesRestsAsOnStock)
{
    SideBySide run(scenes::convexCart);
    stepOnGpu(run, 120);
    EXPECT_TRUE(has(run.gpu->report()->stages, "narrowphase_gjk"));
    EXPECT_NEAR(run.stockY(1), 0.3, 0.01);
    EXPECT_NEAR(run.gpuY(1), run.stockY(1), tol::kRestHeight);
    EXPECT_LT(run.distance(1), tol::kRestPlace);
}

// A static compound ground (a 3 x 3 floor of box tiles, large enough for the large-body pass)
// under a box, a sphere and a table: each lands on the tiles it overlaps, as on stock.
TEST(Compound, BodiesRestOnAStaticCompoundFloorAsOnStock)
{
    SideBySide run([](WorldKind k, const Config& c) {
        auto scene = std::make_unique<scenes::Scene>(k, c, "compound_floor");
        auto* floor = scene->ownShape(new btCompoundShape());
        btBoxShape* tile = scene->boxShape(btVector3(5, btScalar(.5), 5));
        for (int i = 0; i < 9; ++i) {
            btTransform t = btTransform::getIdentity();
            t.setOrigin(btVector3(btScalar(10 * (i % 3 - 1)), 0, btScalar(10 * (i / 3 - 1))));
            floor->addChildShape(t, tile);
        }
        scene->addBody(floor, 0, btVector3(0, btScalar(-.5), 0));
        scene->addBody(scene->boxShape(btVector3(btScalar(.5), btScalar(.5), btScalar(.5))), 1, btVector3(5, 1, 0));
        scene->addBody(scene->sphereShape(btScalar(.5)), 1, btVector3(-2, 1, 3));
        scene->addBody(scenes::tableShape(*scene), 1, btVector3(0, btScalar(.35), btScalar(-7)));
        return scene;
    });
    stepOnGpu(run, 120);
    EXPECT_NEAR(run.stockY(1), 0.5, 0.01);  // the box across two tiles' edge
    EXPECT_NEAR(run.stockY(3), scenes::kTableFootDepth, 0.01);
    for (int i = 1; i <= 3; ++i) {
        EXPECT_NEAR(run.gpuY(i), run.stockY(i), tol::kRestHeight) << "body " << i;
        EXPECT_LT(run.distance(i), tol::kRestPlace) << "body " << i;
    }
}

// A kinematic compound (a post and a 2 m arm) turned by its motion state at 2.4 rad/s sweeps a
// ball on the ground away, as on stock: the bullet mode culls a compound's leaves with stock's
// ungrown boxes (ExpandCompounds.TheBulletModeCullsWithStocksBoxes). Grown by the threshold (the
// soft step's speculative rule), the arm's leaf pair came a step before stock's and the ball,
// met early, ended 4.4 cm from stock's (now 0.6 mm).
TEST(Compound, AKinematicCompoundsArmSweepsABallAsOnStock)
{
    SideBySide run([](WorldKind k, const Config& c) {
        auto scene = std::make_unique<scenes::Scene>(k, c, "kinematic_arm");
        scene->addBody(scene->boxShape(btVector3(50, 1, 50)), 0, btVector3(0, -1, 0));
        auto* arm = scene->ownShape(new btCompoundShape());
        arm->addChildShape(btTransform::getIdentity(), scene->boxShape(btVector3(btScalar(.2), btScalar(.5), btScalar(.2))));
        arm->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(btScalar(1.2), btScalar(-.3), 0)),
                           scene->boxShape(btVector3(1, btScalar(.1), btScalar(.1))));
        btRigidBody* turning = scene->addKinematic(arm, btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(.5), 0)));
        turning->setActivationState(DISABLE_DEACTIVATION);
        scene->addBody(scene->sphereShape(btScalar(.15)), 1, btVector3(0, btScalar(.15), btScalar(-1.5)));
        return scene;
    });
    for (int k = 0; k < 70; ++k) {
        run.both([k](scenes::Scene& s) {
            const btQuaternion q(btVector3(0, 1, 0), btScalar(0.04) * btScalar(k));
            s.body(1)->getMotionState()->setWorldTransform(btTransform(q, btVector3(0, btScalar(.5), 0)));
        });
        run.step();
        ASSERT_TRUE(run.onGpu()) << k;
    }
    const btVector3 stock = run.stock->body(2)->getWorldTransform().getOrigin();
    std::printf("kinematic arm: ball at x %.4f stock, %.4f btgpu\n", stock.x(), run.gpu->body(2)->getWorldTransform().getOrigin().x());
    EXPECT_LT(stock.x(), -0.5) << "the arm swept the ball (the scene is wrong otherwise)";
    EXPECT_LT(run.distance(2), 1e-3) << "measured before: 0.044";
}

// A compound holding a table (turned a quarter about y and raised) and a box beside it: stock
// culls at both levels, btgpu's flattened leaves pass both levels' tests.
TEST(Compound, NestedCompoundStandsAsOnStock)
{
    SideBySide run([](WorldKind k, const Config& c) {
        auto scene = std::make_unique<scenes::Scene>(k, c, "nested_compound");
        scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
        auto* outer = scene->ownShape(new btCompoundShape());
        btTransform t(btQuaternion(btVector3(0, 1, 0), btScalar(SIMD_HALF_PI)), btVector3(0, btScalar(.1), 0));
        outer->addChildShape(t, scenes::tableShape(*scene));
        t = btTransform::getIdentity();
        t.setOrigin(btVector3(btScalar(1.2), btScalar(-.1), 0));
        outer->addChildShape(t, scene->boxShape(btVector3(btScalar(.3), btScalar(.1), btScalar(.3))));
        scene->addBody(outer, 2, btVector3(0, btScalar(.22), 0));
        return scene;
    });
    stepOnGpu(run, 120);
    EXPECT_NEAR(run.stockY(1), 0.2, 0.01);  // legs and box both down: 0.1 below the outer origin
    expectRestLikeStock(run, 1, 1);
}

// What the app changes in its compound between steps is what the next step collides: a leg
// lengthened and moved down (updateChildTransform), a sphere foot added under the top, then
// taken away again; stock and btgpu rest at the same heights after each.
TEST(Compound, ChildChangesBetweenStepsTakeEffect)
{
    SideBySide run([](WorldKind k, const Config& c) {
        auto scene = std::make_unique<scenes::Scene>(k, c, "compound_changes");
        scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
        auto* c2 = scene->ownShape(new btCompoundShape());
        c2->addChildShape(btTransform::getIdentity(), scene->boxShape(btVector3(btScalar(.5), btScalar(.2), btScalar(.5))));
        btRigidBody* b = scene->addBody(c2, 1, btVector3(0, btScalar(.21), 0));
        b->setActivationState(DISABLE_DEACTIVATION);
        return scene;
    });
    auto compound = [](scenes::Scene& s) { return static_cast<btCompoundShape*>(s.body(1)->getCollisionShape()); };
    stepOnGpu(run, 30);
    EXPECT_NEAR(run.stockY(1), 0.2, 0.01);
    EXPECT_NEAR(run.gpuY(1), run.stockY(1), tol::kRestHeight);
    // The box moved 0.3 m down in the body's frame: the body rises by 0.3.
    run.both([&](scenes::Scene& s) {
        btTransform t = btTransform::getIdentity();
        t.setOrigin(btVector3(0, btScalar(-.3), 0));
        compound(s)->updateChildTransform(0, t);
    });
    stepOnGpu(run, 60);
    EXPECT_NEAR(run.stockY(1), 0.5, 0.01);
    EXPECT_NEAR(run.gpuY(1), run.stockY(1), tol::kRestHeight);
    // A box foot (as wide, 0.4 m tall) added 0.4 m further down lifts it by another 0.4.
    run.both([&](scenes::Scene& s) {
        btTransform t = btTransform::getIdentity();
        t.setOrigin(btVector3(0, btScalar(-.7), 0));
        compound(s)->addChildShape(t, s.boxShape(btVector3(btScalar(.5), btScalar(.2), btScalar(.5))));
    });
    stepOnGpu(run, 90);
    EXPECT_NEAR(run.stockY(1), 0.9, 0.01);
    EXPECT_NEAR(run.gpuY(1), run.stockY(1), tol::kRestHeight);
    EXPECT_LT(run.distance(1), tol::kRestPlace);
    // And removed: the first box lands on the ground again.
    run.both([&](scenes::Scene& s) { compound(s)->removeChildShapeByIndex(1); });
    stepOnGpu(run, 90);
    EXPECT_NEAR(run.stockY(1), 0.5, 0.01);
    EXPECT_NEAR(run.gpuY(1), run.stockY(1), tol::kRestHeight);
}

// A compound with a plane child, and one with nested compounds beside another compound keep the
// CPU path, each named; the world comes back to the GPU path when the cause goes. (A compound
// without a tree beside another is served: ThreeTablesWithoutTreesStackedAsOnStock.)
TEST(Compound, UnservedCompoundsFallBackWithTheirReason)
{
    {
        auto scene = scenes::tableStack(WorldKind::Gpu, Config::bulletMode(), 1);
        auto* outer = scene->ownShape(new btCompoundShape(false));
        outer->addChildShape(btTransform::getIdentity(), scenes::tableShape(*scene));
        btRigidBody* b = scene->addBody(outer, 1, btVector3(5, 1, 0));
        scene->step();
        EXPECT_FALSE(scene->gpuWorld()->isGpuPath());
        EXPECT_NE(scene->report()->cpuPathReason.find("with nested compounds meeting another compound"),
                  std::string::npos)
            << scene->report()->cpuPathReason;
        scene->removeBody(b);
        scene->step();
        EXPECT_TRUE(scene->gpuWorld()->isGpuPath()) << scene->report()->cpuPathReason;
    }
    {
        auto scene = scenes::tableStack(WorldKind::Gpu, Config::bulletMode(), 1);
        auto* outer = scene->ownShape(new btCompoundShape());
        outer->addChildShape(btTransform::getIdentity(), scenes::tableShape(*scene));
        scene->addBody(outer, 1, btVector3(5, 1, 0));
        scene->step();
        EXPECT_FALSE(scene->gpuWorld()->isGpuPath());
        EXPECT_NE(scene->report()->cpuPathReason.find("with nested compounds meeting another compound"),
                  std::string::npos)
            << scene->report()->cpuPathReason;
    }
    {
        auto scene = scenes::tableStack(WorldKind::Gpu, Config::bulletMode(), 1);
        auto* withPlane = scene->ownShape(new btCompoundShape());
        withPlane->addChildShape(btTransform::getIdentity(), scene->ownShape(new btStaticPlaneShape(btVector3(0, 1, 0), 0)));
        scene->addBody(withPlane, 0, btVector3(5, 0, 0));
        scene->step();
        EXPECT_FALSE(scene->gpuWorld()->isGpuPath());
        EXPECT_NE(scene->report()->cpuPathReason.find("concave or plane children"), std::string::npos)
            << scene->report()->cpuPathReason;
    }
}
