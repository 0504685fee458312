// narrowphase_mesh_test.cpp — convex against mesh triangles (program "narrowphase_mesh" after
// the midphase): the device against its CPU reference (same shared routines and gather), and
// against Bullet's own btConvexConcaveCollisionAlgorithm run in the test for the same pose
// (SphereTriangleDetector for spheres; the polyhedral path, m_enableSatConvex with the box's
// features, for boxes): the deepest point's normal within 1 degree and depth within 1 mm, and
// on flat meshes the point count of stock's one manifold; capsules, cylinders, a cone, a
// multi-sphere and a plain hull (GJK against each btTriangleShape) against stock the same way.
#include "../compat/shape_tables.h"
#include "mesh_scene.h"
#include "reference/midphase.h"
#include "reference/narrowphase.h"
#include "shared/math.h"
#include "shared/narrowphase_common.h"
#include "shared/triangle_contacts.h"
#include "shared/persistent_manifold.h"
#include "stages/midphase.h"
#include "stages/narrowphase.h"
#include "test_device.h"
#include "tolerances.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>

#include <algorithm>
#include <random>

using namespace btgpu;
using test::BulletMesh;
using test::MeshScene;

namespace {

BtgFloat4 axisAngle(BtgFloat4 axis, float angle)
{
    BtgFloat4 a = btgNormalize3(axis) * std::sin(0.5f * angle);
    return btgMake4(a.x, a.y, a.z, std::cos(0.5f * angle));
}
const BtgFloat4 kIdentity = btgMake4(0, 0, 0, 1);

// The convex shapes of the tests, on both sides: Bullet's and the GPU table's row.
struct Shapes {
    btSphereShape sphere{0.4f};
    btBoxShape box{btVector3(0.5f, 0.3f, 0.7f)};
    int sphereRow = -1, boxRow = -1;
    Shapes() { box.initializePolyhedralFeatures(); }  // the test's own box: Bullet's SAT path
};

// One pair's manifolds, as the device and the reference make them.
struct PairResult {
    std::vector<BtgManifold> manifolds;
};

// `persistent`: the bullet mode (stock's one point a triangle into each pair's persistent
// manifold, a first step: no manifold kept yet), else the soft step's clip, each triangle's
// manifold merged afresh. *states: the pairs' persistent manifolds (gjkPairState).
std::vector<PairResult> runDevice(const MeshScene& s, bool persistent = false,
                                  std::vector<BtgPersistentManifold>* states = nullptr)
{
    cl::Context& ctx = test::context();
    DeviceWorld w(ctx);
    s.upload(w, 1 << 12);
    w.speculativeContacts = !persistent;
    midphase(w);
    narrowphaseMesh(w, s.kinds());
    std::vector<BtgManifoldRange> ranges = w.pairManifolds.download(ctx, s.pairs.size());
    std::vector<BtgManifold> all = w.manifolds.download(ctx, w.pairCapacity + w.subPairCapacity);
    std::vector<uint> counters = w.counters.download(ctx, kNumCounters);
    EXPECT_EQ(counters[kStatus], 0u);
    if (states) *states = w.gjkPairState.download(ctx, s.pairs.size());
    std::vector<PairResult> out(s.pairs.size());
    for (size_t i = 0; i < s.pairs.size(); ++i)
        for (int k = 0; k < ranges[i].count; ++k) out[i].manifolds.push_back(all[size_t(ranges[i].start + k)]);
    return out;
}

std::vector<PairResult> runReference(const MeshScene& s)
{
    std::vector<PairResult> out(s.pairs.size());
    for (size_t i = 0; i < s.pairs.size(); ++i) {
        std::vector<BtgSubPair> sub = ref::referenceMidphase({int(i)}, s.pairs.data(), s.pos.data(), s.rot.data(),
                                                             s.props.data(), s.t.shapes.data(), s.meshView());
        out[i].manifolds = ref::referenceMeshPair(sub, s.pairs.data(), s.pos.data(), s.rot.data(), s.props.data(),
                                                  s.t.view(), s.meshView());
    }
    return out;
}

void expectSameManifold(const BtgManifold& dev, const BtgManifold& ref)
{
    EXPECT_EQ(dev.bodyA, ref.bodyA);
    EXPECT_EQ(dev.bodyB, ref.bodyB);
    EXPECT_EQ(dev.partIdA, ref.partIdA);
    EXPECT_EQ(dev.indexA, ref.indexA);
    EXPECT_EQ(dev.partIdB, ref.partIdB);
    EXPECT_EQ(dev.indexB, ref.indexB);
    ASSERT_EQ(dev.numPoints, ref.numPoints);
    for (int k = 0; k < ref.numPoints; ++k) {
        const BtgManifoldPoint &a = dev.points[k], &b = ref.points[k];
        EXPECT_NEAR(a.px, b.px, tol::kContactPoint);
        EXPECT_NEAR(a.py, b.py, tol::kContactPoint);
        EXPECT_NEAR(a.pz, b.pz, tol::kContactPoint);
        EXPECT_NEAR(a.distance, b.distance, tol::kContactDepth);
        EXPECT_GE(a.nx * b.nx + a.ny * b.ny + a.nz * b.nz, tol::kNormalDot);
        EXPECT_EQ(a.featureId, b.featureId);
    }
}

// Stock Bullet's manifold for one (convex, mesh) pose: the dispatcher's own algorithm
// (btConvexConcaveCollisionAlgorithm), one frame, into its persistent manifold. Points on the
// mesh with the normal from the mesh towards the convex.
struct Point {
    btVector3 onMesh, normal;
    float distance;
};
std::vector<Point> stockContact(btCollisionShape* convex, const btTransform& cx, btCollisionShape* mesh,
                                const btTransform& mx)
{
    static btDefaultCollisionConfiguration config;
    static btCollisionDispatcher dispatcher(&config);
    btCollisionObject a, b;
    a.setCollisionShape(convex);
    a.setWorldTransform(cx);
    b.setCollisionShape(mesh);
    b.setWorldTransform(mx);
    btCollisionObjectWrapper wa(nullptr, convex, &a, cx, -1, -1), wb(nullptr, mesh, &b, mx, -1, -1);
    btCollisionAlgorithm* algo = dispatcher.findAlgorithm(&wa, &wb, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    btManifoldResult result(&wa, &wb);
    btDispatcherInfo info;
    info.m_enableSatConvex = true;
    algo->processCollision(&wa, &wb, info, &result);
    std::vector<Point> out;
    btManifoldArray manifolds;
    algo->getAllContactManifolds(manifolds);
    for (int m = 0; m < manifolds.size(); ++m) {
        const btPersistentManifold* pm = manifolds[m];
        const bool swapped = pm->getBody0() != &a;
        for (int k = 0; k < pm->getNumContacts(); ++k) {
            const btManifoldPoint& p = pm->getContactPoint(k);
            out.push_back({swapped ? p.getPositionWorldOnA() : p.getPositionWorldOnB(),
                           swapped ? -p.m_normalWorldOnB : p.m_normalWorldOnB, p.getDistance()});
        }
    }
    algo->~btCollisionAlgorithm();
    dispatcher.freeCollisionAlgorithm(algo);
    return out;
}

// The GPU pair's points over all its manifolds, the same way round (the mesh is A there).
std::vector<Point> gpuContact(const PairResult& r, std::vector<int>* manifoldOf)
{
    std::vector<Point> out;
    for (size_t i = 0; i < r.manifolds.size(); ++i) {
        const BtgManifold& m = r.manifolds[i];
        for (int k = 0; k < m.numPoints; ++k) {
            const BtgManifoldPoint& p = m.points[k];
            btVector3 n(p.nx, p.ny, p.nz), onB(p.px, p.py, p.pz);  // B: the convex
            out.push_back({onB + n * p.distance, -n, p.distance});
            manifoldOf->push_back(int(i));
        }
    }
    return out;
}

int deepest(const std::vector<Point>& pts)
{
    int best = 0;
    for (size_t i = 1; i < pts.size(); ++i)
        if (pts[i].distance < pts[size_t(best)].distance) best = int(i);
    return best;
}

btTransform xf(BtgFloat4 p, BtgFloat4 q) { return btTransform(btQuaternion(q.x, q.y, q.z, q.w), btVector3(p.x, p.y, p.z)); }

// Convex bodies over `mesh` at the given poses; the mesh is body 0 (pairs: mesh A, convex B).
struct Case {
    bool box;
    BtgFloat4 pos, rot;
    bool countAsStock;  // flat contact: stock's point count too
};

void compareWithStock(const BulletMesh& mesh, const std::vector<Case>& cases)
{
    Shapes shapes;
    MeshScene s;
    shapes.sphereRow = s.t.addSphere(0.4f);
    shapes.boxRow = s.t.addBox(btgMake4(0.5f, 0.3f, 0.7f, 0));
    // Bullet's relative breaking thresholds for these shapes (the dispatcher's default flag).
    s.t.shapes[size_t(shapes.sphereRow)].breakingThreshold = shapes.sphere.getContactBreakingThreshold(0.02f);
    s.t.shapes[size_t(shapes.boxRow)].breakingThreshold = shapes.box.getContactBreakingThreshold(0.02f);
    const int meshRow = s.addMesh(mesh.shape.get());
    s.body(meshRow, btgMake4(0, 0, 0, 0), kIdentity, BTG_BODY_STATIC);
    for (const Case& c : cases) {
        int b = s.body(c.box ? shapes.boxRow : shapes.sphereRow, c.pos, c.rot, BTG_BODY_DYNAMIC);
        s.pairs.push_back(BtgPair{0, b});
    }
    std::vector<PairResult> dev = runDevice(s), ref = runReference(s);
    btTransform meshXf = btTransform::getIdentity();
    int touching = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        SCOPED_TRACE("case " + std::to_string(i));
        ASSERT_EQ(dev[i].manifolds.size(), ref[i].manifolds.size());
        for (size_t m = 0; m < ref[i].manifolds.size(); ++m) expectSameManifold(dev[i].manifolds[m], ref[i].manifolds[m]);
        for (const BtgManifold& m : dev[i].manifolds) {
            EXPECT_EQ(m.bodyA, 0);
            EXPECT_GE(m.indexA, 0);  // the mesh side carries its first triangle's keys
            EXPECT_GE(m.partIdA, 0);
            EXPECT_EQ(m.indexB, BTG_NO_SUB_SHAPE);
            // Each point names its own triangle (Bullet's per-point m_partId / m_index), and
            // lies over it: its point on the mesh is in the triangle's plane, inside its edges.
            for (int k = 0; k < m.numPoints; ++k) {
                const uint key = m.points[k].featureId;
                BtgSubPair sp{0, 0, btgTriangleKeyPart(key), btgTriangleKeyIndex(key)};
                ASSERT_LT(sp.partId, int(s.meshes.meshes[0].numParts));
                sp.triangle = s.meshes.meshes[0].firstTriangle + s.meshes.parts[size_t(sp.partId)] + sp.index;
                BtgTriangleVerts tv = btgConcaveTriangle(s.t.shapes[size_t(meshRow)], sp, nullptr, nullptr, nullptr,
                                                         s.meshes.triangles.data(), s.meshes.vertices.data(), nullptr,
                                                         nullptr);
                const BtgManifoldPoint& p = m.points[k];
                BtgFloat4 onMesh = btgMake4(p.px + p.nx * p.distance, p.py + p.ny * p.distance, p.pz + p.nz * p.distance, 0);
                BtgFloat4 n = btgNormalize3(btgCross3(tv.v[1] - tv.v[0], tv.v[2] - tv.v[0]));
                EXPECT_NEAR(btgDot3(n, onMesh - tv.v[0]), 0.0f, 1e-4f) << "point " << k << " not on its triangle";
                for (int e = 0; e < 3; ++e) {
                    BtgFloat4 side = btgCross3(tv.v[(e + 1) % 3] - tv.v[e], n);
                    float out = btgDot3(side, onMesh - tv.v[e]) * btgDot3(side, tv.v[(e + 2) % 3] - tv.v[e]);
                    EXPECT_GE(out, -1e-4f) << "point " << k << " outside its triangle";
                }
            }
        }
        const Case& c = cases[i];
        std::vector<Point> stock = stockContact(c.box ? static_cast<btCollisionShape*>(&shapes.box) : &shapes.sphere,
                                                xf(c.pos, c.rot), mesh.shape.get(), meshXf);
        std::vector<int> manifoldOf;
        std::vector<Point> gpu = gpuContact(dev[i], &manifoldOf);
        if (stock.empty()) {
            // Stock queries the convex's bare box; the GPU's, grown by the threshold, may also
            // find points apart by less than it (speculative, never pushing).
            for (const Point& gp : gpu) EXPECT_GE(gp.distance, 0.0f);
            continue;
        }
        ASSERT_FALSE(gpu.empty());
        ++touching;
        // A sphere's every stock point is one of the GPU's (one point a triangle; stock keeps, of
        // points closer than its breaking threshold, the last triangle's, the GPU each
        // triangle's). A box's clipped points are reduced to 4 by each its own rule (stock's
        // sortCachedPoints, the GPU's contact_reduce.h), so only depth, normal and count compare.
        const float threshold = c.box ? shapes.box.getContactBreakingThreshold(0.02f)
                                      : shapes.sphere.getContactBreakingThreshold(0.02f);
        for (const Point& sp : stock) {
            if (c.box) break;
            bool found = false;
            for (const Point& gp : gpu)
                found = found || ((gp.onMesh - sp.onMesh).length() < threshold && gp.normal.dot(sp.normal) >= tol::kStockNormalDot &&
                                  std::fabs(gp.distance - sp.distance) <= tol::kStockDepth);
            EXPECT_TRUE(found) << "stock point (" << sp.onMesh.x() << ", " << sp.onMesh.y() << ", " << sp.onMesh.z()
                               << ") d " << sp.distance << " n (" << sp.normal.x() << ", " << sp.normal.y() << ", "
                               << sp.normal.z() << ") has no GPU match";
        }
        const Point &gd = gpu[size_t(deepest(gpu))], &sd = stock[size_t(deepest(stock))];
        if (c.countAsStock || !c.box) {
            EXPECT_NEAR(gd.distance, sd.distance, tol::kStockDepth);
        } else {
            // A box on a slope: stock's manifold keeps, of two triangles' points at one place,
            // the one processed last; the GPU keeps both. Stock's deepest point is the GPU's, or
            // the GPU has a deeper one there.
            bool matched = false;
            for (const Point& gp : gpu) {
                if (!((gp.onMesh - sd.onMesh).length() < threshold)) continue;
                matched = matched || (gp.normal.dot(sd.normal) >= tol::kStockNormalDot &&
                                      std::fabs(gp.distance - sd.distance) <= tol::kStockDepth) ||
                          gp.distance < sd.distance - tol::kStockDepth;
            }
            EXPECT_TRUE(matched) << "stock's deepest point (" << sd.distance << ") has no GPU point there";
            EXPECT_LE(gd.distance, sd.distance + tol::kStockDepth);
        }
        // On a flat mesh: the manifold of the deepest point has as many points as stock's one
        // manifold has along that normal (points at other normals, on triangles beside the
        // convex, are their own manifolds on the GPU: its contact rows carry one normal).
        if (c.countAsStock) {
            EXPECT_GE(gd.normal.dot(sd.normal), tol::kStockNormalDot);
            int alongStock = 0, alongGpu = 0;
            for (const Point& sp : stock) alongStock += sp.normal.dot(sd.normal) >= tol::kStockNormalDot;
            for (size_t k = 0; k < gpu.size(); ++k) alongGpu += manifoldOf[k] == manifoldOf[size_t(deepest(gpu))];
            EXPECT_EQ(alongGpu, alongStock);
        }
        if (getenv("BTGPU_DEBUG_MESH")) {
            std::vector<BtgSubPair> sub = ref::referenceMidphase({int(i)}, s.pairs.data(), s.pos.data(), s.rot.data(),
                                                                 s.props.data(), s.t.shapes.data(), s.meshView());
            for (const BtgSubPair& sp : sub) {
                BtgManifold m = ref::referenceTriangleContact(sp, s.pairs.data(), s.pos.data(), s.rot.data(),
                                                              s.props.data(), s.t.view(), s.meshView(), false);
                printf("case %zu tri %d/%d points %d", i, sp.partId, sp.index, m.numPoints);
                for (int k = 0; k < m.numPoints; ++k)
                    printf(" (%.3f %.3f %.3f; %.4f)", m.points[k].px, m.points[k].py, m.points[k].pz, m.points[k].distance);
                printf("\n");
            }
            for (const Point& p : stock)
                printf("case %zu stock p (%.3f %.3f %.3f) d %.4f n (%.3f %.3f %.3f)\n", i, p.onMesh.x(), p.onMesh.y(),
                       p.onMesh.z(), p.distance, p.normal.x(), p.normal.y(), p.normal.z());
            for (const Point& p : gpu)
                printf("case %zu gpu   p (%.3f %.3f %.3f) d %.4f n (%.3f %.3f %.3f)\n", i, p.onMesh.x(), p.onMesh.y(),
                       p.onMesh.z(), p.distance, p.normal.x(), p.normal.y(), p.normal.z());
        }
    }
    EXPECT_GT(touching, 0);
}

}  // namespace

