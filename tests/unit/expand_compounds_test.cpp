// expand_compounds_test.cpp — the expand_compounds stage against its CPU reference exactly
// (integer pair lists in the same order), its overflow protocol, and the contact sets of the
// leaf pairs against Bullet's own btCompoundCollisionAlgorithm run in the test for the same
// pose: one manifold per processed child with points, each named by its child index, stock's
// point count, every stock point matched by a GPU point within 1 degree and 1 mm (and children
// stock culls by ungrown boxes, which btgpu's grown tests keep, hold only points apart); two
// compounds against btCompoundCompoundCollisionAlgorithm by child pair.
#include "../compat/shape_tables.h"
#include "reference/expand_compounds.h"
#include "reference/narrowphase.h"
#include "shared/math.h"
#include "stages/expand_compounds.h"
#include "test_device.h"
#include "tolerances.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>

using namespace btgpu;

namespace {

BtgFloat4 f4(const btVector3& v) { return btgMake4(v.x(), v.y(), v.z(), 0); }
BtgFloat4 q4(const btQuaternion& q) { return btgMake4(q.x(), q.y(), q.z(), q.w()); }

// Bullet shapes and the GPU tables the world would build from them (compat's ShapeTables).
struct CompoundScene {
    btBoxShape ground{btVector3(50, 50, 50)};
    btBoxShape top{btVector3(btScalar(.6), btScalar(.05), btScalar(.4))};
    btBoxShape leg{btVector3(btScalar(.05), btScalar(.3), btScalar(.05))};
    btBoxShape bar{btVector3(btScalar(.5), btScalar(.08), btScalar(.08))};
    btBoxShape crate{btVector3(btScalar(.3), btScalar(.3), btScalar(.3))};
    btSphereShape ball{btScalar(.3)};
    btCapsuleShape capsule{btScalar(.2), btScalar(.6)};
    btStaticPlaneShape plane{btVector3(0, 1, 0), 0};
    btCompoundShape table, dumbbell, noTree{false}, nested;
    ShapeTables tables;
    std::vector<BtgFloat4> pos, rot;
    std::vector<BtgBodyProps> props;
    std::vector<btCollisionShape*> bulletShape;
    std::vector<btTransform> transform;

