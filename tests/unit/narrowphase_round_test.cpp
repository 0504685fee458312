// narrowphase_round_test.cpp — the soft step's fresh contact of a capsule or a cylinder lying on
// a box's face, a plane (round_contacts.h): the device against the CPU reference, and the
// points where the physics puts them (under the body's axis, at its segment's ends or its cap
// rims), where the bullet mode keeps stock's one GJK point a step.
#include "gjk_fixture.h"

#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <algorithm>
#include <cmath>

using namespace btgpu;
using namespace btgpu::test::gjk;

namespace {

// The fixture's pairs collided by the bullet mode (stock's one GJK point each) and by the soft
// step, which must keep nothing and give the reference's manifold with `expected[i]` points;
// the soft step's manifolds, for the caller's own checks.
std::vector<BtgManifold> softAsReference(Fixture& f, const std::vector<int>& expected)
{
    cl::Context& ctx = test::context();
    std::vector<BtgPersistentManifold> states, softStates;
    const std::vector<BtgManifold> bullet = runDevice(ctx, f, {}, {}, &states);
    const std::vector<BtgManifold> soft = runDevice(ctx, f, {}, {}, &softStates, true);
    for (size_t i = 0; i < expected.size(); ++i) {
        SCOPED_TRACE("pair " + std::to_string(i));
        EXPECT_EQ(bullet[i].numPoints, 1);
        EXPECT_EQ(soft[i].numPoints, expected[i]);
        EXPECT_EQ(softStates[i].numPoints, 0);  // nothing kept
        const BtgManifold ref = ref::referenceContact(f.pairs[i], f.pos.data(), f.rot.data(), f.props.data(),
                                                      f.view.view(), true);
        expectSame(soft[i], ref, i);
    }
    return soft;
}

}  // namespace

// A capsule lying on a box's face or a plane, 1 cm in and tilted 2 mrad, standing on a box, and
// lying across a box's edge: the bullet mode keeps stock's one GJK point a step; the soft step
// lays the segment on the face afresh (btgCollideRoundOnFace), a point under each end, whose
// lever arms trail nothing when the capsule rolls (SoftStepCapsules.*), keeps nothing, and
// takes the one GJK point where the capsule stands on an end or meets an edge.
TEST(NarrowphaseGjk, TheSoftStepLaysACapsuleOnAFaceAlongItsLength)
{
    Fixture f;
    auto* box = f.own(new btBoxShape(btVector3(2, .5, 2)));
    auto* plane = f.own(new btStaticPlaneShape(btVector3(0, 1, 0), 0));
    auto* lying = f.own(new btCapsuleShapeX(btScalar(0.25), 1));   // segment x in [-0.5, 0.5]
    auto* standing = f.own(new btCapsuleShape(btScalar(0.25), 1));  // along y
    auto* across = f.own(new btCapsuleShapeZ(btScalar(0.25), 1));
    const btScalar in = btScalar(0.01), tilt = btScalar(0.002);
    const int c0 = f.body(lying, btVector3(btScalar(0.3), btScalar(0.75) - in, btScalar(0.2)), btVector3(0, 0, 1), tilt);
    const int b0 = f.body(box, btVector3(0, 0, 0));
    const int p1 = f.body(plane, btVector3(10, 0, 0));
    const int c1 = f.body(lying, btVector3(10, btScalar(0.25) - in, 0), btVector3(0, 0, 1), tilt);
    const int c2 = f.body(standing, btVector3(20, btScalar(0.5 + 0.75) - in, 0));
    const int b2 = f.body(box, btVector3(20, 0, 0));
    // across the box's edge (x 22, y 0.5, along z), which Bullet's margin (0.04) rounds: the
    // capsule's axis diagonally off the rounding's centre line, 5 mm into it along (1, 1, 0) / sqrt 2
    const double m = box->getMargin();
    const btScalar a = btScalar((0.25 + m - 0.005) / std::sqrt(2.0) - m);
    const int c3 = f.body(across, btVector3(22 + a, btScalar(0.5) + a, 10));
    const int b3 = f.body(box, btVector3(20, 0, 10));
    f.pair(c0, b0);
    f.pair(p1, c1);
    f.pair(c2, b2);
    f.pair(c3, b3);
    f.build();
    const std::vector<BtgManifold> soft = softAsReference(f, {2, 2, 1, 1});
    if (soft[0].numPoints != 2 || soft[1].numPoints != 2 || soft[2].numPoints != 1 || soft[3].numPoints != 1) return;  // counted above
    // lying: a point under each end of the segment (x = centre -+ 0.5 cos tilt), 10 mm in -+ 1 mm
    for (size_t i = 0; i < 2; ++i)
        for (int k = 0; k < 2; ++k) {
            SCOPED_TRACE("pair " + std::to_string(i) + " point " + std::to_string(k));
            const BtgManifoldPoint& p = soft[i].points[k];
            const float centre = i == 0 ? 0.3f : 10.0f, end = k == 0 ? -0.5f : 0.5f;
            EXPECT_NEAR(p.px, centre + end, 1e-4f);
            // on B: the box's face; the capsule's surface under the plane (A)
            EXPECT_NEAR(p.py, i == 0 ? 0.5f : -0.01f + end * 0.002f, 1e-4f);
            EXPECT_NEAR(p.distance, -0.01f + end * 0.002f, 1e-4f);
            EXPECT_GE(i == 0 ? p.ny : -p.ny, 0.9999f);  // from B towards A: the box's face up; the capsule (B) down to the plane
            EXPECT_EQ(p.featureId, BTG_FEATURE_VERTEX | uint(k));
        }
    // standing: its lower end only, 10 mm in
    EXPECT_NEAR(soft[2].points[0].distance, -0.01f, 1e-4f);
    EXPECT_GE(soft[2].points[0].ny, 0.9999f);
    // across the edge: the diagonal normal, 5 mm in
    EXPECT_NEAR(soft[3].points[0].distance, -0.005f, 1e-4f);
    EXPECT_NEAR(soft[3].points[0].nx, std::sqrt(0.5f), 1e-3f);
    EXPECT_NEAR(soft[3].points[0].ny, std::sqrt(0.5f), 1e-3f);
    EXPECT_EQ(soft[3].points[0].featureId, BTG_FEATURE_VERTEX | 8u);
}

