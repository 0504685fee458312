// solve_soft_test.cpp — the soft step (SolverKind::SoftStep): velocities, impulses and poses
// within tolerance of the reference over the contact chain (warm-started, both launch shapes),
// bitwise repeatable, and physics: a resting box's step impulses sum to m g dt and it does not
// move; a 100 kg box on a 1 kg box sinks less than 1% of the box in 10 s of steps, and so does
// a 1,000 kg box with the light one held (SoftStepConfig::heldMassRatio; device and reference
// alike on it, the ground taking the whole load at once); without contacts a body falls as the
// substeps integrate it.
#include "contact_fixture.h"
#include "reference/solve_soft.h"
#include "stages/color_constraints.h"
#include "stages/contact_cache.h"
#include "stages/prepare_contacts.h"
#include "stages/solve_soft.h"
#include "world/plan.h"
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
const int kIterations = 10;

BtgSoftParams softParams(const BtgStepParams& p, int substeps = 0, float maxSag = SoftStepConfig{}.maxSag,
                         float heldMassRatio = SoftStepConfig{}.heldMassRatio,
                         float rootRatio = SoftStepConfig{}.substepsPerRootMassRatio)
{
    SoftStepConfig c;
    c.substeps = substeps;
    c.substepsPerRootMassRatio = rootRatio;
    c.maxSag = maxSag;
    c.heldMassRatio = heldMassRatio;
    return makeSoftParams(c, p, kIterations);
}

struct Result {
    ref::ContactBodies bodies;
    std::vector<BtgContact> contacts;
    uint status = 0;  // counters[kStatus] after the stage
};

// contacts -> prepare -> batching -> soft step -> poses on the device; prev: last step's contacts.
Result runDevice(const ref::ContactBodies& b, const std::vector<BtgManifold>& ms, const std::vector<BtgContact>& prev,
                 const BtgStepParams& p, const BtgSoftParams& sp, int maxColors, bool fused,
                 DeviceWorld::Resident resident = DeviceWorld::Resident::Auto,
                 DeviceWorld::Resident flow = DeviceWorld::Resident::Off, bool softPrepare = true, size_t groups = 0)
{
    DeviceWorld w(test::context());
    w.resident = resident;
    w.softResidentGroups = groups;
    w.softFlow = flow;
    w.lastContactCount = fused ? 0 : (1 << 30);
    test::uploadWorld(w, b, ms, uint(ms.size()), prev, ms.size() + 4);
    buildContacts(w, p);
    prepareContacts(w, p, softPrepare);  // as the pipeline prepares for the soft step, unless asked
    w.colorRounds = maxColors - 1;
    colorConstraints(w, maxColors);
    solveSoft(w, sp, w.numColors);
    softTransforms(w);
    Result r;
    r.bodies = b;
    size_t n = b.props.size();
    r.bodies.linVel = w.linVel.download(w.ctx, n);
    r.bodies.angVel = w.angVel.download(w.ctx, n);
    r.bodies.pos = w.pos.download(w.ctx, n);
    r.bodies.rot = w.rot.download(w.ctx, n);
    r.contacts = test::downloadContacts(w);
    r.status = w.counters.download(w.ctx, kNumCounters)[kStatus];
    return r;
}

Result runReference(const ref::ContactBodies& b, const std::vector<BtgManifold>& ms, const std::vector<BtgContact>& prev,
                    const BtgStepParams& p, const BtgSoftParams& sp, int maxColors)
{
    Result r;
    r.bodies = b;
    r.contacts = ref::buildContacts(ms, int(ms.size()), b, prev, p);
    std::vector<BtgFrictionDirs> dirs;  // with BTG_SOLVER_ANISOTROPIC_FRICTION
    std::vector<BtgEdge> edges = ref::prepareContacts(r.contacts, r.bodies, p, nullptr, &dirs);
    std::vector<int> colors = ref::colorConstraints(edges, r.bodies, maxColors);
    std::vector<BtgFloat4> rows = ref::solveSoft(r.contacts, colors, r.bodies, sp, maxColors, &dirs);
    ref::softTransforms(r.bodies, rows);
    return r;
}

