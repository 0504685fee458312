// solve_constraints_test.cpp — the solve stage: velocities, push velocities and impulses
// within tolerance of the reference over the whole contact chain (with warm start), and
// physics: a resting box stops with impulses summing to m g dt, friction holds a slow slide
// and saturates on a fast one, a 2:1 collision leaves with Bullet's restitution target, and
// deep penetration is resolved by push velocities only.
#include "contact_fixture.h"
#include "stages/color_constraints.h"
#include "stages/contact_cache.h"
#include "stages/prepare_contacts.h"
#include "stages/solve_constraints.h"
#include "test_device.h"
#include "tolerances.h"

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <set>
#include <string>
#include <gtest/gtest.h>

using namespace btgpu;

namespace {

const float kG = 9.81f;
const int kIterations = 10;

struct Result {
    ref::ContactBodies bodies;
    std::vector<BtgContact> contacts;
    std::vector<int> colors;  // the contacts' edge colors
    uint status = 0;          // counters[kStatus] after the solve
    std::vector<BtgRollingContact> rolling;  // with BTG_SOLVER_ROLLING_FRICTION
    std::vector<BtgFrictionDirs> frictionDirs;  // with BTG_SOLVER_ANISOTROPIC_FRICTION
};

// contacts -> prepare -> batching -> solve on the device; prev is last step's contact list.
// fused: the one-work-group batching and solve small scenes take (by the last contact count).
Result runDevice(const ref::ContactBodies& b, const std::vector<BtgManifold>& ms, const std::vector<BtgContact>& prev,
                 const BtgStepParams& p, int maxColors, bool fused = false,
                 DeviceWorld::Resident resident = DeviceWorld::Resident::Auto,
                 DeviceWorld::Resident flow = DeviceWorld::Resident::Off,
                 DeviceWorld::Resident local = DeviceWorld::Resident::Off)
{
    DeviceWorld w(test::context());
    w.resident = resident;
    w.pgsFlow = flow;
    w.pgsLocal = local;
    w.lastContactCount = fused ? 0 : (1 << 30);
    test::uploadWorld(w, b, ms, uint(ms.size()), prev, ms.size() + 4);
    buildContacts(w, p);
    prepareContacts(w, p);
    w.colorRounds = maxColors - 1;
    colorConstraints(w, maxColors);
    solveConstraints(w, p, kIterations, w.numColors);
    Result r;
    r.bodies = b;
    size_t n = b.props.size();
    r.bodies.linVel = w.linVel.download(w.ctx, n);
    r.bodies.angVel = w.angVel.download(w.ctx, n);
    r.bodies.pushLin = w.pushLin.download(w.ctx, n);
    r.bodies.pushAng = w.pushAng.download(w.ctx, n);
    r.contacts = test::downloadContacts(w);
    r.colors = w.edgeColor.download(w.ctx, r.contacts.size());
    r.status = w.counters.download(w.ctx, kNumCounters)[kStatus];
    if (p.solverFlags & BTG_SOLVER_ROLLING_FRICTION) r.rolling = w.rollingContacts.download(w.ctx, r.contacts.size());
    if (p.solverFlags & BTG_SOLVER_ANISOTROPIC_FRICTION)
        r.frictionDirs = w.frictionDirs.download(w.ctx, r.contacts.size());
    return r;
}

Result runReference(const ref::ContactBodies& b, const std::vector<BtgManifold>& ms, const std::vector<BtgContact>& prev,
                    const BtgStepParams& p, int maxColors)
{
    Result r;
    r.bodies = b;
    r.contacts = ref::buildContacts(ms, int(ms.size()), b, prev, p);
    std::vector<BtgEdge> edges = ref::prepareContacts(r.contacts, r.bodies, p, &r.rolling, &r.frictionDirs);
    r.colors = ref::colorConstraints(edges, r.bodies, maxColors);
    ref::solveConstraints(r.contacts, r.colors, r.bodies, p, kIterations, maxColors, &r.rolling, &r.frictionDirs);
    return r;
}

// Relative velocity along dir at point k of contact c (A minus B), from solved body velocities.
float pointVelocity(const ref::ContactBodies& b, const BtgContact& c, int k, BtgFloat4 dir)
{
    BtgFloat4 va = b.linVel[c.bodyA] + btgCross3(b.angVel[c.bodyA], btgXyz(c.rA[k]));
    BtgFloat4 vb = btgZero4();
    if (btgIsSolverMoving(b.props[c.bodyB].flags))
        vb = b.linVel[c.bodyB] + btgCross3(b.angVel[c.bodyB], btgXyz(c.rB[k]));
    return btgDot3(dir, va - vb);
}

struct Resting {
    ref::ContactBodies bodies;
    std::vector<BtgManifold> manifolds;
    int box;
};
Resting restingBox(BtgFloat4 slide, float distance)
{
    Resting s;
    int ground = test::addBody(s.bodies, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.5f);
    s.box = test::addBody(s.bodies, btgMake4(0, 0.5f + distance, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC, 0.5f);
    s.bodies.linVel0[s.box] = slide;
    s.bodies.linVel[s.box] = slide + btgMake4(0, -kG / 60.0f, 0, 0);
    s.manifolds.push_back(test::boxOnPlane(s.box, ground, s.bodies.pos[s.box], 0.5f, distance));
    return s;
}

}  // namespace

TEST(SolveConstraints, MatchesReferenceWithWarmStart)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    const int maxColors = 2;  // few colors, so the serial last color has work too
    Result d1 = runDevice(s.bodies, s.manifolds, {}, p, maxColors);
    Result r1 = runReference(s.bodies, s.manifolds, {}, p, maxColors);
    // The second step warm-starts from each side's own first-step contacts.
    Result d = runDevice(s.bodies, s.manifolds, d1.contacts, p, maxColors);
    Result r = runReference(s.bodies, s.manifolds, r1.contacts, p, maxColors);

