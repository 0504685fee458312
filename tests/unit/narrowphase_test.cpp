// narrowphase_test.cpp — the narrowphase stage against its CPU reference (same shared
// routines; points matched as sets within tests/tolerances.h), and the physics directly:
// face–face, edge–edge and vertex–face boxes, spheres, planes, a sphere on an 18-vertex hull.
#include "reference/narrowphase.h"
#include "shape_tables.h"
#include "shared/clip.h"
#include "shared/math.h"
#include "shared/narrowphase_common.h"
#include "stages/find_pairs.h"
#include "world/pair_kinds.h"
#include "stages/narrowphase.h"
#include "test_device.h"
#include "tolerances.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>

using namespace btgpu;

namespace {

constexpr float kThreshold = test::kTestBreakingThreshold;  // m, every test shape's
const BtgFloat4 kIdentity = btgMake4(0, 0, 0, 1);

BtgFloat4 axisAngle(BtgFloat4 axis, float angle)
{
    BtgFloat4 a = btgNormalize3(axis) * std::sin(0.5f * angle);
    return btgMake4(a.x, a.y, a.z, std::cos(0.5f * angle));
}
// Rotation taking unit vector u onto unit vector v.
BtgFloat4 rotationBetween(BtgFloat4 u, BtgFloat4 v)
{
    u = btgNormalize3(u);
    v = btgNormalize3(v);
    return axisAngle(btgCross3(u, v), std::acos(btgDot3(u, v)));
}

struct Scene {
    test::ShapeTables t;
    std::vector<BtgFloat4> pos, rot;
    std::vector<BtgBodyProps> props;
    std::vector<BtgPair> pairs;
    int body(int shape, BtgFloat4 p, BtgFloat4 q = kIdentity)
    {
        BtgBodyProps bp{};
        bp.shape = shape;
        bp.flags = BTG_BODY_DYNAMIC;
        pos.push_back(p);
        rot.push_back(q);
        props.push_back(bp);
        return int(pos.size()) - 1;
    }
    void pair(int a, int b) { pairs.push_back(BtgPair{a, b}); }
    PairKinds kinds() const
    {
        PairKinds k;
        for (const BtgPair& p : pairs) {
            const int kind = ref::pairKind(p, props.data(), t.view());
            if (kind != BTG_PAIR_NONE) k.add(kind);
        }
        return k;
    }
};

// A manifold point as one vector: xyz on B, w the signed distance; the manifold's normal (its
// first point's: they share it).
BtgFloat4 pointB(const BtgManifold& m, int k)
{
    const BtgManifoldPoint& p = m.points[k];
    return btgMake4(p.px, p.py, p.pz, p.distance);
}
BtgFloat4 normalOf(const BtgManifold& m) { return btgPointNormal(m.points[0]); }

constexpr int kSpareSlots = 3;  // slots past the pair count: must stay untouched

// speculative: the soft step's collision (two boxes clipped afresh); *stateSlots: the
// persistent-manifold entries the world then holds (gjkPairState, gjkCache).
std::vector<BtgManifold> runDevice(cl::Context& ctx, const Scene& s, bool speculative = false,
                                   std::pair<size_t, size_t>* stateSlots = nullptr)
{
    DeviceWorld w(ctx);
    w.speculativeContacts = speculative;
    w.numBodies = int(s.pos.size());
    w.pos.upload(ctx, s.pos);
    w.rot.upload(ctx, s.rot);
    w.props.upload(ctx, s.props);
    s.t.upload(w);
    w.pairCapacity = s.pairs.size() + kSpareSlots;
    std::vector<BtgPair> pairs = s.pairs;
    pairs.resize(w.pairCapacity, BtgPair{0, 0});
    w.pairs.upload(ctx, pairs);
    std::vector<uint> counters(kNumCounters, 0);
    counters[kPairCount] = uint(s.pairs.size());
    w.counters.upload(ctx, counters);
    BtgManifold sentinel{};
    sentinel.numPoints = -1;
    w.manifolds.upload(ctx, std::vector<BtgManifold>(w.pairCapacity, sentinel));
    groupPairsByKind(w, s.kinds());
    narrowphase(w, s.kinds());
    std::vector<BtgManifold> out = w.manifolds.download(ctx, w.pairCapacity);
    if (stateSlots) *stateSlots = {w.gjkPairState.capacity(), w.gjkCache.capacity()};
    for (size_t i = s.pairs.size(); i < out.size(); ++i) EXPECT_EQ(out[i].numPoints, -1) << "slot past the count written";
    out.resize(s.pairs.size());
    return out;
}

void expectSame(const BtgManifold& dev, const BtgManifold& ref, size_t i)
{
    SCOPED_TRACE("pair " + std::to_string(i));
    EXPECT_EQ(dev.bodyA, ref.bodyA);
    EXPECT_EQ(dev.bodyB, ref.bodyB);
    EXPECT_EQ(dev.partIdA, BTG_NO_SUB_SHAPE);  // whole convex shapes
    EXPECT_EQ(dev.indexA, BTG_NO_SUB_SHAPE);
    EXPECT_EQ(dev.partIdB, BTG_NO_SUB_SHAPE);
    EXPECT_EQ(dev.indexB, BTG_NO_SUB_SHAPE);
    ASSERT_EQ(dev.numPoints, ref.numPoints);
    if (ref.numPoints == 0) return;
    EXPECT_GE(btgDot3(normalOf(dev), normalOf(ref)), tol::kNormalDot);
    for (int k = 0; k < ref.numPoints; ++k) {
        bool found = false;
        for (int j = 0; j < dev.numPoints && !found; ++j) {
            BtgFloat4 d = pointB(dev, j) - pointB(ref, k);
            found = btgLength3(d) <= tol::kContactPoint && std::fabs(d.w) <= tol::kContactDepth;
            if (found) EXPECT_EQ(dev.points[j].featureId, ref.points[k].featureId) << "point " << k;
        }
        EXPECT_TRUE(found) << "reference point " << k << " (" << pointB(ref, k).x << ", " << pointB(ref, k).y << ", "
                           << pointB(ref, k).z << "; " << pointB(ref, k).w << ") has no device match";
    }
}

// Device result, checked against the reference.
std::vector<BtgManifold> collide(const Scene& s)
{
    std::vector<BtgManifold> dev = runDevice(test::context(), s);
    std::vector<BtgManifold> ref = ref::referenceNarrowphase(s.pairs, s.pos.data(), s.rot.data(), s.props.data(), s.t.view());
    for (size_t i = 0; i < s.pairs.size(); ++i) expectSame(dev[i], ref[i], i);
    return dev;
}

void expectNormal(const BtgManifold& m, BtgFloat4 n) { EXPECT_GE(btgDot3(normalOf(m), btgNormalize3(n)), tol::kNormalDot); }
void expectAllDepths(const BtgManifold& m, float distance)
{
    for (int k = 0; k < m.numPoints; ++k) EXPECT_NEAR(pointB(m, k).w, distance, tol::kContactDepth) << "point " << k;
}
bool hasPoint(const BtgManifold& m, BtgFloat4 p, float tolerance = tol::kContactPoint)
{
    for (int k = 0; k < m.numPoints; ++k)
        if (btgLength3(btgXyz(pointB(m, k)) - btgXyz(p)) <= tolerance) return true;
    return false;
}

}  // namespace

