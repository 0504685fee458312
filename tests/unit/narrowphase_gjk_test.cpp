// narrowphase_gjk_test.cpp — the GJK narrowphase stage on the device against its CPU reference
// (same shared code) over two substeps (the second continuing each pair's persistent manifold
// through the warm-start cache), and the point each step adds against Bullet's own algorithm
// (btCollisionWorld::contactPairTest: GJK/EPA, the capsule closed form, convex–plane) for the
// same poses: normal within 1 degree, depth within 1 mm, the same point.
#include "reference/narrowphase_gjk.h"
#include "shape_tables.h"
#include "shared/aabb.h"
#include "shared/gjk.h"
#include "shared/persistent_manifold.h"
#include "stages/find_pairs.h"
#include "stages/narrowphase.h"
#include "gjk_fixture.h"
#include "test_device.h"
#include "tolerances.h"

#include "../../compat/shape_tables.h"

#include <btBulletCollisionCommon.h>
#include <BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btMultiSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleMesh.h>
#include <BulletCollision/CollisionShapes/btUniformScalingShape.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <gtest/gtest.h>

using namespace btgpu;

using namespace btgpu::test::gjk;

namespace {

constexpr float kDegree = 0.99984770f;  // cos 1 degree
constexpr float kMillimetre = 1e-3f;

// Bullet's algorithm for the pair in this pose: the point it adds (the nearest, if several).
struct StockPoint {
    bool found = false;
    btVector3 normal, pointB;
    btScalar distance = 0;
};
StockPoint stockPoint(const Body& a, const Body& b)
{
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btCollisionWorld world(&dispatcher, &broadphase, &config);
    btCollisionObject oa, ob;
    oa.setCollisionShape(a.shape);
    oa.setWorldTransform(a.pose);
    ob.setCollisionShape(b.shape);
    ob.setWorldTransform(b.pose);
    struct Callback : btCollisionWorld::ContactResultCallback {
        StockPoint p;
        const btCollisionObject* a;
        btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int,
                                 const btCollisionObjectWrapper*, int, int) override
        {
            if (p.found && cp.getDistance() >= p.distance) return 0;
            const bool swapped = w0->getCollisionObject() != a;
            p.found = true;
            p.distance = cp.getDistance();
            p.normal = swapped ? -cp.m_normalWorldOnB : cp.m_normalWorldOnB;
            p.pointB = swapped ? cp.getPositionWorldOnA() : cp.getPositionWorldOnB();
            return 0;
        }
    } cb;
    cb.a = &oa;
    world.contactPairTest(&oa, &ob, cb);
    return cb.p;
}

// The cache a substep leaves: pairs in (a, b) order, those with points.
void cacheOf(const Fixture& f, const std::vector<BtgManifold>& m, const std::vector<BtgPersistentManifold>& states,
             std::vector<BtgCachedContact>* cache, std::vector<BtgPersistentManifold>* gjk)
{
    cache->clear();
    gjk->clear();
    for (size_t i = 0; i < f.pairs.size(); ++i) {
        if (m[i].numPoints == 0) continue;
        BtgCachedContact c{};
        c.bodyA = m[i].bodyA;
        c.bodyB = m[i].bodyB;
        c.partIdA = c.indexA = c.partIdB = c.indexB = BTG_NO_SUB_SHAPE;
        c.numPoints = m[i].numPoints;
        cache->push_back(c);
        gjk->push_back(states[i]);
    }
}