TEST(NarrowphaseMesh, FlatMeshAgainstStock)
{
    auto mesh = BulletMesh::terrain(8, 1.0f, true);
    const BtgFloat4 tilt = axisAngle(btgMake4(1, 0, 1, 0), 0.5f);
    std::vector<Case> cases = {
        {false, btgMake4(-3.3f, 0.395f, 0.2f, 0), kIdentity, true},      // sphere inside a triangle
        {false, btgMake4(-2.5f, 0.392f, 0.5f, 0), kIdentity, true},      // on a quad's diagonal
        {false, btgMake4(2.0f, 0.397f, 1.0f, 0), kIdentity, true},       // on a grid vertex, 32-bit part
        {true, btgMake4(-1.7f, 0.295f, -1.3f, 0), kIdentity, true},      // box flat over several quads
        {true, btgMake4(1.6f, 0.296f, 0.4f, 0), axisAngle(btgMake4(0, 1, 0, 0), 0.3f), true},  // turned, flat
        {true, btgMake4(-0.2f, 0.296f, 0.1f, 0), kIdentity, true},       // across the parts' seam
        {true, btgMake4(3.0f, 0.72f, -2.0f, 0), tilt, true},             // a corner down
        {false, btgMake4(0.5f, 0.9f, 0.5f, 0), kIdentity, true},         // apart
    };
    compareWithStock(*mesh, cases);
}

