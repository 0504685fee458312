// midphase_test.cpp — the midphase stage against its CPU reference exactly (integer sub-pair
// lists in the same order), against Bullet's own btBvhTriangleMeshShape::processAllTriangles for
// the same boxes (as sets of (part, triangle)), and its overflow protocol: past capacity it
// counts on and raises the status bit, writing nothing out of bounds.
#include "../compat/shape_tables.h"
#include "mesh_scene.h"
#include "reference/midphase.h"
#include "shared/math.h"
#include "stages/midphase.h"
#include "test_device.h"

#include <BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

using namespace btgpu;
using test::BulletMesh;
using test::MeshScene;

namespace {

const BtgFloat4 kIdentity = btgMake4(0, 0, 0, 1);

BtgFloat4 randomRotation(std::mt19937& rng)
{
    std::normal_distribution<float> g(0.0f, 1.0f);
    BtgFloat4 q = btgMake4(g(rng), g(rng), g(rng), g(rng));
    float l = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    return btgMake4(q.x / l, q.y / l, q.z / l, q.w / l);
}

// 60 spheres and boxes over (and into) a two-part terrain; the mesh is body 0 (so every pair
// has the mesh as A) and, with `meshLast`, the last body instead.
MeshScene terrainScene(const BulletMesh& mesh, bool meshLast, unsigned seed)
{
    MeshScene s;
    const int sphere = s.t.addSphere(0.4f), box = s.t.addBox(btgMake4(0.5f, 0.3f, 0.7f, 0));
    const int meshShape = s.addMesh(mesh.shape.get());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> x(-9.5f, 9.5f), z(-4.5f, 4.5f), y(-0.3f, 1.2f);
    if (!meshLast) s.body(meshShape, btgMake4(0, 0, 0, 0), kIdentity, BTG_BODY_STATIC);
    for (int i = 0; i < 60; ++i) {
        float px = x(rng), pz = z(rng);
        s.body(i % 2 ? box : sphere, btgMake4(px, BulletMesh::height(px, pz) + y(rng), pz, 0), randomRotation(rng),
               BTG_BODY_DYNAMIC);
    }
    if (meshLast) s.body(meshShape, btgMake4(0.2f, -0.1f, 0.3f, 0), btgMake4(0, 0.0998f, 0, 0.995f), BTG_BODY_KINEMATIC);
    const int meshBody = meshLast ? int(s.pos.size()) - 1 : 0;
    for (int i = 0; i < int(s.pos.size()); ++i)
        if (i != meshBody) s.pairs.push_back(meshLast ? BtgPair{i, meshBody} : BtgPair{meshBody, i});
    return s;
}

struct DeviceResult {
    std::vector<BtgSubPair> subPairs;
    uint total = 0, status = 0;
};

DeviceResult runMidphase(const MeshScene& s, size_t capacity)
{
    cl::Context& ctx = test::context();
    DeviceWorld w(ctx);
    s.upload(w, capacity);
    midphase(w);
    DeviceResult r;
    std::vector<uint> counters = w.counters.download(ctx, kNumCounters);
    r.total = counters[kSubPairCount];
    r.status = counters[kStatus];
    r.subPairs = w.subPairs.download(ctx, std::min<size_t>(r.total, w.subPairCapacity));
    return r;
}

void expectSame(const std::vector<BtgSubPair>& dev, const std::vector<BtgSubPair>& ref)
{
    ASSERT_EQ(dev.size(), ref.size());
    for (size_t i = 0; i < ref.size(); ++i) {
        SCOPED_TRACE("sub-pair " + std::to_string(i));
        EXPECT_EQ(dev[i].pair, ref[i].pair);
        EXPECT_EQ(dev[i].triangle, ref[i].triangle);
        EXPECT_EQ(dev[i].partId, ref[i].partId);
        EXPECT_EQ(dev[i].index, ref[i].index);
    }
}

// What Bullet's own walk reports for a mesh-local box.
struct Collect : btTriangleCallback {
    std::set<std::pair<int, int>> found;
    void processTriangle(btVector3*, int partId, int triangleIndex) override { found.insert({partId, triangleIndex}); }
};

}  // namespace