void expectAlike(const Result& d, const Result& r, float tol)
{
    ASSERT_EQ(d.contacts.size(), r.contacts.size());
    for (size_t i = 0; i < r.bodies.props.size(); ++i) {
        test::expectNear4(d.bodies.linVel[i], r.bodies.linVel[i], tol, "linVel", i);
        test::expectNear4(d.bodies.angVel[i], r.bodies.angVel[i], tol, "angVel", i);
        test::expectNear4(d.bodies.pos[i], r.bodies.pos[i], tol, "pos", i);
        test::expectNear4(d.bodies.rot[i], r.bodies.rot[i], tol, "rot", i);
    }
    for (size_t i = 0; i < r.contacts.size(); ++i) {
        test::expectNear4(d.contacts[i].normalImpulse, r.contacts[i].normalImpulse, tol, "normalImpulse", i);
        test::expectNear4(d.contacts[i].friction1Impulse, r.contacts[i].friction1Impulse, tol, "friction1Impulse", i);
        test::expectNear4(d.contacts[i].friction2Impulse, r.contacts[i].friction2Impulse, tol, "friction2Impulse", i);
    }
}

float normalSum(const BtgContact& c)
{
    float s = 0.0f;
    for (int k = 0; k < c.numPoints; ++k) s += btgLane(c.normalImpulse, k);
    return s;
}

}  // namespace

TEST(SolveSoft, MatchesReferenceWithWarmStart)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    BtgSoftParams sp = softParams(p);
    ASSERT_EQ(sp.substeps, kIterations);  // substeps 0: m_numIterations of them
    Result r1 = runReference(s.bodies, s.manifolds, {}, p, sp, 8);
    Result r = runReference(s.bodies, s.manifolds, r1.contacts, p, sp, 8);
    // 10 substeps of 3 passes each: a few hundred rounded row updates per body.
    const float tol = 30 * tol::kStageAbs;
    for (bool fused : {true, false}) {
        SCOPED_TRACE(fused ? "one launch" : "per-color launches");
        Result d1 = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, fused);
        expectAlike(d1, r1, tol);
        Result d = runDevice(s.bodies, s.manifolds, d1.contacts, p, sp, 8, fused);
        expectAlike(d, r, tol);
        Result again = runDevice(s.bodies, s.manifolds, d1.contacts, p, sp, 8, fused);
        EXPECT_EQ(0, std::memcmp(again.bodies.linVel.data(), d.bodies.linVel.data(), d.bodies.linVel.size() * sizeof(BtgFloat4)));
        EXPECT_EQ(0, std::memcmp(again.bodies.pos.data(), d.bodies.pos.data(), d.bodies.pos.size() * sizeof(BtgFloat4)));
    }
    // Something was solved: the warm-started step carries the stacks' weight.
    float total = 0.0f;
    for (const BtgContact& c : r.contacts) total += normalSum(c);
    EXPECT_GT(total, 1.0f);
}

// The substeps after the first carry their warm start (the velocity change the last substep's
// impulses made: btgSoftBodyCarry) where no rolling rows or held pairs break that identity; the
// gather every substep (BtgSoftParams::gather) stays for those. Both give the same step within
// rounding, warm-started across steps, friction in the relax or also in the solve (where the
// friction's totals are added), on the reference and the device; and the gather still runs where
// it must.
TEST(SolveSoft, CarriedWarmStartIsTheGatheredOne)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    const BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    const float tol = 30 * tol::kStageAbs;
    for (bool frictionInSolve : {false, true}) {
        SCOPED_TRACE(frictionInSolve ? "friction also in the solve" : "friction in the relax");
        BtgSoftParams carried = softParams(p);
        carried.frictionInSolve = frictionInSolve ? 1 : 0;
        ASSERT_EQ(0, carried.gather);
        BtgSoftParams gathered = carried;
        gathered.gather = 1;
        const Result c1 = runReference(s.bodies, s.manifolds, {}, p, carried, 8);
        const Result g1 = runReference(s.bodies, s.manifolds, {}, p, gathered, 8);
        expectAlike(c1, g1, tol);
        const Result c = runReference(s.bodies, s.manifolds, c1.contacts, p, carried, 8);
        const Result g = runReference(s.bodies, s.manifolds, g1.contacts, p, gathered, 8);
        expectAlike(c, g, tol);
        for (bool fused : {true, false}) {
            SCOPED_TRACE(fused ? "one launch" : "per-color launches");
            expectAlike(runDevice(s.bodies, s.manifolds, c1.contacts, p, gathered, 8, fused), g, tol);
        }
    }
    BtgStepParams rolling = p;
    rolling.solverFlags |= BTG_SOLVER_ROLLING_FRICTION;
    EXPECT_EQ(1, softParams(rolling).gather);
    EXPECT_EQ(1, softParams(p, 0, SoftStepConfig{}.maxSag, 100.0f).gather);
}