    // Same device, same input: bitwise the same velocities.
    Result again = runDevice(s.bodies, s.manifolds, d1.contacts, p, maxColors);
    EXPECT_EQ(0, std::memcmp(again.bodies.linVel.data(), d.bodies.linVel.data(), d.bodies.linVel.size() * sizeof(BtgFloat4)));
    EXPECT_EQ(0, std::memcmp(again.bodies.angVel.data(), d.bodies.angVel.data(), d.bodies.angVel.size() * sizeof(BtgFloat4)));

    int serial = 0;
    for (int c : r.colors) serial += c == maxColors - 1;
    EXPECT_GT(serial, 0);
    const float tv = 10 * tol::kStageAbs;  // ten iterations of accumulated rounding
    RecordProperty("max_velocity_deviation",
                   std::to_string(test::expectSolvedAlike(d.bodies, d.contacts, r.bodies, r.contacts, tv)));
    bool warm = false;
    for (size_t i = 0; i < std::min(d.contacts.size(), r.contacts.size()); ++i) {
        EXPECT_EQ(d.colors[i], r.colors[i]);
        warm = warm || btgLane(d1.contacts[i].normalImpulse, 0) > 0.0f;
    }
    EXPECT_TRUE(warm);
    // The kinematic body is never written.
    int kin = 0;
    for (size_t i = 0; i < s.bodies.props.size(); ++i)
        if (s.bodies.props[i].flags & BTG_BODY_KINEMATIC) kin = int(i);
    EXPECT_EQ(d.bodies.linVel[kin].x, s.bodies.linVel[kin].x);
}

// SOLVER_USE_2_FRICTION_DIRECTIONS: the second friction rows are built, solved and warm-started
// (without it the solve does not read them), the same on the device as in the reference.
TEST(SolveConstraints, TwoFrictionDirectionsMatchReference)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    p.twoFrictionDirections = 1;
    const int maxColors = 3;
    Result d1 = runDevice(s.bodies, s.manifolds, {}, p, maxColors);
    Result r1 = runReference(s.bodies, s.manifolds, {}, p, maxColors);
    Result d = runDevice(s.bodies, s.manifolds, d1.contacts, p, maxColors);
    Result r = runReference(s.bodies, s.manifolds, r1.contacts, p, maxColors);
    test::expectSolvedAlike(d.bodies, d.contacts, r.bodies, r.contacts, 10 * tol::kStageAbs);
    int second = 0;
    for (const BtgContact& c : d.contacts)
        for (int k = 0; k < c.numPoints; ++k) second += btgLane(c.friction2Impulse, k) != 0.0f;
    EXPECT_GT(second, 0);
}

// One launch on one work-group walks the colors in the same order as one launch per color:
// bitwise the same velocities and impulses, leftovers included.
TEST(SolveConstraints, OneWorkGroupLaunchSolvesTheSame)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    for (int maxColors : {3, 16}) {
        Result a = runDevice(s.bodies, s.manifolds, {}, p, maxColors, false);
        Result b = runDevice(s.bodies, s.manifolds, {}, p, maxColors, true);
        Result a2 = runDevice(s.bodies, s.manifolds, a.contacts, p, maxColors, false);
        Result b2 = runDevice(s.bodies, s.manifolds, b.contacts, p, maxColors, true);
        size_t n = a2.bodies.linVel.size() * sizeof(BtgFloat4);
        EXPECT_EQ(0, std::memcmp(a2.bodies.linVel.data(), b2.bodies.linVel.data(), n)) << maxColors;
        EXPECT_EQ(0, std::memcmp(a2.bodies.angVel.data(), b2.bodies.angVel.data(), n)) << maxColors;
        EXPECT_EQ(0, std::memcmp(a2.bodies.pushLin.data(), b2.bodies.pushLin.data(), n)) << maxColors;
        ASSERT_EQ(a2.contacts.size(), b2.contacts.size());
        EXPECT_EQ(0, std::memcmp(a2.contacts.data(), b2.contacts.data(), a2.contacts.size() * sizeof(BtgContact)));
    }
}

