// contact_fixture.h — builders shared by the contact-stage tests: body rows, manifolds,
// default Bullet 3.24 solver parameters, and a DeviceWorld uploaded from host columns.
#pragma once
#include "reference/contact_solver_reference.h"
#include "shared/cache_search.h"
#include "shared/narrowphase_common.h"
#include "world/device_world.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace btgpu::test {

// btContactSolverInfo defaults of Bullet 3.24 at 60 Hz.
inline BtgStepParams defaultParams(int numBodies)
{
    BtgStepParams p{};
    p.dt = 1.0f / 60.0f;
    p.erp = 0.2f;
    p.erp2 = 0.2f;
    p.splitPenetrationThreshold = -0.04f;
    p.splitTurnErp = 0.1f;
    p.warmstartFactor = 0.85f;
    p.restitutionThreshold = 0.2f;
    p.contactThreshold = 0.02f;
    p.splitImpulse = 1;
    p.numBodies = numBodies;
    p.sor = 1.0f;
    return p;
}

// Appends a body: invMass 0 with BTG_BODY_STATIC makes a static row. Inertia is diagonal
// (identity rotation), so the world inverse inertia is the local one.
inline int addBody(ref::ContactBodies& b, BtgFloat4 pos, float invMass, BtgFloat4 invInertia, uint flags,
                   float friction = 0.5f, float restitution = 0.0f)
{
    BtgBodyProps p{};
    p.invInertiaLocal = btgMake4(invInertia.x, invInertia.y, invInertia.z, 0);
    p.invMass = invMass;
    p.linearFactor = btgMake4(1, 1, 1, 0);
    p.angularFactor = btgMake4(1, 1, 1, 0);
    p.gravity = btgMake4(0, -9.81f, 0, 0);
    p.friction = friction;
    p.restitution = restitution;
    p.flags = flags;
    p.contactStiffness = 1e18f;  // btCollisionObject's defaults (BT_LARGE_FLOAT, 0.1)
    p.contactDamping = 0.1f;
    p.contactProcessingThreshold = 1e18f;
    b.props.push_back(p);
    b.pos.push_back(pos);
    b.rot.push_back(btgMake4(0, 0, 0, 1));
    for (auto* col : {&b.linVel, &b.angVel, &b.linVel0, &b.angVel0, &b.pushLin, &b.pushAng}) col->push_back(btgZero4());
    b.invInertiaWorld.push_back(btgMake4(invInertia.x, 0, 0, 0));
    b.invInertiaWorld.push_back(btgMake4(0, invInertia.y, 0, 0));
    b.invInertiaWorld.push_back(btgMake4(0, 0, invInertia.z, 0));
    return int(b.props.size()) - 1;
}

// A manifold of A on B with one point: on B at pointB, `distance` along the normal (B to A).
inline BtgManifold onePointManifold(int bodyA, int bodyB, BtgFloat4 normal, BtgFloat4 pointB, float distance,
                                    uint featureId = BTG_FEATURE_SINGLE)
{
    BtgManifold m = btgEmptyManifold(bodyA, bodyB);
    m.breakingThreshold = 0.02f;
    btgAddPoint(&m, normal, pointB, distance, featureId);
    return m;
}

// A unit box (half extent h, mass m) resting on B: four corner points on B's surface plane y0,
// each with its vertex's feature id (as hull–plane gives them).
inline BtgManifold boxOnPlane(int box, int ground, BtgFloat4 boxPos, float h, float distance)
{
    BtgManifold m = btgEmptyManifold(box, ground);
    m.breakingThreshold = 0.02f;
    const float sx[4] = {-1, 1, 1, -1}, sz[4] = {-1, -1, 1, 1};
    for (int k = 0; k < 4; ++k)
        btgAddPoint(&m, btgMake4(0, 1, 0, 0), btgMake4(boxPos.x + sx[k] * h, boxPos.y - h - distance, boxPos.z + sz[k] * h, 0),
                    distance, BTG_FEATURE_VERTEX | uint(k));
    return m;
}