// Every pair of the fixture, one per case; all within reach of each other by construction.
void addCases(Fixture& f)
{
    btBoxShape* ground = f.own(new btBoxShape(btVector3(2, .5, 2)));
    auto at = [](double x) { return btScalar(x); };
    // 0: capsule tilted 30 degrees, 1 cm into a box's top face
    {
        auto* c = f.own(new btCapsuleShape(.3, 1.0));
        const double tilt = 0.5236, low = 0.5 * std::cos(tilt) + 0.3;
        f.pair(f.body(c, btVector3(0, at(0.5 + low - 0.01), 0), btVector3(0, 0, 1), at(tilt)), f.body(ground, btVector3(0, 0, 0)));
    }
    // 1: two capsules crossing, 1 cm deep (the closed form)
    {
        auto* c = f.own(new btCapsuleShapeX(.25, .8));
        auto* d = f.own(new btCapsuleShapeZ(.2, 1.0));
        f.pair(f.body(c, btVector3(10, at(0.45 - 0.01), 0.1)), f.body(d, btVector3(10, 0, 0)));
    }
    // 2: sphere against a capsule's cap (the closed form, sphere first)
    {
        btSphereShape* s = f.own(new btSphereShape(.3));
        auto* c = f.own(new btCapsuleShape(.2, .6));
        f.pair(f.body(s, btVector3(20.1, at(0.3 + 0.5 - 0.005), 0)), f.body(c, btVector3(20, 0, 0)));
    }
    // 3: cylinder tilted 20 degrees, its rim 5 mm into a box
    {
        auto* c = f.own(new btCylinderShape(btVector3(.4, .5, .4)));
        const double tilt = 0.349, low = 0.5 * std::cos(tilt) + 0.4 * std::sin(tilt);
        f.pair(f.body(c, btVector3(30, at(0.5 + low - 0.005), 0), btVector3(0, 0, 1), at(tilt)), f.body(ground, btVector3(30, 0, 0)));
    }
    // 4: cone (x axis) tilted 10 degrees on a box, apex sideways
    {
        auto* c = f.own(new btConeShapeX(.4, 1.0));
        f.pair(f.body(c, btVector3(40, at(0.5 + 0.4 - 0.01), 0), btVector3(1, 0, 0), at(0.1745)), f.body(ground, btVector3(40, 0, 0)));
    }
    // 5: a static plane (A) and a tilted cylinder (z axis) touching it
    {
        auto* plane = f.own(new btStaticPlaneShape(btVector3(0, 1, 0), 0));
        auto* c = f.own(new btCylinderShapeZ(btVector3(.3, .3, .6)));
        f.pair(f.body(plane, btVector3(50, 0, 0)), f.body(c, btVector3(50, at(0.3 + 0.6 * std::sin(0.2) - 0.01), 0), btVector3(1, 0, 0), at(0.2)));
    }
    // 6: a multi-sphere tilted on a box
    {
        const btVector3 p[2] = {{-.3, 0, 0}, {.3, 0, 0}};
        const btScalar r[2] = {.25, .15};
        auto* m = f.own(new btMultiSphereShape(p, r, 2));
        f.pair(f.body(m, btVector3(60, at(0.5 + 0.25 - 0.008), 0), btVector3(0, 0, 1), at(0.1)), f.body(ground, btVector3(60, 0, 0)));
    }
    // 7: a convex triangle mesh (tetrahedron) with a vertex 5 mm into a box
    {
        auto* mesh = new btTriangleMesh();
        f.meshes.emplace_back(mesh);
        const btVector3 v[4] = {{0, -.5, 0}, {.4, .3, 0}, {-.3, .3, .3}, {-.2, .3, -.4}};
        mesh->addTriangle(v[0], v[1], v[2]);
        mesh->addTriangle(v[0], v[2], v[3]);
        mesh->addTriangle(v[0], v[3], v[1]);
        mesh->addTriangle(v[1], v[3], v[2]);
        auto* c = f.own(new btConvexTriangleMeshShape(mesh));
        f.pair(f.body(c, btVector3(70, at(0.5 + 0.5 + 0.04 - 0.005), 0)), f.body(ground, btVector3(70, 0, 0)));
    }
    // 8: a cylinder 10 cm into a box: the cores overlap, EPA
    {
        auto* c = f.own(new btCylinderShape(btVector3(.4, .5, .4)));
        const double tilt = 0.2, low = 0.5 * std::cos(tilt) + 0.4 * std::sin(tilt);
        f.pair(f.body(c, btVector3(80, at(0.5 + low - 0.1), 0), btVector3(0, 0, 1), at(tilt)), f.body(ground, btVector3(80, 0, 0)));
    }
    // 9: a cone against a sphere (GJK between two curved cores)
    {
        auto* c = f.own(new btConeShape(.4, .8));
        btSphereShape* s = f.own(new btSphereShape(.3));
        f.pair(f.body(c, btVector3(90, 0, 0)), f.body(s, btVector3(90.02, at(0.4 + 0.04 + 0.3 - 0.005), 0)));
    }
    // 10: a uniformly scaled box against a capsule
    {
        auto* box = f.own(new btBoxShape(btVector3(.3, .3, .3)));
        auto* u = f.own(new btUniformScalingShape(box, 1.5));
        auto* c = f.own(new btCapsuleShapeZ(.2, .8));
        f.pair(f.body(u, btVector3(100, 0, 0), btVector3(0, 1, 0), at(0.3)), f.body(c, btVector3(100.1, at(0.45 + 0.2 - 0.01), 0)));
    }
    // 11: two spheres 1 cm into each other (btSphereSphereCollisionAlgorithm's closed form)
    {
        btSphereShape* s = f.own(new btSphereShape(.3));
        btSphereShape* t = f.own(new btSphereShape(.2));
        f.pair(f.body(s, btVector3(110, at(0.5 - 0.01), 0.05)), f.body(t, btVector3(110, 0, 0)));
    }
}

}  // namespace