TEST(Narrowphase, BoxOnBoxFaceFace)
{
    Scene s;
    int ground = s.t.addBox(btgMake4(2, 0.5f, 2, 0)), cube = s.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0));
    s.body(cube, btgMake4(0, 0.99f, 0, 0));   // 1 cm into the ground's top face (y = 0.5)
    s.body(ground, btgMake4(0, 0, 0, 0));
    s.body(ground, btgMake4(10, 0, 0, 0));
    s.body(cube, btgMake4(10, 0.99f, 0, 0));  // also 1 cm in, the ground as A
    s.pair(0, 1);
    s.pair(2, 3);  // reversed roles: the ground is A
    std::vector<BtgManifold> m = collide(s);
    ASSERT_EQ(m[0].numPoints, 4);
    expectNormal(m[0], btgMake4(0, 1, 0, 0));
    expectAllDepths(m[0], -0.01f);
    for (float x : {-0.5f, 0.5f})
        for (float z : {-0.5f, 0.5f}) EXPECT_TRUE(hasPoint(m[0], btgMake4(x, 0.5f, z, 0)));
    ASSERT_EQ(m[1].numPoints, 4);
    expectNormal(m[1], btgMake4(0, -1, 0, 0));
    expectAllDepths(m[1], -0.01f);
    for (float x : {9.5f, 10.5f})
        for (float z : {-0.5f, 0.5f}) EXPECT_TRUE(hasPoint(m[1], btgMake4(x, 0.49f, z, 0)));  // on the cube
    // 1 cm apart, within the breaking threshold: stock's box detector reports nothing, so a
    // pair with no manifold kept holds nothing (a kept one goes on: box_box_test.cpp).
    Scene apart;
    ground = apart.t.addBox(btgMake4(2, 0.5f, 2, 0));
    cube = apart.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0));
    apart.body(cube, btgMake4(0, 1.01f, 0, 0));
    apart.body(ground, btgMake4(0, 0, 0, 0));
    apart.pair(0, 1);
    EXPECT_EQ(collide(apart)[0].numPoints, 0);
}