// All passes and colors in one launch over resident work-groups, with grid barriers between
// colors: bitwise what one launch per color gives. A device that does not keep the groups
// resident may time out instead (the world then redoes the step per color); a GPU must not.
// Also with the flow (per-body counts, no barrier between colours; on a CPU device in groups of
// one work-item, so it must not time out anywhere), leftovers (3 colours) and split impulse's
// push list included.
class SolveConstraintsResident : public ::testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(SolveConstraints, SolveConstraintsResident, ::testing::Values(false, true));
TEST_P(SolveConstraintsResident, OneResidentLaunchSolvesTheSame)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    using Resident = DeviceWorld::Resident;
    const bool flow = GetParam();
    for (int maxColors : {3, 16}) {
        Result a = runDevice(s.bodies, s.manifolds, {}, p, maxColors, false, Resident::Off);
        Result b = runDevice(s.bodies, s.manifolds, {}, p, maxColors, false, Resident::On,
                             flow ? Resident::On : Resident::Off);
        EXPECT_EQ(a.status & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u);
        if (flow) EXPECT_EQ(b.status & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u) << "the flow timed out";
        if (b.status & BTG_STATUS_GRID_BARRIER_TIMEOUT) {
            EXPECT_FALSE(test::context().device().isGpu) << "a GPU must keep one group per compute unit resident";
            continue;
        }
        size_t n = a.bodies.linVel.size();
        EXPECT_EQ(0, std::memcmp(a.bodies.linVel.data(), b.bodies.linVel.data(), n * sizeof(BtgFloat4))) << maxColors;
        EXPECT_EQ(0, std::memcmp(a.bodies.angVel.data(), b.bodies.angVel.data(), n * sizeof(BtgFloat4))) << maxColors;
        EXPECT_EQ(0, std::memcmp(a.bodies.pushLin.data(), b.bodies.pushLin.data(), n * sizeof(BtgFloat4))) << maxColors;
        ASSERT_EQ(a.contacts.size(), b.contacts.size());
        for (size_t i = 0; i < a.contacts.size(); ++i) {
            EXPECT_EQ(0, std::memcmp(&a.contacts[i].normalImpulse, &b.contacts[i].normalImpulse, sizeof(BtgFloat4)));
            EXPECT_EQ(0, std::memcmp(&a.contacts[i].pushImpulse, &b.contacts[i].pushImpulse, sizeof(BtgFloat4)));
        }
    }
}

// solve_local (one work-group, the velocities in local memory) against one launch per colour:
// the same bits, with leftovers (3 colours), the push list, and a SOLVER_RANDMIZE_ORDER seed.
TEST(SolveConstraints, LocalSolveIsTheResidentSolveBitForBit)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    using Resident = DeviceWorld::Resident;
    for (uint seed : {0u, 12345u})
        for (int maxColors : {3, 16}) {
            BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
            p.randomSeed = seed;
            Result a = runDevice(s.bodies, s.manifolds, {}, p, maxColors, false, Resident::Off);
            Result b = runDevice(s.bodies, s.manifolds, {}, p, maxColors, false, Resident::Off, Resident::Off,
                                 Resident::On);
            Result warm = runDevice(s.bodies, s.manifolds, b.contacts, p, maxColors, false, Resident::Off,
                                    Resident::Off, Resident::On);
            Result warmRef = runDevice(s.bodies, s.manifolds, a.contacts, p, maxColors, false, Resident::Off);
            for (const auto& [x, y] : {std::pair<const Result*, const Result*>{&a, &b}, {&warmRef, &warm}}) {
                size_t n = x->bodies.linVel.size();
                EXPECT_EQ(0, std::memcmp(x->bodies.linVel.data(), y->bodies.linVel.data(), n * sizeof(BtgFloat4))) << maxColors;
                EXPECT_EQ(0, std::memcmp(x->bodies.angVel.data(), y->bodies.angVel.data(), n * sizeof(BtgFloat4))) << maxColors;
                EXPECT_EQ(0, std::memcmp(x->bodies.pushLin.data(), y->bodies.pushLin.data(), n * sizeof(BtgFloat4))) << maxColors;
                EXPECT_EQ(0, std::memcmp(x->bodies.pushAng.data(), y->bodies.pushAng.data(), n * sizeof(BtgFloat4))) << maxColors;
                ASSERT_EQ(x->contacts.size(), y->contacts.size());
                for (size_t i = 0; i < x->contacts.size(); ++i) {
                    EXPECT_EQ(0, std::memcmp(&x->contacts[i].normalImpulse, &y->contacts[i].normalImpulse, sizeof(BtgFloat4)));
                    EXPECT_EQ(0, std::memcmp(&x->contacts[i].friction1Impulse, &y->contacts[i].friction1Impulse, sizeof(BtgFloat4)));
                    EXPECT_EQ(0, std::memcmp(&x->contacts[i].pushImpulse, &y->contacts[i].pushImpulse, sizeof(BtgFloat4)));
                }
            }
            bool moved = false;  // the solve did something to compare
            for (const BtgFloat4& v : b.bodies.pushLin) moved = moved || v.y != 0.0f;
            EXPECT_TRUE(moved);
        }
}

