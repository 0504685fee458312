// update_activation_test.cpp — deactivation on the device against the CPU reference, and
// Bullet's rules: an island sleeps only when all its bodies have been slow for the
// deactivation time; one moving body keeps its island awake; a moving body touching a
// sleeper wakes it, and so does its pair at the step's end (the whole island); DISABLE_DEACTIVATION
// never sleeps.
#include "reference/update_activation.h"
#include "shared/activation.h"
#include "stages/sync_bodies.h"
#include "stages/update_activation.h"
#include "test_device.h"

#include <gtest/gtest.h>

#include <tuple>

using namespace btgpu;

namespace {

struct Scene {
    reference::ActivationState s;
    std::vector<BtgEdge> edges;
};

// A chain 0-1-2-3 of dynamic bodies in contact (edges of the constraint graph), body 4 apart,
// body 5 static under body 0.
Scene chain()
{
    Scene sc;
    const int n = 6;
    for (int i = 0; i < n; ++i) {
        BtgBodyProps p{};
        p.flags = i == 5 ? BTG_BODY_STATIC : BTG_BODY_DYNAMIC;
        p.invInertiaLocal = btgMake4(1, 1, 1, 0);
        p.invMass = i == 5 ? 0.0f : 1.0f;
        p.sleepLinear = 0.8f;
        p.sleepAngular = 1.0f;
        sc.s.props.push_back(p);
        sc.s.linVel.push_back(btgZero4());
        sc.s.angVel.push_back(btgZero4());
        sc.s.sleepTime.push_back(0.0f);
        sc.s.islandTime.push_back(BTG_NEVER_UINT);
        sc.s.sleepState.push_back(0);
    }
    int links[4][2] = {{0, 1}, {1, 2}, {2, 3}, {0, 5}};
    for (auto& l : links) sc.edges.push_back(BtgEdge{l[0], l[1]});
    return sc;
}

// The graph's edges on the device, as prepare_contacts (and other kinds) leave them.
void setEdges(DeviceWorld& w, const std::vector<BtgEdge>& edges)
{
    w.edgeCapacity = edges.size();
    w.edges.upload(w.ctx, edges);
    std::vector<uint> counters(kNumCounters, 0);
    counters[kEdgeCount] = uint(edges.size());
    w.counters.upload(w.ctx, counters);
}

struct Device {
    DeviceWorld w{test::context()};
    explicit Device(const Scene& sc)
    {
        int n = int(sc.s.props.size());
        resizeBodies(w, n);
        w.linVel.upload(w.ctx, sc.s.linVel);
        w.angVel.upload(w.ctx, sc.s.angVel);
        w.props.upload(w.ctx, sc.s.props);
        w.sleepTime.upload(w.ctx, sc.s.sleepTime);
        w.islandTime.upload(w.ctx, sc.s.islandTime);
        setEdges(w, sc.edges);
    }
    std::vector<uint> sleepState() { return w.sleepState.download(w.ctx, size_t(w.numBodies)); }
};

}  // namespace

TEST(UpdateActivation, IslandSleepsTogetherAndMatchesReference)
{
    Scene sc = chain();
    sc.s.linVel[3] = btgMake4(2, 0, 0, 0);  // the chain's far end keeps moving
    Device d(sc);
    const float dt = 1.0f / 60.0f;
    for (int step = 0; step < 150; ++step) {
        updateActivation(d.w, dt, 2.0f);
        reference::updateActivation(sc.s, sc.edges, dt, 2.0f);
    }
    std::vector<uint> dev = d.sleepState();
    EXPECT_EQ(dev, sc.s.sleepState);
    // Body 4 is alone and still: asleep after 2 s. The chain holds a moving body: awake.
    EXPECT_EQ(dev[4], 1u);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(dev[i], 0u) << i;
    EXPECT_EQ(dev[5], 0u);  // static bodies never report sleep
    auto t = d.w.islandTime.download(d.w.ctx, 6);
    EXPECT_EQ(t, sc.s.islandTime);
}