TEST(Midphase, MatchesReferenceOnATwoPartTerrain)
{
    auto mesh = BulletMesh::terrain(20, 0.5f, false);
    for (bool meshLast : {false, true}) {
        SCOPED_TRACE(meshLast ? "mesh is B, kinematic and turned" : "mesh is A");
        MeshScene s = terrainScene(*mesh, meshLast, 7);
        std::vector<BtgSubPair> ref = ref::referenceMidphase(s.meshSlots(), s.pairs.data(), s.pos.data(), s.rot.data(),
                                                             s.props.data(), s.t.shapes.data(), s.meshView());
        EXPECT_GT(ref.size(), 100u);  // the bodies really reach the terrain
        DeviceResult dev = runMidphase(s, 1 << 14);
        EXPECT_EQ(dev.status & BTG_STATUS_SUB_PAIR_OVERFLOW, 0u);
        EXPECT_EQ(dev.total, ref.size());
        expectSame(dev.subPairs, ref);
        std::set<int> parts;
        for (const BtgSubPair& p : ref) parts.insert(p.partId);
        EXPECT_EQ(parts.size(), 2u);  // both parts (16- and 32-bit indices) are walked
    }
}

TEST(Midphase, SameTrianglesAsBulletsOwnWalk)
{
    auto mesh = BulletMesh::terrain(20, 0.5f, false);
    MeshScene s = terrainScene(*mesh, false, 11);
    std::vector<int> slots = s.meshSlots();
    for (int slot : slots) {
        const BtgPair p = s.pairs[size_t(slot)];
        // The midphase's box, handed to Bullet's processAllTriangles: the same triangles.
        const BtgShape& convex = s.t.shapes[size_t(s.props[size_t(p.b)].shape)];
        const BtgShape& meshShape = s.t.shapes[size_t(s.props[size_t(p.a)].shape)];
        BtgAabb box = btgMidphaseBox(s.pos[size_t(p.b)], s.rot[size_t(p.b)], convex, s.pos[size_t(p.a)],
                                     s.rot[size_t(p.a)], meshShape, test::kTestBreakingThreshold);
        Collect c;
        mesh->shape->processAllTriangles(&c, btVector3(box.lo.x, box.lo.y, box.lo.z), btVector3(box.hi.x, box.hi.y, box.hi.z));
        std::set<std::pair<int, int>> ours;
        std::vector<BtgSubPair> one = ref::referenceMidphase({slot}, s.pairs.data(), s.pos.data(), s.rot.data(),
                                                             s.props.data(), s.t.shapes.data(), s.meshView());
        for (const BtgSubPair& sp : one) ours.insert({sp.partId, sp.index});
        EXPECT_EQ(ours, c.found) << "pair " << slot;
    }
}

TEST(Midphase, OverflowCountsOnAndRaisesTheStatus)
{
    auto mesh = BulletMesh::terrain(20, 0.5f, false);
    MeshScene s = terrainScene(*mesh, false, 3);
    std::vector<BtgSubPair> ref = ref::referenceMidphase(s.meshSlots(), s.pairs.data(), s.pos.data(), s.rot.data(),
                                                         s.props.data(), s.t.shapes.data(), s.meshView());
    ASSERT_GT(ref.size(), 300u);
    DeviceResult dev = runMidphase(s, 256);
    EXPECT_NE(dev.status & BTG_STATUS_SUB_PAIR_OVERFLOW, 0u);
    EXPECT_EQ(dev.total, ref.size());  // the full count, for the host to grow to
    ref.resize(256);
    expectSame(dev.subPairs, ref);  // what fits is written, in order
}

TEST(Midphase, AMeshIsStoredOnceWhateverUsesIt)
{
    // compat's tables: the mesh shape and a scaled wrapper of it are two shape rows of one mesh.
    auto mesh = BulletMesh::terrain(6, 1.0f, true);
    ShapeTables tables;
    std::string why;
    const int plain = tables.add(mesh->shape.get(), &why);
    ASSERT_GE(plain, 0) << why;
    const size_t triangles = tables.meshTables.triangles.size(), nodes = tables.meshTables.nodes.size();
    EXPECT_EQ(triangles, 2u * 2u * 36u);
    btScaledBvhTriangleMeshShape scaled(mesh->shape.get(), btVector3(2, 1, 2));
    const int wrapped = tables.add(&scaled, &why);
    ASSERT_GE(wrapped, 0) << why;
    EXPECT_NE(plain, wrapped);
    EXPECT_EQ(tables.add(mesh->shape.get(), &why), plain);  // a second body on the same shape
    EXPECT_EQ(tables.shapes[size_t(plain)].mesh, tables.shapes[size_t(wrapped)].mesh);
    EXPECT_EQ(tables.meshTables.meshes.size(), 1u);
    EXPECT_EQ(tables.meshTables.triangles.size(), triangles);
    EXPECT_EQ(tables.meshTables.nodes.size(), nodes);
    EXPECT_EQ(tables.shapes[size_t(wrapped)].param.x, 2.0f);
    EXPECT_EQ(tables.shapes[size_t(plain)].type, BTG_SHAPE_MESH);
}