TEST(Narrowphase, TheSoftStepsBoxesHoldNoPersistentManifolds)
{
    // The bullet mode keeps each box pair's manifold (stock's box detector): an entry a pair
    // slot. The soft step clips two boxes afresh every substep and keeps nothing, so it holds
    // one placeholder entry, not 256 bytes a pair slot and a contact slot (device memory at
    // 1,000,000 cubes), and its clip is the same whether or not a world held them before.
    Scene s;
    int ground = s.t.addBox(btgMake4(2, 0.5f, 2, 0)), cube = s.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0));
    s.body(cube, btgMake4(0, 0.99f, 0, 0));
    s.body(ground, btgMake4(0, 0, 0, 0));
    s.pair(0, 1);
    std::pair<size_t, size_t> held;
    runDevice(test::context(), s, false, &held);
    EXPECT_GE(held.first, s.pairs.size());
    const std::vector<BtgManifold> soft = runDevice(test::context(), s, true, &held);
    EXPECT_EQ(held.first, 1u);
    EXPECT_EQ(held.second, 1u);
    ASSERT_EQ(soft[0].numPoints, 4);
    expectNormal(soft[0], btgMake4(0, 1, 0, 0));
    expectAllDepths(soft[0], -0.01f);
}

TEST(Narrowphase, CrossedBoxesEdgeEdge)
{
    Scene s;
    int cube = s.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0));
    const float r = 0.5f * std::sqrt(2.0f);  // centre to edge of a cube turned 45 degrees
    s.body(cube, btgMake4(0, 2 * r - 0.01f, 0, 0), axisAngle(btgMake4(1, 0, 0, 0), 0.78539816f));  // bottom edge along x
    s.body(cube, btgMake4(0, 0, 0, 0), axisAngle(btgMake4(0, 0, 1, 0), 0.78539816f));              // top edge along z
    s.body(cube, btgMake4(5, 0, 0, 0), axisAngle(btgMake4(0, 0, 1, 0), 0.78539816f));  // same, lower box is A
    s.body(cube, btgMake4(5, 2 * r - 0.01f, 0, 0), axisAngle(btgMake4(1, 0, 0, 0), 0.78539816f));
    s.pair(0, 1);
    s.pair(2, 3);
    std::vector<BtgManifold> m = collide(s);
    ASSERT_EQ(m[0].numPoints, 1);
    expectNormal(m[0], btgMake4(0, 1, 0, 0));
    EXPECT_NEAR(pointB(m[0], 0).w, -0.01f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[0], btgMake4(0, r, 0, 0)));
    ASSERT_EQ(m[1].numPoints, 1);
    expectNormal(m[1], btgMake4(0, -1, 0, 0));
    EXPECT_NEAR(pointB(m[1], 0).w, -0.01f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[1], btgMake4(5, r - 0.01f, 0, 0)));  // on the upper box's edge
}

TEST(Narrowphase, VertexOnFace)
{
    Scene s;
    int ground = s.t.addBox(btgMake4(2, 0.5f, 2, 0)), cube = s.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0));
    BtgFloat4 q = rotationBetween(btgMake4(1, 1, 1, 0), btgMake4(0, -1, 0, 0));  // a corner points down
    const float corner = 0.5f * std::sqrt(3.0f);
    s.body(cube, btgMake4(0.3f, 0.5f + corner - 0.01f, -0.2f, 0), q);
    s.body(ground, btgMake4(0, 0, 0, 0));
    s.pair(0, 1);
    std::vector<BtgManifold> m = collide(s);
    ASSERT_EQ(m[0].numPoints, 1);
    expectNormal(m[0], btgMake4(0, 1, 0, 0));
    EXPECT_NEAR(pointB(m[0], 0).w, -0.01f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[0], btgMake4(0.3f, 0.5f, -0.2f, 0)));
}