TEST(UpdateActivation, WholeIslandSleepsThenWakes)
{
    Scene sc = chain();
    sc.s.props[4].flags |= BTG_BODY_NEVER_SLEEP;
    Device d(sc);
    const float dt = 1.0f / 60.0f;
    for (int step = 0; step < 130; ++step) updateActivation(d.w, dt, 2.0f);
    std::vector<uint> st = d.sleepState();
    for (int i = 0; i < 4; ++i) EXPECT_EQ(st[i], 1u) << i;
    EXPECT_EQ(st[4], 0u);  // DISABLE_DEACTIVATION
    // Wake: body 4 moves and touches body 3.
    std::vector<BtgEdge> es = sc.edges;
    es.push_back(BtgEdge{3, 4});
    setEdges(d.w, es);
    std::vector<BtgFloat4> v(6, btgZero4());
    v[4] = btgMake4(3, 0, 0, 0);
    d.w.linVel.upload(d.w.ctx, v);
    updateActivation(d.w, dt, 2.0f);
    st = d.sleepState();
    EXPECT_EQ(st[3], 0u);  // woken by the moving body
}

namespace {
// The chain's bodies 0-3 asleep (timers past the deactivation time), 4 and 5 as they were.
void sleepChain(Scene& sc)
{
    for (int i = 0; i < 4; ++i) {
        sc.s.props[i].flags |= BTG_BODY_SLEEPING;
        sc.s.sleepTime[i] = 2.5f;
        sc.s.sleepState[i] = 1;
    }
}

// The device's flags, timers and sleep states, body by body, as the reference's.
void expectAsReference(Device& d, const reference::ActivationState& ref)
{
    const std::vector<BtgBodyProps> props = d.w.props.download(d.w.ctx, 6);
    const std::vector<float> timers = d.w.sleepTime.download(d.w.ctx, 6);
    const std::vector<uint> st = d.sleepState();
    for (int i = 0; i < 6; ++i) {
        EXPECT_EQ(props[size_t(i)].flags, ref.props[size_t(i)].flags) << i;
        EXPECT_EQ(timers[size_t(i)], ref.sleepTime[size_t(i)]) << i;
        EXPECT_EQ(st[size_t(i)], ref.sleepState[size_t(i)]) << i;
    }
}
}  // namespace

// A substep that overflowed (or gave up at a grid barrier) is redone from the state before the
// call, and the snapshot holds poses and velocities only: the deactivation of the attempt must
// leave the timers, the island timers, the wake marks and the flags as it found them, else the
// redo starts with the step counted once already (a body could fall asleep a step early, and
// start its redo asleep). Found by a landscape's results changing with the pair buffers' size.
TEST(UpdateActivation, AnOverflowedStepLeavesTheTimersAndFlagsAlone)
{
    Scene sc = chain();
    Device d(sc);
    const float dt = 1.0f / 60.0f;
    for (int step = 0; step < 119; ++step) {
        updateActivation(d.w, dt, 2.0f);
        reference::updateActivation(sc.s, sc.edges, dt, 2.0f);
    }
    auto state = [&] {
        return std::make_tuple(d.w.sleepTime.download(d.w.ctx, 6), d.w.islandTime.download(d.w.ctx, 6),
                               d.w.wake.download(d.w.ctx, 6), d.w.sleepState.download(d.w.ctx, 6));
    };
    const auto before = state();
    const std::vector<BtgBodyProps> propsBefore = d.w.props.download(d.w.ctx, 6);
    for (uint status : {BTG_STATUS_PAIR_OVERFLOW, BTG_STATUS_CONTACT_OVERFLOW, BTG_STATUS_SUB_PAIR_OVERFLOW,
                        BTG_STATUS_GRID_BARRIER_TIMEOUT}) {
        d.w.counters.fill(d.w.ctx, status, size_t(kStatus), 1);
        for (int attempt = 0; attempt < 3; ++attempt) updateActivation(d.w, dt, 2.0f);
        EXPECT_TRUE(state() == before) << "status " << status;
        const std::vector<BtgBodyProps> props = d.w.props.download(d.w.ctx, 6);
        for (int i = 0; i < 6; ++i) EXPECT_EQ(props[size_t(i)].flags, propsBefore[size_t(i)].flags) << status << " body " << i;
    }
    // The redo then goes on as if the attempts never ran: the chain falls asleep at the
    // reference's step (2 s), not before.
    d.w.counters.fill(d.w.ctx, 0u, size_t(kStatus), 1);
    for (int step = 0; step < 3; ++step) {
        updateActivation(d.w, dt, 2.0f);
        reference::updateActivation(sc.s, sc.edges, dt, 2.0f);
        EXPECT_EQ(d.sleepState(), sc.s.sleepState) << "step " << step;
        EXPECT_EQ(d.w.sleepTime.download(d.w.ctx, 6), sc.s.sleepTime) << "step " << step;
    }
}

