// midphase_test.cpp — the midphase stage against its CPU reference exactly (integer sub-pair
// lists in the same order), against Bullet's own processAllTriangles for the same boxes (a
// btBvhTriangleMeshShape: as sets of (part, triangle); a btHeightfieldTerrainShape of every height
// type, up axis and subdivision: the same cells and each triangle's vertices bit for bit), and its
// overflow protocol: past capacity it counts on and raises the status bit, writing nothing out of
// bounds. Meshes are stored once whatever uses them.
#include "../compat/shape_tables.h"
#include "mesh_scene.h"
#include "reference/midphase.h"
#include "shared/math.h"
#include "stages/midphase.h"
#include "test_device.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h>

#include <algorithm>
#include <array>
#include <map>
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

// `persistent`: the bullet mode's box (no threshold), else the soft step's (the reference's default).
DeviceResult runMidphase(const MeshScene& s, size_t capacity, bool persistent = false)
{
    cl::Context& ctx = test::context();
    DeviceWorld w(ctx);
    s.upload(w, capacity);
    w.speculativeContacts = !persistent;
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

namespace {

// What Bullet's own heightfield walk reports, with each triangle's vertices.
struct CollectTriangles : btTriangleCallback {
    std::map<std::pair<int, int>, std::array<btVector3, 3>> found;
    void processTriangle(btVector3* v, int partId, int index) override { found[{partId, index}] = {v[0], v[1], v[2]}; }
};

struct HeightfieldCase {
    PHY_ScalarType type;
    int upAxis;
    btVector3 scaling;
    bool flipQuadEdges, diamond, zigzag, flipWinding;
};

}  // namespace

TEST(Midphase, HeightfieldCellsAndTrianglesAsBullets)
{
    const int w = 17, l = 13;
    std::vector<float> f(w * l);
    std::vector<double> d(w * l);
    std::vector<short> s(w * l);
    std::vector<unsigned char> u(w * l);
    for (int y = 0; y < l; ++y)
        for (int x = 0; x < w; ++x) {
            float h = 1.5f * std::sin(0.4f * float(x)) * std::cos(0.3f * float(y)) + 0.2f * float(x % 3);
            f[size_t(y * w + x)] = h;
            d[size_t(y * w + x)] = double(h) + 1e-9;
            s[size_t(y * w + x)] = short(std::lround(h * 100.0f));
            u[size_t(y * w + x)] = (unsigned char)std::lround((h + 2.0f) * 50.0f);
        }
    const std::vector<HeightfieldCase> cases = {
        {PHY_FLOAT, 1, btVector3(1, 1, 1), false, false, false, false},
        {PHY_FLOAT, 1, btVector3(0.7f, 1.3f, 2.0f), true, false, false, false},
        {PHY_DOUBLE, 0, btVector3(1.2f, 0.5f, 0.8f), false, true, false, false},
        {PHY_SHORT, 2, btVector3(0.9f, 1.1f, 1.0f), false, false, true, true},
        {PHY_UCHAR, 1, btVector3(1, 1, 1), false, true, false, true},
        {PHY_FLOAT, 2, btVector3(-1.0f, 1.0f, 1.5f), false, false, false, true},
    };
    for (size_t ci = 0; ci < cases.size(); ++ci) {
        SCOPED_TRACE("heightfield case " + std::to_string(ci));
        const HeightfieldCase& c = cases[ci];
        const void* data = c.type == PHY_FLOAT ? static_cast<const void*>(f.data())
                           : c.type == PHY_DOUBLE ? static_cast<const void*>(d.data())
                           : c.type == PHY_SHORT  ? static_cast<const void*>(s.data())
                                                  : static_cast<const void*>(u.data());
        const float scale = c.type == PHY_SHORT ? 0.01f : c.type == PHY_UCHAR ? 0.02f : 1.0f;
        btHeightfieldTerrainShape hf(w, l, data, scale, -3.0f, 6.0f, c.upAxis, c.type, c.flipQuadEdges);
        hf.setUseDiamondSubdivision(c.diamond);
        hf.setUseZigzagSubdivision(c.zigzag);
        hf.setFlipTriangleWinding(c.flipWinding);
        hf.setLocalScaling(c.scaling);
        ShapeTables tables;
        std::string why;
        const int row = tables.add(&hf, &why);
        ASSERT_GE(row, 0) << why;
        MeshScene sc;
        const int sphere = sc.t.addSphere(0.6f), box = sc.t.addBox(btgMake4(0.8f, 0.4f, 1.1f, 0));
        BtgShape hs = tables.shapes[size_t(row)];
        sc.t.shapes.push_back(hs);
        const int hfShape = int(sc.t.shapes.size()) - 1;
        sc.heightfields = tables.meshTables.heightfields;
        sc.heights = tables.meshTables.heights;
        sc.body(hfShape, btgMake4(0.3f, -0.2f, 0.1f, 0), kIdentity, BTG_BODY_STATIC);
        std::mt19937 rng(unsigned(ci) + 1);
        std::uniform_real_distribution<float> a(-7.0f, 7.0f), up(-2.0f, 3.0f);
        for (int i = 0; i < 30; ++i) {
            BtgFloat4 p = btgMake4(a(rng), a(rng), a(rng), 0);
            if (c.upAxis == 0) p.x = up(rng);
            if (c.upAxis == 1) p.y = up(rng);
            if (c.upAxis == 2) p.z = up(rng);
            sc.body(i % 2 ? box : sphere, p, randomRotation(rng), BTG_BODY_DYNAMIC);
            sc.pairs.push_back(BtgPair{0, i + 1});
        }
        std::vector<BtgSubPair> ref = ref::referenceMidphase(sc.meshSlots(), sc.pairs.data(), sc.pos.data(), sc.rot.data(),
                                                             sc.props.data(), sc.t.shapes.data(), sc.meshView());
        // Bullet does not swap a box's ends under negative scaling, so that case finds fewer.
        EXPECT_GT(ref.size(), c.scaling.x() < 0 ? 10u : 50u);
        DeviceResult dev = runMidphase(sc, 1 << 14);
        EXPECT_EQ(dev.total, ref.size());
        expectSame(dev.subPairs, ref);
        // Bullet's processAllTriangles for each pair's box: the same triangles, bit for bit.
        for (size_t pi = 0; pi < sc.pairs.size(); ++pi) {
            const BtgPair p = sc.pairs[pi];
            BtgAabb q = btgMidphaseBox(sc.pos[size_t(p.b)], sc.rot[size_t(p.b)], sc.t.shapes[size_t(sc.props[size_t(p.b)].shape)],
                                       sc.pos[0], sc.rot[0], hs, test::kTestBreakingThreshold);
            CollectTriangles bullet;
            hf.processAllTriangles(&bullet, btVector3(q.lo.x, q.lo.y, q.lo.z), btVector3(q.hi.x, q.hi.y, q.hi.z));
            std::vector<BtgSubPair> ours = ref::referenceMidphase({int(pi)}, sc.pairs.data(), sc.pos.data(), sc.rot.data(),
                                                                  sc.props.data(), sc.t.shapes.data(), sc.meshView());
            ASSERT_EQ(ours.size(), bullet.found.size()) << "pair " << pi;
            for (const BtgSubPair& sp : ours) {
                auto it = bullet.found.find({sp.partId, sp.index});
                ASSERT_NE(it, bullet.found.end()) << "triangle " << sp.partId << "/" << sp.index;
                BtgTriangleVerts v = btgConcaveTriangle(hs, sp, nullptr, nullptr, nullptr, nullptr, nullptr,
                                                        sc.heightfields.data(), sc.heights.data());
                for (int k = 0; k < 3; ++k) {
                    EXPECT_EQ(v.v[k].x, it->second[size_t(k)].x());
                    EXPECT_EQ(v.v[k].y, it->second[size_t(k)].y());
                    EXPECT_EQ(v.v[k].z, it->second[size_t(k)].z());
                }
            }
        }
    }
}
