// mesh_test.cpp — triangle-mesh ground (btBvhTriangleMeshShape) on stock Bullet and on btgpu in
// the same test, the GPU path asserted after every step and the midphase seen to run: a box
// and a sphere at rest, 100 bodies dropped apart, a mesh shared by two ground bodies, a scaled
// wrapper, vertices edited and the BVH refitted between steps, a kinematic mesh platform; the
// same on a btHeightfieldTerrainShape (heights changed by the app between steps); a capsule, a
// cylinder, a cone and a plain hull (GJK against each triangle) at rest on both grounds; and the cases that
// keep the CPU path, each with its reason.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h>

#include <algorithm>
#include <cmath>

#include "scenes/mesh_scenes.h"
#include "scenes/stock_chaos.h"
#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

constexpr double kConvexRollDrift = 0.06;  // m: see CapsuleCylinderConeAndPlainHull...

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

// Steps both worlds, the btgpu one on the GPU path every step, with the mesh stages in its plan
// and their programs built.
void stepOnGpu(SideBySide& run, int steps)
{
    int contacts = 0;  // the most in any step (bodies at rest fall asleep and have none)
    for (int i = 0; i < steps; ++i) {
        run.step();
        ASSERT_TRUE(run.onGpu()) << "step " << i << ": " << run.gpu->report()->cpuPathReason;
        contacts = std::max(contacts, run.gpu->report()->contacts);
    }
    const Report& r = *run.gpu->report();
    EXPECT_TRUE(has(r.stages, "midphase"));
    EXPECT_TRUE(has(r.stages, "narrowphase_mesh"));
    EXPECT_TRUE(has(r.builtPrograms, "midphase"));
    EXPECT_TRUE(has(r.builtPrograms, "narrowphase_mesh"));
    EXPECT_GT(contacts, 0);
}

// Where the btgpu world's bodies started, for their horizontal drift.
struct Starts {
    std::vector<btVector3> gpu, stock;
    explicit Starts(const SideBySide& run)
    {
        for (btRigidBody* b : run.gpu->bodies()) gpu.push_back(b->getWorldTransform().getOrigin());
        for (btRigidBody* b : run.stock->bodies()) stock.push_back(b->getWorldTransform().getOrigin());
    }
};
double drift(const scenes::Scene& s, const std::vector<btVector3>& starts, int i)
{
    btVector3 d = s.body(i)->getWorldTransform().getOrigin() - starts[size_t(i)];
    d.setY(0);
    return d.length();
}

// Each body's rest height within 1 mm of stock's; sideways it stays within `driftBound` of where
// it started. Both engines collide a convex with a mesh as stock's btConvexConcaveCollisionAlgorithm
// (one point a triangle into a persistent manifold), so a body landing on a mesh rocks a little
// on both; where many bodies land, their drift is judged against stock's own chaos instead
// (expectDriftWithinStocksChaos).
void expectRestHeights(const SideBySide& run, const Starts& starts, int first, int last,
                       double driftBound = tol::kMeshDrift, double heightBound = tol::kRestHeight)
{
    for (int i = first; i <= last; ++i) {
        EXPECT_NEAR(run.gpuY(i), run.stockY(i), heightBound) << "body " << i;
        EXPECT_LE(drift(*run.gpu, starts.gpu, i), driftBound) << "body " << i;
    }
}