TEST(Narrowphase, SphereOnBox)
{
    Scene s;
    int ground = s.t.addBox(btgMake4(2, 0.5f, 2, 0)), ball = s.t.addSphere(0.5f);
    s.body(ball, btgMake4(0.2f, 0.98f, 0.1f, 0));  // on the top face, 2 cm deep
    s.body(ground, btgMake4(0, 0, 0, 0));
    s.body(ground, btgMake4(10, 0, 0, 0));
    s.body(ball, btgMake4(12.3f, 0.8f, 0, 0));     // beyond the +x top edge: closest point on the edge
    s.body(ball, btgMake4(20, 0.3f, 0, 0));        // centre inside, below the top face
    s.body(ground, btgMake4(20, 0, 0, 0));
    s.pair(0, 1);
    s.pair(2, 3);
    s.pair(4, 5);
    int rounded = s.t.addPrism(9, 0.5f, 0.2f, 0.04f);  // top face at 0.2, grown by 4 cm
    s.body(ball, btgMake4(30.1f, 0.2f + 0.04f + 0.5f - 0.01f, 0, 0));
    s.body(rounded, btgMake4(30, 0, 0, 0));
    s.pair(6, 7);
    std::vector<BtgManifold> m = collide(s);
    ASSERT_EQ(m[3].numPoints, 1);
    expectNormal(m[3], btgMake4(0, 1, 0, 0));
    EXPECT_NEAR(pointB(m[3], 0).w, -0.01f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[3], btgMake4(30.1f, 0.24f, 0, 0)));  // on the grown surface
    ASSERT_EQ(m[0].numPoints, 1);
    expectNormal(m[0], btgMake4(0, 1, 0, 0));
    EXPECT_NEAR(pointB(m[0], 0).w, -0.02f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[0], btgMake4(0.2f, 0.5f, 0.1f, 0)));
    // ground is A here: the normal points from the ball to the box
    ASSERT_EQ(m[1].numPoints, 1);
    expectNormal(m[1], btgMake4(-1, -1, 0, 0));
    EXPECT_NEAR(pointB(m[1], 0).w, std::sqrt(0.18f) - 0.5f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[1], btgMake4(12.3f, 0.8f, 0, 0) + btgMake4(-1, -1, 0, 0) * (0.5f / std::sqrt(2.0f))));
    ASSERT_EQ(m[2].numPoints, 1);
    expectNormal(m[2], btgMake4(0, 1, 0, 0));
    EXPECT_NEAR(pointB(m[2], 0).w, -0.2f - 0.5f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[2], btgMake4(20, 0.5f, 0, 0)));
}

TEST(Narrowphase, SphereSphereAndPlane)
{
    Scene s;
    int big = s.t.addSphere(0.5f), small = s.t.addSphere(0.3f);
    int floor = s.t.addPlane(btgMake4(0, 1, 0, 0), 0.25f);  // y = 0.25 locally
    s.body(big, btgMake4(0, 0, 0, 0));
    s.body(small, btgMake4(0.7f, 0, 0, 0));
    s.body(floor, btgMake4(0, -0.5f, 0, 0));        // world plane y = -0.25
    s.body(small, btgMake4(3, -0.25f + 0.29f, 0, 0));  // 1 cm into the plane
    s.pair(0, 1);
    s.pair(2, 3);
    s.pair(0, 2);  // big sphere: 0.25 - 0.5 = -0.25 deep
    std::vector<BtgManifold> m = collide(s);
    ASSERT_EQ(m[0].numPoints, 1);
    expectNormal(m[0], btgMake4(-1, 0, 0, 0));
    EXPECT_NEAR(pointB(m[0], 0).w, -0.1f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[0], btgMake4(0.4f, 0, 0, 0)));
    ASSERT_EQ(m[1].numPoints, 1);
    expectNormal(m[1], btgMake4(0, -1, 0, 0));  // plane is A: from the sphere down to the plane
    EXPECT_NEAR(pointB(m[1], 0).w, -0.01f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[1], btgMake4(3, -0.26f, 0, 0)));  // on the sphere
    ASSERT_EQ(m[2].numPoints, 1);
    expectNormal(m[2], btgMake4(0, 1, 0, 0));
    EXPECT_NEAR(pointB(m[2], 0).w, -0.25f, tol::kContactDepth);
    EXPECT_TRUE(hasPoint(m[2], btgMake4(0, -0.25f, 0, 0)));
}