TEST(SolveConstraints, RestingBoxStops)
{
    Resting s = restingBox(btgZero4(), 0.0f);
    BtgStepParams p = test::defaultParams(2);
    Result d = runDevice(s.bodies, s.manifolds, {}, p, 4);
    ASSERT_EQ(d.contacts.size(), 1u);
    const BtgContact& c = d.contacts[0];
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(pointVelocity(d.bodies, c, k, c.normal), 0.0f, 1e-4f) << "point " << k;
        EXPECT_GE(btgLane(c.normalImpulse, k), 0.0f);
        sum += btgLane(c.normalImpulse, k);
    }
    EXPECT_NEAR(sum, 1.0f * kG / 60.0f, 1e-4f);  // m g dt
    test::expectNear4(d.bodies.linVel[s.box], btgZero4(), 1e-4f, "linVel", 0);
    test::expectNear4(d.bodies.angVel[s.box], btgZero4(), 1e-4f, "angVel", 0);
}

TEST(SolveConstraints, FrictionHoldsSlowSlideAndSaturatesOnFastOne)
{
    BtgStepParams p = test::defaultParams(2);
    const float mu = 0.25f;  // 0.5 * 0.5
    {
        // 2 cm/s needs 0.02 N s; the cone allows mu m g dt = 0.041 N s: the box sticks.
        Resting s = restingBox(btgMake4(0.02f, 0, 0, 0), 0.0f);
        Result d = runDevice(s.bodies, s.manifolds, {}, p, 4);
        const BtgContact& c = d.contacts[0];
        BtgFloat4 total = btgZero4();
        for (int k = 0; k < 4; ++k) {
            EXPECT_NEAR(pointVelocity(d.bodies, c, k, btgFrictionDir1(&c, k)), 0.0f, 1e-3f) << "point " << k;
            EXPECT_NEAR(pointVelocity(d.bodies, c, k, btgFrictionDir2(&c, k)), 0.0f, 1e-3f) << "point " << k;
            float n = btgLane(c.normalImpulse, k);
            EXPECT_LE(std::fabs(btgLane(c.friction1Impulse, k)), mu * n + 1e-6f);
            EXPECT_LE(std::fabs(btgLane(c.friction2Impulse, k)), mu * n + 1e-6f);
            total = total + btgFrictionDir1(&c, k) * btgLane(c.friction1Impulse, k) + btgFrictionDir2(&c, k) * btgLane(c.friction2Impulse, k);
        }
        EXPECT_NEAR(total.x, -0.02f, 1e-3f);
        EXPECT_NEAR(d.bodies.linVel[s.box].x, 0.0f, 1e-3f);
    }
    {
        // 1 m/s: friction saturates; the box slows by about mu g dt.
        Resting s = restingBox(btgMake4(1.0f, 0, 0, 0), 0.0f);
        Result d = runDevice(s.bodies, s.manifolds, {}, p, 4);
        const BtgContact& c = d.contacts[0];
        float normal = 0.0f, friction = 0.0f;
        for (int k = 0; k < 4; ++k) {
            normal += btgLane(c.normalImpulse, k);
            float f1 = btgLane(c.friction1Impulse, k), f2 = btgLane(c.friction2Impulse, k);
            float f = std::sqrt(f1 * f1 + f2 * f2);
            EXPECT_LE(std::fabs(f1), mu * btgLane(c.normalImpulse, k) + 1e-6f);
            friction += f;
        }
        EXPECT_GT(d.bodies.linVel[s.box].x, 0.9f);
        EXPECT_NEAR(1.0f - d.bodies.linVel[s.box].x, mu * kG / 60.0f, 0.25f * mu * kG / 60.0f);
        EXPECT_GT(friction, 0.9f * mu * normal);
    }
}