// The mean and largest sideways drift of bodies [first, last] after `steps`, within stock's own
// chaos (its nudged runs of the same scene); starts are the unnudged scene's (0.1 mm apart).
void expectDriftWithinStocksChaos(const std::function<ScenePtr(WorldKind)>& make, int steps, const SideBySide& run,
                                  const Starts& starts, int first, int last)
{
    auto measure = [&starts, first, last](const scenes::Scene& s) {
        double sum = 0.0, most = 0.0;
        for (int i = first; i <= last; ++i) {
            const double d = drift(s, starts.stock, i);
            sum += d;
            most = std::max(most, d);
        }
        return std::vector<double>{sum / double(last - first + 1), most};
    };
    const auto bands = scenes::stockChaos(make, steps, measure, {"mean drift", "largest drift"},
                                          {tol::kChaosPositionFloor, tol::kChaosPositionFloor});
    std::vector<double> got;
    {
        double sum = 0.0, most = 0.0;
        for (int i = first; i <= last; ++i) {
            const double d = drift(*run.gpu, starts.gpu, i);
            sum += d;
            most = std::max(most, d);
        }
        got = {sum / double(last - first + 1), most};
    }
    for (size_t k = 0; k < bands.size(); ++k) {
        std::printf("%s %s: btgpu %.4f, stock %.4f +- %.4f\n", run.gpu->name().c_str(), bands[k].name.c_str(), got[k],
                    bands[k].stockMean, bands[k].bound());
        EXPECT_TRUE(bands[k].admits(got[k])) << bands[k].name << ": btgpu " << got[k] << ", stock " << bands[k].stockMean
                                             << " +- " << bands[k].bound();
    }
}

}  // namespace

TEST(Mesh, BoxAndSphereRestOnAMeshGroundAsOnStock)
{
    SideBySide run(scenes::restOnMesh);
    Starts starts(run);
    stepOnGpu(run, 120);
    expectRestHeights(run, starts, 1, 2);
    EXPECT_NEAR(run.gpuY(1), 0.5, 0.01);  // on the mesh, not through it
    EXPECT_NEAR(run.gpuY(2), 0.5, 0.01);
}

TEST(Mesh, CapsuleCylinderConeAndPlainHullRestOnAMeshAndAHeightfieldAsOnStock)
{
    // Support-function convex shapes (a capsule, a cylinder, a cone, a hull without polyhedral
    // features) against triangles: GJK per triangle, as stock's btConvexConcaveCollisionAlgorithm.
    for (auto make : {scenes::convexRestOnMesh, scenes::convexRestOnHeightfield}) {
        SideBySide run(make);
        SCOPED_TRACE(run.gpu->name());
        Starts starts(run);
        stepOnGpu(run, 150);
        // Rest heights within 1 mm of stock's. Sideways: a cylinder on its side rolls a little
        // on both (one GJK point a triangle; measured: btgpu 4.3 cm on the mesh, 0.2 cm on the
        // heightfield; stock 0.2 and 2.3 cm), so the drift bound is kConvexRollDrift.
        for (int i = 1; i <= 4; ++i) {
            EXPECT_NEAR(run.gpuY(i), run.stockY(i), tol::kRestHeight) << "body " << i;
            EXPECT_LE(drift(*run.gpu, starts.gpu, i), kConvexRollDrift) << "body " << i;
        }
        EXPECT_NEAR(run.gpuY(1), 0.3, 0.01);  // on the ground, not through it
        EXPECT_NEAR(run.gpuY(2), 0.3, 0.01);
    }
}

TEST(Mesh, HundredBodiesDroppedApartRestAsOnStock)
{
    SideBySide run(scenes::dropOnMesh);
    Starts starts(run);
    stepOnGpu(run, 150);
    // A body resting on one point a triangle may sink a few mm where stock's rests at contact
    // (both: up to 2 cm on a fine mesh, SubPairOverflowGrowsAndRedoesTheStep).
    expectRestHeights(run, starts, 1, 100, 1.0, tol::kMeshRestHeight);
    expectDriftWithinStocksChaos([](WorldKind k) { return scenes::dropOnMesh(k); }, 150, run, starts, 1, 100);
}

TEST(Mesh, OneMeshOnTwoBodies)
{
    SideBySide run(scenes::sharedMesh);
    Starts starts(run);
    stepOnGpu(run, 120);
    expectRestHeights(run, starts, 2, 5);
}