TEST(NarrowphaseGjk, MatchesReferenceOverTwoSubsteps)
{
    Fixture f;
    addCases(f);
    f.build();
    std::vector<BtgPersistentManifold> states;
    std::vector<BtgManifold> dev = runDevice(test::context(), f, {}, {}, &states);
    ref::GjkStep ref = ref::referenceGjkStep(f.pairs, f.pos.data(), f.rot.data(), f.props.data(), f.view.view(), {});
    for (size_t i = 0; i < f.pairs.size(); ++i) {
        EXPECT_EQ(dev[i].numPoints, 1) << "pair " << i << ": every case touches";
        expectSame(dev[i], ref.manifolds[i], i);
    }
    // Second substep: every body 2 mm lower and turned a little; each pair continues its manifold.
    std::vector<BtgCachedContact> cache;
    std::vector<BtgPersistentManifold> gjk;
    cacheOf(f, dev, states, &cache, &gjk);
    std::vector<BtgPersistentManifold> previous(f.pairs.size());
    for (size_t i = 0, j = 0; i < f.pairs.size(); ++i) previous[i] = dev[i].numPoints ? gjk[j++] : btgEmptyPersistent(f.pairs[i].a, f.pairs[i].b, 0);
    for (size_t b = 0; b < f.bodies.size(); b += 2) {
        f.bodies[b].pose.getOrigin() -= btVector3(0, btScalar(0.002), 0);
        f.bodies[b].pose.setRotation(f.bodies[b].pose.getRotation() * btQuaternion(btVector3(0, 1, 0), btScalar(0.02)));
    }
    f.build();
    std::vector<BtgPersistentManifold> states2;
    std::vector<BtgManifold> dev2 = runDevice(test::context(), f, cache, gjk, &states2);
    ref::GjkStep ref2 = ref::referenceGjkStep(f.pairs, f.pos.data(), f.rot.data(), f.props.data(), f.view.view(), previous);
    int continued = 0;
    for (size_t i = 0; i < f.pairs.size(); ++i) {
        expectSame(dev2[i], ref2.manifolds[i], i);
        for (int k = 0; k < dev2[i].numPoints; ++k) continued += dev2[i].points[k].featureId == dev[i].points[0].featureId;
        // The point this substep added (the app's added callback is called for it alone) is one
        // of the manifold's, named by its identity.
        ASSERT_LT(i, states2.size());
        if (dev2[i].numPoints == 0) continue;
        int named = 0;
        for (int k = 0; k < dev2[i].numPoints; ++k)
            named += states2[i].added >= 0 && dev2[i].points[k].featureId == (BTG_FEATURE_SINGLE | uint(states2[i].added));
        EXPECT_EQ(named, 1) << "pair " << i << " added " << states2[i].added;
    }
    EXPECT_GT(continued, 0) << "no point kept its identity across the substeps";
}