// The three launch shapes compute the same arithmetic in the same color order: per-color
// launches, one launch on one group, and one launch over resident groups (where the device
// keeps them resident; a CPU device may time out at the grid barrier, which the pipeline
// redoes), and that one launch on a single resident group. On a CPU device the first three take the solve and relax sweeps eight contacts at a
// time in float8 lanes (soft_wide.h) and the flow's launch the scalar rows, so the flow checks
// the wide rows against the scalar ones bit for bit.
// Twice: with the scene's moving kinematic body (whose position passes keep their barriers in the
// flow), and with it made static (every body pass in the flow).
class SolveSoftLaunch : public ::testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(SolveSoft, SolveSoftLaunch, ::testing::Values(true, false));
TEST_P(SolveSoftLaunch, LaunchShapesAgreeBitwise)
{
    using Resident = DeviceWorld::Resident;
    test::StackScene s = test::stackScene(6, 4, 9);
    if (!GetParam()) {
        int kinematic = 0;
        for (size_t b = 0; b < s.bodies.props.size(); ++b)
            if (s.bodies.props[b].flags & BTG_BODY_KINEMATIC) {
                s.bodies.props[b].flags = BTG_BODY_STATIC;
                s.bodies.linVel[b] = s.bodies.linVel0[b] = btgZero4();
                ++kinematic;
            }
        ASSERT_EQ(kinematic, 1);
    }
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    BtgSoftParams sp = softParams(p);
    Result perColor = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false, Resident::Off);
    Result oneGroup = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, true, Resident::Off);
    Result resident = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false, Resident::On);
    // the resident launch on one group (its grid barriers the group's own)
    Result residentOne = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false, Resident::On, Resident::Off, true, 1);
    // the resident launch with the flow (per-body counts, no barrier between colours): on a CPU
    // device in groups of one work-item, so it must not time out anywhere
    Result flow = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false, Resident::On, Resident::On);
    EXPECT_EQ(perColor.status & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u);
    EXPECT_EQ(flow.status & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u) << "the flow timed out";
    EXPECT_EQ(residentOne.status & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u) << "one group timed out";
    std::vector<const Result*> others = {&oneGroup, &flow, &residentOne};
    if (resident.status & BTG_STATUS_GRID_BARRIER_TIMEOUT)
        EXPECT_FALSE(test::context().device().isGpu) << "a GPU must keep one group per compute unit resident";
    else
        others.push_back(&resident);
    const size_t n = perColor.bodies.linVel.size();
    for (const Result* o : others) {
        EXPECT_EQ(0, std::memcmp(o->bodies.linVel.data(), perColor.bodies.linVel.data(), n * sizeof(BtgFloat4)));
        EXPECT_EQ(0, std::memcmp(o->bodies.angVel.data(), perColor.bodies.angVel.data(), n * sizeof(BtgFloat4)));
        EXPECT_EQ(0, std::memcmp(o->bodies.pos.data(), perColor.bodies.pos.data(), n * sizeof(BtgFloat4)));
        EXPECT_EQ(0, std::memcmp(o->bodies.rot.data(), perColor.bodies.rot.data(), n * sizeof(BtgFloat4)));
        ASSERT_EQ(o->contacts.size(), perColor.contacts.size());
        for (size_t i = 0; i < o->contacts.size(); ++i)
            EXPECT_EQ(0, std::memcmp(&o->contacts[i].normalImpulse, &perColor.contacts[i].normalImpulse, sizeof(BtgFloat4)));
    }
    // friction in the solve too (the wide sweeps' other friction pass), per-color launches against
    // the flow's scalar rows
    sp.frictionInSolve = 1;
    Result perColorF = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false, Resident::Off);
    Result oneGroupF = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false, Resident::On, Resident::On);
    EXPECT_EQ(oneGroupF.status & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u) << "the flow timed out";
    EXPECT_EQ(0, std::memcmp(oneGroupF.bodies.linVel.data(), perColorF.bodies.linVel.data(), n * sizeof(BtgFloat4)));
    EXPECT_EQ(0, std::memcmp(oneGroupF.bodies.angVel.data(), perColorF.bodies.angVel.data(), n * sizeof(BtgFloat4)));
    EXPECT_EQ(0, std::memcmp(oneGroupF.bodies.pos.data(), perColorF.bodies.pos.data(), n * sizeof(BtgFloat4)));
    for (size_t i = 0; i < oneGroupF.contacts.size(); ++i)
        EXPECT_EQ(0, std::memcmp(&oneGroupF.contacts[i].friction1Impulse, &perColorF.contacts[i].friction1Impulse,
                                 sizeof(BtgFloat4)));
}