TEST(Mesh, ScaledWrapperOfAMesh)
{
    // btScaledBvhTriangleMeshShape, twice as wide and lifted by 0.5 in y scaling a mesh whose
    // surface is at y = 1: the box rests at 1.0 * 0.5 + 0.5.
    auto make = [](WorldKind kind, const Config& config) {
        auto scene = std::make_unique<scenes::Scene>(kind, config, "scaled_mesh");
        btBvhTriangleMeshShape* mesh = scenes::gridMesh(*scene, 8, 1.0f, true, true);
        auto* scaled = scene->ownShape(new btScaledBvhTriangleMeshShape(mesh, btVector3(2, btScalar(.5), 2)));
        scene->addBody(scaled, 0, btVector3(0, 0, 0));
        scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(3, btScalar(.6), 1));
        scene->addBody(scene->sphereShape(.5), 1, btVector3(-5, btScalar(.6), -2));
        return scene;
    };
    SideBySide run(make);
    Starts starts(run);
    stepOnGpu(run, 120);
    expectRestHeights(run, starts, 1, 2);
}

TEST(Mesh, EditedVerticesAndRefittedTreeArePickedUp)
{
    // The app lowers the whole mesh by 0.3 m and refits its BVH after 1 s: the bodies on it fall
    // onto it on both worlds (the GPU path reads the mesh again: its fingerprint changed).
    auto make = [](WorldKind kind, const Config& config) {
        ScenePtr scene = scenes::restOnMesh(kind, config);
        scene->beforeStep = [done = false](scenes::Scene& s, double end) mutable {
            if (done || end < 1.0 + 1e-9) return;
            done = true;
            auto* mesh = static_cast<btBvhTriangleMeshShape*>(s.body(0)->getCollisionShape());
            btStridingMeshInterface* iface = mesh->getMeshInterface();
            for (int p = 0; p < iface->getNumSubParts(); ++p) {
                unsigned char *vb, *ib;
                int nv, stride, istride, nf;
                PHY_ScalarType vt, it;
                iface->getLockedVertexIndexBase(&vb, nv, vt, stride, &ib, istride, nf, it, p);
                for (int i = 0; i < nv; ++i) reinterpret_cast<float*>(vb + i * stride)[1] -= 0.3f;
                iface->unLockVertexBase(p);
            }
            btVector3 lo, hi;
            iface->calculateAabbBruteForce(lo, hi);
            mesh->refitTree(lo, hi);
            for (int i = 1; i <= 2; ++i) s.body(i)->activate(true);
        };
        return scene;
    };
    SideBySide run(make);
    Starts starts(run);
    stepOnGpu(run, 150);
    // The box lands on the lowered mesh from 0.3 m on one point a triangle and rocks sideways:
    // its drift judged against stock's own chaos.
    expectRestHeights(run, starts, 1, 2, 1.0);
    expectDriftWithinStocksChaos([&make](WorldKind k) { return make(k, Config::bulletMode()); }, 150, run, starts, 1, 2);
    EXPECT_NEAR(run.gpuY(1), 0.2, 0.01);
}

TEST(Mesh, KinematicMeshPlatformLiftsABox)
{
    // A kinematic mesh platform rising at 0.5 m/s for 1 s carries a box up, as on stock.
    auto make = [](WorldKind kind, const Config& config) {
        auto scene = std::make_unique<scenes::Scene>(kind, config, "mesh_platform");
        btBvhTriangleMeshShape* mesh = scenes::gridMesh(*scene, 6, 1.0f, true, false);
        btRigidBody* platform = scene->addKinematic(mesh, btTransform::getIdentity());
        scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(btScalar(.3), btScalar(.55), btScalar(-.2)));
        scene->beforeStep = [platform](scenes::Scene&, double end) {
            btTransform t = btTransform::getIdentity();
            t.setOrigin(btVector3(0, btScalar(0.5 * std::min(std::max(end - 0.5, 0.0), 1.0)), 0));
            platform->getMotionState()->setWorldTransform(t);
        };
        return scene;
    };
    SideBySide run(make);
    stepOnGpu(run, 150);
    EXPECT_NEAR(run.gpuY(1), run.stockY(1), tol::kRestHeight);
    EXPECT_NEAR(run.gpuY(1), 1.0, 0.01);
}