// A cylinder lying on a box's face and on a plane (1 cm in, tilted 2 mrad) and standing on a
// box: the soft step takes its cap rims (btgCollideRoundOnFace): lying, the lowest rim point of
// each cap, under the axis; standing, four points of the lower cap's rim; nothing kept.
TEST(NarrowphaseGjk, TheSoftStepSetsACylinderOnItsRims)
{
    Fixture f;
    auto* box = f.own(new btBoxShape(btVector3(2, .5, 2)));
    auto* plane = f.own(new btStaticPlaneShape(btVector3(0, 1, 0), 0));
    auto* lying = f.own(new btCylinderShapeX(btVector3(btScalar(0.5), btScalar(0.25), btScalar(0.25))));
    auto* standing = f.own(new btCylinderShape(btVector3(btScalar(0.25), btScalar(0.5), btScalar(0.25))));
    const btScalar in = btScalar(0.01), tilt = btScalar(0.002);
    const int c0 = f.body(lying, btVector3(btScalar(0.3), btScalar(0.75) - in, btScalar(0.2)), btVector3(0, 0, 1), tilt);
    const int b0 = f.body(box, btVector3(0, 0, 0));
    const int p1 = f.body(plane, btVector3(10, 0, 0));
    const int c1 = f.body(lying, btVector3(10, btScalar(0.25) - in, 0), btVector3(0, 0, 1), tilt);
    const int c2 = f.body(standing, btVector3(20, btScalar(0.5 + 0.5) - in, 0));
    const int b2 = f.body(box, btVector3(20, 0, 0));
    f.pair(c0, b0);
    f.pair(p1, c1);
    f.pair(c2, b2);
    f.build();
    const std::vector<BtgManifold> soft = softAsReference(f, {2, 2, 4});
    if (soft[0].numPoints != 2 || soft[1].numPoints != 2 || soft[2].numPoints != 4) return;  // counted above
    for (size_t i = 0; i < 3; ++i) {
        for (int k = 0; k < soft[i].numPoints; ++k) {
            const BtgManifoldPoint& p = soft[i].points[k];
            EXPECT_GE(i == 1 ? -p.ny : p.ny, 0.9999f) << "point " << k;
            EXPECT_NEAR(p.distance, -0.01f, i == 2 ? 1e-4f : 1.1e-3f) << "point " << k;  // lying: the tilt, -+1 mm
        }
    }
    // lying: under the axis (z of the centre), at the core's caps (half length less the margin)
    const float core = 0.5f - float(lying->getMargin());
    for (size_t i = 0; i < 2; ++i) {
        const float centre = i == 0 ? 0.3f : 10.0f, z = i == 0 ? 0.2f : 0.0f;
        float lo = 1e9f, hi = -1e9f;
        for (int k = 0; k < 2; ++k) {
            EXPECT_NEAR(soft[i].points[k].pz, z, 1e-4f) << "pair " << i << " point " << k;
            lo = std::min(lo, soft[i].points[k].px);
            hi = std::max(hi, soft[i].points[k].px);
        }
        EXPECT_NEAR(lo, centre - core, 1e-3f) << "pair " << i;  // the tilt moves the rim's lowest point 0.4 mm
        EXPECT_NEAR(hi, centre + core, 1e-3f) << "pair " << i;
    }
    // standing: on the lower cap's core rim (radius 0.25 less the margin) about the axis
    const float rim = 0.25f - float(standing->getMargin());
    for (int k = 0; k < 4; ++k) {
        const BtgManifoldPoint& p = soft[2].points[k];
        EXPECT_NEAR(std::hypot(p.px - 20.0f, p.pz), rim, 1e-4f) << "point " << k;
        EXPECT_NEAR(p.py, 0.5f, 1e-5f) << "point " << k;
    }
}