    CompoundScene()
    {
        btTransform t = btTransform::getIdentity();
        t.setOrigin(btVector3(0, btScalar(.35), 0));
        table.addChildShape(t, &top);
        for (int i = 0; i < 4; ++i) {
            t.setOrigin(btVector3(btScalar((i & 1) ? .5 : -.5), 0, btScalar((i & 2) ? .3 : -.3)));
            table.addChildShape(t, &leg);
        }
        t.setOrigin(btVector3(btScalar(-.5), 0, 0));
        dumbbell.addChildShape(t, &ball);
        t.setOrigin(btVector3(btScalar(.5), 0, 0));
        dumbbell.addChildShape(t, &ball);
        dumbbell.addChildShape(btTransform::getIdentity(), &bar);
        t.setOrigin(btVector3(0, btScalar(-.3), btScalar(.2)));
        t.setRotation(btQuaternion(btVector3(0, 0, 1), btScalar(1.2)));
        noTree.addChildShape(t, &capsule);
        t.setOrigin(btVector3(btScalar(.4), btScalar(.1), 0));
        noTree.addChildShape(t, &crate);
        // A table turned about y and a dumbbell under it, in one compound.
        t = btTransform(btQuaternion(btVector3(0, 1, 0), btScalar(.5)), btVector3(0, btScalar(.3), 0));
        nested.addChildShape(t, &table);
        t = btTransform(btQuaternion(btVector3(0, 0, 1), btScalar(.2)), btVector3(btScalar(.2), btScalar(-.4), 0));
        nested.addChildShape(t, &dumbbell);
    }
    int add(btCollisionShape* shape, const btTransform& tr, uint flags)
    {
        std::string why;
        const int row = tables.add(shape, &why);
        EXPECT_GE(row, 0) << why;
        BtgBodyProps p{};
        p.shape = row;
        p.flags = flags;
        props.push_back(p);
        pos.push_back(f4(tr.getOrigin()));
        rot.push_back(q4(tr.getRotation()));
        bulletShape.push_back(shape);
        transform.push_back(tr);
        return int(props.size()) - 1;
    }
    ref::ShapeTablesView view() const
    {
        ref::ShapeTablesView v;
        v.shapes = tables.shapes.data();
        v.hullVertices = tables.vertices.data();
        v.hullFaces = tables.faces.data();
        v.hullIndices = tables.indices.data();
        v.hullEdges = tables.edges.data();
        v.children = tables.children.data();
        return v;
    }
};

btTransform pose(float x, float y, float z, const btQuaternion& q = btQuaternion::getIdentity())
{
    btTransform t(q, btVector3(x, y, z));
    return t;
}

// Compounds scattered over a ground box and a plane among spheres, boxes and capsules; every
// pair of a compound with another body (the broadphase's list, sorted by (a, b)).
CompoundScene scatteredScene(unsigned seed, std::vector<BtgPair>* pairs)
{
    CompoundScene s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> xz(-2.0f, 2.0f), y(0.0f, 1.5f), angle(-3.14f, 3.14f);
    auto randomPose = [&] {
        btQuaternion q(btVector3(xz(rng), xz(rng) + 0.1f, xz(rng)).normalized(), angle(rng));
        return pose(xz(rng), y(rng), xz(rng), q);
    };
    s.add(&s.ground, pose(0, -50, 0), BTG_BODY_STATIC);
    s.add(&s.plane, pose(0, -0.5f, 0), BTG_BODY_STATIC);
    btCollisionShape* pool[] = {&s.table, &s.dumbbell, &s.noTree, &s.nested, &s.ball, &s.crate, &s.capsule};
    for (int i = 0; i < 35; ++i) s.add(pool[i % 7], randomPose(), BTG_BODY_DYNAMIC);
    for (int a = 0; a < int(s.props.size()); ++a)
        for (int b = a + 1; b < int(s.props.size()); ++b) {
            const bool ca = s.tables.shapes[size_t(s.props[size_t(a)].shape)].type == BTG_SHAPE_COMPOUND;
            const bool cb = s.tables.shapes[size_t(s.props[size_t(b)].shape)].type == BTG_SHAPE_COMPOUND;
            if (ca != cb) pairs->push_back(BtgPair{a, b, BTG_WHOLE_BODY, BTG_WHOLE_BODY});
        }
    return s;
}

struct DeviceResult {
    std::vector<BtgPair> pairs;
    uint total = 0, status = 0;
};

// found: the broadphase's count (more than capacity: it overflowed; 0: the pairs that fit).
// speculative: the soft step's grown culling tests (compound.h), else the bullet mode's stock ones.
DeviceResult runExpand(const CompoundScene& s, const std::vector<BtgPair>& pairs, size_t capacity, uint found = 0,
                       bool speculative = true)
{
    cl::Context& ctx = test::context();
    DeviceWorld w(ctx);
    w.speculativeContacts = speculative;
    w.numBodies = int(s.pos.size());
    w.pos.upload(ctx, s.pos);
    w.rot.upload(ctx, s.rot);
    w.props.upload(ctx, s.props);
    w.shapes.upload(ctx, s.tables.shapes);
    w.children.upload(ctx, s.tables.children);
    w.hullVertices.upload(ctx, s.tables.vertices);
    w.pairCapacity = capacity;
    std::vector<BtgPair> padded = pairs;
    padded.resize(std::max(capacity, pairs.size()), BtgPair{});
    padded.resize(capacity);
    w.pairs.upload(ctx, padded);
    w.pairManifolds.reserveExact(ctx, capacity);
    std::vector<uint> counters(kNumCounters, 0);
    counters[kPairCount] = found ? found : uint(std::min(pairs.size(), capacity));
    w.counters.upload(ctx, counters);
    expandCompounds(w, PairKinds());
    DeviceResult r;
    std::vector<uint> c = w.counters.download(ctx, kNumCounters);
    r.total = c[kPairCount];
    r.status = c[kStatus];
    r.pairs = w.pairs.download(ctx, std::min<size_t>(r.total, capacity));
    return r;
}

}  // namespace