// prepare_contacts for the soft step makes only what the soft step reads of it
// (btgPrepareSoftContact: the normal, the friction, impulses of points without rows zeroed):
// the soft step's answer is the one after the bullet mode's full preparation, bit for bit, also
// with a kinematic body, friction in the solve and a contact whose pair is not solved.
TEST(SolveSoft, ItsPrepareIsBitwiseTheFullOne)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    for (int frictionInSolve : {0, 1}) {
        SCOPED_TRACE(frictionInSolve ? "friction in the solve" : "friction in the relax");
        BtgSoftParams sp = softParams(p);
        sp.frictionInSolve = frictionInSolve;
        const Result full = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false, DeviceWorld::Resident::Auto,
                                      DeviceWorld::Resident::Off, false);
        const Result own = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false);
        const size_t n = full.bodies.linVel.size();
        EXPECT_EQ(0, std::memcmp(own.bodies.linVel.data(), full.bodies.linVel.data(), n * sizeof(BtgFloat4)));
        EXPECT_EQ(0, std::memcmp(own.bodies.angVel.data(), full.bodies.angVel.data(), n * sizeof(BtgFloat4)));
        EXPECT_EQ(0, std::memcmp(own.bodies.pos.data(), full.bodies.pos.data(), n * sizeof(BtgFloat4)));
        EXPECT_EQ(0, std::memcmp(own.bodies.rot.data(), full.bodies.rot.data(), n * sizeof(BtgFloat4)));
        ASSERT_EQ(own.contacts.size(), full.contacts.size());
        for (size_t i = 0; i < own.contacts.size(); ++i) {
            EXPECT_EQ(0, std::memcmp(&own.contacts[i].normalImpulse, &full.contacts[i].normalImpulse, sizeof(BtgFloat4)));
            EXPECT_EQ(0, std::memcmp(&own.contacts[i].friction1Impulse, &full.contacts[i].friction1Impulse,
                                     sizeof(BtgFloat4)));
            EXPECT_EQ(0, std::memcmp(&own.contacts[i].tangent1, &full.contacts[i].tangent1, sizeof(BtgFloat4)));
            EXPECT_EQ(own.contacts[i].friction, full.contacts[i].friction);
        }
    }
}

// SOLVER_RANDMIZE_ORDER (the step's order seed: each substep's solve and relax sweeps permute
// their colours and points) and SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS (the relax's
// friction rows point by point after the normal): the device follows its reference, both
// launch shapes alike bit for bit, and each changes the answer.
TEST(SolveSoft, OrderBitsMatchReferenceAndChangeTheAnswer)
{
    test::StackScene s = test::stackScene(6, 4, 9);
    const BtgStepParams plain = test::defaultParams(int(s.bodies.props.size()));
    const Result base = runReference(s.bodies, s.manifolds, {}, plain, softParams(plain), 8);
    const float tol = 30 * tol::kStageAbs;
    for (int bits : {1, 2, 3}) {
        SCOPED_TRACE(bits == 1 ? "randomised order" : bits == 2 ? "interleaved" : "both");
        BtgStepParams p = plain;
        if (bits & 1) p.randomSeed = 12345u;
        if (bits & 2) p.solverFlags |= BTG_SOLVER_INTERLEAVE;
        const BtgSoftParams sp = softParams(p);
        EXPECT_EQ((bits & 1) ? 12345u : 0u, sp.orderSeed);
        EXPECT_EQ((bits & 2) ? 1 : 0, sp.interleave);
        const Result r = runReference(s.bodies, s.manifolds, {}, p, sp, 8);
        const Result perColor = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, false);
        const Result fused = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, true);
        expectAlike(perColor, r, tol);
        const size_t n = r.bodies.linVel.size();
        EXPECT_EQ(0, std::memcmp(fused.bodies.linVel.data(), perColor.bodies.linVel.data(), n * sizeof(BtgFloat4)));
        EXPECT_EQ(0, std::memcmp(fused.bodies.pos.data(), perColor.bodies.pos.data(), n * sizeof(BtgFloat4)));
        EXPECT_NE(0, std::memcmp(r.bodies.angVel.data(), base.bodies.angVel.data(), n * sizeof(BtgFloat4)))
            << "the order bits changed nothing";
    }
}