// Columns of unit boxes on a static ground (row 0), with random small penetrations and
// velocities (linVel = linVel0 + gravity dt, as after integration). The bottom box of the last
// column is kinematic and moves sideways, so infinite-mass moving bodies are covered too.
struct StackScene {
    ref::ContactBodies bodies;
    std::vector<BtgManifold> manifolds;
};
inline StackScene stackScene(int columns, int height, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    StackScene s;
    const float gdt = 9.81f / 60.0f;
    addBody(s.bodies, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.8f, 0.5f);
    for (int c = 0; c < columns; ++c) {
        int below = 0;
        float top = 0.0f;
        for (int h = 0; h < height; ++h) {
            float d = 0.03f * u(rng) - 0.02f;  // -5 cm .. +1 cm: split, combined and speculative rows
            BtgFloat4 pos = btgMake4(2.0f * c + 0.05f * u(rng), top + 0.5f + d, 0.05f * u(rng), 0);
            bool kinematic = c == columns - 1 && h == 0;
            int b = addBody(s.bodies, pos, kinematic ? 0.0f : 1.0f + 0.5f * u(rng),
                            kinematic ? btgZero4() : btgMake4(6 + u(rng), 6 + u(rng), 6 + u(rng), 0),
                            kinematic ? BTG_BODY_KINEMATIC : BTG_BODY_DYNAMIC, 0.6f + 0.3f * u(rng), 0.5f + 0.5f * u(rng));
            BtgFloat4 v0 = kinematic ? btgMake4(0.3f, 0, 0, 0) : btgMake4(0.1f * u(rng), -0.5f * (1 + u(rng)), 0.1f * u(rng), 0);
            s.bodies.linVel0[b] = v0;
            s.bodies.linVel[b] = kinematic ? v0 : v0 + btgMake4(0, -gdt, 0, 0);
            s.bodies.angVel0[b] = kinematic ? btgZero4() : btgMake4(0.2f * u(rng), 0.2f * u(rng), 0.2f * u(rng), 0);
            s.bodies.angVel[b] = s.bodies.angVel0[b];
            s.manifolds.push_back(boxOnPlane(b, below, pos, 0.5f, d));  // points on the face at y = top
            below = b;
            top = pos.y + 0.5f;
        }
    }
    // In pair order, as the pipeline's pairs and so its contacts and cache are: the warm start
    // seeks a manifold's cached entry by its pair (shared/cache_search.h). Built column by
    // column, (0, 5) came after (3, 4), and bisections missed entries.
    std::stable_sort(s.manifolds.begin(), s.manifolds.end(), [](const BtgManifold& x, const BtgManifold& y) {
        return btgPairKeyLess(std::min(x.bodyA, x.bodyB), std::max(x.bodyA, x.bodyB), std::min(y.bodyA, y.bodyB),
                              std::max(y.bodyA, y.bodyB));
    });
    return s;
}

// Whether a cache is in pair order (the searches' premise).
inline bool cacheInPairOrder(const std::vector<BtgCachedContact>& cache)
{
    for (size_t i = 1; i < cache.size(); ++i)
        if (btgCachedPairBelow(cache.data(), int(i), std::min(cache[i - 1].bodyA, cache[i - 1].bodyB),
                               std::max(cache[i - 1].bodyA, cache[i - 1].bodyB)))
            return false;
    return true;
}

