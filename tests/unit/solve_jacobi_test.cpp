// solve_jacobi_test.cpp — the Jacobi mass-splitting solve: per-body contact lists exactly as
// the reference builds them, velocities, push velocities and impulses within tolerance of the
// reference (with warm start), bitwise repeatable, and physics: a resting box stops with
// impulses summing to m g dt, a two-box stack comes to rest carrying m g dt and 2 m g dt.
#include "contact_fixture.h"
#include "reference/solve_jacobi.h"
#include "stages/contact_cache.h"
#include "stages/prepare_contacts.h"
#include "stages/solve_jacobi.h"
#include "test_device.h"
#include "tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <gtest/gtest.h>

using namespace btgpu;

namespace {

const float kG = 9.81f;
const float kDt = 1.0f / 60.0f;

struct Result {
    ref::ContactBodies bodies;
    std::vector<BtgContact> contacts;
    std::vector<uint> start, entries;
};

// contacts -> prepare -> Jacobi solve on the device; prev is last step's contact list.
Result runDevice(const ref::ContactBodies& b, const std::vector<BtgManifold>& ms, const std::vector<BtgContact>& prev,
                 const BtgStepParams& p, int iterations)
{
    DeviceWorld w(test::context());
    test::uploadWorld(w, b, ms, uint(ms.size()), prev, ms.size() + 4);
    buildContacts(w, p);
    prepareContacts(w, p);
    solveJacobi(w, p, iterations);
    Result r;
    r.bodies = b;
    size_t n = b.props.size();
    r.bodies.linVel = w.linVel.download(w.ctx, n);
    r.bodies.angVel = w.angVel.download(w.ctx, n);
    r.bodies.pushLin = w.pushLin.download(w.ctx, n);
    r.bodies.pushAng = w.pushAng.download(w.ctx, n);
    r.contacts = test::downloadContacts(w);
    r.start = w.solverScratch.jacobiStart.download(w.ctx, n + 1);
    r.entries = w.solverScratch.jacobiEntries.download(w.ctx, r.start[n]);
    return r;
}

Result runReference(const ref::ContactBodies& b, const std::vector<BtgManifold>& ms, const std::vector<BtgContact>& prev,
                    const BtgStepParams& p, int iterations)
{
    Result r;
    r.bodies = b;
    r.contacts = ref::buildContacts(ms, int(ms.size()), b, prev, p);
    ref::prepareContacts(r.contacts, r.bodies, p);
    ref::JacobiLists l = ref::jacobiLists(r.contacts, r.bodies);
    r.start = l.start;
    r.entries = l.entries;
    ref::solveJacobi(r.contacts, r.bodies, p, iterations);
    return r;
}

float normalSum(const BtgContact& c)
{
    float s = 0.0f;
    for (int k = 0; k < c.numPoints; ++k) s += btgLane(c.normalImpulse, k);
    return s;
}

// Boxes of 1 kg, half extent 0.5, stacked on a static ground, touching (distance 0), moving
// down at g dt as after integration.
struct Stack {
    ref::ContactBodies bodies;
    std::vector<BtgManifold> manifolds;
};
Stack stack(int height)
{
    Stack s;
    int below = test::addBody(s.bodies, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.5f);
    for (int h = 0; h < height; ++h) {
        BtgFloat4 pos = btgMake4(0, 0.5f + h, 0, 0);
        int b = test::addBody(s.bodies, pos, 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC, 0.5f);
        s.bodies.linVel[b] = btgMake4(0, -kG * kDt, 0, 0);
        s.manifolds.push_back(test::boxOnPlane(b, below, pos, 0.5f, 0.0f));
        below = b;
    }
    return s;
}

}  // namespace

TEST(SolveJacobi, MatchesReferenceWithWarmStart)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    const int iterations = 10;
    Result d1 = runDevice(s.bodies, s.manifolds, {}, p, iterations);
    Result r1 = runReference(s.bodies, s.manifolds, {}, p, iterations);
    Result d = runDevice(s.bodies, s.manifolds, d1.contacts, p, iterations);
    Result r = runReference(s.bodies, s.manifolds, r1.contacts, p, iterations);

    // The lists are integers: exactly the reference's, sorted per body whatever the atomics did.
    EXPECT_EQ(d.start, r.start);
    EXPECT_EQ(d.entries, r.entries);
    EXPECT_GT(r.start.back(), 0u);

    // Same device, same input: bitwise the same velocities.
    Result again = runDevice(s.bodies, s.manifolds, d1.contacts, p, iterations);
    EXPECT_EQ(0, std::memcmp(again.bodies.linVel.data(), d.bodies.linVel.data(), d.bodies.linVel.size() * sizeof(BtgFloat4)));
    EXPECT_EQ(0, std::memcmp(again.bodies.angVel.data(), d.bodies.angVel.data(), d.bodies.angVel.size() * sizeof(BtgFloat4)));
    EXPECT_EQ(0, std::memcmp(again.bodies.pushLin.data(), d.bodies.pushLin.data(), d.bodies.pushLin.size() * sizeof(BtgFloat4)));

    const float tv = 10 * tol::kStageAbs;  // ten iterations of accumulated rounding
    RecordProperty("max_velocity_deviation",
                   std::to_string(test::expectSolvedAlike(d.bodies, d.contacts, r.bodies, r.contacts, tv)));
    bool warm = false;
    for (size_t i = 0; i < std::min(d.contacts.size(), r.contacts.size()); ++i) {
        warm = warm || btgLane(d1.contacts[i].normalImpulse, 0) > 0.0f;
    }
    EXPECT_TRUE(warm);
    // Infinite-mass bodies are never written.
    for (size_t i = 0; i < s.bodies.props.size(); ++i)
        if (s.bodies.props[i].flags & (BTG_BODY_KINEMATIC | BTG_BODY_STATIC)) {
            EXPECT_EQ(d.bodies.linVel[i].x, s.bodies.linVel[i].x) << i;
            EXPECT_EQ(d.bodies.linVel[i].y, s.bodies.linVel[i].y) << i;
        }
}