// Anisotropic friction (BtgSoftParams::anisotropic: each point's friction rows along
// prepare_contacts' scaled directions; with one direction the first alone), warm-started: the
// device against the reference on the stack scene with every box turned and anisotropic, and
// the directions change the answer.
TEST(SolveSoft, AnisotropicFrictionMatchesReference)
{
    test::StackScene s = test::stackScene(4, 3, 5);
    for (size_t i = 1; i < s.bodies.props.size(); ++i) {
        s.bodies.props[i].flags |= BTG_BODY_ANISOTROPIC;
        s.bodies.props[i].anisotropicFriction = btgMake4(1.0f, 0.6f, 0.2f, 0);
        s.bodies.rot[i] = btgQuatNormalize(btgMake4(0.1f * float(i % 3), 0.3f, -0.05f * float(i % 2), 1.0f));
        s.bodies.linVel[i] = btgMake4(0.5f, -0.1f, 0.3f * float(i % 2), 0.0f);  // sliding: directions along the slip
    }
    const BtgStepParams plain = test::defaultParams(int(s.bodies.props.size()));
    const Result isotropic = runReference(s.bodies, s.manifolds, {}, plain, softParams(plain), 8);
    const float tol = 30 * tol::kStageAbs;
    for (int two : {0, 1}) {
        SCOPED_TRACE(two);
        BtgStepParams p = plain;
        p.solverFlags = BTG_SOLVER_ANISOTROPIC_FRICTION;
        p.twoFrictionDirections = two;
        const BtgSoftParams sp = softParams(p);
        EXPECT_EQ(1, sp.anisotropic);
        EXPECT_EQ(two, sp.twoDirections);
        const Result r1 = runReference(s.bodies, s.manifolds, {}, p, sp, 8);
        const Result r = runReference(s.bodies, s.manifolds, r1.contacts, p, sp, 8);
        for (bool fused : {true, false}) {
            SCOPED_TRACE(fused ? "one launch" : "per-color launches");
            const Result d1 = runDevice(s.bodies, s.manifolds, {}, p, sp, 8, fused);
            expectAlike(d1, r1, tol);
            expectAlike(runDevice(s.bodies, s.manifolds, d1.contacts, p, sp, 8, fused), r, tol);
        }
        if (!two)
            for (const BtgContact& c : r1.contacts)
                for (int k = 0; k < c.numPoints; ++k) EXPECT_EQ(0.0f, btgLane(c.friction2Impulse, k));
        const size_t n = r1.bodies.linVel.size();
        EXPECT_NE(0, std::memcmp(r1.bodies.linVel.data(), isotropic.bodies.linVel.data(), n * sizeof(BtgFloat4)))
            << "the anisotropy changed nothing";
    }
}

// A unit box of 1 kg resting on a static ground, moving down at g dt as after the forces: its
// step's normal impulses sum to m g dt, and it stays where it is.
TEST(SolveSoft, RestingBoxCarriesItsWeight)
{
    ref::ContactBodies b;
    test::addBody(b, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC);
    BtgFloat4 pos = btgMake4(0, 0.5f, 0, 0);
    int box = test::addBody(b, pos, 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC);
    const float dt = 1.0f / 60.0f;
    b.linVel[box] = btgMake4(0, -kG * dt, 0, 0);
    std::vector<BtgManifold> ms = {test::boxOnPlane(box, 0, pos, 0.5f, 0.0f)};
    BtgStepParams p = test::defaultParams(2);
    BtgSoftParams sp = softParams(p);
    std::vector<BtgContact> prev;
    Result d;
    for (int step = 0; step < 3; ++step) {
        d = runDevice(b, ms, prev, p, sp, 4, true);
        prev = d.contacts;
    }
    ASSERT_EQ(d.contacts.size(), 1u);
    EXPECT_NEAR(normalSum(d.contacts[0]), kG * dt, 0.02f * kG * dt);
    EXPECT_NEAR(d.bodies.linVel[box].y, 0.0f, 1e-3f);
    EXPECT_NEAR(d.bodies.pos[box].y, 0.5f, 1e-4f);
}