TEST(SolveConstraints, RestitutionTwoToOne)
{
    ref::ContactBodies b;
    int lower = test::addBody(b, btgZero4(), 1.0f, btgMake4(2.5f, 2.5f, 2.5f, 0), BTG_BODY_DYNAMIC, 0.5f, 0.5f);
    int upper = test::addBody(b, btgMake4(0, 1, 0, 0), 0.5f, btgMake4(1.25f, 1.25f, 1.25f, 0), BTG_BODY_DYNAMIC, 0.5f, 1.0f);
    b.linVel0[upper] = b.linVel[upper] = btgMake4(0, -2, 0, 0);
    b.linVel0[lower] = b.linVel[lower] = btgMake4(0, 1, 0, 0);
    BtgManifold m = test::onePointManifold(upper, lower, btgMake4(0, 1, 0, 0), btgMake4(0, 0.5f, 0, 0), 0.0f);
    Result d = runDevice(b, {m}, {}, test::defaultParams(2), 4);
    // Separating at e * 3 m/s = 1.5 m/s, momentum (2 * -2 + 1 * 1) kept: J = 3 N s.
    EXPECT_NEAR(d.bodies.linVel[upper].y - d.bodies.linVel[lower].y, 1.5f, 1e-5f);
    EXPECT_NEAR(d.bodies.linVel[upper].y, -0.5f, 1e-5f);
    EXPECT_NEAR(d.bodies.linVel[lower].y, -2.0f, 1e-5f);
    EXPECT_NEAR(d.contacts[0].normalImpulse.x, 3.0f, 1e-5f);
}

TEST(SolveConstraints, SplitImpulsePushesWithoutAddingVelocity)
{
    Resting s = restingBox(btgZero4(), -0.05f);  // deeper than the -0.04 m split threshold
    BtgStepParams p = test::defaultParams(2);
    Result d = runDevice(s.bodies, s.manifolds, {}, p, 4);
    const BtgContact& c = d.contacts[0];
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(pointVelocity(d.bodies, c, k, c.normal), 0.0f, 1e-4f);
    EXPECT_NEAR(d.bodies.pushLin[s.box].y, 0.05f * p.erp2 * 60.0f, 1e-4f);
    test::expectNear4(d.bodies.pushAng[s.box], btgZero4(), 1e-4f, "pushAng", 0);
    EXPECT_EQ(d.bodies.pushLin[0].y, 0.0f);  // the ground has no push velocity
    p.splitImpulse = 0;                      // without split impulse the bias is velocity
    d = runDevice(s.bodies, s.manifolds, {}, p, 4);
    EXPECT_NEAR(d.bodies.linVel[s.box].y, 0.05f * p.erp2 * 60.0f, 1e-4f);
}

TEST(SolveConstraints, FewerColorsThanAssignedStillSolvesEveryContact)
{
    test::StackScene s = test::stackScene(4, 3, 13);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    DeviceWorld w(test::context());
    test::uploadWorld(w, s.bodies, s.manifolds, uint(s.manifolds.size()), {}, s.manifolds.size());
    buildContacts(w, p);
    prepareContacts(w, p);
    w.colorRounds = 7;
    colorConstraints(w, 8);
    solveConstraints(w, p, kIterations, 1);  // one serial launch takes colors 0..7 in index order
    Result r;
    r.bodies = s.bodies;
    r.contacts = ref::buildContacts(s.manifolds, int(s.manifolds.size()), s.bodies, {}, p);
    std::vector<BtgEdge> edges = ref::prepareContacts(r.contacts, r.bodies, p);
    ref::solveConstraints(r.contacts, ref::colorConstraints(edges, r.bodies, 8), r.bodies, p, kIterations, 1);
    std::vector<BtgContact> got = test::downloadContacts(w);
    ASSERT_EQ(got.size(), r.contacts.size());
    size_t active = 0;  // contacts that pushed at all (the rest separate or approach from afar)
    for (size_t i = 0; i < got.size(); ++i) {
        float sum = 0.0f;
        for (int k = 0; k < 4; ++k) sum += btgLane(got[i].normalImpulse, k) + btgLane(got[i].pushImpulse, k);
        active += sum > 0.0f;
        test::expectNear4(got[i].normalImpulse, r.contacts[i].normalImpulse, 10 * tol::kStageAbs, "normalImpulse", i);
    }
    EXPECT_GT(active, got.size() / 2);
    std::vector<BtgFloat4> lin = w.linVel.download(w.ctx, s.bodies.props.size());
    for (size_t i = 0; i < lin.size(); ++i) test::expectNear4(lin[i], r.bodies.linVel[i], 10 * tol::kStageAbs, "linVel", i);
}

