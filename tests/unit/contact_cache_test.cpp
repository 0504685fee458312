// contact_cache_test.cpp — the contacts stage: compaction of the pairs' manifold ranges is
// exactly the reference's (pair order, counts, overflow flag, the manifold of each contact,
// pairs of several manifolds), warm starting keeps the impulse (times the factor) of a point
// that moved less than the contact threshold in A's frame, and only of such a point, from the
// cached manifold of the same sub-shape keys, and the cache store keeps exactly the keys,
// impulses and ids the next warm start reads, leaving the cache alone when the substep
// overflowed; the soft step's store (through its rows' storage) leaves the same cache.
#include "contact_fixture.h"
#include "stages/contact_cache.h"
#include "test_device.h"
#include "tolerances.h"

#include <algorithm>
#include <cstring>
#include <gtest/gtest.h>
#include <random>

using namespace btgpu;

namespace {

ref::ContactBodies randomBodies(int n, std::mt19937& rng)
{
    std::uniform_real_distribution<float> u(-5.0f, 5.0f);
    ref::ContactBodies b;
    for (int i = 0; i < n; ++i) {
        test::addBody(b, btgMake4(u(rng), u(rng), u(rng), 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC);
        b.rot.back() = btgQuatNormalize(btgMake4(u(rng), u(rng), u(rng), u(rng)));
    }
    return b;
}

std::vector<BtgManifold> randomManifolds(int slots, int numBodies, std::mt19937& rng)
{
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<BtgManifold> ms(slots);
    for (int i = 0; i < slots; ++i) {
        const int bodyA = int(rng() % numBodies);
        BtgManifold& m = ms[i] = btgEmptyManifold(bodyA, (bodyA + 1 + int(rng() % (numBodies - 1))) % numBodies);
        m.breakingThreshold = 0.02f;
        const int points = (rng() % 10) < 3 ? 1 + int(rng() % 4) : 0;
        const BtgFloat4 normal = btgNormalize3(btgMake4(u(rng), u(rng), u(rng), 0));
        for (int k = 0; k < points; ++k)
            btgAddPoint(&m, normal, btgMake4(u(rng), u(rng), u(rng), 0), 0.01f * u(rng), BTG_FEATURE_VERTEX | uint(k));
    }
    return ms;
}

void expectSameContact(const BtgContact& d, const BtgContact& r, int i)
{
    ASSERT_EQ(d.bodyA, r.bodyA) << i;
    ASSERT_EQ(d.bodyB, r.bodyB) << i;
    ASSERT_EQ(d.numPoints, r.numPoints) << i;
    for (int k = 0; k < r.numPoints; ++k) {
        for (int e = 0; e < 4; ++e) {
            EXPECT_NEAR(btgLane(d.rA[k], e), btgLane(r.rA[k], e), tol::kStageAbs) << i;
            EXPECT_NEAR(btgLane(d.rB[k], e), btgLane(r.rB[k], e), tol::kStageAbs) << i;
        }
        EXPECT_EQ(btgLane(d.separation, k), btgLane(r.separation, k)) << i;
        EXPECT_NEAR(btgLane(d.normalImpulse, k), btgLane(r.normalImpulse, k), tol::kStageAbs) << i;
        EXPECT_NEAR(btgLane(d.friction1Impulse, k), btgLane(r.friction1Impulse, k), tol::kStageAbs) << i;
    }
}

}  // namespace


namespace {
// The warm-start cache as the previous substep left it: its entries and their count.
void uploadCache(DeviceWorld& w, const std::vector<BtgCachedContact>& cache)
{
    w.contactCache.upload(w.ctx, cache);
    std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    counters[kPrevContactCount] = uint(cache.size());
    w.counters.upload(w.ctx, counters);
}
}  // namespace

TEST(ContactCache, CompactionMatchesReference)
{
    std::mt19937 rng(7);
    ref::ContactBodies bodies = randomBodies(40, rng);
    std::vector<BtgManifold> ms = randomManifolds(1000, 40, rng);  // several scan blocks
    uint pairCount = 900;                                          // slots past the count are stale
    BtgStepParams params = test::defaultParams(40);
    std::vector<BtgContact> expect = ref::buildContacts(ms, int(pairCount), bodies, {}, params);
    ASSERT_GT(expect.size(), 200u);

    DeviceWorld w(test::context());
    test::uploadWorld(w, bodies, ms, pairCount, {}, 1000);
    buildContacts(w, params);
    std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    EXPECT_EQ(counters[kContactCount], expect.size());
    EXPECT_EQ(counters[kStatus] & BTG_STATUS_CONTACT_OVERFLOW, 0u);
    std::vector<BtgContact> got = test::downloadContacts(w);
    ASSERT_EQ(got.size(), expect.size());
    for (size_t i = 0; i < got.size(); ++i) expectSameContact(got[i], expect[i], int(i));
    // Each contact names the manifold it came from (one per pair: the pair's slot).
    std::vector<uint> from = w.contactManifolds.download(w.ctx, got.size());
    for (size_t i = 0; i < got.size(); ++i) {
        EXPECT_GT(ms[from[i]].numPoints, 0);
        EXPECT_EQ(ms[from[i]].bodyA, got[i].bodyA);
        if (i > 0) EXPECT_LT(from[i - 1], from[i]);
    }
}

TEST(ContactCache, OverflowIsFlaggedAndCounted)
{
    std::mt19937 rng(11);
    ref::ContactBodies bodies = randomBodies(10, rng);
    std::vector<BtgManifold> ms = randomManifolds(300, 10, rng);
    BtgStepParams params = test::defaultParams(10);
    std::vector<BtgContact> expect = ref::buildContacts(ms, 300, bodies, {}, params);
    DeviceWorld w(test::context());
    test::uploadWorld(w, bodies, ms, 300, {}, 20);
    buildContacts(w, params);
    std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    EXPECT_EQ(counters[kContactCount], expect.size());  // the full count, so the host can grow
    EXPECT_NE(counters[kStatus] & BTG_STATUS_CONTACT_OVERFLOW, 0u);
    std::vector<BtgContact> got = w.contacts.download(w.ctx, 20);
    for (size_t i = 0; i < 20; ++i) expectSameContact(got[i], expect[i], int(i));
}

TEST(ContactCache, WarmStartMatchesNearPointsOnly)
{
    ref::ContactBodies bodies;
    BtgFloat4 boxPos = btgMake4(0, 0.5f, 0, 0);
    int ground = test::addBody(bodies, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC);
    int box = test::addBody(bodies, boxPos, 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC);
    int other = test::addBody(bodies, btgMake4(3, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC);
    int third = test::addBody(bodies, btgMake4(6, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC);
    BtgStepParams params = test::defaultParams(4);

    // Last step's contacts (pair order): (ground, box), (ground, other), (ground, third).
    std::vector<BtgContact> prev;
    for (int body : {box, other, third}) {
        BtgManifold m = test::boxOnPlane(body, ground, bodies.pos[body], 0.5f, 0.0f);
        BtgContact c = btgContactFromManifold(m, bodies.pos[body], bodies.pos[ground]);
        c.normalImpulse = btgMake4(1, 2, 3, 4);
        c.friction1Impulse = btgMake4(0.1f, 0.2f, 0.3f, 0.4f);
        c.friction2Impulse = btgMake4(-0.1f, -0.2f, -0.3f, -0.4f);
        prev.push_back(c);
    }
    // This step: the box's corners 0 and 1 moved 5 mm (kept), corner 2 moved 10 cm (lost),
    // corner 3 unchanged; `third` has no previous contact with body 1 (different pair).
    BtgManifold now = test::boxOnPlane(box, ground, boxPos, 0.5f, 0.0f);
    now.points[0].px += 0.005f;
    now.points[1].pz -= 0.005f;
    now.points[2].px += 0.1f;
    BtgManifold unrelated = test::boxOnPlane(third, box, bodies.pos[third], 0.5f, 0.0f);
    std::vector<BtgManifold> ms = {now, btgEmptyManifold(0, 0), unrelated};

    std::vector<BtgContact> expect = ref::buildContacts(ms, 3, bodies, prev, params);
    DeviceWorld w(test::context());
    test::uploadWorld(w, bodies, ms, 3, prev, 16);
    buildContacts(w, params);
    std::vector<BtgContact> got = test::downloadContacts(w);
    ASSERT_EQ(got.size(), 2u);
    for (size_t i = 0; i < got.size(); ++i) expectSameContact(got[i], expect[i], int(i));

    const float f = params.warmstartFactor;
    EXPECT_FLOAT_EQ(got[0].normalImpulse.x, 1 * f);
    EXPECT_FLOAT_EQ(got[0].normalImpulse.y, 2 * f);
    EXPECT_EQ(got[0].normalImpulse.z, 0.0f);
    EXPECT_FLOAT_EQ(got[0].normalImpulse.w, 4 * f);
    EXPECT_EQ(got[0].pushImpulse.x, 0.0f);
    // Bullet 3.24's rule: the friction impulses start at zero ...
    for (int k = 0; k < 4; ++k) EXPECT_EQ(btgLane(got[0].friction1Impulse, k), 0.0f);
    EXPECT_EQ(got[0].friction1Impulse.z, 0.0f);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(btgLane(got[1].normalImpulse, k), 0.0f);
    // Geometry: the point on A sits on the box's bottom face, at distance 0.
    EXPECT_NEAR(got[0].rA[3].y, -0.5f, 1e-6f);
    EXPECT_EQ(got[0].separation.w, 0.0f);
    EXPECT_NEAR(got[0].rB[3].x, -0.5f, 1e-6f);

    // ... and with BTG_SOLVER_WARM_FRICTION (the soft step) they continue as the normal ones do.
    params.solverFlags |= BTG_SOLVER_WARM_FRICTION;
    expect = ref::buildContacts(ms, 3, bodies, prev, params);
    DeviceWorld warm(test::context());
    test::uploadWorld(warm, bodies, ms, 3, prev, 16);
    buildContacts(warm, params);
    got = test::downloadContacts(warm);
    ASSERT_EQ(got.size(), 2u);
    for (size_t i = 0; i < got.size(); ++i) expectSameContact(got[i], expect[i], int(i));
    EXPECT_FLOAT_EQ(got[0].friction1Impulse.y, 0.2f * f);
    EXPECT_FLOAT_EQ(got[0].friction2Impulse.w, -0.4f * f);
    EXPECT_EQ(got[0].friction1Impulse.z, 0.0f);  // the lost corner starts afresh
}

TEST(ContactCache, StoreKeepsKeysImpulsesAndIds)
{
    std::mt19937 rng(5);
    ref::ContactBodies bodies = randomBodies(30, rng);
    std::vector<BtgManifold> ms = randomManifolds(600, 30, rng);
    for (size_t i = 0; i < ms.size(); ++i) ms[i].indexB = int(i % 7) - 1;  // some sub-shape keys
    BtgStepParams params = test::defaultParams(30);
    ref::BuiltContacts built = ref::buildContactsFromRanges(ref::oneManifoldPerPair(ms), ms, 600, bodies, {}, params);
    std::vector<BtgContact>& contacts = built.contacts;
    ASSERT_GT(contacts.size(), 100u);
    for (size_t i = 0; i < contacts.size(); ++i) {  // as a solve would leave them
        contacts[i].normalImpulse = btgMake4(float(i), 0.5f, 0.25f, 2.0f);
        contacts[i].friction1Impulse = btgMake4(-1, -2, -3, -4);
    }
    std::vector<BtgCachedContact> expect = ref::storeContactCache(contacts, built.manifoldOf, ms, bodies);

    // The soft step stores through its rows' dead storage and copies back (one cache buffer,
    // no second to swap with): the same cache.
    for (bool overSoftRows : {false, true}) {
        SCOPED_TRACE(overSoftRows ? "over the soft rows" : "swapped");
        DeviceWorld w(test::context());
        test::uploadWorld(w, bodies, ms, 600, {}, contacts.size());
        w.contacts.upload(w.ctx, contacts);
        w.contactManifolds.upload(w.ctx, built.manifoldOf);
        std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
        counters[kContactCount] = uint(contacts.size());
        w.counters.upload(w.ctx, counters);
        storeContactCache(w, true, overSoftRows);
        if (overSoftRows) EXPECT_EQ(w.contactCacheNext.capacity(), 0u);
        counters = w.counters.download(w.ctx, kNumCounters);
        ASSERT_EQ(counters[kPrevContactCount], contacts.size());
        std::vector<BtgCachedContact> got = w.contactCache.download(w.ctx, contacts.size());
        for (size_t i = 0; i < got.size(); ++i) {
            const BtgCachedContact &g = got[i], &e = expect[i];
            const BtgManifold& m = ms[built.manifoldOf[i]];
            ASSERT_EQ(g.bodyA, contacts[i].bodyA) << i;
            ASSERT_EQ(g.bodyB, contacts[i].bodyB) << i;
            ASSERT_EQ(g.numPoints, contacts[i].numPoints) << i;
            EXPECT_EQ(g.indexB, m.indexB) << i;
            EXPECT_EQ(g.partIdA, BTG_NO_SUB_SHAPE) << i;
            for (int k = 0; k < g.numPoints; ++k) {
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(btgLane(g.point[k], c), btgLane(e.point[k], c), tol::kStageAbs) << i;
                EXPECT_EQ(g.point[k].w, btgLane(contacts[i].normalImpulse, k)) << i;
                EXPECT_EQ(g.featureId[k], m.points[k].featureId) << i;
                // The key is the point on A in A's frame: rotated back, it is rA again.
                BtgFloat4 back = btgQuatRotate(bodies.rot[g.bodyA], g.point[k]);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(btgLane(back, c), btgLane(contacts[i].rA[k], c), 1e-5f) << i;
            }
            EXPECT_EQ(g.friction1Impulse.y, -2.0f);
        }

        // An overflowed substep is redone from the cache as it was: the store leaves it alone.
        std::vector<BtgContact> other(contacts.begin(), contacts.begin() + 10);
        w.contacts.upload(w.ctx, other);
        counters[kContactCount] = 10;
        counters[kStatus] = BTG_STATUS_CONTACT_OVERFLOW;
        w.counters.upload(w.ctx, counters);
        storeContactCache(w, true, overSoftRows);
        std::vector<uint> after = w.counters.download(w.ctx, kNumCounters);
        EXPECT_EQ(after[kPrevContactCount], contacts.size());
        std::vector<BtgCachedContact> kept = w.contactCache.download(w.ctx, contacts.size());
        EXPECT_EQ(0, std::memcmp(kept.data(), got.data(), got.size() * sizeof(BtgCachedContact)));
    }
}

// Pairs that own several manifolds (what compounds and meshes will give): each pair's range
// compacts into consecutive contacts in range order, and each manifold warm-starts from the
// cached manifold of its own sub-shape keys, not from its pair's first.
TEST(ContactCache, SeveralManifoldsPerPair)
{
    std::mt19937 rng(17);
    const int numBodies = 20;
    ref::ContactBodies bodies = randomBodies(numBodies, rng);
    // Every body pair once, in (a, b) order as find_pairs leaves them; up to three manifolds
    // each (children 0..2 of A), the range holding those with points.
    std::vector<BtgManifold> ms;
    std::vector<BtgManifoldRange> ranges;
    std::vector<BtgManifold> pool = randomManifolds(3 * numBodies * numBodies, numBodies, rng);
    size_t next = 0;
    for (int a = 0; a < numBodies; ++a)
        for (int b = a + 1; b < numBodies; ++b) {
            BtgManifoldRange r{int(ms.size()), 0};
            for (int j = 0; j < 3; ++j) {
                BtgManifold m = pool[next++];
                m.bodyA = a;
                m.bodyB = b;
                m.indexA = j;
                if (m.numPoints == 0) continue;
                ms.push_back(m);
                ++r.count;
            }
            ranges.push_back(r);
        }
    const int pairs = int(ranges.size());
    ms.push_back(btgEmptyManifold(0, 1));  // a stale slot past every range
    BtgStepParams params = test::defaultParams(numBodies);
    // A previous step with the same manifolds and a distinct impulse per manifold.
    ref::BuiltContacts prev = ref::buildContactsFromRanges(ranges, ms, pairs, bodies, {}, params);
    ASSERT_GT(prev.contacts.size(), size_t(pairs) / 2);
    for (size_t i = 0; i < prev.contacts.size(); ++i) prev.contacts[i].normalImpulse = btgMake4(float(i + 1), 1, 1, 1);
    std::vector<BtgCachedContact> cache = ref::storeContactCache(prev.contacts, prev.manifoldOf, ms, bodies);

    ref::BuiltContacts expect = ref::buildContactsFromRanges(ranges, ms, pairs, bodies, cache, params);
    DeviceWorld w(test::context());
    test::uploadWorld(w, bodies, ms, uint(pairs), {}, expect.contacts.size() + 8);
    w.pairManifolds.upload(w.ctx, ranges);
    w.pairCapacity = ranges.size();  // pair slots, not manifold slots
    uploadCache(w, cache);
    buildContacts(w, params);
    std::vector<BtgContact> got = test::downloadContacts(w);
    ASSERT_EQ(got.size(), expect.contacts.size());
    EXPECT_EQ(w.contactManifolds.download(w.ctx, got.size()), expect.manifoldOf);
    for (size_t i = 0; i < got.size(); ++i) {
        expectSameContact(got[i], expect.contacts[i], int(i));
        // Each manifold found its own cached self (same pair, same child): impulse i + 1.
        EXPECT_FLOAT_EQ(got[i].normalImpulse.x, float(i + 1) * params.warmstartFactor) << i;
    }
}

namespace {
// A previous step's manifold of `box` on `ground` and its cache entry with the given impulses.
struct Warm {
    ref::ContactBodies bodies;
    int ground = 0, box = 0;
    BtgStepParams params = test::defaultParams(2);
    Warm()
    {
        ground = test::addBody(bodies, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC);
        box = test::addBody(bodies, btgMake4(0, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC);
    }
    // Points on the ground's top face (y = 0), touching (distance 0), with ids; threshold 3.5 mm
    // (a 0.1 m box's, as in BasicDemo).
    BtgManifold manifold(const std::vector<BtgFloat4>& xz, const std::vector<uint>& ids) const
    {
        BtgManifold m = btgEmptyManifold(box, ground);
        m.breakingThreshold = 0.0035f;
        for (size_t k = 0; k < xz.size(); ++k)
            btgAddPoint(&m, btgMake4(0, 1, 0, 0), btgMake4(xz[k].x, 0, xz[k].z, 0), 0.0f, ids[k]);
        return m;
    }
    std::vector<BtgCachedContact> cache(const BtgManifold& m, BtgFloat4 impulses) const
    {
        BtgContact c = btgContactFromManifold(m, bodies.pos[size_t(box)], bodies.pos[size_t(ground)]);
        c.normalImpulse = impulses;
        return ref::storeContactCache({c}, {0u}, {m}, bodies);
    }
    // The warm-started normal impulses of `now` from `cache`, on the device (checked against the
    // reference).
    BtgFloat4 warmStart(const BtgManifold& now, const std::vector<BtgCachedContact>& cache) const
    {
        std::vector<BtgContact> expect = ref::buildContactsFromCache({now}, 1, bodies, cache, params);
        DeviceWorld w(test::context());
        test::uploadWorld(w, bodies, {now}, 1, {}, 4);
        uploadCache(w, cache);
        buildContacts(w, params);
        std::vector<BtgContact> got = test::downloadContacts(w);
        EXPECT_EQ(got.size(), 1u);
        if (got.size() != 1u) return btgZero4();
        expectSameContact(got[0], expect[0], 0);
        return got[0].normalImpulse * (1.0f / params.warmstartFactor);
    }
};
const uint kCorner = BTG_FEATURE_CLIP | 0x0201u, kCrossing = BTG_FEATURE_CLIP | 0x8002u;
const uint kCornerB = BTG_FEATURE_CLIP | 0x0302u;
}  // namespace

// The cases where matching by distance alone warm-starts from the wrong point, as BasicDemo
// meets them (0.1 m boxes: a 3.5 mm breaking threshold). Clipping puts a face corner and the
// crossing of an edge with the other face's side 0.47 mm apart: by distance both took the
// corner's impulse, so the warm start pushed twice at one place; by identity the crossing,
// a new point, starts cold. And a corner that slid 2 mm towards another corner 3 mm away is
// nearer the other: by distance it took that corner's impulse, by identity its own.
TEST(ContactCache, WarmStartFollowsFeatureIds)
{
    Warm t;
    const BtgFloat4 p = btgMake4(0.05f, 0, 0.05f, 0);
    // One old corner (impulse 5); now the corner and a crossing 0.47 mm from it.
    BtgManifold old1 = t.manifold({p}, {kCorner});
    BtgManifold now1 = t.manifold({p + btgMake4(0.0001f, 0, 0, 0), p + btgMake4(0.00047f, 0, 0, 0)}, {kCorner, kCrossing});
    BtgFloat4 w1 = t.warmStart(now1, t.cache(old1, btgMake4(5, 0, 0, 0)));
    EXPECT_FLOAT_EQ(w1.x, 5.0f);
    EXPECT_EQ(w1.y, 0.0f) << "the crossing took the corner's impulse too";
    // Two old corners 3 mm apart (impulses 1 and 2); the first slid 2 mm towards the second.
    BtgManifold old2 = t.manifold({p, p + btgMake4(0.003f, 0, 0, 0)}, {kCorner, kCornerB});
    BtgManifold now2 = t.manifold({p + btgMake4(0.002f, 0, 0, 0)}, {kCorner});
    EXPECT_FLOAT_EQ(t.warmStart(now2, t.cache(old2, btgMake4(1, 2, 0, 0))).x, 1.0f);
    // Identity never reaches past the breaking threshold (Bullet's rule: a point that moved
    // further starts cold) ...
    BtgManifold now3 = t.manifold({p + btgMake4(0.004f, 0, 0, 0)}, {kCorner});
    EXPECT_EQ(t.warmStart(now3, t.cache(old1, btgMake4(5, 0, 0, 0))).x, 0.0f);
    // ... and a point whose id no old point has falls back to the nearest one within it.
    BtgManifold now4 = t.manifold({p + btgMake4(0.001f, 0, 0, 0)}, {kCrossing});
    EXPECT_FLOAT_EQ(t.warmStart(now4, t.cache(old1, btgMake4(5, 0, 0, 0))).x, 5.0f);
    // An old point an identity match took is not also some other point's nearest.
    BtgManifold now5 = t.manifold({p + btgMake4(0.0002f, 0, 0, 0), p}, {kCrossing, kCorner});
    BtgFloat4 w5 = t.warmStart(now5, t.cache(old1, btgMake4(5, 0, 0, 0)));
    EXPECT_EQ(w5.x, 0.0f);
    EXPECT_FLOAT_EQ(w5.y, 5.0f);
}

// The search for a pair's cached entries from a hint (collide_persistent's runs of pairs on CPU
// devices) finds the same lower bound as the plain bisection, for hints below, at and past it,
// runs of equal pairs, both orientations of an entry and pairs absent from the cache; and leaves
// the hint at that bound.
TEST(ContactCache, SearchFromAHintFindsTheBisectionsEntry)
{
    std::mt19937 rng(20261206u);
    for (int trial = 0; trial < 200; ++trial) {
        const int n = int(rng() % 300);
        std::vector<std::pair<int, int>> keys;
        for (int i = 0; i < n; ++i) {
            int a = int(rng() % 60), b = int(rng() % 60);
            if (a == b) b = a + 1;
            keys.emplace_back(std::min(a, b), std::max(a, b));
        }
        std::sort(keys.begin(), keys.end());
        std::vector<BtgCachedContact> cache(size_t(std::max(n, 1)));
        for (int i = 0; i < n; ++i) {
            const bool flip = rng() & 1u;  // the entry's own orientation
            cache[size_t(i)].bodyA = flip ? keys[size_t(i)].second : keys[size_t(i)].first;
            cache[size_t(i)].bodyB = flip ? keys[size_t(i)].first : keys[size_t(i)].second;
        }
        for (int q = 0; q < 50; ++q) {
            int ka = int(rng() % 61), kb = int(rng() % 61);
            if (ka > kb) std::swap(ka, kb);
            const int want = btgCachedLowerBound(cache.data(), 0, n, ka, kb);
            int hint = int(rng() % unsigned(n + 3));  // anywhere, past the end included
            ASSERT_EQ(btgCachedLowerBoundNear(cache.data(), n, ka, kb, &hint), want) << trial << " " << q;
            EXPECT_EQ(hint, want);
            int none = -1;
            ASSERT_EQ(btgCachedLowerBoundNear(cache.data(), n, ka, kb, &none), want);
        }
    }
}