TEST(Heightfield, BoxAndSphereRestAsOnStock)
{
    SideBySide run(scenes::restOnHeightfield);
    Starts starts(run);
    stepOnGpu(run, 120);
    expectRestHeights(run, starts, 1, 2);
    EXPECT_NEAR(run.gpuY(1), 0.5, 0.01);
    EXPECT_NEAR(run.gpuY(2), 0.5, 0.01);
}

TEST(Heightfield, HundredBodiesDroppedApartRestAsOnStock)
{
    SideBySide run(scenes::dropOnHeightfield);
    Starts starts(run);
    stepOnGpu(run, 150);
    expectRestHeights(run, starts, 1, 100, 1.0, tol::kMeshRestHeight);
    expectDriftWithinStocksChaos([](WorldKind k) { return scenes::dropOnHeightfield(k); }, 150, run, starts, 1, 100);
}

TEST(Heightfield, HeightsChangedByTheAppArePickedUp)
{
    // The app lowers its height array by 0.25 m between steps (the shape points into it).
    std::vector<std::vector<float>*> arrays;
    auto make = [&arrays](WorldKind kind, const Config& config) {
        auto scene = std::make_unique<scenes::Scene>(kind, config, "heightfield_edit");
        std::vector<float>* heights = nullptr;
        scene->addBody(scenes::flatHeightfield(*scene, 17, &heights), 0, btVector3(0, 0, 0));
        arrays.push_back(heights);
        scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(1, btScalar(.55), 0));
        scene->addBody(scene->sphereShape(.5), 1, btVector3(-3, btScalar(.55), 2));
        return scene;
    };
    SideBySide run(make);
    Starts starts(run);
    stepOnGpu(run, 60);
    for (std::vector<float>* h : arrays)
        for (float& v : *h) v -= 0.25f;
    // As a Bullet app must after changing the heights under resting bodies: stock's manifolds
    // would keep the old surface's points (the GPU path builds its manifolds afresh anyway).
    run.both([](scenes::Scene& s) {
        s.world().getBroadphase()->getOverlappingPairCache()->cleanProxyFromPairs(s.body(0)->getBroadphaseHandle(),
                                                                                  s.world().getDispatcher());
        for (int i = 1; i <= 2; ++i) s.body(i)->activate(true);
    });
    stepOnGpu(run, 90);
    expectRestHeights(run, starts, 1, 2);
    EXPECT_NEAR(run.gpuY(1), 0.25, 0.01);
}