TEST(SolveJacobi, RestingBoxStops)
{
    // One contact: no splitting, so Jacobi is PGS here.
    Stack s = stack(1);
    Result d = runDevice(s.bodies, s.manifolds, {}, test::defaultParams(2), 10);
    ASSERT_EQ(d.contacts.size(), 1u);
    EXPECT_NEAR(normalSum(d.contacts[0]), 1.0f * kG * kDt, 1e-4f);  // m g dt
    for (int k = 0; k < 4; ++k) EXPECT_GE(btgLane(d.contacts[0].normalImpulse, k), 0.0f);
    test::expectNear4(d.bodies.linVel[1], btgZero4(), 1e-4f, "linVel", 1);
    test::expectNear4(d.bodies.angVel[1], btgZero4(), 1e-4f, "angVel", 1);
}

TEST(SolveJacobi, TwoBoxStackComesToRest)
{
    // The middle box is split in two; Jacobi needs more iterations than PGS to carry the top
    // box's weight down to the ground, but converges to the same answer.
    Stack s = stack(2);
    BtgStepParams p = test::defaultParams(3);
    for (int iterations : {10, 100}) {
        Result d = runDevice(s.bodies, s.manifolds, {}, p, iterations);
        ASSERT_EQ(d.contacts.size(), 2u);
        float ground = normalSum(d.contacts[0]), upper = normalSum(d.contacts[1]);
        float vmax = 0.0f;
        for (int b = 1; b <= 2; ++b)
            vmax = std::max({vmax, std::fabs(d.bodies.linVel[b].y), std::fabs(d.bodies.angVel[b].x), std::fabs(d.bodies.angVel[b].z)});
        RecordProperty("residual_velocity_" + std::to_string(iterations), std::to_string(vmax));
        if (iterations == 100) {
            EXPECT_NEAR(upper, kG * kDt, 1e-3f * kG * kDt);
            EXPECT_NEAR(ground, 2.0f * kG * kDt, 1e-3f * kG * kDt);
            EXPECT_LT(vmax, 1e-3f);
        } else {
            // Ten iterations: the weight is mostly carried, nothing pulls (impulses never negative).
            EXPECT_GT(ground, 1.5f * kG * kDt);
            EXPECT_LT(vmax, 0.05f * kG * kDt * 10.0f);
        }
        for (const BtgContact& c : d.contacts)
            for (int k = 0; k < 4; ++k) EXPECT_GE(btgLane(c.normalImpulse, k), 0.0f);
    }
    // Warm-started from its own previous step (factor 0.85), ten iterations a step stay within
    // 5 % of the weights: the 15 % the warm start drops is not all recovered in ten Jacobi passes.
    Result first = runDevice(s.bodies, s.manifolds, {}, p, 10);
    Result second = first;
    for (int step = 0; step < 8; ++step) second = runDevice(s.bodies, s.manifolds, second.contacts, p, 10);
    RecordProperty("warm_upper_ratio", std::to_string(normalSum(second.contacts[1]) / (kG * kDt)));
    EXPECT_NEAR(normalSum(second.contacts[1]), kG * kDt, 0.05f * kG * kDt);
    EXPECT_NEAR(normalSum(second.contacts[0]), 2.0f * kG * kDt, 0.05f * 2.0f * kG * kDt);
}

TEST(SolveJacobi, SplitImpulsePushesWithoutAddingVelocity)
{
    Stack s = stack(1);
    s.manifolds[0] = test::boxOnPlane(1, 0, s.bodies.pos[1], 0.5f, -0.05f);  // deeper than the split threshold
    BtgStepParams p = test::defaultParams(2);
    Result d = runDevice(s.bodies, s.manifolds, {}, p, 10);
    EXPECT_NEAR(d.bodies.linVel[1].y, 0.0f, 1e-4f);
    EXPECT_NEAR(d.bodies.pushLin[1].y, 0.05f * p.erp2 * 60.0f, 1e-4f);
    EXPECT_EQ(d.bodies.pushLin[0].y, 0.0f);
}