TEST(Narrowphase, SeparatedPairsHaveNoPoints)
{
    Scene s;
    int cube = s.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0)), ball = s.t.addSphere(0.5f);
    s.body(cube, btgMake4(0, 0, 0, 0));
    s.body(cube, btgMake4(0.3f, 1.05f, 0, 0), axisAngle(btgMake4(0, 1, 0, 0), 0.3f));  // 5 cm gap
    s.body(ball, btgMake4(0, 0, 1.1f, 0));
    s.body(ball, btgMake4(1.04f, 0, 1.1f, 0));
    s.pair(0, 1);
    s.pair(0, 2);  // 10 cm gap
    s.pair(2, 3);  // 4 cm gap
    std::vector<BtgManifold> m = collide(s);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(m[i].numPoints, 0) << "pair " << i;
        EXPECT_EQ(m[i].bodyA, s.pairs[i].a);
        EXPECT_EQ(m[i].bodyB, s.pairs[i].b);
    }
}

TEST(Narrowphase, DeterministicAcrossRuns)
{
    Scene s;
    int cube = s.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0)), prism = s.t.addPrism(9, 0.5f, 0.25f, 0.01f);
    s.body(cube, btgMake4(0, 0, 0, 0));
    s.body(prism, btgMake4(0.2f, 0.7f, 0.1f, 0), axisAngle(btgMake4(1, 0, 1, 0), 0.2f));
    s.body(cube, btgMake4(0.9f, 0.1f, 0.3f, 0), axisAngle(btgMake4(0, 1, 1, 0), 0.7f));
    s.pair(0, 1);
    s.pair(0, 2);
    s.pair(1, 2);
    std::vector<BtgManifold> a = collide(s), b = collide(s);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(BtgManifold)), 0);
    EXPECT_GT(a[0].numPoints, 0);
    EXPECT_GT(a[1].numPoints, 0);
}

// Spheres on a box: the sphere–box program and, for the two balls' persistent manifold, the GJK
// program's; never the box–box SAT's.
TEST(Narrowphase, SpheresOnlyBuildsNoSatProgram)
{
    cl::Context ctx(cl::selectDevice(""));
    Scene s;
    int ball = s.t.addSphere(0.5f), cube = s.t.addBox(btgMake4(2, 0.5f, 2, 0));
    s.body(ball, btgMake4(0, 0, 0, 0));
    s.body(ball, btgMake4(0.9f, 0, 0, 0));
    s.body(cube, btgMake4(0, -0.99f, 0, 0));
    s.pair(0, 1);
    s.pair(0, 2);
    std::vector<BtgManifold> m = runDevice(ctx, s);
    EXPECT_EQ(m[0].numPoints, 1);
    EXPECT_EQ(m[1].numPoints, 1);
    const std::vector<std::string>& built = ctx.builtPrograms();
    EXPECT_NE(std::find(built.begin(), built.end(), "narrowphase"), built.end());
    EXPECT_NE(std::find(built.begin(), built.end(), "narrowphase_gjk"), built.end());
    EXPECT_EQ(std::find(built.begin(), built.end(), "narrowphase_sat"), built.end());
}

namespace {
// Largest signed distance of world point p to the planes of hull h (0 on its surface).
float hullPlaneDistance(const Scene& s, int body, BtgFloat4 p)
{
    BtgMat3 r = btgQuatToMat3(s.rot[body]);
    BtgFloat4 local = btgMat3TMulVec(r, p - s.pos[body]);
    const BtgShape& sh = s.t.shapes[s.props[body].shape];
    float best = -1e30f;
    for (int f = 0; f < sh.numFaces; ++f) {
        BtgFloat4 pl = s.t.faces[sh.firstFace + f].plane;
        best = std::fmax(best, btgDot3(pl, local) + pl.w);
    }
    return best;
}
// Distance of p from body's surface (margin-free shapes): 0 when p lies on it.
float surfaceOffset(const Scene& s, int body, BtgFloat4 p)
{
    const BtgShape& sh = s.t.shapes[s.props[body].shape];
    if (sh.type == BTG_SHAPE_SPHERE) return btgLength3(p - s.pos[body]) - sh.param.x;
    return hullPlaneDistance(s, body, p);
}
}  // namespace