TEST(Mesh, UnservedMeshCasesKeepTheCpuPathWithTheirReason)
{
    struct Case {
        const char* what;
        std::function<void(scenes::Scene&)> build;
        const char* reason;
    };
    const std::vector<Case> cases = {
        {"dynamic mesh",
         [](scenes::Scene& s) {
             btBvhTriangleMeshShape* mesh = scenes::gridMesh(s, 2, 1.0f, true, false);
             s.addBody(mesh, 1, btVector3(0, 2, 0));
         },
         "dynamic triangle mesh or heightfield body"},
        {"mesh without quantized BVH",
         [](scenes::Scene& s) {
             scenes::MeshData* d = nullptr;
             scenes::gridMesh(s, 2, 1.0f, true, false, &d);
             s.addBody(s.ownShape(new btBvhTriangleMeshShape(d->array, false)), 0, btVector3(0, 0, 0));
         },
         "without quantized AABB compression"},
        {"heightfield subclass",
         [](scenes::Scene& s) {
             struct Own : btHeightfieldTerrainShape {
                 using btHeightfieldTerrainShape::btHeightfieldTerrainShape;
             };
             auto* heights = s.ownData(new std::vector<float>(16 * 16, 0.0f));
             s.addBody(s.ownShape(new Own(16, 16, heights->data(), 1, -1, 1, 1, PHY_FLOAT, false)), 0, btVector3(0, 0, 0));
         },
         "unsupported shape"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        scenes::Scene scene(WorldKind::Gpu);
        c.build(scene);
        scene.addBody(scene.sphereShape(.5), 1, btVector3(0, 3, 0));
        scene.step();
        const Report& r = *scene.report();
        EXPECT_FALSE(r.gpuPath);
        EXPECT_NE(r.cpuPathReason.find(c.reason), std::string::npos) << r.cpuPathReason;
    }
}

TEST(Mesh, SameLandscapeTwiceGivesSameHashes)
{
    // Bitwise the same, step by step (the midphase's count/scan/write order, the gather's).
    auto make = [] { return scenes::landscape(WorldKind::Gpu, Config::bulletMode(), 120); };
    ScenePtr a = make(), b = make();
    for (int i = 0; i < 90; ++i) {
        a->step();
        b->step();
        ASSERT_TRUE(a->report()->gpuPath);
        ASSERT_EQ(a->gpuWorld()->stateHash(), b->gpuWorld()->stateHash()) << "step " << i;
    }
    EXPECT_GT(a->report()->contacts, 0);
}

TEST(Mesh, SubPairOverflowGrowsAndRedoesTheStep)
{
    // A fine mesh (10 cm cells) under 25 boxes: each meets ~300 triangles, far past the
    // midphase's first buffer; the step is redone with a bigger one (reported), nothing dropped:
    // every box rests on the mesh as stock's, both engines' sinking up to about 2 cm into it here
    // (one GJK point per triangle a frame, replacing each other in a manifold of 4).
    std::vector<Issue> issues;
    Config config = Config::bulletMode();
    config.onIssue = [&issues](const Issue& i) { issues.push_back(i); };
    auto make = [](WorldKind kind, const Config& c) {
        auto scene = std::make_unique<scenes::Scene>(kind, c, "fine_mesh");
        scene->addBody(scenes::gridMesh(*scene, 120, 0.1f, true, false), 0, btVector3(0, 0, 0));
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j)
                scene->addBody(scene->boxShape(btVector3(btScalar(.6), btScalar(.3), btScalar(.6))), 1,
                               btVector3(btScalar(-4 + 2 * i), btScalar(.35), btScalar(-4 + 2 * j)));
        return scene;
    };
    SideBySide run(make, config);
    stepOnGpu(run, 90);
    double lowestGpu = 1.0, lowestStock = 1.0;
    for (int i = 1; i <= 25; ++i) {
        lowestGpu = std::min(lowestGpu, run.gpuY(i));
        lowestStock = std::min(lowestStock, run.stockY(i));
    }
    std::printf("fine mesh: the lowest box at %.4f m on btgpu, %.4f m on stock (half height 0.3)\n", lowestGpu, lowestStock);
    for (int i = 1; i <= 25; ++i) {
        EXPECT_NEAR(run.gpuY(i), run.stockY(i), 0.03) << "body " << i;
        EXPECT_GT(run.gpuY(i), 0.2) << "body " << i;  // on the mesh, not through it
    }
    bool grew = false;
    for (const Issue& i : issues) grew = grew || (i.kind == Issue::Kind::Overflow && i.message.find("sub-pair") != std::string::npos);
    EXPECT_TRUE(grew);
    EXPECT_GT(run.gpu->report()->redoneSteps, 0);
}