TEST(NarrowphaseMesh, CurvedTerrainAgainstStock)
{
    auto mesh = BulletMesh::terrain(12, 0.5f, false);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> x(-5.0f, 5.0f), z(-2.5f, 2.5f), sink(0.0f, 0.008f), angle(-0.4f, 0.4f);
    std::vector<Case> cases;
    for (int i = 0; i < 24; ++i) {
        float px = x(rng), pz = z(rng);
        // A sphere dropped onto the surface: centre above the nearest surface point by r - sink.
        float h = BulletMesh::height(px, pz);
        cases.push_back({false, btgMake4(px, h + 0.4f - sink(rng), pz, 0), kIdentity, false});
    }
    // Boxes level, a little into the slope's highest point under them.
    for (int i = 0; i < 12; ++i) {
        float px = x(rng), pz = z(rng);
        float highest = -1e9f;  // the surface's highest point under the footprint
        for (int a = 0; a <= 20; ++a)
            for (int b = 0; b <= 20; ++b)
                highest = std::max(highest, BulletMesh::height(px - 0.5f + 0.05f * float(a), pz - 0.7f + 0.07f * float(b)));
        cases.push_back({true, btgMake4(px, highest + 0.3f - sink(rng), pz, 0), kIdentity, false});
    }
    compareWithStock(*mesh, cases);
}