// Two balls as btSphereSphereCollisionAlgorithm steps them: no point while they are apart, however
// near (pair 1: 1 cm apart); a point once they touch (pair 0: 1 cm in), and none kept when they
// part again within the breaking threshold (the next substep pair 0's ball is 2 cm out, 1 cm
// apart): Bullet 3.24 clears that manifold every step (CLEAR_MANIFOLD). Before, one fresh point a
// step with speculative points: two balls closing fast met a point a step before the impact,
// whose restitution went into the approach. The soft step collides them afresh, speculatively:
// a point for both pairs, kept by nothing.
TEST(NarrowphaseGjk, SpheresMakeAPointOnlyWhileTheyTouch)
{
    Fixture f;
    btSphereShape* ball = f.own(new btSphereShape(.5));
    const int a0 = f.body(ball, btVector3(0, 1, 0)), b0 = f.body(ball, btVector3(btScalar(0.99), 1, 0));
    const int a1 = f.body(ball, btVector3(0, 1, 5)), b1 = f.body(ball, btVector3(btScalar(1.01), 1, 5));
    f.pair(a0, b0);
    f.pair(a1, b1);
    f.build();
    cl::Context& ctx = test::context();
    std::vector<BtgPersistentManifold> states, softStates;
    const std::vector<BtgManifold> dev = runDevice(ctx, f, {}, {}, &states);
    const ref::GjkStep ref = ref::referenceGjkStep(f.pairs, f.pos.data(), f.rot.data(), f.props.data(), f.view.view(), {});
    ASSERT_EQ(dev[0].numPoints, 1);
    EXPECT_NEAR(dev[0].points[0].distance, -0.01f, tol::kContactDepth);
    EXPECT_EQ(dev[1].numPoints, 0);
    for (size_t i = 0; i < 2; ++i) expectSame(dev[i], ref.manifolds[i], i);
    const std::vector<BtgManifold> soft = runDevice(ctx, f, {}, {}, &softStates, true);
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(soft[i].numPoints, 1) << "pair " << i;
        EXPECT_EQ(softStates[i].numPoints, 0) << "pair " << i;
    }
    EXPECT_NEAR(soft[1].points[0].distance, 0.01f, tol::kContactDepth);

    std::vector<BtgCachedContact> cache;
    std::vector<BtgPersistentManifold> gjk;
    cacheOf(f, dev, states, &cache, &gjk);
    f.bodies[size_t(a0)].pose.getOrigin() -= btVector3(btScalar(0.02), 0, 0);
    f.build();
    std::vector<BtgPersistentManifold> states2;
    const std::vector<BtgManifold> dev2 = runDevice(ctx, f, cache, gjk, &states2);
    const ref::GjkStep ref2 = ref::referenceGjkStep(f.pairs, f.pos.data(), f.rot.data(), f.props.data(), f.view.view(),
                                                    {states[0], btgEmptyPersistent(f.pairs[1].a, f.pairs[1].b, BTG_PAIR_SPHERE_SPHERE)});
    EXPECT_EQ(dev2[0].numPoints, 0);  // apart now: stock's cleared manifold holds nothing
    EXPECT_EQ(dev2[1].numPoints, 0);
    for (size_t i = 0; i < 2; ++i) expectSame(dev2[i], ref2.manifolds[i], i);
}

// A box and a hull without polyhedral features (a row of points) resting 1 cm into a static
// plane, tilted a little: the bullet mode's first step
// is stock's convex–plane algorithm's one support point; the soft step collides them afresh with
// every vertex within reach, reduced to four (btgCollideSoftAfresh), so a box dropped flat meets
// the plane with its face (BoxApproach.ABoxDroppedFlatOnAPlaneLandsFlat), and keeps nothing.
TEST(NarrowphaseGjk, TheSoftStepMeetsAPlaneWithTheWholeFace)
{
    Fixture f;
    auto* plane = f.own(new btStaticPlaneShape(btVector3(0, 1, 0), 0));
    auto* box = f.own(new btBoxShape(btVector3(.5, .25, .5)));
    std::vector<btVector3> pts;
    for (int i = 0; i < 8; ++i) pts.push_back(btVector3(i & 1 ? .4 : -.4, i & 2 ? .2 : -.2, i & 4 ? .3 : -.3));
    auto* hull = f.own(new btConvexHullShape(&pts[0].x(), int(pts.size()), sizeof(btVector3)));
    const int p0 = f.body(plane, btVector3(0, 0, 0));
    const int b0 = f.body(box, btVector3(0, btScalar(0.25 - 0.01), 0), btVector3(1, 0, 1), btScalar(0.002));
    const int p1 = f.body(plane, btVector3(10, 0, 0));
    const int h1 = f.body(hull, btVector3(10, btScalar(0.2 + 0.04 - 0.01), 0), btVector3(1, 0, 0), btScalar(0.002));
    f.pair(p0, b0);
    f.pair(p1, h1);
    f.build();
    cl::Context& ctx = test::context();
    std::vector<BtgPersistentManifold> states, softStates;
    const std::vector<BtgManifold> bullet = runDevice(ctx, f, {}, {}, &states);
    const std::vector<BtgManifold> soft = runDevice(ctx, f, {}, {}, &softStates, true);
    for (size_t i = 0; i < 2; ++i) {
        SCOPED_TRACE("pair " + std::to_string(i));
        EXPECT_EQ(bullet[i].numPoints, 1);
        ASSERT_EQ(soft[i].numPoints, 4);
        EXPECT_EQ(softStates[i].numPoints, 0);  // nothing kept
        const BtgManifold ref = ref::referenceContact(f.pairs[i], f.pos.data(), f.rot.data(), f.props.data(),
                                                      f.view.view(), true);
        expectSame(soft[i], ref, i);
        for (int k = 0; k < 4; ++k) {
            EXPECT_NEAR(soft[i].points[k].distance, -0.01f, 0.003f) << "point " << k;  // the tilt: +-2 mm
            EXPECT_LE(soft[i].points[k].ny, -0.9999f) << "point " << k;  // from the box (B) to the plane (A)
        }
    }
}