// Random poses of boxes, prisms, tetrahedra and spheres near touching: the device agrees with
// the reference, and every contact's two points lie on the two surfaces, `distance` apart. The
// pairs of this stage only: box-box, sphere-box, sphere-sphere and sphere-hull (a hull meets a
// box or a hull through GJK, narrowphase_gjk_test.cpp).
TEST(Narrowphase, RandomPosesAgreeAndLieOnSurfaces)
{
    Scene s;
    std::vector<int> kinds = {s.t.addBox(btgMake4(0.5f, 0.3f, 0.4f, 0)), s.t.addPrism(9, 0.4f, 0.2f),
                              s.t.addTetrahedron(0.35f), s.t.addSphere(0.4f), s.t.addBox(btgMake4(1.5f, 0.2f, 1.0f, 0))};
    auto thisStage = [&](int sa, int sb) {
        const PairKindRow* row = pairKindRow(btgPairKind(s.t.shapes[size_t(sa)].type, s.t.shapes[size_t(sb)].type));
        return row && std::strcmp(row->program, "narrowphase_gjk") != 0;
    };
    uint32_t seed = 12345u;
    auto rnd = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return float(seed >> 8) / float(1u << 24);
    };
    auto randomRot = [&] {
        return btgQuatNormalize(btgMake4(rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f));
    };
    for (int i = 0; i < 60; ++i) {
        int sa = kinds[i % kinds.size()], sb = kinds[(i / kinds.size() + i) % kinds.size()];
        if (!thisStage(sa, sb)) continue;
        BtgFloat4 centre = btgMake4(10.0f * float(i), 0, 0, 0);
        BtgFloat4 dir = btgNormalize3(btgMake4(rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f, 0));
        float gap = 0.45f + 0.6f * rnd();
        int a = s.body(sa, centre + dir * gap, randomRot());
        int b = s.body(sb, centre, randomRot());
        s.pair(a, b);
    }
    std::vector<BtgManifold> m = collide(s);
    int touching = 0;
    for (size_t i = 0; i < m.size(); ++i) {
        SCOPED_TRACE("pair " + std::to_string(i));
        ASSERT_LE(m[i].numPoints, BTG_MAX_POINTS);
        if (m[i].numPoints == 0) continue;
        ++touching;
        EXPECT_NEAR(btgLength3(normalOf(m[i])), 1.0f, 1e-5f);
        for (int k = 0; k < m[i].numPoints; ++k) {
            BtgFloat4 pb = pointB(m[i], k);
            EXPECT_LT(pb.w, kThreshold);
            BtgFloat4 pa = btgXyz(pb) + normalOf(m[i]) * pb.w;
            EXPECT_NEAR(surfaceOffset(s, m[i].bodyB, pb), 0.0f, tol::kContactPoint) << "point " << k << " not on B";
            EXPECT_NEAR(surfaceOffset(s, m[i].bodyA, pa), 0.0f, tol::kContactPoint) << "point " << k << " not on A";
        }
    }
    EXPECT_GT(touching, 12);
}