TEST(ExpandCompounds, MatchesReferenceExactly)
{
    std::vector<BtgPair> pairs;
    CompoundScene s = scatteredScene(5, &pairs);
    const std::vector<BtgPair> ref = ref::referenceExpandCompounds(pairs, s.pos.data(), s.rot.data(), s.props.data(),
                                                                   s.tables.shapes.data(), s.tables.children.data());
    // The culling really culls, and really keeps leaves (the plane keeps every one).
    EXPECT_GT(ref.size(), 60u);
    EXPECT_LT(ref.size(), pairs.size() * 5);
    const DeviceResult dev = runExpand(s, pairs, std::max(ref.size(), pairs.size()) + 16);
    EXPECT_EQ(dev.status & BTG_STATUS_PAIR_OVERFLOW, 0u);
    ASSERT_EQ(dev.total, ref.size());
    for (size_t i = 0; i < ref.size(); ++i) {
        SCOPED_TRACE("pair " + std::to_string(i));
        EXPECT_EQ(dev.pairs[i].a, ref[i].a);
        EXPECT_EQ(dev.pairs[i].b, ref[i].b);
        EXPECT_EQ(dev.pairs[i].childA, ref[i].childA);
        EXPECT_EQ(dev.pairs[i].childB, ref[i].childB);
    }
    // Still sorted by (a, b), each pair's leaves in child order; every leaf pair names one leaf.
    for (size_t i = 1; i < ref.size(); ++i) {
        const BtgPair p = ref[i - 1], q = ref[i];
        EXPECT_TRUE(p.a < q.a || (p.a == q.a && p.b < q.b) ||
                    (p.a == q.a && p.b == q.b && p.childA + p.childB < q.childA + q.childB));
    }
    for (const BtgPair& p : ref) EXPECT_TRUE((p.childA == BTG_WHOLE_BODY) != (p.childB == BTG_WHOLE_BODY));
}

// The bullet mode culls leaves as stock's btCompoundCollisionAlgorithm does (ungrown boxes): a
// leaf whose box is within the pair's threshold of the other body's but apart is a leaf pair of
// the soft step's (its speculative points) and not of the bullet mode's. Grown there too, a
// kinematic compound's turning arm met a ball a step before stock's and stopped it early.
TEST(ExpandCompounds, TheBulletModeCullsWithStocksBoxes)
{
    std::vector<BtgPair> pairs;
    CompoundScene s = scatteredScene(5, &pairs);
    for (bool speculative : {true, false}) {
        SCOPED_TRACE(speculative ? "soft step" : "bullet mode");
        const std::vector<BtgPair> ref = ref::referenceExpandCompounds(pairs, s.pos.data(), s.rot.data(), s.props.data(),
                                                                       s.tables.shapes.data(), s.tables.children.data(),
                                                                       speculative);
        const DeviceResult dev = runExpand(s, pairs, std::max(ref.size(), pairs.size()) + 16, 0, speculative);
        ASSERT_EQ(dev.total, ref.size());
        for (size_t i = 0; i < ref.size(); ++i) {
            EXPECT_EQ(dev.pairs[i].a, ref[i].a) << i;
            EXPECT_EQ(dev.pairs[i].childA, ref[i].childA) << i;
            EXPECT_EQ(dev.pairs[i].childB, ref[i].childB) << i;
        }
    }
    // A table's legs 5 mm above the ground, within the pair's threshold (the table's, about 1.6
    // cm), apart.
    CompoundScene t;
    const int ground = t.add(&t.ground, pose(0, -50, 0), BTG_BODY_STATIC);
    const int table = t.add(&t.table, pose(0, 0.3f + 0.005f, 0), BTG_BODY_DYNAMIC);
    const std::vector<BtgPair> body = {BtgPair{ground, table, 0, 0}};
    const auto leaves = [&](bool speculative) {
        return ref::referenceExpandCompounds(body, t.pos.data(), t.rot.data(), t.props.data(), t.tables.shapes.data(),
                                             t.tables.children.data(), speculative)
            .size();
    };
    EXPECT_EQ(leaves(false), 0u) << "stock culls every leaf 5 mm away";
    EXPECT_GT(leaves(true), 0u) << "the soft step keeps the legs within its threshold";
}