TEST(Mesh, BoxSlidesDownAnInclinedMeshAsOnStock)
{
    // A unit box released on a flat mesh tilted 20 degrees (combined friction 0.25 < tan 20):
    // s = g (sin - mu cos) t^2 / 2 = 1.205 m in 1.5 s. On a tilted box ground both engines slide
    // it that far (within 2%). On the mesh both collide as stock's btConvexConcaveCollisionAlgorithm
    // (one GJK point a triangle a frame, kept in a persistent manifold): the box rocks from corner
    // to corner and falls short on both; btgpu's slide within stock's own chaos (its nudged runs).
    const float theta = 0.349066f;
    auto make = [theta](bool mesh) {
        return [theta, mesh](WorldKind kind, const Config& c) {
            auto scene = std::make_unique<scenes::Scene>(kind, c, "incline");
            const btTransform tilt(btQuaternion(btVector3(0, 0, 1), theta), btVector3(0, 0, 0));
            if (mesh) {
                scene->addBody(scenes::gridMesh(*scene, 16, 1.0f, true, false), 0, tilt);
            } else {
                btTransform below = tilt;
                below.setOrigin(tilt.getBasis() * btVector3(0, -1, 0));
                scene->addBody(scene->boxShape(btVector3(8, 1, 8)), 0, below);
            }
            scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1,
                           btTransform(tilt.getRotation(), tilt.getBasis() * btVector3(btScalar(2.3), btScalar(.5), btScalar(.2))));
            return scene;
        };
    };
    const double analytic = 0.5 * 10.0 * (std::sin(double(theta)) - 0.25 * std::cos(double(theta))) * 1.5 * 1.5;
    const int steps = 90;
    double slid[2][2];  // [mesh][gpu]
    btVector3 start;
    for (int mesh = 0; mesh < 2; ++mesh) {
        SideBySide run(make(mesh != 0));
        const btVector3 s0 = run.stock->body(1)->getWorldTransform().getOrigin();
        const btVector3 g0 = run.gpu->body(1)->getWorldTransform().getOrigin();
        start = s0;
        for (int i = 0; i < steps; ++i) {
            run.step();
            ASSERT_TRUE(run.onGpu()) << run.gpu->report()->cpuPathReason;
        }
        slid[mesh][0] = (run.stock->body(1)->getWorldTransform().getOrigin() - s0).length();
        slid[mesh][1] = (run.gpu->body(1)->getWorldTransform().getOrigin() - g0).length();
    }
    const auto bands = scenes::stockChaos([&make](WorldKind k) { return make(true)(k, Config::bulletMode()); }, steps,
                                          [start](const scenes::Scene& s) {
                                              return std::vector<double>{
                                                  (s.body(1)->getWorldTransform().getOrigin() - start).length()};
                                          },
                                          {"slid"}, {tol::kChaosPositionFloor});
    std::printf("incline: analytic %.4f m; box ground stock %.4f btgpu %.4f; mesh ground stock %.4f btgpu %.4f "
                "(stock's chaos %.4f +- %.4f)\n",
                analytic, slid[0][0], slid[0][1], slid[1][0], slid[1][1], bands[0].stockMean, bands[0].bound());
    EXPECT_NEAR(slid[0][1], analytic, 0.02 * analytic);
    EXPECT_TRUE(bands[0].admits(slid[1][1])) << "btgpu " << slid[1][1] << ", stock " << bands[0].stockMean << " +- "
                                             << bands[0].bound();
}

// Bullet's bench 5 (a convex mix on the rolling mesh landscape), 200 bodies for 4 s, against
// stock's own chaos on mean height, spread and kinetic energy.
TEST(Mesh, LandscapeWithinStocksChaos)
{
    const int steps = 240;
    auto measure = [](const scenes::Scene& s) {
        const scenes::Aggregates a = scenes::aggregates(s);
        return std::vector<double>{a.meanHeight, a.spread, a.kineticEnergy};
    };
    const auto bands = scenes::stockChaos([](WorldKind kind) { return scenes::landscape(kind, Config::bulletMode(), 200); }, steps,
                                          measure, {"mean height", "spread", "kinetic energy"},
                                          {tol::kChaosHeightFloor, tol::kChaosSpreadFloor, tol::kChaosEnergyFloor});
    ScenePtr gpu = scenes::landscape(WorldKind::Gpu, Config::bulletMode(), 200);
    for (int i = 0; i < steps; ++i) {
        gpu->step();
        ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << "step " << i;
    }
    const std::vector<double> got = measure(*gpu);
    for (size_t k = 0; k < bands.size(); ++k) {
        std::printf("landscape %s: btgpu %.3f, stock %.3f +- %.3f\n", bands[k].name.c_str(), got[k], bands[k].stockMean,
                    bands[k].bound());
        EXPECT_TRUE(bands[k].admits(got[k])) << bands[k].name << ": btgpu " << got[k] << ", stock "
                                             << bands[k].stockMean << " +- " << bands[k].bound();
    }
}