// Before the solve (wakeTouched): a sleeping body that a moving body's contact touches wakes in
// the same step, its flags, timers and sleep state as the reference's; one touched by a slow
// body, or by a contact without points, sleeps on; a stale wake mark from the last step's end
// wakes nothing.
TEST(UpdateActivation, WakeTouchedBeforeTheSolveMatchesReference)
{
    Scene sc = chain();
    sleepChain(sc);
    sc.s.sleepTime[4] = 0.0f;  // body 4 moving (its own timer 0)
    Device d(sc);
    BtgContact touch{}, slow{}, empty{};
    touch.bodyA = 4, touch.bodyB = 1, touch.numPoints = 2;  // the moving body on sleeper 1
    slow.bodyA = 3, slow.bodyB = 0, slow.numPoints = 1;     // two sleepers
    empty.bodyA = 2, empty.bodyB = 4, empty.numPoints = 0;  // no points: no touch
    const std::vector<BtgContact> contacts = {touch, slow, empty};
    d.w.contactCapacity = contacts.size();
    d.w.contacts.upload(d.w.ctx, contacts);
    std::vector<uint> counters(kNumCounters, 0);
    counters[kContactCount] = uint(contacts.size());
    d.w.counters.upload(d.w.ctx, counters);
    std::vector<uint> stale(6, 0u);
    stale[3] = 1u;  // left by the last step's island_min
    d.w.wake.upload(d.w.ctx, stale);
    d.w.sleepState.upload(d.w.ctx, sc.s.sleepState);
    wakeTouched(d.w);
    reference::ActivationState ref = sc.s;
    reference::wakeTouched(ref, contacts);
    const std::vector<BtgBodyProps> props = d.w.props.download(d.w.ctx, 6);
    const std::vector<float> timers = d.w.sleepTime.download(d.w.ctx, 6);
    expectAsReference(d, ref);
    EXPECT_FALSE(props[1].flags & BTG_BODY_SLEEPING);  // touched by the moving body
    EXPECT_EQ(timers[1], 0.0f);
    for (int i : {0, 2, 3}) EXPECT_TRUE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << i;
}

// Stock activates a sleeping island whole before its solve once any body of it is active: the
// app's activate() on the top box of a sleeping stack wakes the boxes under it in the same step.
// btgpu woke them a contact a step (the end-of-step path). The chain 0-1-2-3 falls asleep as one
// island (labelled by island_min), body 4 alone in another; the app wakes body 3 (its flags
// uploaded awake, reset_rows marking its island): before the solve 0, 1 and 2 wake too, 4 sleeps.
TEST(UpdateActivation, AnIslandWakesWholeBeforeTheSolve)
{
    Scene sc = chain();
    Device d(sc);
    const float dt = 1.0f / 60.0f;
    for (int step = 0; step < 130; ++step) updateActivation(d.w, dt, 2.0f);
    std::vector<BtgBodyProps> props = d.w.props.download(d.w.ctx, 6);
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << i;
    props[3].flags &= ~BTG_BODY_SLEEPING;  // the app's activate(), as sync-in uploads it
    d.w.props.upload(d.w.ctx, props);
    resetRows(d.w, {3}, true);
    d.w.contactCapacity = 0;  // no contacts this step: only the island wakes them
    wakeTouched(d.w);
    props = d.w.props.download(d.w.ctx, 6);
    const std::vector<uint> st = d.sleepState();
    for (int i = 0; i < 4; ++i) {
        EXPECT_FALSE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << "body " << i << " of the woken island";
        EXPECT_EQ(st[size_t(i)], 0u) << i;
    }
    EXPECT_TRUE(props[4].flags & BTG_BODY_SLEEPING) << "another island sleeps on";
    // A fresh row (a body added, perhaps in a removed one's row) marks no island.
    for (int step = 0; step < 130; ++step) updateActivation(d.w, dt, 2.0f);
    resetRows(d.w, {0}, false);
    wakeTouched(d.w);
    props = d.w.props.download(d.w.ctx, 6);
    for (int i : {1, 2, 3}) EXPECT_TRUE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << i;
}