namespace {

// Support-function convex shapes (BTG_SHAPE_CONVEX rows) against triangles: the device against
// the reference, and the deepest point against stock's (GJK between the convex and each
// btTriangleShape, one point a triangle, into the pair's one manifold): normal within 1 degree,
// depth within 1 mm.
struct ConvexCase {
    btConvexShape* shape;
    BtgFloat4 pos, rot;
    bool touching;
    bool flatContact = false;  // a line or a face on the mesh: no one deepest point
};
void compareConvexWithStock(const BulletMesh& mesh, const std::vector<ConvexCase>& cases)
{
    MeshScene s;
    const int meshRow = s.addMesh(mesh.shape.get());
    s.body(meshRow, btgMake4(0, 0, 0, 0), kIdentity, BTG_BODY_STATIC);
    ::btgpu::ShapeTables rows;  // the world's own rows of these shapes
    for (const ConvexCase& c : cases) {
        std::string why;
        const int r = rows.add(c.shape, &why);
        ASSERT_GE(r, 0) << why;
        ASSERT_EQ(rows.shapes[size_t(r)].type, BTG_SHAPE_CONVEX);
        BtgShape copy = rows.shapes[size_t(r)];  // its vertex rows (multi-sphere, hull) moved along
        const int first = copy.firstVertex;
        copy.firstVertex = int(s.t.vertices.size());
        for (int v = 0; v < copy.numVertices; ++v) s.t.vertices.push_back(rows.vertices[size_t(first + v)]);
        s.t.shapes.push_back(copy);
        const int row = int(s.t.shapes.size()) - 1;
        s.pairs.push_back(BtgPair{0, s.body(row, c.pos, c.rot, BTG_BODY_DYNAMIC)});
    }
    std::vector<PairResult> dev = runDevice(s), ref = runReference(s);
    for (size_t i = 0; i < cases.size(); ++i) {
        SCOPED_TRACE("convex case " + std::to_string(i));
        ASSERT_EQ(dev[i].manifolds.size(), ref[i].manifolds.size());
        for (size_t m = 0; m < ref[i].manifolds.size(); ++m) expectSameManifold(dev[i].manifolds[m], ref[i].manifolds[m]);
        std::vector<Point> stock = stockContact(cases[i].shape, xf(cases[i].pos, cases[i].rot), mesh.shape.get(),
                                                btTransform::getIdentity());
        std::vector<int> manifoldOf;
        std::vector<Point> gpu = gpuContact(dev[i], &manifoldOf);
        EXPECT_EQ(!stock.empty(), cases[i].touching) << "gpu points " << gpu.size();
        if (stock.empty()) {
            for (const Point& gp : gpu) EXPECT_GE(gp.distance, 0.0f);
            continue;
        }
        ASSERT_FALSE(gpu.empty());
        // Stock's deepest point has a GPU point of its normal and depth (one point a triangle on
        // both; stock's manifold keeps, of two triangles' points closer than its breaking
        // threshold, the last one's, the GPU each triangle's), and the GPU has none deeper.
        // Where it lies is compared only off flat contacts: along a lying cylinder's line or a
        // base's disc every point is deepest, and which one GJK ends on is its path's choice.
        const Point &gd = gpu[size_t(deepest(gpu))], &sd = stock[size_t(deepest(stock))];
        const float threshold = cases[i].shape->getContactBreakingThreshold(0.02f);
        bool matched = false;
        for (const Point& gp : gpu)
            matched = matched || ((cases[i].flatContact || (gp.onMesh - sd.onMesh).length() < threshold) &&
                                  gp.normal.dot(sd.normal) >= tol::kStockNormalDot &&
                                  std::fabs(gp.distance - sd.distance) <= tol::kStockDepth);
        EXPECT_TRUE(matched) << "stock's deepest (" << sd.onMesh.x() << ", " << sd.onMesh.y() << ", " << sd.onMesh.z()
                             << ") d " << sd.distance << " n (" << sd.normal.x() << ", " << sd.normal.y() << ", "
                             << sd.normal.z() << ") has no GPU match";
        EXPECT_GE(gd.distance, sd.distance - tol::kStockDepth);
        for (size_t k = 0; k < gpu.size(); ++k) EXPECT_LT(manifoldOf[k], int(dev[i].manifolds.size()));
    }
}

}  // namespace

