// contact_cache_test.cpp — the contacts stage: compaction is exactly the reference's (pair
// order, counts, overflow flag), warm starting keeps the impulse (times the factor) of a
// point that moved less than the contact threshold in A's frame, and only of such a point, and
// the cache store keeps exactly the keys and impulses the next warm start reads, leaving the
// cache alone when the substep overflowed.
#include "contact_fixture.h"
#include "stages/contact_cache.h"
#include "test_device.h"
#include "tolerances.h"

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
        BtgManifold& m = ms[i];
        m.bodyA = int(rng() % numBodies);
        m.bodyB = (m.bodyA + 1 + int(rng() % (numBodies - 1))) % numBodies;
        m.numPoints = (rng() % 10) < 3 ? 1 + int(rng() % 4) : 0;
        m.normal = btgNormalize3(btgMake4(u(rng), u(rng), u(rng), 0));
        for (int k = 0; k < BTG_MAX_POINTS; ++k) m.pointB[k] = btgMake4(u(rng), u(rng), u(rng), 0.01f * u(rng));
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
    now.pointB[0].x += 0.005f;
    now.pointB[1].z -= 0.005f;
    now.pointB[2].x += 0.1f;
    BtgManifold unrelated = test::boxOnPlane(third, box, bodies.pos[third], 0.5f, 0.0f);
    std::vector<BtgManifold> ms = {now, BtgManifold{}, unrelated};

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
#if BTG_WARMSTART_FRICTION
    EXPECT_FLOAT_EQ(got[0].friction1Impulse.y, 0.2f * f);
    EXPECT_FLOAT_EQ(got[0].friction2Impulse.w, -0.4f * f);
#endif
    EXPECT_EQ(got[0].friction1Impulse.z, 0.0f);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(btgLane(got[1].normalImpulse, k), 0.0f);
    // Geometry: the point on A sits on the box's bottom face, at distance 0.
    EXPECT_NEAR(got[0].rA[3].y, -0.5f, 1e-6f);
    EXPECT_EQ(got[0].separation.w, 0.0f);
    EXPECT_NEAR(got[0].rB[3].x, -0.5f, 1e-6f);
}

TEST(ContactCache, StoreKeepsKeysAndImpulses)
{
    std::mt19937 rng(5);
    ref::ContactBodies bodies = randomBodies(30, rng);
    std::vector<BtgManifold> ms = randomManifolds(600, 30, rng);
    BtgStepParams params = test::defaultParams(30);
    std::vector<BtgContact> contacts = ref::buildContacts(ms, 600, bodies, {}, params);
    ASSERT_GT(contacts.size(), 100u);
    for (size_t i = 0; i < contacts.size(); ++i) {  // as a solve would leave them
        contacts[i].normalImpulse = btgMake4(float(i), 0.5f, 0.25f, 2.0f);
        contacts[i].friction1Impulse = btgMake4(-1, -2, -3, -4);
    }
    std::vector<BtgCachedContact> expect = ref::storeContactCache(contacts, bodies);

    DeviceWorld w(test::context());
    test::uploadWorld(w, bodies, ms, 600, {}, contacts.size());
    w.contacts.upload(w.ctx, contacts);
    std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    counters[kContactCount] = uint(contacts.size());
    w.counters.upload(w.ctx, counters);
    storeContactCache(w);
    counters = w.counters.download(w.ctx, kNumCounters);
    ASSERT_EQ(counters[kPrevContactCount], contacts.size());
    std::vector<BtgCachedContact> got = w.contactCache.download(w.ctx, contacts.size());
    for (size_t i = 0; i < got.size(); ++i) {
        const BtgCachedContact &g = got[i], &e = expect[i];
        ASSERT_EQ(g.bodyA, contacts[i].bodyA) << i;
        ASSERT_EQ(g.bodyB, contacts[i].bodyB) << i;
        ASSERT_EQ(g.numPoints, contacts[i].numPoints) << i;
        for (int k = 0; k < g.numPoints; ++k) {
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(btgLane(g.point[k], c), btgLane(e.point[k], c), tol::kStageAbs) << i;
            EXPECT_EQ(g.point[k].w, btgLane(contacts[i].normalImpulse, k)) << i;
            // The key is the point on A in A's frame: rotated back, it is rA again.
            BtgFloat4 back = btgQuatRotate(bodies.rot[g.bodyA], g.point[k]);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(btgLane(back, c), btgLane(contacts[i].rA[k], c), 1e-5f) << i;
        }
#if BTG_WARMSTART_FRICTION
        EXPECT_EQ(g.friction1Impulse.y, -2.0f);
#endif
    }

    // An overflowed substep is redone from the cache as it was: the store leaves it alone.
    std::vector<BtgContact> other(contacts.begin(), contacts.begin() + 10);
    w.contacts.upload(w.ctx, other);
    counters[kContactCount] = 10;
    counters[kStatus] = BTG_STATUS_CONTACT_OVERFLOW;
    w.counters.upload(w.ctx, counters);
    storeContactCache(w);
    std::vector<uint> after = w.counters.download(w.ctx, kNumCounters);
    EXPECT_EQ(after[kPrevContactCount], contacts.size());
    std::vector<BtgCachedContact> kept = w.contactCache.download(w.ctx, contacts.size());
    EXPECT_EQ(0, std::memcmp(kept.data(), got.data(), got.size() * sizeof(BtgCachedContact)));
}