// Rolling and spinning friction (BtgRollingContact rows, the rolling sweep after the friction
// sweep), with m_sor and m_globalCfm in the normal and friction rows: the device (per-color
// launches and the one-group solve) against the reference on the stack scene.
TEST(SolveConstraints, RollingFrictionSorAndCfmMatchReference)
{
    test::StackScene s = test::stackScene(5, 3, 21);
    for (size_t i = 0; i < s.bodies.props.size(); ++i) {
        s.bodies.props[i].rollingFriction = 0.05f + 0.01f * float(i % 3);
        s.bodies.props[i].spinningFriction = 0.03f;
        s.bodies.angVel[i] = s.bodies.angVel0[i] = s.bodies.angVel0[i] + btgMake4(0, 1.5f, 0, 0);
    }
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    p.solverFlags = BTG_SOLVER_ROLLING_FRICTION;
    p.sor = 0.9f;
    p.globalCfm = 0.01f;
    const int maxColors = 3;
    Result r = runReference(s.bodies, s.manifolds, {}, p, maxColors);
    for (bool fused : {false, true}) {
        SCOPED_TRACE(fused ? "one group" : "per color");
        Result d = runDevice(s.bodies, s.manifolds, {}, p, maxColors, fused);
        test::expectSolvedAlike(d.bodies, d.contacts, r.bodies, r.contacts, 10 * tol::kStageAbs);
        ASSERT_EQ(d.rolling.size(), r.rolling.size());
        int spun = 0;
        for (size_t i = 0; i < r.rolling.size(); ++i) {
            test::expectNear4(d.rolling[i].spinImpulse, r.rolling[i].spinImpulse, 10 * tol::kStageAbs, "spin", i);
            test::expectNear4(d.rolling[i].roll1Impulse, r.rolling[i].roll1Impulse, 10 * tol::kStageAbs, "roll1", i);
            test::expectNear4(d.rolling[i].roll2Impulse, r.rolling[i].roll2Impulse, 10 * tol::kStageAbs, "roll2", i);
            spun += btgLane(r.rolling[i].spinImpulse, 0) != 0.0f;
        }
        EXPECT_GT(spun, 0);  // the rows did act
    }
}

// A sphere-like body on one point, spinning about the normal: the torsional row's impulse is
// bounded by the spinning friction times the point's normal impulse (at most the coefficient
// itself, solveSingleIteration's clamp), and a large enough coefficient stops the spin.
TEST(SolveConstraints, SpinningFrictionClampsAndStops)
{
    for (float spinning : {0.02f, 5.0f}) {
        SCOPED_TRACE(spinning);
        ref::ContactBodies b;
        int ground = test::addBody(b, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 1.0f);
        int ball = test::addBody(b, btgMake4(0, 0.5f, 0, 0), 1.0f, btgMake4(10, 10, 10, 0), BTG_BODY_DYNAMIC, 1.0f);
        b.props[ball].rollingFriction = 0.01f;  // 3.24 adds the torsional row only with rolling friction
        b.props[ball].spinningFriction = spinning;
        b.angVel0[ball] = b.angVel[ball] = btgMake4(0, 3, 0, 0);
        b.linVel[ball] = btgMake4(0, -kG / 60.0f, 0, 0);
        BtgManifold m = test::onePointManifold(ball, ground, btgMake4(0, 1, 0, 0), btgZero4(), 0.0f);
        BtgStepParams p = test::defaultParams(2);
        p.solverFlags = BTG_SOLVER_ROLLING_FRICTION;
        Result d = runDevice(b, {m}, {}, p, 3);
        ASSERT_EQ(d.rolling.size(), 1u);
        const float normal = btgLane(d.contacts[0].normalImpulse, 0);
        const float spin = btgLane(d.rolling[0].spinImpulse, 0);
        const float bound = std::min(spinning * normal, spinning);  // combined: 1.0 * spinning
        EXPECT_NEAR(normal, kG / 60.0f, 1e-4f);
        if (spinning < 1.0f) {
            EXPECT_NEAR(std::fabs(spin), bound, 1e-6f);  // saturated: the spin slows by bound / I
            EXPECT_NEAR(d.bodies.angVel[ball].y, 3.0f - 10.0f * bound, 1e-4f);
        } else {
            EXPECT_LT(std::fabs(spin), bound);
            EXPECT_NEAR(d.bodies.angVel[ball].y, 0.0f, 1e-4f);
        }
    }
}