TEST(ExpandCompounds, OverflowCountsOnAndRaisesTheStatusBit)
{
    // Against the plane every leaf is kept: more leaf pairs than body pairs.
    std::vector<BtgPair> all, pairs;
    CompoundScene s = scatteredScene(9, &all);
    for (const BtgPair& p : all)
        if (p.a == 1) pairs.push_back(p);
    const std::vector<BtgPair> ref = ref::referenceExpandCompounds(pairs, s.pos.data(), s.rot.data(), s.props.data(),
                                                                   s.tables.shapes.data(), s.tables.children.data());
    ASSERT_GT(ref.size(), pairs.size());
    const DeviceResult dev = runExpand(s, pairs, pairs.size());
    EXPECT_NE(dev.status & BTG_STATUS_PAIR_OVERFLOW, 0u);
    EXPECT_EQ(dev.total, ref.size());  // every leaf pair counted, for the growth
    for (size_t i = 0; i < dev.pairs.size(); ++i) EXPECT_EQ(dev.pairs[i].childA + dev.pairs[i].childB,
                                                            ref[i].childA + ref[i].childB);
    // The broadphase overflowed too (it found twice what was stored): the total is scaled up
    // so that one growth fits them all.
    const std::vector<BtgPair> half(pairs.begin(), pairs.begin() + long(pairs.size() / 2));
    const size_t halfLeaves = ref::referenceExpandCompounds(half, s.pos.data(), s.rot.data(), s.props.data(),
                                                            s.tables.shapes.data(), s.tables.children.data())
                                  .size();
    const DeviceResult both = runExpand(s, half, half.size(), uint(2 * half.size()));
    EXPECT_NE(both.status & BTG_STATUS_PAIR_OVERFLOW, 0u);
    EXPECT_EQ(both.total, uint(2 * halfLeaves));
}