// Uploads the body columns, manifolds (as pair slots, one each) and the previous step's contacts
// (as a cache from contacts alone, ref::storeContactCache(prev, b), keyed with the bodies'
// rotations); counters as given.
inline void uploadWorld(DeviceWorld& w, const ref::ContactBodies& b, const std::vector<BtgManifold>& manifolds,
                        uint pairCount, const std::vector<BtgContact>& prev, size_t contactCapacity)
{
    cl::Context& ctx = w.ctx;
    w.numBodies = int(b.props.size());
    w.pos.upload(ctx, b.pos);
    w.rot.upload(ctx, b.rot);
    w.linVel.upload(ctx, b.linVel);
    w.angVel.upload(ctx, b.angVel);
    w.linVel0.upload(ctx, b.linVel0);
    w.angVel0.upload(ctx, b.angVel0);
    w.invInertiaWorld.upload(ctx, b.invInertiaWorld);
    w.props.upload(ctx, b.props);
    w.pushLin.upload(ctx, b.pushLin);
    w.pushAng.upload(ctx, b.pushAng);
    w.pairCapacity = manifolds.size();
    w.manifolds.upload(ctx, manifolds);
    w.pairManifolds.upload(ctx, ref::oneManifoldPerPair(manifolds));
    w.contactCache.reserve(ctx, prev.size() + 1);
    const std::vector<BtgCachedContact> cache = ref::storeContactCache(prev, b);
    EXPECT_TRUE(cacheInPairOrder(cache)) << "a fixture's cache out of pair order: warm starts would miss entries";
    w.contactCache.upload(ctx, cache);
    w.contactCapacity = contactCapacity;
    w.contacts.reserve(ctx, contactCapacity);
    w.contactManifolds.reserve(ctx, contactCapacity);
    std::vector<uint> counters(kNumCounters, 0u);
    counters[kPairCount] = pairCount;
    counters[kPrevContactCount] = uint(prev.size());
    counters[kNanBody] = 0xffffffffu;
    w.counters.upload(ctx, counters);
}

inline std::vector<BtgContact> downloadContacts(DeviceWorld& w)
{
    std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    size_t n = std::min<size_t>(counters[kContactCount], w.contactCapacity);
    return w.contacts.download(w.ctx, n);
}

// Device against reference: the three velocity components within tol.
inline void expectNear4(BtgFloat4 got, BtgFloat4 want, float tol, const char* what, size_t i)
{
    EXPECT_NEAR(got.x, want.x, tol) << what << " " << i;
    EXPECT_NEAR(got.y, want.y, tol) << what << " " << i;
    EXPECT_NEAR(got.z, want.z, tol) << what << " " << i;
}

// A solver stage's device result against its reference: every body's velocities and push
// velocities, then every contact's accumulated impulses, within tol. Returns the largest
// velocity deviation (for the test's record).
inline float expectSolvedAlike(const ref::ContactBodies& got, const std::vector<BtgContact>& gotContacts,
                               const ref::ContactBodies& want, const std::vector<BtgContact>& wantContacts, float tol)
{
    float worst = 0.0f;
    for (size_t i = 0; i < want.props.size(); ++i) {
        expectNear4(got.linVel[i], want.linVel[i], tol, "linVel", i);
        expectNear4(got.angVel[i], want.angVel[i], tol, "angVel", i);
        expectNear4(got.pushLin[i], want.pushLin[i], tol, "pushLin", i);
        expectNear4(got.pushAng[i], want.pushAng[i], tol, "pushAng", i);
        for (int e = 0; e < 3; ++e)
            worst = std::max({worst, std::fabs(btgLane(got.linVel[i], e) - btgLane(want.linVel[i], e)),
                              std::fabs(btgLane(got.angVel[i], e) - btgLane(want.angVel[i], e))});
    }
    EXPECT_EQ(gotContacts.size(), wantContacts.size());
    for (size_t i = 0; i < std::min(gotContacts.size(), wantContacts.size()); ++i) {
        expectNear4(gotContacts[i].normalImpulse, wantContacts[i].normalImpulse, tol, "normalImpulse", i);
        expectNear4(gotContacts[i].pushImpulse, wantContacts[i].pushImpulse, tol, "pushImpulse", i);
        expectNear4(gotContacts[i].friction1Impulse, wantContacts[i].friction1Impulse, tol, "friction1Impulse", i);
        expectNear4(gotContacts[i].friction2Impulse, wantContacts[i].friction2Impulse, tol, "friction2Impulse", i);
    }
    return worst;
}

}  // namespace btgpu::test