// Anisotropic friction (BtgFrictionDirs: each point's directions scaled in its bodies' frames),
// one and two directions, warm-started: the device against the reference on the stack scene
// with every box turned and anisotropic.
TEST(SolveConstraints, AnisotropicFrictionMatchesReference)
{
    for (int two : {0, 1}) {
        SCOPED_TRACE(two);
        test::StackScene s = test::stackScene(4, 3, 5);
        for (size_t i = 1; i < s.bodies.props.size(); ++i) {
            s.bodies.props[i].flags |= BTG_BODY_ANISOTROPIC;
            s.bodies.props[i].anisotropicFriction = btgMake4(1.0f, 0.6f, 0.2f, 0);
            s.bodies.rot[i] = btgQuatNormalize(btgMake4(0.1f * float(i % 3), 0.3f, -0.05f * float(i % 2), 1.0f));
        }
        BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
        p.solverFlags = BTG_SOLVER_ANISOTROPIC_FRICTION;
        p.twoFrictionDirections = two;
        const int maxColors = 3;
        Result r1 = runReference(s.bodies, s.manifolds, {}, p, maxColors);
        Result d1 = runDevice(s.bodies, s.manifolds, {}, p, maxColors);
        Result r = runReference(s.bodies, s.manifolds, r1.contacts, p, maxColors);
        Result d = runDevice(s.bodies, s.manifolds, d1.contacts, p, maxColors);
        test::expectSolvedAlike(d.bodies, d.contacts, r.bodies, r.contacts, 10 * tol::kStageAbs);
        ASSERT_EQ(d.frictionDirs.size(), r.frictionDirs.size());
        for (size_t i = 0; i < r.frictionDirs.size(); ++i)
            for (int k = 0; k < r.contacts[i].numPoints; ++k) {
                test::expectNear4(d.frictionDirs[i].dir1[k], r.frictionDirs[i].dir1[k], tol::kStageAbs, "dir1", i);
                if (two) test::expectNear4(d.frictionDirs[i].dir2[k], r.frictionDirs[i].dir2[k], tol::kStageAbs, "dir2", i);
            }
    }
}

namespace {

// A cold then a warm-started solve of s with q, on the device (per-color launches) and in the
// reference: the warm-started ones within tolerance of each other, and the device's bitwise
// the same again, in one work-group and in one resident launch (push velocities too).
struct Warmed {
    Result firstDevice, firstReference, device, reference;
};
Warmed solveWarmedEveryWay(const test::StackScene& s, const BtgStepParams& q, int maxColors)
{
    Warmed w;
    w.firstDevice = runDevice(s.bodies, s.manifolds, {}, q, maxColors);
    w.firstReference = runReference(s.bodies, s.manifolds, {}, q, maxColors);
    w.device = runDevice(s.bodies, s.manifolds, w.firstDevice.contacts, q, maxColors);
    w.reference = runReference(s.bodies, s.manifolds, w.firstReference.contacts, q, maxColors);
    const Result& d = w.device;
    test::expectSolvedAlike(d.bodies, d.contacts, w.reference.bodies, w.reference.contacts, 10 * tol::kStageAbs);
    const size_t n = d.bodies.linVel.size() * sizeof(BtgFloat4);
    Result again = runDevice(s.bodies, s.manifolds, w.firstDevice.contacts, q, maxColors);
    EXPECT_EQ(0, std::memcmp(again.bodies.linVel.data(), d.bodies.linVel.data(), n));
    Result fused = runDevice(s.bodies, s.manifolds, w.firstDevice.contacts, q, maxColors, true);
    EXPECT_EQ(0, std::memcmp(fused.bodies.linVel.data(), d.bodies.linVel.data(), n));
    EXPECT_EQ(0, std::memcmp(fused.bodies.pushLin.data(), d.bodies.pushLin.data(), n));
    Result resident =
        runDevice(s.bodies, s.manifolds, w.firstDevice.contacts, q, maxColors, false, DeviceWorld::Resident::On);
    if (!(resident.status & BTG_STATUS_GRID_BARRIER_TIMEOUT))
        EXPECT_EQ(0, std::memcmp(resident.bodies.linVel.data(), d.bodies.linVel.data(), n));
    return w;
}

}  // namespace