namespace {

struct Point {
    btVector3 normal;  // from the other body towards the compound
    float distance;
};

// Stock Bullet's manifolds for (compound body, other body) at their poses: the dispatcher's own
// btCompoundCollisionAlgorithm, one frame; by child index.
std::map<int, std::vector<Point>> stockContacts(const CompoundScene& s, int compound, int other)
{
    static btDefaultCollisionConfiguration config;
    static btCollisionDispatcher dispatcher(&config);
    btCollisionObject a, b;
    a.setCollisionShape(s.bulletShape[size_t(compound)]);
    a.setWorldTransform(s.transform[size_t(compound)]);
    b.setCollisionShape(s.bulletShape[size_t(other)]);
    b.setWorldTransform(s.transform[size_t(other)]);
    btCollisionObjectWrapper wa(nullptr, a.getCollisionShape(), &a, a.getWorldTransform(), -1, -1);
    btCollisionObjectWrapper wb(nullptr, b.getCollisionShape(), &b, b.getWorldTransform(), -1, -1);
    btCollisionAlgorithm* algo = dispatcher.findAlgorithm(&wa, &wb, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    btManifoldResult result(&wa, &wb);
    btDispatcherInfo info;
    algo->processCollision(&wa, &wb, info, &result);
    std::map<int, std::vector<Point>> out;
    btManifoldArray manifolds;
    algo->getAllContactManifolds(manifolds);
    for (int m = 0; m < manifolds.size(); ++m) {
        const btPersistentManifold* pm = manifolds[m];
        const bool compoundIs0 = pm->getBody0() == &a;
        for (int k = 0; k < pm->getNumContacts(); ++k) {
            const btManifoldPoint& p = pm->getContactPoint(k);
            const int child = compoundIs0 ? p.m_index0 : p.m_index1;
            out[child].push_back({compoundIs0 ? p.m_normalWorldOnB : -p.m_normalWorldOnB, p.getDistance()});
        }
    }
    algo->~btCollisionAlgorithm();
    dispatcher.freeCollisionAlgorithm(algo);
    return out;
}

// The GPU's manifolds of the same pair: the reference expansion, then each leaf pair's
// routine (what the kernels run), by child index.
std::map<int, std::vector<Point>> gpuContacts(const CompoundScene& s, int compound, int other)
{
    const std::vector<BtgPair> pairs = {BtgPair{std::min(compound, other), std::max(compound, other), 0, 0}};
    const std::vector<BtgPair> leaves = ref::referenceExpandCompounds(
        pairs, s.pos.data(), s.rot.data(), s.props.data(), s.tables.shapes.data(), s.tables.children.data());
    std::map<int, std::vector<Point>> out;
    for (const BtgPair& p : leaves) {
        const BtgManifold m = ref::referenceContact(p, s.pos.data(), s.rot.data(), s.props.data(), s.view());
        const bool compoundIsA = p.a == compound;
        const int child = compoundIsA ? m.indexA : m.indexB;
        EXPECT_EQ(compoundIsA ? m.partIdA : m.partIdB, BTG_NO_SUB_SHAPE);
        for (int k = 0; k < m.numPoints; ++k) {
            const BtgManifoldPoint& q = m.points[k];
            const btVector3 n(q.nx, q.ny, q.nz);  // from B towards A
            out[child].push_back({compoundIsA ? n : -n, q.distance});
        }
    }
    return out;
}

// A nested compound's points carry Bullet's inner child index, which is not unique within the
// body: the manifolds are compared as a set (each stock manifold has a GPU one of its count
// whose points match).
void expectSameContactsAsSets(const CompoundScene& s, int compound, int other)
{
    static btDefaultCollisionConfiguration config;
    static btCollisionDispatcher dispatcher(&config);
    btCollisionObject a, b;
    a.setCollisionShape(s.bulletShape[size_t(compound)]);
    a.setWorldTransform(s.transform[size_t(compound)]);
    b.setCollisionShape(s.bulletShape[size_t(other)]);
    b.setWorldTransform(s.transform[size_t(other)]);
    btCollisionObjectWrapper wa(nullptr, a.getCollisionShape(), &a, a.getWorldTransform(), -1, -1);
    btCollisionObjectWrapper wb(nullptr, b.getCollisionShape(), &b, b.getWorldTransform(), -1, -1);
    btCollisionAlgorithm* algo = dispatcher.findAlgorithm(&wa, &wb, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    btManifoldResult result(&wa, &wb);
    btDispatcherInfo info;
    algo->processCollision(&wa, &wb, info, &result);
    std::vector<std::vector<Point>> stock;
    btManifoldArray manifolds;
    algo->getAllContactManifolds(manifolds);
    for (int m = 0; m < manifolds.size(); ++m) {
        const btPersistentManifold* pm = manifolds[m];
        if (pm->getNumContacts() == 0) continue;
        const bool compoundIs0 = pm->getBody0() == &a;
        stock.emplace_back();
        for (int k = 0; k < pm->getNumContacts(); ++k) {
            const btManifoldPoint& p = pm->getContactPoint(k);
            stock.back().push_back({compoundIs0 ? p.m_normalWorldOnB : -p.m_normalWorldOnB, p.getDistance()});
        }
    }
    algo->~btCollisionAlgorithm();
    dispatcher.freeCollisionAlgorithm(algo);
    const auto gpu = gpuContacts(s, compound, other);
    size_t touching = 0;  // GPU manifolds with a point not apart (stock's culling keeps those)
    for (const auto& [child, mine] : gpu) {
        bool t = false;
        for (const Point& q : mine) t |= q.distance <= 0.0f;
        touching += t;
    }
    EXPECT_EQ(touching, stock.size());
    EXPECT_FALSE(stock.empty());
    for (const std::vector<Point>& points : stock) {
        bool found = false;
        for (const auto& [child, mine] : gpu) {
            if (mine.size() != points.size()) continue;
            bool all = true;
            for (const Point& p : points) {
                bool matched = false;
                for (const Point& q : mine)
                    matched |= p.normal.dot(q.normal) >= tol::kStockNormalDot &&
                               std::fabs(p.distance - q.distance) <= tol::kStockDepth;
                all &= matched;
            }
            found |= all;
        }
        EXPECT_TRUE(found) << "a stock manifold of " << points.size() << " points has no GPU match";
    }
}

void expectSameContacts(const CompoundScene& s, int compound, int other)
{
    const auto stock = stockContacts(s, compound, other);
    const auto gpu = gpuContacts(s, compound, other);
    EXPECT_FALSE(stock.empty());
    for (const auto& [child, points] : stock) {
        SCOPED_TRACE("child " + std::to_string(child));
        auto it = gpu.find(child);
        ASSERT_NE(it, gpu.end()) << "stock has a manifold for this child, the GPU none";
        EXPECT_EQ(it->second.size(), points.size());
        for (const Point& p : points) {
            bool matched = false;
            for (const Point& q : it->second)
                matched |= p.normal.dot(q.normal) >= tol::kStockNormalDot &&
                           std::fabs(p.distance - q.distance) <= tol::kStockDepth;
            EXPECT_TRUE(matched) << "stock point of depth " << p.distance << " has no GPU match";
        }
    }
    // A child stock culls by its ungrown boxes may have GPU points (the tests are grown by the
    // threshold, compound.h): speculative ones only, apart, never touching.
    for (const auto& [child, points] : gpu)
        if (!stock.count(child))
            for (const Point& q : points) EXPECT_GT(q.distance, 0.0f) << "GPU child " << child << " only";
}

}  // namespace

namespace {

// Two compounds: stock's btCompoundCompoundCollisionAlgorithm against the leaf pairs' routines,
// by (child of the lower row, child of the higher row).
void expectSameCompoundCompoundContacts(const CompoundScene& s, int lo, int hi)
{
    static btDefaultCollisionConfiguration config;
    static btCollisionDispatcher dispatcher(&config);
    btCollisionObject a, b;
    a.setCollisionShape(s.bulletShape[size_t(lo)]);
    a.setWorldTransform(s.transform[size_t(lo)]);
    b.setCollisionShape(s.bulletShape[size_t(hi)]);
    b.setWorldTransform(s.transform[size_t(hi)]);
    btCollisionObjectWrapper wa(nullptr, a.getCollisionShape(), &a, a.getWorldTransform(), -1, -1);
    btCollisionObjectWrapper wb(nullptr, b.getCollisionShape(), &b, b.getWorldTransform(), -1, -1);
    btCollisionAlgorithm* algo = dispatcher.findAlgorithm(&wa, &wb, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    btManifoldResult result(&wa, &wb);
    btDispatcherInfo info;
    algo->processCollision(&wa, &wb, info, &result);
    std::map<std::pair<int, int>, std::vector<Point>> stock, gpu;
    btManifoldArray manifolds;
    algo->getAllContactManifolds(manifolds);
    for (int m = 0; m < manifolds.size(); ++m) {
        const btPersistentManifold* pm = manifolds[m];
        const bool loIs0 = pm->getBody0() == &a;
        for (int k = 0; k < pm->getNumContacts(); ++k) {
            const btManifoldPoint& p = pm->getContactPoint(k);
            const std::pair<int, int> key = loIs0 ? std::make_pair(p.m_index0, p.m_index1)
                                                  : std::make_pair(p.m_index1, p.m_index0);
            stock[key].push_back({loIs0 ? p.m_normalWorldOnB : -p.m_normalWorldOnB, p.getDistance()});
        }
    }
    algo->~btCollisionAlgorithm();
    dispatcher.freeCollisionAlgorithm(algo);
    const std::vector<BtgPair> leaves = ref::referenceExpandCompounds(
        {BtgPair{lo, hi, 0, 0}}, s.pos.data(), s.rot.data(), s.props.data(), s.tables.shapes.data(),
        s.tables.children.data());
    for (const BtgPair& p : leaves) {
        EXPECT_TRUE(p.childA != BTG_WHOLE_BODY && p.childB != BTG_WHOLE_BODY);
        const BtgManifold m = ref::referenceContact(p, s.pos.data(), s.rot.data(), s.props.data(), s.view());
        for (int k = 0; k < m.numPoints; ++k) {
            const BtgManifoldPoint& q = m.points[k];
            // normal from B (hi) towards A (lo): stock's from the other (hi) towards lo's body 0
            gpu[{m.indexA, m.indexB}].push_back({btVector3(q.nx, q.ny, q.nz), q.distance});
        }
    }
    EXPECT_FALSE(stock.empty());
    for (const auto& [key, points] : stock) {
        SCOPED_TRACE("children " + std::to_string(key.first) + ", " + std::to_string(key.second));
        auto it = gpu.find(key);
        ASSERT_NE(it, gpu.end()) << "stock has a manifold for this child pair, the GPU none";
        EXPECT_EQ(it->second.size(), points.size());
        for (const Point& p : points) {
            bool matched = false;
            for (const Point& q : it->second)
                matched |= p.normal.dot(q.normal) >= tol::kStockNormalDot &&
                           std::fabs(p.distance - q.distance) <= tol::kStockDepth;
            EXPECT_TRUE(matched) << "stock point of depth " << p.distance << " has no GPU match";
        }
    }
    for (const auto& [key, points] : gpu)
        if (!stock.count(key))
            for (const Point& q : points) EXPECT_GT(q.distance, 0.0f) << "GPU child pair only";
}

}  // namespace

// A table standing 2 mm into the top of another (legs on the top), one turned about y; and a
// dumbbell lying 2 mm into a table's top.
TEST(ExpandCompounds, CompoundPairsMatchBulletsCompoundCompoundAlgorithm)
{
    CompoundScene s;
    const int lower = s.add(&s.table, pose(0, 0.3f, 0), BTG_BODY_DYNAMIC);
    const int upper = s.add(&s.table, pose(0, 0.3f + 0.7f - 0.002f, 0), BTG_BODY_DYNAMIC);
    const int turned = s.add(&s.table, pose(5, 0.3f, 0), BTG_BODY_DYNAMIC);
    const int onTurned =
        s.add(&s.table, pose(5, 0.3f + 0.7f - 0.002f, 0, btQuaternion(btVector3(0, 1, 0), btScalar(0.3))), BTG_BODY_DYNAMIC);
    const int bell = s.add(&s.dumbbell, pose(0, 0.4f + 0.3f + 0.3f - 0.002f, 0.1f), BTG_BODY_DYNAMIC);
    {
        SCOPED_TRACE("table on a table");
        expectSameCompoundCompoundContacts(s, lower, upper);
    }
    {
        SCOPED_TRACE("turned table on a table");
        expectSameCompoundCompoundContacts(s, turned, onTurned);
    }
    {
        SCOPED_TRACE("dumbbell on a table");
        expectSameCompoundCompoundContacts(s, lower, bell);
    }
}

TEST(ExpandCompounds, ContactsMatchBulletsCompoundAlgorithm)
{
    CompoundScene s;
    const int ground = s.add(&s.ground, pose(0, -50, 0), BTG_BODY_STATIC);
    const int plane = s.add(&s.plane, pose(0, 0, 0), BTG_BODY_STATIC);
    // A table sinking 3 mm flat, one tipped by 2 degrees (two legs down), a dumbbell on its
    // balls turned about y, a compound without a tree (a capsule and a box) touching.
    const int flat = s.add(&s.table, pose(0, 0.297f, 0), BTG_BODY_DYNAMIC);
    const int tipped = s.add(&s.table, pose(3, 0.3f, 0, btQuaternion(btVector3(0, 0, 1), btScalar(0.035))), BTG_BODY_DYNAMIC);
    const int bell = s.add(&s.dumbbell, pose(-3, 0.298f, 0, btQuaternion(btVector3(0, 1, 0), btScalar(0.7))), BTG_BODY_DYNAMIC);
    const int loose = s.add(&s.noTree, pose(0, 0.604f, 3), BTG_BODY_DYNAMIC);
    // The nested one: the dumbbell's lower ball 2 mm into the ground (its table stands higher).
    const int deep = s.add(&s.nested, pose(-3, 0.0f, 3), BTG_BODY_DYNAMIC);
    for (int c : {flat, tipped, bell, loose})
        for (int o : {ground, plane}) {
            SCOPED_TRACE("compound body " + std::to_string(c) + " on body " + std::to_string(o));
            expectSameContacts(s, c, o);
        }
    {
        // The lowest point: the bottom of the dumbbell's lower ball (turned 0.2 rad about z at
        // y = -0.4), sunk 2 mm.
        const float lowest = -0.4f - 0.5f * std::sin(0.2f) - 0.3f;
        const btTransform t = pose(-3, -lowest - 0.002f, 3);
        s.transform[size_t(deep)] = t;
        s.pos[size_t(deep)] = f4(t.getOrigin());
    }
    for (int o : {ground, plane}) {
        SCOPED_TRACE("nested compound on body " + std::to_string(o));
        expectSameContactsAsSets(s, deep, o);
    }
    // A sphere and a box meeting a table's top from above and a leg from beside, 2 mm deep
    // (stock culls a child whose box only comes within the threshold: no contact at all).
    const int ball = s.add(&s.ball, pose(0.1f, 0.697f + 0.3f - 0.002f, 0), BTG_BODY_DYNAMIC);
    const int crate = s.add(&s.crate, pose(0.5f + 0.05f + 0.3f - 0.002f, 0.25f, 0.3f), BTG_BODY_DYNAMIC);
    {
        SCOPED_TRACE("sphere on a table top");
        expectSameContacts(s, flat, ball);
    }
    {
        SCOPED_TRACE("box beside a table's leg");
        expectSameContacts(s, flat, crate);
    }
}