TEST(NarrowphaseGjk, PointMatchesBulletsAlgorithm)
{
    Fixture f;
    addCases(f);
    f.build();
    std::vector<BtgPersistentManifold> states;
    std::vector<BtgManifold> dev = runDevice(test::context(), f, {}, {}, &states);
    for (size_t i = 0; i < f.pairs.size(); ++i) {
        SCOPED_TRACE("case " + std::to_string(i));
        StockPoint s = stockPoint(f.bodies[size_t(f.pairs[i].a)], f.bodies[size_t(f.pairs[i].b)]);
        ASSERT_TRUE(s.found);
        ASSERT_EQ(dev[i].numPoints, 1);
        const BtgManifoldPoint& p = dev[i].points[0];
        EXPECT_GE(p.nx * s.normal.x() + p.ny * s.normal.y() + p.nz * s.normal.z(), kDegree)
            << "normal " << p.nx << " " << p.ny << " " << p.nz << " stock " << s.normal.x() << " " << s.normal.y() << " "
            << s.normal.z();
        EXPECT_NEAR(p.distance, s.distance, kMillimetre);
        // EPA's witness points (case 8) are only as good as its 0.1 mm face accuracy lets the
        // closest face's barycentre move along a flat rim: Bullet's lies 6 mm from the exact one.
        const float pointTol = i == 8 ? 10 * kMillimetre : 2 * kMillimetre;
        EXPECT_NEAR(p.px, s.pointB.x(), pointTol);
        EXPECT_NEAR(p.py, s.pointB.y(), pointTol);
        EXPECT_NEAR(p.pz, s.pointB.z(), pointTol);
    }
}

TEST(NarrowphaseGjk, PersistentManifoldKeepsFourByArea)
{
    // Bullet's rules on a manifold fed one point a step: a point near a cached one replaces it
    // (same identity), a fifth point replaces by sortCachedPoints, a point pulled apart is dropped.
    BtgPose pa, pb;
    pa.pos = btgMake4(0, 1, 0, 0);
    pa.rot = btgQuatToMat3(btgMake4(0, 0, 0, 1));
    pb.pos = btgZero4();
    pb.rot = pa.rot;
    const float t = 0.02f;
    float dist[BTG_MAX_POINTS];
    BtgPersistentManifold m = btgEmptyPersistent(0, 1, BTG_PAIR_HULL_CONVEX);
    const float corners[5][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0.1f, 0.1f}};
    for (int k = 0; k < 5; ++k) {
        BtgConvexPoint p = btgMakeConvexPoint(btgMake4(0, 1, 0, 0), btgMake4(corners[k][0], 0, corners[k][1], 0), -0.001f * (k + 1));
        m = btgPersistentStep(m, p, pa, pb, t, dist);
    }
    ASSERT_EQ(m.numPoints, 4);
    // the centre point (deepest) replaced one corner; the four kept span the largest area left
    bool centre = false;
    for (int k = 0; k < 4; ++k) centre |= std::fabs(m.localA[k].x - 0.1f) < 1e-5f;
    EXPECT_TRUE(centre);
    const uint idBefore = m.id[0];
    BtgConvexPoint near = btgMakeConvexPoint(btgMake4(0, 1, 0, 0), btgMake4(m.localA[0].x + 0.005f, 0, m.localA[0].z, 0), -0.002f);
    m = btgPersistentStep(m, near, pa, pb, t, dist);
    EXPECT_EQ(m.numPoints, 4);
    bool kept = false;
    for (int k = 0; k < 4; ++k) kept |= m.id[k] == idBefore;
    EXPECT_TRUE(kept) << "a replaced point keeps its identity";
    EXPECT_EQ(m.added, int(idBefore)) << "the replaced point is the one added this step";
    BtgConvexPoint none = near;
    none.valid = 0;
    m = btgPersistentStep(m, none, pa, pb, t, dist);
    EXPECT_EQ(m.added, -1) << "no point found: every point persisted";
    pa.pos = btgMake4(0, 1.05f, 0, 0);  // pulled 5 cm apart: every point beyond the threshold
    m = btgPersistentStep(m, btgNoPoint(), pa, pb, t, dist);
    EXPECT_EQ(m.numPoints, 0);
}