TEST(NarrowphaseMesh, SupportShapesAgainstTrianglesAsStock)
{
    auto flat = BulletMesh::terrain(8, 1.0f, true);
    btCapsuleShape capsule(0.3f, 1.0f);
    btCylinderShape cylinder(btVector3(0.3f, 0.5f, 0.3f));
    btConeShape cone(0.4f, 1.0f);
    const btVector3 centres[2] = {btVector3(-0.3f, 0, 0), btVector3(0.3f, 0.1f, 0)};
    const btScalar radii[2] = {0.25f, 0.2f};
    btMultiSphereShape spheres(centres, radii, 2);
    const btScalar corners[] = {-0.4f, -0.3f, -0.4f, 0.4f, -0.3f, -0.4f, -0.4f, -0.3f, 0.4f, 0.4f, -0.3f, 0.4f,
                                -0.4f, 0.3f,  -0.4f, 0.4f, 0.3f,  -0.4f, -0.4f, 0.3f,  0.4f, 0.4f, 0.3f,  0.4f};
    btConvexHullShape plainHull(corners, 8, 3 * sizeof(btScalar));  // no polyhedral features: GJK on stock
    const BtgFloat4 onSide = axisAngle(btgMake4(0, 0, 1, 0), 1.5707963f);
    const BtgFloat4 tilted = axisAngle(btgMake4(1, 0, 0.3f, 0), 0.6f);
    std::vector<ConvexCase> flatCases = {
        {&capsule, btgMake4(-2.3f, 0.795f, 0.4f, 0), kIdentity, true},     // upright on a cap
        {&capsule, btgMake4(1.3f, 0.296f, -0.6f, 0), onSide, true, true},        // lying across triangles
        {&capsule, btgMake4(0.6f, 0.62f, 1.1f, 0), tilted, true},          // tilted
        {&cylinder, btgMake4(-1.4f, 0.496f, -1.2f, 0), kIdentity, true, true},   // on its base
        {&cylinder, btgMake4(2.4f, 0.297f, 0.3f, 0), onSide, true, true},        // on its side
        {&cylinder, btgMake4(-0.5f, 0.55f, 2.2f, 0), tilted, true},        // on its rim
        {&cone, btgMake4(3.1f, 0.496f, -2.1f, 0), kIdentity, true, true},        // on its base
        {&spheres, btgMake4(-3.1f, 0.246f, 1.9f, 0), kIdentity, true},     // a multi-sphere's lower sphere
        {&plainHull, btgMake4(1.9f, 0.336f, 2.3f, 0), kIdentity, true, true},  // a plain hull flat
        {&plainHull, btgMake4(-2.9f, 0.5f, -2.6f, 0), tilted, true},       // ... on an edge
        {&capsule, btgMake4(0.2f, 1.2f, -2.4f, 0), kIdentity, false},      // apart
    };
    compareConvexWithStock(*flat, flatCases);
    auto curved = BulletMesh::terrain(12, 0.5f, false);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> x(-4.5f, 4.5f), z(-2.0f, 2.0f), sink(0.001f, 0.008f);
    std::vector<ConvexCase> curvedCases;
    for (int i = 0; i < 16; ++i) {
        const float px = x(rng), pz = z(rng);
        // The shape's lowest point (an upright capsule's, a lying cylinder's line) `sink` below
        // the surface under its centre: touching on the slope.
        const float h = BulletMesh::height(px, pz);
        if (i % 2 == 0) curvedCases.push_back({&cylinder, btgMake4(px, h + 0.3f - sink(rng), pz, 0), onSide, true});
        else curvedCases.push_back({&capsule, btgMake4(px, h + 0.8f - sink(rng), pz, 0), kIdentity, true});
    }
    compareConvexWithStock(*curved, curvedCases);
}