// At the step's end a sleeping island one of whose bodies a moving body's pair reaches (AABBs
// met, no contact yet) wakes whole (wake_paired): stock's islands are its broadphase pairs, and
// the next step then collides the island's own pairs. A slow body's pair wakes nothing (btgWakes,
// as for a touch), nor does any pair under a redo status.
TEST(UpdateActivation, APairWithAMovingBodyWakesTheSleepingIslandAtTheStepsEnd)
{
    Scene sc = chain();
    sc.s.linVel[4] = btgMake4(3, 0, 0, 0);  // body 4 stays awake, apart from the chain
    Device d(sc);
    const float dt = 1.0f / 60.0f;
    for (int step = 0; step < 130; ++step) updateActivation(d.w, dt, 2.0f);
    std::vector<BtgBodyProps> props = d.w.props.download(d.w.ctx, 6);
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << i;
    ASSERT_FALSE(props[4].flags & BTG_BODY_SLEEPING);
    // Body 4 comes to rest (its own timer runs: slow), then its pair with body 3 (the chain's far
    // end) is found: nothing wakes.
    d.w.linVel.upload(d.w.ctx, std::vector<BtgFloat4>(6, btgZero4()));
    updateActivation(d.w, dt, 2.0f);
    d.w.pairCapacity = 1;
    d.w.pairs.upload(d.w.ctx, std::vector<BtgPair>{BtgPair{3, 4, BTG_WHOLE_BODY, BTG_WHOLE_BODY}});
    std::vector<uint> counters = d.w.counters.download(d.w.ctx, kNumCounters);
    counters[kPairCount] = 1;
    d.w.counters.upload(d.w.ctx, counters);
    updateActivation(d.w, dt, 2.0f);
    props = d.w.props.download(d.w.ctx, 6);
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << "slow pair, body " << i;
    // Body 4 moving: under a redo status nothing wakes; then the whole chain does.
    std::vector<BtgFloat4> v(6, btgZero4());
    v[4] = btgMake4(3, 0, 0, 0);
    d.w.linVel.upload(d.w.ctx, v);
    counters = d.w.counters.download(d.w.ctx, kNumCounters);
    counters[kStatus] = BTG_STATUS_PAIR_OVERFLOW;
    d.w.counters.upload(d.w.ctx, counters);
    updateActivation(d.w, dt, 2.0f);
    props = d.w.props.download(d.w.ctx, 6);
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << "redo, body " << i;
    counters[kStatus] = 0;
    d.w.counters.upload(d.w.ctx, counters);
    updateActivation(d.w, dt, 2.0f);
    props = d.w.props.download(d.w.ctx, 6);
    const std::vector<uint> st = d.sleepState();
    for (int i = 0; i < 4; ++i) {
        EXPECT_FALSE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << "body " << i << " of the paired island";
        EXPECT_EQ(st[size_t(i)], 0u) << i;
    }
}

// Joints before the solve (wake_jointed): a sleeping body joined to an awake one wakes, and so
// does the one joined to it in turn, as stock activates the whole island; joints between sleepers
// only, disabled joints and joints to static bodies or the fixed body wake nothing. The joint
// that reaches the awake body is listed last, so one pass in list order would not wake body 2.
TEST(UpdateActivation, WakeJointedFollowsTheJointsAsTheReference)
{
    Scene sc = chain();
    sleepChain(sc);
    auto joint = [](int a, int b, bool enabled) {
        BtgJoint j{};
        j.type = BTG_JOINT_HINGE;
        j.bodyA = a;
        j.bodyB = b;
        j.flags = enabled ? BTG_JOINT_ENABLED : 0u;
        return j;
    };
    const std::vector<BtgJoint> joints = {joint(2, 3, true), joint(1, 0, true), joint(2, 1, false),
                                          joint(5, 0, true), joint(BTG_JOINT_FIXED_BODY, 1, true), joint(4, 3, true)};
    Device d(sc);
    d.w.contactCapacity = 1;
    d.w.contacts.reserve(d.w.ctx, 1);
    std::vector<uint> counters(kNumCounters, 0);  // no contacts
    d.w.counters.upload(d.w.ctx, counters);
    d.w.joints.upload(d.w.ctx, joints);
    d.w.numJoints = int(joints.size());
    d.w.sleepState.upload(d.w.ctx, sc.s.sleepState);
    wakeTouched(d.w);
    reference::ActivationState ref = sc.s;
    reference::wakeTouched(ref, {}, joints);
    const std::vector<BtgBodyProps> props = d.w.props.download(d.w.ctx, 6);
    expectAsReference(d, ref);
    for (int i : {2, 3}) EXPECT_FALSE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << i;
    for (int i : {0, 1}) EXPECT_TRUE(props[size_t(i)].flags & BTG_BODY_SLEEPING) << i;
    EXPECT_EQ(d.w.wake.download(d.w.ctx, 6), std::vector<uint>(6, 0u));  // the marks cleared for the step's end
}