// A friction anchor (btPersistentManifold::replaceContactPoint with BT_CONTACT_FLAG_FRICTION_ANCHOR):
// a new point matching an old one whose identity the last solve marked inside its friction
// cone (anchorMask) leaves the old point as it was, body-frame points and all, and still counts
// as this step's added point; without the mark the new point replaces it as always.
TEST(NarrowphaseGjk, FrictionAnchorKeepsTheOldPoint)
{
    BtgPose pa, pb;
    pa.pos = btgMake4(0, 1, 0, 0);
    pa.rot = btgQuatToMat3(btgMake4(0, 0, 0, 1));
    pb.pos = btgZero4();
    pb.rot = pa.rot;
    const float t = 0.02f;
    float dist[BTG_MAX_POINTS];
    BtgPersistentManifold m = btgEmptyPersistent(0, 1, BTG_PAIR_HULL_CONVEX);
    m = btgPersistentStep(m, btgMakeConvexPoint(btgMake4(0, 1, 0, 0), btgMake4(0.3f, 0, 0.2f, 0), -0.001f), pa, pb, t, dist);
    ASSERT_EQ(m.numPoints, 1);
    const BtgPersistentManifold first = m;
    // the same feature found 5 mm along x
    const BtgConvexPoint moved = btgMakeConvexPoint(btgMake4(0, 1, 0, 0), btgMake4(0.305f, 0, 0.2f, 0), -0.001f);
    for (bool anchored : {true, false}) {
        SCOPED_TRACE(anchored);
        BtgPersistentManifold prev = first;
        prev.anchorMask = anchored ? 1u << first.id[0] : 0u;
        BtgPersistentManifold next = btgPersistentStep(prev, moved, pa, pb, t, dist);
        ASSERT_EQ(next.numPoints, 1);
        EXPECT_EQ(next.id[0], first.id[0]);
        EXPECT_EQ(next.added, int(first.id[0]));
        EXPECT_EQ(next.localB[0].x, anchored ? first.localB[0].x : 0.305f);
        EXPECT_EQ(next.localA[0].x, anchored ? first.localA[0].x : 0.305f);
    }
}