namespace {

// Stock's manifold of one (convex, mesh) pair after colliding it at each of `poses` in turn with
// one algorithm (its manifold persisting between them), the dispatcher's defaults (no SAT).
std::vector<Point> stockSteps(btCollisionShape* convex, const std::vector<btTransform>& poses, btCollisionShape* mesh)
{
    static btDefaultCollisionConfiguration config;
    static btCollisionDispatcher dispatcher(&config);
    btCollisionObject a, b;
    a.setCollisionShape(convex);
    b.setCollisionShape(mesh);
    b.setWorldTransform(btTransform::getIdentity());
    btCollisionObjectWrapper wb(nullptr, mesh, &b, b.getWorldTransform(), -1, -1);
    btCollisionAlgorithm* algo = nullptr;
    btDispatcherInfo info;
    for (const btTransform& x : poses) {
        a.setWorldTransform(x);
        btCollisionObjectWrapper wa(nullptr, convex, &a, x, -1, -1);
        if (!algo) algo = dispatcher.findAlgorithm(&wa, &wb, nullptr, BT_CONTACT_POINT_ALGORITHMS);
        btManifoldResult result(&wa, &wb);
        algo->processCollision(&wa, &wb, info, &result);
    }
    std::vector<Point> out;
    btManifoldArray manifolds;
    algo->getAllContactManifolds(manifolds);
    for (int m = 0; m < manifolds.size(); ++m)
        for (int k = 0; k < manifolds[m]->getNumContacts(); ++k) {
            const btManifoldPoint& p = manifolds[m]->getContactPoint(k);
            out.push_back({p.getPositionWorldOnB(), p.m_normalWorldOnB, p.getDistance()});
        }
    algo->~btCollisionAlgorithm();
    dispatcher.freeCollisionAlgorithm(algo);
    return out;
}

// As many points as stock's, and each of stock's has one of ours of its normal and depth, within
// `place` of it (where a flat contact's GJK point lies is its path's choice, and which points a
// manifold then keeps follows from it: after several steps only normals and depths compare).
void expectStockPoints(const std::vector<Point>& stock, const std::vector<Point>& ours, float place)
{
    EXPECT_EQ(ours.size(), stock.size());
    for (const Point& sp : stock) {
        bool found = false;
        for (const Point& gp : ours)
            found = found || ((gp.onMesh - sp.onMesh).length() < place && gp.normal.dot(sp.normal) >= tol::kStockNormalDot &&
                              std::fabs(gp.distance - sp.distance) <= tol::kStockDepth);
        EXPECT_TRUE(found) << "stock point (" << sp.onMesh.x() << ", " << sp.onMesh.y() << ", " << sp.onMesh.z() << ") d "
                           << sp.distance << " has no match";
    }
}

// A pair's points from its manifolds (the mesh A), on the mesh with the normal towards the convex.
std::vector<Point> meshPoints(const std::vector<BtgManifold>& manifolds)
{
    PairResult r{manifolds};
    std::vector<int> manifoldOf;
    return gpuContact(r, &manifoldOf);
}

}  // namespace