// A heavy unit box (1 kg times ratio) on a 1 kg unit box on a static ground, at rest, touching.
struct HeavyOnLight {
    ref::ContactBodies b;
    int light = 0, heavy = 0;
};
HeavyOnLight heavyOnLight(float ratio)
{
    HeavyOnLight s;
    test::addBody(s.b, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC);
    s.light = test::addBody(s.b, btgMake4(0, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC);
    s.heavy = test::addBody(s.b, btgMake4(0, 1.5f, 0, 0), 1.0f / ratio, btgMake4(6 / ratio, 6 / ratio, 6 / ratio, 0),
                            BTG_BODY_DYNAMIC);
    return s;
}
// Gravity for one step (velocities before it kept as the soft step's start) and the two
// manifolds from the poses.
std::vector<BtgManifold> stepHeavyOnLight(HeavyOnLight& s)
{
    const float dt = 1.0f / 60.0f;
    for (int i : {s.light, s.heavy}) {
        s.b.linVel0[i] = s.b.linVel[i];
        s.b.angVel0[i] = s.b.angVel[i];
        s.b.linVel[i] = s.b.linVel[i] + btgMake4(0, -kG * dt, 0, 0);
    }
    return {test::boxOnPlane(s.light, 0, s.b.pos[s.light], 0.5f, s.b.pos[s.light].y - 0.5f),
            test::boxOnPlane(s.heavy, s.light, s.b.pos[s.heavy], 0.5f, s.b.pos[s.heavy].y - s.b.pos[s.light].y - 1.0f)};
}

// The heavy box on the light one stepped 600 times (10 s) through the stage alone; returns the
// deepest penetration of either contact.
float sinkOfHeavyOnLight(float ratio, float maxSag, float heldMassRatio = SoftStepConfig{}.heldMassRatio,
                         float rootRatio = SoftStepConfig{}.substepsPerRootMassRatio)
{
    HeavyOnLight s = heavyOnLight(ratio);
    ref::ContactBodies& b = s.b;
    const int light = s.light, heavy = s.heavy;
    BtgStepParams p = test::defaultParams(3);
    BtgSoftParams sp = softParams(p, 0, maxSag, heldMassRatio, rootRatio);
    std::vector<BtgContact> prev;
    float worst = 0.0f;
    for (int step = 0; step < 600; ++step) {
        std::vector<BtgManifold> ms = stepHeavyOnLight(s);
        Result r = runReference(b, ms, prev, p, sp, 4);
        prev = r.contacts;
        b.pos = r.bodies.pos;
        b.rot = r.bodies.rot;
        b.linVel = r.bodies.linVel;
        b.angVel = r.bodies.angVel;
        worst = std::max({worst, 0.5f - b.pos[light].y, b.pos[light].y + 1.0f - b.pos[heavy].y});
    }
    return worst;
}

// Mass ratio 100 at the defaults (the 20 substeps it takes): neither contact sinks by 1% of the box. Box2D's
// springs (maxSag 0), relative to the light box's effective mass, sink further.
TEST(SolveSoft, MassRatio100Stands)
{
    const float stiffened = sinkOfHeavyOnLight(100.0f, SoftStepConfig{}.maxSag);
    const float box2d = sinkOfHeavyOnLight(100.0f, 0.0f);
    RecordProperty("sink_m", std::to_string(stiffened));
    RecordProperty("sink_box2d_springs_m", std::to_string(box2d));
    EXPECT_LT(stiffened, 0.01f);
    EXPECT_GT(box2d, stiffened);
}

const float kHeld = 100.0f;  // SoftStepConfig::heldMassRatio as the README suggests it

// Mass ratio 1,000 at 10 substeps: with the light box held (heldMassRatio 100) neither contact
// sinks by 1% of the box in 10 s; without (the default), the pair rings on the ground and sinks further.
// Mass ratio 1,000: at 10 substeps the pair sinks; held at 10 it stands, and so it does at the
// 64 substeps the default takes for it.
TEST(SolveSoft, MassRatio1000StandsHeldOrWithItsSubsteps)
{
    const float held = sinkOfHeavyOnLight(1000.0f, SoftStepConfig{}.maxSag, kHeld);
    const float ten = sinkOfHeavyOnLight(1000.0f, SoftStepConfig{}.maxSag, 0.0f, 0.0f);
    const float own = sinkOfHeavyOnLight(1000.0f, SoftStepConfig{}.maxSag);
    RecordProperty("sink_m", std::to_string(held));
    RecordProperty("sink_ten_substeps_m", std::to_string(ten));
    RecordProperty("sink_own_substeps_m", std::to_string(own));
    EXPECT_LT(held, 0.01f);
    EXPECT_GT(ten, 0.01f);
    EXPECT_LT(own, 0.01f);
}

// The substeps the default takes: m_numIterations up to a mass ratio of 25 (2 sqrt(25) = 10),
// then the least n with n^2 >= 4 r, up to maxSubsteps; an explicit count and holding keep theirs.
TEST(SolveSoft, SubstepsFollowTheMassRatio)
{
    const SoftStepConfig d;
    EXPECT_EQ(10, softSubsteps(d, 10, 0.0f));
    EXPECT_EQ(10, softSubsteps(d, 10, 25.0f));
    EXPECT_EQ(11, softSubsteps(d, 10, 26.0f));
    EXPECT_EQ(20, softSubsteps(d, 10, 100.0f));
    EXPECT_EQ(40, softSubsteps(d, 10, 400.0f));
    EXPECT_EQ(64, softSubsteps(d, 10, 1000.0f));
    EXPECT_EQ(128, softSubsteps(d, 10, 1e6f));
    EXPECT_EQ(30, softSubsteps(d, 30, 100.0f));
    SoftStepConfig fixed = d;
    fixed.substeps = 12;
    EXPECT_EQ(12, softSubsteps(fixed, 10, 1000.0f));
    SoftStepConfig held = d;
    held.heldMassRatio = kHeld;
    EXPECT_EQ(10, softSubsteps(held, 10, 1000.0f));
    SoftStepConfig off = d;
    off.substepsPerRootMassRatio = 0.0f;
    EXPECT_EQ(10, softSubsteps(off, 10, 1000.0f));
    // The device takes the same count from the same ratio: the stage's parameters for it.
    const BtgSoftParams p = makeSoftParams(d, test::defaultParams(3), 10);
    EXPECT_EQ(64, btgSoftSubstepsFor(p, 1000.0f));
    const BtgSoftParams q = btgSoftParamsWith(p, 64);
    EXPECT_FLOAT_EQ(q.h, p.dt / 64.0f);
    const BtgSoftParams same = btgSoftParamsWith(p, 10);
    EXPECT_EQ(0, std::memcmp(&p, &same, sizeof p)) << "the host's scalars are the device's formula";
}

// The push speed the default takes from the app's solver info: stock's largest real-velocity push
// of a penetration (m_erp x |m_splitImpulsePenetrationThreshold| / dt: 0.2 x 0.04 x 60 = 0.48
// m/s at Bullet's defaults), Box2D's 3 m/s without split impulse; a set value stands.
TEST(SolveSoft, PushSpeedFollowsTheSolverInfo)
{
    const SoftStepConfig d;
    BtgStepParams params = test::defaultParams(3);
    params.dt = 1.0f / 60.0f;
    params.erp = 0.2f;
    params.splitPenetrationThreshold = -0.04f;
    params.splitImpulse = 1;
    EXPECT_NEAR(pushSpeedFor(d, params), 0.48f, 1e-5f);
    EXPECT_NEAR(makeSoftParams(d, params, 10).pushSpeed, 0.48f, 1e-5f);
    params.erp = 0.4f;
    EXPECT_NEAR(pushSpeedFor(d, params), 0.96f, 1e-5f);
    params.splitImpulse = 0;
    EXPECT_EQ(pushSpeedFor(d, params), 3.0f);
    SoftStepConfig set = d;
    set.pushSpeed = 1.5f;
    EXPECT_EQ(pushSpeedFor(set, params), 1.5f);
}

// The held pair on the device, both launch shapes, against the reference over a cold and a
// warm-started step, bitwise repeatable; the ground takes the pair's weight in the first step already (within 10%;
// without holding, Gauss-Seidel passes it on a thousandth at a time: under half of it).
TEST(SolveSoft, HeldPairMatchesReference)
{
    const float dt = 1.0f / 60.0f, ratio = 1000.0f;
    for (bool fused : {true, false}) {
        SCOPED_TRACE(fused ? "one launch" : "per-color launches");
        HeavyOnLight s = heavyOnLight(ratio);
        BtgStepParams p = test::defaultParams(3);
        BtgSoftParams sp = softParams(p, 0, SoftStepConfig{}.maxSag, kHeld);
        std::vector<BtgContact> prevD, prevR;
        for (int step = 0; step < 2; ++step) {
            std::vector<BtgManifold> ms = stepHeavyOnLight(s);
            Result d = runDevice(s.b, ms, prevD, p, sp, 4, fused);
            Result r = runReference(s.b, ms, prevR, p, sp, 4);
            Result again = runDevice(s.b, ms, prevD, p, sp, 4, fused);
            EXPECT_EQ(0, std::memcmp(again.bodies.linVel.data(), d.bodies.linVel.data(), 3 * sizeof(BtgFloat4)));
            EXPECT_EQ(0, std::memcmp(again.bodies.pos.data(), d.bodies.pos.data(), 3 * sizeof(BtgFloat4)));
            EXPECT_EQ(d.status & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u);
            expectAlike(d, r, 30 * tol::kStageAbs * ratio);  // impulses of a 1,000 kg body
            ASSERT_EQ(r.contacts.size(), 2u);
            const BtgContact& ground = r.contacts[0].bodyA == 0 || r.contacts[0].bodyB == 0 ? r.contacts[0] : r.contacts[1];
            // (the first step's first substep starts from nothing: 93% of it on PoCL)
            EXPECT_NEAR(normalSum(ground), (1.0f + ratio) * kG * dt, (step ? 0.05f : 0.1f) * (1.0f + ratio) * kG * dt)
                << "step " << step;
            if (step == 0) {
                Result unheld = runReference(s.b, ms, {}, p, softParams(p), 4);
                const BtgContact& g = unheld.contacts[0].bodyA == 0 || unheld.contacts[0].bodyB == 0 ? unheld.contacts[0]
                                                                                                    : unheld.contacts[1];
                EXPECT_LT(normalSum(g), 0.5f * (1.0f + ratio) * kG * dt);
            }
            prevD = d.contacts;
            prevR = r.contacts;
            s.b.pos = r.bodies.pos;
            s.b.rot = r.bodies.rot;
            s.b.linVel = r.bodies.linVel;
            s.b.angVel = r.bodies.angVel;
        }
    }
}

// No contacts: the stage still moves the bodies, each substep taking its share of gravity
// (x = v0 t + g t^2 (n + 1) / 2n after one step).
TEST(SolveSoft, FreeBodyFallsThroughSubsteps)
{
    ref::ContactBodies b;
    int ball = test::addBody(b, btgMake4(0, 10, 0, 0), 1.0f, btgMake4(1, 1, 1, 0), BTG_BODY_DYNAMIC);
    const float dt = 1.0f / 60.0f;
    b.linVel[ball] = btgMake4(0, -kG * dt, 0, 0);
    BtgStepParams p = test::defaultParams(1);
    BtgSoftParams sp = softParams(p, 4);
    Result d = runDevice(b, {}, {}, p, sp, 4, true);
    EXPECT_NEAR(d.bodies.linVel[ball].y, -kG * dt, 1e-6f);
    EXPECT_NEAR(d.bodies.pos[ball].y, 10.0f - kG * dt * dt * 5.0f / 8.0f, 1e-5f);
}

// The plan of a soft-step scene: the soft stages in place of the PGS solve and the Euler
// integration; a scene with nothing to collide or join keeps integrate_transforms.
TEST(SolveSoft, PlanRunsTheSoftStages)
{
    PlanInput in;
    in.solver = SolverKind::SoftStep;
    PlanBody ground, box;
    ground.shapeType = BTG_SHAPE_BOX;
    ground.size = 10.0f;
    box.shapeType = BTG_SHAPE_BOX;
    box.size = 1.7f;
    box.movable = box.dynamic = true;
    in.bodies = {ground, box, box};
    const std::vector<std::string> stages = derivePlan(in).plan.stages();
    auto has = [&](const char* name) { return std::find(stages.begin(), stages.end(), name) != stages.end(); };
    EXPECT_TRUE(has("color_constraints") && has("solve_soft") && has("soft_transforms"));
    EXPECT_FALSE(has("solve_constraints") || has("solve_jacobi") || has("integrate_transforms"));
    in.bodies = {box};
    const std::vector<std::string> alone = derivePlan(in).plan.stages();
    EXPECT_NE(std::find(alone.begin(), alone.end(), "integrate_transforms"), alone.end());
    EXPECT_EQ(std::find(alone.begin(), alone.end(), "solve_soft"), alone.end());
}