namespace {

// Bullet's algorithm for the pair in this pose, run once from an empty manifold as the
// dispatcher runs it (btConvexConvexAlgorithm for two featured hulls: the GJK point, then the
// clipped faces, into its own persistent manifold): the manifold's points.
std::vector<btManifoldPoint> stockManifold(const Body& a, const Body& b)
{
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btCollisionObject oa, ob;
    oa.setCollisionShape(a.shape);
    oa.setWorldTransform(a.pose);
    ob.setCollisionShape(b.shape);
    ob.setWorldTransform(b.pose);
    btCollisionObjectWrapper wa(nullptr, a.shape, &oa, oa.getWorldTransform(), -1, -1);
    btCollisionObjectWrapper wb(nullptr, b.shape, &ob, ob.getWorldTransform(), -1, -1);
    btCollisionAlgorithm* algo = dispatcher.findAlgorithm(&wa, &wb, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    btManifoldResult result(&wa, &wb);
    btDispatcherInfo info;
    algo->processCollision(&wa, &wb, info, &result);
    std::vector<btManifoldPoint> out;
    if (const btPersistentManifold* m = result.getPersistentManifold())
        for (int k = 0; k < m->getNumContacts(); ++k) out.push_back(m->getContactPoint(k));
    algo->~btCollisionAlgorithm();
    dispatcher.freeCollisionAlgorithm(algo);
    return out;
}

btConvexHullShape* featuredHull(Fixture& f, const std::vector<btVector3>& points)
{
    auto* h = f.own(new btConvexHullShape(&points[0].x(), int(points.size()), sizeof(btVector3)));
    h->initializePolyhedralFeatures();
    return h;
}
std::vector<btVector3> prismPoints(int sides, double radius, double halfHeight)
{
    std::vector<btVector3> v;
    for (int k = 0; k < sides; ++k)
        for (int s = -1; s <= 1; s += 2) {
            const double t = 2 * M_PI * k / sides;
            v.emplace_back(btScalar(radius * std::cos(t)), btScalar(s * halfHeight), btScalar(radius * std::sin(t)));
        }
    return v;
}

}  // namespace

TEST(NarrowphaseGjk, FeaturedHullsClipAsBullet)
{
    // Two hulls with polyhedral features: the manifold one step builds from nothing, on the
    // device, on the reference and by Bullet's own algorithm for the same pose.
    Fixture f;
    btConvexHullShape* slab = featuredHull(f, prismPoints(4, 2.0, 0.5));  // a square slab, top at 0.5
    btConvexHullShape* barrel = featuredHull(f, prismPoints(16, 0.4, 0.6));
    btConvexHullShape* tetra = featuredHull(f, {{0, -0.4f, 0}, {0.4f, 0.3f, 0}, {-0.3f, 0.3f, 0.3f}, {-0.2f, 0.3f, -0.4f}});
    // 0: the barrel standing 1 cm into the slab, turned about its axis
    f.pair(f.body(barrel, btVector3(0, btScalar(0.5 + 0.6 - 0.01), 0), btVector3(0, 1, 0), btScalar(0.3)),
           f.body(slab, btVector3(0, 0, 0)));
    // 1: the barrel tilted 5 degrees, its low rim 2 cm in (the first step of a landing)
    const double tilt = 5 * M_PI / 180, low = 0.6 * std::cos(tilt) + 0.4 * std::sin(tilt);
    f.pair(f.body(barrel, btVector3(10, btScalar(0.5 + low - 0.02), 0), btVector3(1, 0, 0), btScalar(tilt)),
           f.body(slab, btVector3(10, 0, 0)));
    // 2: the slab (A) under a tetrahedron whose vertex is 5 mm in
    f.pair(f.body(slab, btVector3(20, 0, 0)), f.body(tetra, btVector3(20, btScalar(0.5 + 0.4 - 0.005), 0)));
    // 3: the tetrahedron 2 cm apart, inside the margins (4 cm each) but polyhedra apart: the GJK point only
    f.pair(f.body(tetra, btVector3(30, btScalar(0.5 + 0.4 + 0.02), 0)), f.body(slab, btVector3(30, 0, 0)));
    f.build();
    std::vector<BtgPersistentManifold> states;
    std::vector<BtgManifold> dev = runDevice(test::context(), f, {}, {}, &states);
    ref::GjkStep ref = ref::referenceGjkStep(f.pairs, f.pos.data(), f.rot.data(), f.props.data(), f.view.view(), {});
    const int expectPoints[4] = {4, 4, 1, 0};  // stock's own counts, checked below
    for (size_t i = 0; i < f.pairs.size(); ++i) {
        SCOPED_TRACE("case " + std::to_string(i));
        EXPECT_EQ(f.view.shapes[size_t(f.props[size_t(f.pairs[i].a)].shape)].type, BTG_SHAPE_HULL);
        expectSame(dev[i], ref.manifolds[i], i);
        std::vector<btManifoldPoint> stock = stockManifold(f.bodies[size_t(f.pairs[i].a)], f.bodies[size_t(f.pairs[i].b)]);
        EXPECT_EQ(int(stock.size()), expectPoints[i]);
        ASSERT_EQ(dev[i].numPoints, int(stock.size()));
        for (const btManifoldPoint& s : stock) {
            bool found = false;
            for (int k = 0; k < dev[i].numPoints && !found; ++k) {
                const BtgManifoldPoint& p = dev[i].points[k];
                const btVector3& q = s.getPositionWorldOnB();
                found = std::fabs(p.px - q.x()) < kMillimetre && std::fabs(p.py - q.y()) < kMillimetre &&
                        std::fabs(p.pz - q.z()) < kMillimetre && std::fabs(p.distance - s.getDistance()) < kMillimetre &&
                        p.nx * s.m_normalWorldOnB.x() + p.ny * s.m_normalWorldOnB.y() + p.nz * s.m_normalWorldOnB.z() >= kDegree;
            }
            EXPECT_TRUE(found) << "stock point (" << s.getPositionWorldOnB().x() << ", " << s.getPositionWorldOnB().y()
                               << ", " << s.getPositionWorldOnB().z() << "; " << s.getDistance() << ") has no match";
        }
    }
}

// A wheel (a z-axis cylinder, radius 0.3) resting on a 40 m ramp turned 15 degrees, in twelve
// turns about its own axis (the same contact each time): the GJK point under the wheel, as
// Bullet's. The box's face corners come back around the flat contact a fraction of a millimetre
// apart; taken as new vertices they made a sliver or a flat tetrahedron, and the point was
// 3.86 m from the wheel (its lever stopped the wheel rolling down) or missing (5 of the 12)
// until the search ended as Bullet's does (a vertex within 1 cm of one it holds, a flat
// tetrahedron: the last simplex stands).
TEST(NarrowphaseGjk, WheelOnALongRampTouchesUnderTheWheel)
{
    Fixture f;
    btBoxShape* ramp = f.own(new btBoxShape(btVector3(20, 0.5f, 3)));
    auto* wheel = f.own(new btCylinderShapeZ(btVector3(0.3f, 0.3f, 0.1f)));
    const int a = f.body(ramp, btVector3(0, 0, 0), btVector3(0, 0, 1), btScalar(-M_PI / 12));
    // a pose the rolling wheel of the ramp probe reached (bits as written back)
    const btQuaternion q(-0x1.e2d746p-8f, 0x1.510658p-8f, 0x1.d4f316p-1f, -0x1.9ae5bcp-2f);
    const btVector3 centre(-0x1.0095bap+2f, 0x1.e6740cp+0f, 0x1.069ca8p-7f);
    for (int k = 0; k < 12; ++k) {
        const int b = f.body(wheel, centre);
        f.bodies[size_t(b)].pose.setRotation(q * btQuaternion(btVector3(0, 0, 1), btScalar(k * 0.0137)));
        f.pair(a, b);
    }
    f.build();
    std::vector<BtgPersistentManifold> states;
    std::vector<BtgManifold> dev = runDevice(test::context(), f, {}, {}, &states);
    for (size_t i = 0; i < f.pairs.size(); ++i) {
        SCOPED_TRACE("turn " + std::to_string(i));
        StockPoint s = stockPoint(f.bodies[size_t(f.pairs[i].a)], f.bodies[size_t(f.pairs[i].b)]);
        ASSERT_TRUE(s.found);
        ASSERT_EQ(dev[i].numPoints, 1) << "the wheel touches (before: no point for 5 of the 12 turns)";
        const BtgManifoldPoint& p = dev[i].points[0];
        const btVector3 point(p.px, p.py, p.pz);
        EXPECT_LT((point - s.pointB).length(), 0.01) << "metres from Bullet's point (before: 3.86 for 4 of the 12)";
        EXPECT_NEAR(p.distance, s.distance, kMillimetre);
        EXPECT_GE(p.nx * s.normal.x() + p.ny * s.normal.y() + p.nz * s.normal.z(), kDegree);
    }
}

// A capsule (r 0.2, h 0.8) lying on a 100 m box, at a pose a slowly rolling one reached: the box's
// corners lie 50 m out, and the simplex's closest point came out 0.2403 m after 0.2400 (rounding;
// in exact arithmetic a vertex never moves it away). The search kept that last axis, tilted 2.9
// degrees, and the manifold's tilted normals pushed the resting capsule sideways until it rolled
// away (a capsule given 0.01 rad/s turned at 0.93 rad/s 5 s later on the default solver, 0.28 in
// the bullet mode, stock's 0.018). Bullet stops with the last axis: the normal and the depth as
// Bullet's; the point anywhere on the contact line (the capsule's axis is x).
TEST(NarrowphaseGjk, CapsuleOnALargeBoxHasItsFaceNormal)
{
    Fixture f;
    btBoxShape* ground = f.own(new btBoxShape(btVector3(50, 1, 50)));
    auto* capsule = f.own(new btCapsuleShape(0.2f, 0.8f));
    const int a = f.body(ground, btVector3(0, -1, 0));
    const int b = f.body(capsule, btVector3(0, 0, 0));
    f.bodies[size_t(b)].pose = btTransform(btQuaternion(0x1.a3bc08p-3f, -0x1.a3bbfep-3f, 0x1.5a7d7p-1f, 0x1.5a8198p-1f),
                                           btVector3(0x1.aa8082p-16f, 0x1.998d56p-3f, 0x1.dea1c4p-4f));
    f.pair(a, b);
    f.build();
    std::vector<BtgPersistentManifold> states;
    std::vector<BtgManifold> dev = runDevice(test::context(), f, {}, {}, &states);
    StockPoint s = stockPoint(f.bodies[size_t(a)], f.bodies[size_t(b)]);
    ASSERT_TRUE(s.found);
    ASSERT_EQ(dev[0].numPoints, 1);
    const BtgManifoldPoint& p = dev[0].points[0];
    EXPECT_GE(p.nx * s.normal.x() + p.ny * s.normal.y() + p.nz * s.normal.z(), kDegree)
        << "normal " << p.nx << " " << p.ny << " " << p.nz << " (before: 0.0370 -0.9987 0.0348)";
    EXPECT_NEAR(p.distance, s.distance, kMillimetre) << "before: 0.28 mm apart, Bullet's touching";
    EXPECT_NEAR(p.py, s.pointB.y(), kMillimetre);
    EXPECT_NEAR(p.pz, s.pointB.z(), 2 * kMillimetre);
    EXPECT_LT(std::fabs(p.px), 0.4f) << "on the capsule's segment";
}