// The SAT's box shortcuts (a box's interval from its half extents, one face of each opposite
// pair) must give the answer of the generic hull loops bit for bit: the same rows with the type
// HULL run those loops. Random poses, touching, near and apart, and exact stacks (ties).
TEST(Narrowphase, BoxSatIsTheHullSatBitForBit)
{
    test::ShapeTables t;
    const int boxes[] = {t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0)), t.addBox(btgMake4(1.5f, 0.2f, 1.0f, 0)),
                         t.addBox(btgMake4(0.05f, 0.3f, 0.17f, 0))};
    const ref::ShapeTablesView v = t.view();
    uint32_t seed = 777u;
    auto rnd = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return float(seed >> 8) / float(1u << 24);
    };
    auto collider = [&](int shape, BtgFloat4 pos, BtgFloat4 q, int asHull) {
        BtgCollider c{};
        c.pose.pos = pos;
        c.pose.rot = btgQuatToMat3(q);
        c.shape = t.shapes[size_t(shape)];
        if (asHull) c.shape.type = BTG_SHAPE_HULL;
        c.body = 0;
        return c;
    };
    int touching = 0, edges = 0;
    for (int i = 0; i < 3000; ++i) {
        const int sa = boxes[i % 3], sb = boxes[(i / 3) % 3];
        BtgFloat4 qa = kIdentity, qb = kIdentity;
        BtgFloat4 pa = btgMake4(0, 0, 0, 0), pb = btgMake4(0, 0, 0, 0);
        if (i % 4 == 0) {  // stacked, axis-aligned: every face axis of a pair ties
            pa = btgMake4(0.3f * (rnd() - 0.5f), t.shapes[size_t(sa)].param.y + t.shapes[size_t(sb)].param.y -
                                                     0.01f * rnd(), 0.0f, 0);
        } else {
            qa = btgQuatNormalize(btgMake4(rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f));
            qb = btgQuatNormalize(btgMake4(rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f));
            pa = btgNormalize3(btgMake4(rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f, 0)) * (0.2f + 2.0f * rnd());
        }
        BtgManifold m[2];
        BtgSatResult sat[2];
        float lo[2], hi[2];
        const BtgFloat4 dir = btgNormalize3(btgMake4(rnd() - 0.5f, rnd() - 0.5f, rnd() - 0.5f, 0));
        for (int asHull = 0; asHull < 2; ++asHull) {
            const BtgCollider a = collider(sa, pa, qa, asHull), b = collider(sb, pb, qb, asHull);
            btgHullInterval(a, v.hullVertices, dir, &lo[asHull], &hi[asHull]);
            sat[asHull] = btgFindSeparatingAxis(a, b, v.hullVertices, v.hullFaces, v.hullEdges, kThreshold);
            m[asHull] = btgCollideHullHull(a, b, v.hullVertices, v.hullFaces, v.hullIndices, v.hullEdges, kThreshold);
        }
        SCOPED_TRACE("pose " + std::to_string(i));
        ASSERT_EQ(std::memcmp(lo, lo + 1, sizeof(float)), 0);
        ASSERT_EQ(std::memcmp(hi, hi + 1, sizeof(float)), 0);
        ASSERT_EQ(std::memcmp(&sat[0].axis, &sat[1].axis, sizeof(BtgFloat4)), 0);
        ASSERT_EQ(std::memcmp(&sat[0].separation, &sat[1].separation, sizeof(float)), 0);
        ASSERT_EQ(sat[0].feature, sat[1].feature);
        ASSERT_EQ(sat[0].indexA, sat[1].indexA);
        ASSERT_EQ(sat[0].indexB, sat[1].indexB);
        ASSERT_EQ(std::memcmp(&m[0], &m[1], sizeof(BtgManifold)), 0);
        touching += m[0].numPoints > 0;
        edges += sat[0].feature == BTG_SAT_EDGE;
    }
    EXPECT_GT(touching, 1000);  // the cases are not all apart ...
    EXPECT_GT(edges, 100);      // ... nor all face contacts
}

// Equal boxes stacked exactly: every incident corner lies on a side plane of the reference
// face, the case where clipping makes duplicates. The four corners must all be kept, so the
// support is symmetric and a stack gets no torque.
TEST(Narrowphase, EqualBoxesStackedKeepAllFourCorners)
{
    Scene s;
    int cube = s.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0));
    s.body(cube, btgMake4(0, 0.5f, 0, 0));
    s.body(cube, btgMake4(0, 1.495f, 0, 0));
    s.pair(0, 1);
    std::vector<BtgManifold> m = collide(s);
    ASSERT_EQ(m[0].numPoints, 4);
    expectAllDepths(m[0], -0.005f);
    for (float x : {-0.5f, 0.5f})
        for (float z : {-0.5f, 0.5f}) EXPECT_TRUE(hasPoint(m[0], btgMake4(x, 0.995f, z, 0)));
}