// SOLVER_RANDMIZE_ORDER (BtgStepParams.randomSeed): each sweep's colours and each contact's
// points in the solver's own permuted order. The device follows the reference (within the same
// rounding bound as in order), the one-work-group launch and the resident launch take the same
// order as one launch per colour (bitwise), two runs are bitwise alike, and the order is not a
// no-op: velocities differ from the unpermuted solve's, and another seed's.
TEST(SolveConstraints, RandomizedOrderMatchesReferenceAndDiffers)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    p.splitImpulse = 1;
    for (int maxColors : {3, 16}) {
        SCOPED_TRACE(maxColors);
        BtgStepParams q = p;
        q.randomSeed = 12345u;
        const Warmed w = solveWarmedEveryWay(s, q, maxColors);
        const Result &d1 = w.firstDevice, &d = w.device;
        const size_t n = d.bodies.linVel.size() * sizeof(BtgFloat4);
        Result inOrder = runDevice(s.bodies, s.manifolds, d1.contacts, p, maxColors);
        EXPECT_NE(0, std::memcmp(inOrder.bodies.linVel.data(), d.bodies.linVel.data(), n));
        BtgStepParams other = q;
        other.randomSeed = 777u;
        Result otherSeed = runDevice(s.bodies, s.manifolds, d1.contacts, other, maxColors);
        EXPECT_NE(0, std::memcmp(otherSeed.bodies.linVel.data(), d.bodies.linVel.data(), n));
    }
}

// SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS: each velocity iteration one sweep, each
// point's friction rows right after its normal row. On a stack whose boxes also slide: the
// device (per-color, one-group and resident launches alike) within tolerance of the reference,
// bitwise repeatable, and not the split sweeps' answer; with two friction directions and with
// the randomised order too.
TEST(SolveConstraints, InterleavedMatchesReferenceAndDiffers)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    for (size_t i = 0; i < s.bodies.props.size(); ++i)
        if (s.bodies.props[i].flags & BTG_BODY_DYNAMIC) {
            const BtgFloat4 slide = btgMake4(0.3f + 0.05f * float(i % 5), 0, -0.2f, 0);
            s.bodies.linVel0[i] = s.bodies.linVel0[i] + slide;
            s.bodies.linVel[i] = s.bodies.linVel[i] + slide;
        }
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    p.splitImpulse = 1;
    for (int variant = 0; variant < 3; ++variant) {
        SCOPED_TRACE(variant);
        BtgStepParams split = p;
        if (variant == 1) split.twoFrictionDirections = 1;
        if (variant == 2) split.randomSeed = 4242u;
        BtgStepParams q = split;
        q.solverFlags |= BTG_SOLVER_INTERLEAVE;
        const int maxColors = 16;
        const Warmed w = solveWarmedEveryWay(s, q, maxColors);
        const Result &d1 = w.firstDevice, &r1 = w.firstReference, &d = w.device, &r = w.reference;
        // the split sweeps' answer differs, on the device and in the reference alike
        Result splitD = runDevice(s.bodies, s.manifolds, d1.contacts, split, maxColors);
        Result splitR = runReference(s.bodies, s.manifolds, r1.contacts, split, maxColors);
        float apart = 0.0f, refApart = 0.0f;
        auto distance = [](BtgFloat4 a, BtgFloat4 b) { return std::sqrt(btgDot3(a - b, a - b)); };
        for (size_t i = 0; i < d.bodies.linVel.size(); ++i) {
            apart = std::max(apart, distance(d.bodies.linVel[i], splitD.bodies.linVel[i]));
            refApart = std::max(refApart, distance(r.bodies.linVel[i], splitR.bodies.linVel[i]));
        }
        EXPECT_GT(apart, 100 * tol::kStageAbs);
        EXPECT_GT(refApart, 100 * tol::kStageAbs);
    }
}

// The permutation itself: a bijection of [0, n) for every n the solver permutes (points 1-4,
// colours up to 63), the identity for key 0, and more than one order over keys.
TEST(SolveConstraints, PermutationIsABijection)
{
    for (int n = 1; n <= 63; ++n) {
        std::set<std::vector<int>> orders;
        for (uint key : {0u, 1u, 3u, 12345u, 0xdeadbeefu, btgSweepKey(7u, 2, BTG_ORDER_FRICTION)}) {
            std::vector<int> seen(size_t(n), 0), order;
            for (int i = 0; i < n; ++i) {
                const int j = btgPermute(key, n, i);
                ASSERT_GE(j, 0);
                ASSERT_LT(j, n);
                ++seen[size_t(j)];
                order.push_back(j);
                if (key == 0u) EXPECT_EQ(j, i);
            }
            for (int c : seen) EXPECT_EQ(c, 1) << "n " << n << " key " << key;
            orders.insert(order);
        }
        if (n >= 3) EXPECT_GT(orders.size(), 2u) << n;
    }
}