// The bullet mode's convex–mesh manifold (shared/concave_manifold.h): boxes without polyhedral
// features and spheres on a flat and a curved mesh. A first step on the device equals the
// reference (the same shared functions) and holds stock's points (btConvexConcaveCollisionAlgorithm
// with the dispatcher's defaults: one point a triangle, GJK, reduced by sortCachedPoints); three
// steps of a body moving over the mesh, the manifold kept in between, hold stock's points too.
TEST(NarrowphaseMesh, PersistentManifoldAsStocksAlgorithm)
{
    btBoxShape box(btVector3(0.5f, 0.3f, 0.7f));  // no polyhedral features: GJK on stock
    btSphereShape sphere(0.4f);
    auto flat = BulletMesh::terrain(8, 1.0f, true);
    auto curved = BulletMesh::terrain(12, 0.5f, false);
    const BtgFloat4 tilt = axisAngle(btgMake4(1, 0, 1, 0), 0.5f);
    struct Pose {
        bool isBox;
        BtgFloat4 pos, rot;
        bool flat;  // a face on the mesh: every point of it is deepest, GJK's path picks one
    };
    for (int m = 0; m < 2; ++m) {
        const BulletMesh& mesh = m == 0 ? *flat : *curved;
        std::vector<Pose> poses = {{true, btgMake4(-1.7f, 0.295f, -1.3f, 0), kIdentity, true},
                                   {true, btgMake4(1.6f, 0.296f, 0.4f, 0), axisAngle(btgMake4(0, 1, 0, 0), 0.3f), true},
                                   {true, btgMake4(3.0f, 0.72f, -2.0f, 0), tilt, m == 1},
                                   {false, btgMake4(-2.5f, 0.392f, 0.5f, 0), kIdentity, false}};
        if (m == 1)
            for (Pose& p : poses) p.pos.y += BulletMesh::height(p.pos.x, p.pos.z) - (p.isBox ? 0.004f : 0.002f);
        MeshScene s;
        // The world's own rows of these shapes (the box's margin, its GJK core, as Bullet's).
        ::btgpu::ShapeTables rows;
        std::string why;
        const int sphereRow = int(s.t.shapes.size());
        s.t.shapes.push_back(rows.shapes[size_t(rows.add(&sphere, &why))]);
        const int boxRow = int(s.t.shapes.size());
        BtgShape boxShape = rows.shapes[size_t(rows.add(&box, &why))];
        boxShape.numFaces = boxShape.numEdges = 0;  // its hull's faces are the SAT's: GJK reads the box's size
        boxShape.numVertices = 0;
        s.t.shapes.push_back(boxShape);
        const int meshRow = s.addMesh(mesh.shape.get());
        s.body(meshRow, btgMake4(0, 0, 0, 0), kIdentity, BTG_BODY_STATIC);
        for (const Pose& p : poses) s.pairs.push_back(BtgPair{0, s.body(p.isBox ? boxRow : sphereRow, p.pos, p.rot, BTG_BODY_DYNAMIC)});
        std::vector<BtgPersistentManifold> states;
        std::vector<PairResult> dev = runDevice(s, true, &states);
        int touching = 0;
        for (size_t i = 0; i < poses.size(); ++i) {
            SCOPED_TRACE("mesh " + std::to_string(m) + " pose " + std::to_string(i));
            std::vector<BtgSubPair> sub = ref::referenceMidphase({int(i)}, s.pairs.data(), s.pos.data(), s.rot.data(),
                                                                 s.props.data(), s.t.shapes.data(), s.meshView(), nullptr, true);
            const BtgPersistentManifold none = btgEmptyPersistent(s.pairs[i].b, s.pairs[i].a, BTG_PAIR_NONE);
            ref::ConcavePairResult r = ref::referenceConcavePair(sub, int(i), s.pairs.data(), s.pos.data(), s.rot.data(),
                                                                 s.props.data(), s.t.view(), s.meshView(), none);
            ASSERT_EQ(dev[i].manifolds.size(), r.manifolds.size());
            for (size_t k = 0; k < r.manifolds.size(); ++k) expectSameManifold(dev[i].manifolds[k], r.manifolds[k]);
            EXPECT_EQ(states[i].numPoints, r.state.numPoints);
            EXPECT_EQ(states[i].bodyA, s.pairs[i].b);  // kept with the convex first
            btCollisionShape* shape = poses[i].isBox ? static_cast<btCollisionShape*>(&box) : &sphere;
            const std::vector<Point> stock = stockSteps(shape, {xf(poses[i].pos, poses[i].rot)}, mesh.shape.get());
            touching += !stock.empty();
            expectStockPoints(stock, meshPoints(dev[i].manifolds), poses[i].flat ? 1e9f : 2e-3f);
            // Two more steps, the body slid 3 mm and 6 mm along x and turned a little: the
            // reference keeps its manifold between them as the device does, stock its own.
            std::vector<btTransform> moved = {xf(poses[i].pos, poses[i].rot)};
            BtgPersistentManifold prev = r.state;
            for (int step = 1; step <= 2; ++step) {
                MeshScene t = s;
                t.pos[size_t(s.pairs[i].b)].x += 0.003f * float(step);
                t.rot[size_t(s.pairs[i].b)] = btgQuatMul(axisAngle(btgMake4(0, 1, 0, 0), 0.01f * float(step)), poses[i].rot);
                moved.push_back(xf(t.pos[size_t(s.pairs[i].b)], t.rot[size_t(s.pairs[i].b)]));
                std::vector<BtgSubPair> sub2 = ref::referenceMidphase({int(i)}, t.pairs.data(), t.pos.data(), t.rot.data(),
                                                                      t.props.data(), t.t.shapes.data(), t.meshView(), nullptr, true);
                r = ref::referenceConcavePair(sub2, int(i), t.pairs.data(), t.pos.data(), t.rot.data(), t.props.data(),
                                              t.t.view(), t.meshView(), prev);
                prev = r.state;
            }
            // Which points the manifold keeps then follows from where each step's points fell:
            // as many as stock's, the deepest as deep.
            const std::vector<Point> after = stockSteps(shape, moved, mesh.shape.get()), ours = meshPoints(r.manifolds);
            EXPECT_EQ(ours.size(), after.size());
            if (!after.empty() && !ours.empty())
                EXPECT_NEAR(ours[size_t(deepest(ours))].distance, after[size_t(deepest(after))].distance, tol::kStockDepth);
        }
        EXPECT_GE(touching, 3);
    }
}