namespace {
// The same scene with every body nudged: turned by `angle` about a fixed tilted axis, moved by `shift`.
Scene nudged(const Scene& s, float angle, BtgFloat4 shift)
{
    Scene n = s;
    const BtgFloat4 q = axisAngle(btgMake4(0.3f, 1, 0.2f, 0), angle);
    for (size_t i = 0; i < n.pos.size(); i += 2) {  // the first body of each pair
        n.rot[i] = btgQuatNormalize(btgQuatMul(q, n.rot[i]));
        n.pos[i] = n.pos[i] + shift;
    }
    return n;
}
}  // namespace

// Feature ids name points by the features that make them: unique within a manifold, and a
// small motion keeps each corner's id (the point with the same id is the same corner, nearby),
// for face contacts (clipping; in pair 0 the nudge moves the reference face from A to B, and
// the corners keep their ids), vertex contacts on planes, edge contacts and spheres.
TEST(Narrowphase, FeatureIdsAreUniqueAndStable)
{
    // The pairs this stage makes at once (sphere-box); two boxes (stock's box detector) and a
    // box or hull against a plane or a hull keep their points' identities in the pair's
    // persistent manifold instead (box_box_test.cpp, narrowphase_gjk_test.cpp): here, from no
    // manifold, only their counts and kinds of identity are checked.
    Scene s;
    int ground = s.t.addBox(btgMake4(2, 0.5f, 2, 0)), cube = s.t.addBox(btgMake4(0.5f, 0.5f, 0.5f, 0));
    int ball = s.t.addSphere(0.5f);
    const float r = 0.5f * std::sqrt(2.0f);
    s.body(cube, btgMake4(0.1f, 0.99f, 0, 0), axisAngle(btgMake4(0, 1, 0, 0), 0.4f));  // face on face, cube is A
    s.body(ground, btgMake4(0, 0, 0, 0));
    s.body(ground, btgMake4(10, 0, 0, 0));  // ground is A: the reference face is B's or A's
    s.body(cube, btgMake4(10.2f, 0.99f, 0, 0), axisAngle(btgMake4(0, 1, 0, 0), 0.2f));
    s.body(cube, btgMake4(30, 2 * r - 0.01f, 0, 0), axisAngle(btgMake4(1, 0, 0, 0), 0.78539816f));  // edge on edge
    s.body(cube, btgMake4(30, 0, 0, 0), axisAngle(btgMake4(0, 0, 1, 0), 0.78539816f));
    s.body(ball, btgMake4(40, 0.98f, 0, 0));
    s.body(ground, btgMake4(40, 0, 0, 0));
    for (int i = 0; i < 8; i += 2) s.pair(i, i + 1);
    std::vector<BtgManifold> before = collide(s);
    std::vector<BtgManifold> after = collide(nudged(s, 0.004f, btgMake4(0.002f, -0.001f, 0.001f, 0)));
    const int expectPoints[4] = {4, 4, 1, 1};
    for (size_t i = 0; i < before.size(); ++i) {
        SCOPED_TRACE("pair " + std::to_string(i));
        ASSERT_EQ(before[i].numPoints, expectPoints[i]);
        ASSERT_EQ(after[i].numPoints, expectPoints[i]);
        if (i < 3) {  // box pairs: unique identities of the persistent kind, in the detector's order
            for (int k = 0; k < after[i].numPoints; ++k) EXPECT_EQ(after[i].points[k].featureId, BTG_FEATURE_SINGLE | uint(k));
            continue;
        }
        int kept = 0;
        for (int k = 0; k < after[i].numPoints; ++k) {
            const BtgManifoldPoint& p = after[i].points[k];
            EXPECT_NE(p.featureId, BTG_FEATURE_UNKNOWN);
            int same = -1;
            for (int j = 0; j < before[i].numPoints; ++j) {
                if (j != k) EXPECT_NE(after[i].points[j].featureId, p.featureId) << "ids repeat in a manifold";
                if (before[i].points[j].featureId == p.featureId) same = j;
            }
            if (same < 0) continue;
            ++kept;
            EXPECT_LT(btgLength3(pointB(after[i], k) - pointB(before[i], same)), 0.01f) << "point " << k;
        }
        EXPECT_GE(kept, after[i].numPoints);
    }
    EXPECT_EQ(before[3].points[0].featureId, BTG_FEATURE_SINGLE);
}
