// broadphase_leaves_test.cpp — stage broadphase_leaves against its CPU reference: the leaves
// after several calls of moving bodies (within the stage bounds: the predicted rotation's sin and
// cos may round differently; exactly without rotation), and, on the device's own leaves, the
// overlapping pairs, m_newpairs and the added/removed lists exactly, also after the list
// overflowed and was made again (and the pairs stock's pass meets on the way, from the old
// leaves), and no list made while no leaf moves; and the leaf rules
// themselves as btDbvtBroadphase::setAabb.
#include "broadphase_scene.h"
#include "reference/broadphase_leaves.h"
#include "shared/broadphase_leaves.h"
#include "stages/broadphase_leaves.h"
#include "test_device.h"
#include "tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace btgpu;

namespace {

void expectLeavesNear(const std::vector<BtgFloat4>& got, const std::vector<BtgFloat4>& want, bool exact)
{
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < got.size(); ++i) {
        const float t = exact ? 0.0f : tol::kStageAbs + tol::kStageRel * std::fabs(want[i].x);
        EXPECT_NEAR(got[i].x, want[i].x, t) << "row " << i;
        EXPECT_NEAR(got[i].y, want[i].y, t) << "row " << i;
        EXPECT_NEAR(got[i].z, want[i].z, t) << "row " << i;
    }
}

bool samePairs(const std::vector<BtgPair>& x, const std::vector<BtgPair>& y)
{
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i)
        if (x[i].a != y[i].a || x[i].b != y[i].b) return false;
    return true;
}

// Calls of one substep over a scene whose bodies drift, checked against the reference each call;
// the sweep's cells cellFactor x the largest small body.
void runCalls(bool rotate, size_t startCapacity, float cellFactor = 2.0f)
{
    test::BroadphaseScene s = test::makeBroadphaseScene(1500, 16.0f, 23);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<BtgFloat4> lin(s.pos.size()), ang(s.pos.size());
    for (size_t i = 0; i < s.pos.size(); ++i) {
        const bool moves = (s.props[i].flags & BTG_BODY_DYNAMIC) && !(s.props[i].flags & BTG_BODY_SLEEPING);
        lin[i] = moves ? btgMake4(3 * u(rng), 3 * u(rng), 3 * u(rng), 0) : btgZero4();
        ang[i] = moves && rotate ? btgMake4(4 * u(rng), 4 * u(rng), 4 * u(rng), 0) : btgZero4();
    }
    DeviceWorld w(test::context());
    s.upload(w);
    w.linVel.upload(w.ctx, lin);
    w.angVel.upload(w.ctx, ang);
    if (startCapacity) reserveLeafPairs(w, startCapacity);
    const float threshold = 0.02f, dt = 1.0f / 60.0f;
    const float cell = cellFactor * (s.maxSmallExtent + 2 * threshold);
    std::vector<BtgFloat4> refMin, refMax, refOldMin, refOldMax;
    std::vector<BtgPair> prev;
    bool reset = true, redone = false;
    size_t changes = 0, transients = 0;
    for (int call = 0; call < 12; ++call) {
        startLeafCall(w);
        updateLeaves(w, threshold, dt);
        leafPairs(w, cell);
        std::vector<unsigned> refMoved(s.pos.size(), 0u);
        const int refMovedCount = ref::updateLeaves(s.pos, s.rot, lin, ang, s.props, s.shapes, threshold, dt, true,
                                                    reset, refMin, refMax, refOldMin, refOldMax, refMoved);
        reset = false;
        const std::vector<BtgFloat4> gotMin = w.leaves.leafMin.download(w.ctx, s.pos.size());
        const std::vector<BtgFloat4> gotMax = w.leaves.leafMax.download(w.ctx, s.pos.size());
        const std::vector<unsigned> moved = w.leaves.moved.download(w.ctx, s.pos.size());
        const std::vector<BtgFloat4> gotOldMin = w.leaves.oldMin.download(w.ctx, s.pos.size());
        const std::vector<BtgFloat4> gotOldMax = w.leaves.oldMax.download(w.ctx, s.pos.size());
        expectLeavesNear(gotMin, refMin, !rotate);
        expectLeavesNear(gotMax, refMax, !rotate);
        expectLeavesNear(gotOldMin, refOldMin, !rotate);
        expectLeavesNear(gotOldMax, refOldMax, !rotate);
        if (!rotate) EXPECT_EQ(moved, refMoved) << "call " << call;
        const LeafChanges c = readLeafChanges(w);
        redone |= c.redone;
        unsigned newPairs = 0;
        std::vector<BtgPair> transient;
        const std::vector<BtgPair> pairs =
            ref::leafPairs(s.props, gotMin, gotMax, gotOldMin, gotOldMax, moved, &newPairs, &transient);
        EXPECT_TRUE(samePairs(c.transient, transient)) << "call " << call << ": " << c.transient.size() << " against "
                                                       << transient.size();
        transients += transient.size();
        std::vector<BtgPair> added, removed;
        ref::leafDiff(pairs, prev, &added, &removed);
        EXPECT_EQ(c.pairs, pairs.size()) << "call " << call;
        EXPECT_EQ(c.newPairs, newPairs) << "call " << call;
        if (!rotate) EXPECT_EQ(int(c.moved), refMovedCount) << "call " << call;
        EXPECT_TRUE(samePairs(c.added, added)) << "call " << call << ": " << c.added.size() << " against " << added.size();
        EXPECT_TRUE(samePairs(c.removed, removed)) << "call " << call << ": " << c.removed.size() << " against "
                                                   << removed.size();
        const std::vector<BtgPair> list = w.leaves.lists[w.leaves.current].download(w.ctx, c.pairs);
        EXPECT_TRUE(samePairs(list, pairs)) << "call " << call;
        changes += added.size() + removed.size();
        prev = pairs;
        // The bodies move on as their predicted motion says (rotation left alone: the leaves
        // are what is checked).
        for (size_t i = 0; i < s.pos.size(); ++i) s.pos[i] = btgXyz(s.pos[i]) + btgXyz(lin[i]) * dt;
        w.pos.upload(w.ctx, s.pos);
    }
    EXPECT_GT(prev.size(), 500u);  // the scene has pairs to lose and gain
    EXPECT_GT(changes, 100u);
    EXPECT_GT(transients, 0u);  // leaves that parted within a pass
    if (startCapacity) EXPECT_TRUE(redone);
    // Everything stops: every AABB is inside its leaf, no leaf moves, and the pairs stay the
    // last list's (no list is made: stock collides only leaves that moved). Not after the rotating
    // calls: their bodies never took the rotations their leaves were predicted with.
    if (rotate) return;
    std::fill(lin.begin(), lin.end(), btgZero4());
    std::fill(ang.begin(), ang.end(), btgZero4());
    w.linVel.upload(w.ctx, lin);
    w.angVel.upload(w.ctx, ang);
    for (int call = 0; call < 2; ++call) {
        startLeafCall(w);
        updateLeaves(w, threshold, dt);
        leafPairs(w, cell);
        const LeafChanges c = readLeafChanges(w);
        EXPECT_EQ(c.moved, 0u);
        EXPECT_EQ(c.pairs, prev.size());
        EXPECT_TRUE(c.added.empty() && c.removed.empty());
        EXPECT_TRUE(samePairs(w.leaves.lists[w.leaves.current].download(w.ctx, c.pairs), prev));
    }
    // One body moves again: its leaf moves and the list is made anew, the same pairs or its own changed.
    for (size_t i = 0; i < s.pos.size(); ++i)
        if (s.props[i].flags == BTG_BODY_DYNAMIC) {
            s.pos[i] = btgXyz(s.pos[i]) + btgMake4(0.5f, 0, 0, 0);
            break;
        }
    w.pos.upload(w.ctx, s.pos);
    startLeafCall(w);
    updateLeaves(w, threshold, dt);
    leafPairs(w, cell);
    const LeafChanges c = readLeafChanges(w);
    EXPECT_EQ(c.moved, 1u);
    const std::vector<BtgFloat4> gotMin = w.leaves.leafMin.download(w.ctx, s.pos.size());
    const std::vector<BtgFloat4> gotMax = w.leaves.leafMax.download(w.ctx, s.pos.size());
    unsigned newPairs = 0;
    std::vector<BtgPair> transient;
    const std::vector<BtgPair> pairs =
        ref::leafPairs(s.props, gotMin, gotMax, w.leaves.oldMin.download(w.ctx, s.pos.size()),
                       w.leaves.oldMax.download(w.ctx, s.pos.size()), w.leaves.moved.download(w.ctx, s.pos.size()),
                       &newPairs, &transient);
    EXPECT_TRUE(samePairs(c.transient, transient));
    std::vector<BtgPair> added, removed;
    ref::leafDiff(pairs, prev, &added, &removed);
    EXPECT_TRUE(samePairs(c.added, added));
    EXPECT_TRUE(samePairs(c.removed, removed));
    EXPECT_EQ(c.newPairs, newPairs);
}

}  // namespace

TEST(BroadphaseLeaves, MatchesReferenceWithoutRotation) { runCalls(false, 0); }

TEST(BroadphaseLeaves, MatchesReferenceRotating) { runCalls(true, 0); }

// Small cells besides: many leaves span three and go to the large pass.
TEST(BroadphaseLeaves, OverflowGrowsAndMakesTheListAgain) { runCalls(false, 16, 0.6f); }

TEST(BroadphaseLeaves, LeafRulesAsSetAabb)
{
    BtgAabb leaf{btgMake4(0, 0, 0, 0), btgMake4(1, 1, 1, 0)};
    // Contained: kept as it is.
    BtgAabb a{btgMake4(0.1f, 0.1f, 0.1f, 0), btgMake4(0.9f, 1.0f, 0.9f, 0)};
    EXPECT_EQ(btgLeafUpdate(&leaf, a), 0);
    EXPECT_EQ(leaf.hi.y, 1.0f);
    // Poking out but meeting: the AABB fattened by gDbvtMargin.
    a = BtgAabb{btgMake4(0.2f, 0.1f, 0.1f, 0), btgMake4(1.1f, 0.9f, 0.9f, 0)};
    EXPECT_EQ(btgLeafUpdate(&leaf, a), 1);
    EXPECT_FLOAT_EQ(leaf.lo.x, 0.2f - 0.05f);
    EXPECT_FLOAT_EQ(leaf.hi.x, 1.1f + 0.05f);
    EXPECT_FLOAT_EQ(leaf.hi.y, 0.9f + 0.05f);
    // Apart (a teleport): the AABB itself.
    a = BtgAabb{btgMake4(5, 5, 5, 0), btgMake4(6, 6, 6, 0)};
    EXPECT_EQ(btgLeafUpdate(&leaf, a), 1);
    EXPECT_EQ(leaf.lo.x, 5.0f);
    EXPECT_EQ(leaf.hi.z, 6.0f);
    // Touching leaves meet (btDbvtAabbMm's Intersect is inclusive).
    BtgAabb b{btgMake4(6, 0, 0, 0), btgMake4(7, 6, 6, 0)};
    EXPECT_EQ(btgLeafMeets(leaf, b), 1);
    // A plane's leaf is stock's +-BT_LARGE_FLOAT box; a dynamic body's AABB spans its predicted motion.
    BtgShape plane{};
    plane.type = BTG_SHAPE_PLANE;
    EXPECT_EQ(btgLeafShapeAabb(btgZero4(), btgMake4(0, 0, 0, 1), plane, BTG_BODY_STATIC, 0.02f).hi.x, 1e30f);
    BtgShape box = test::makeBoxShape(0.5f, 0.5f, 0.5f);
    BtgAabb moving = btgStockAabb(btgZero4(), btgMake4(0, 0, 0, 1), btgMake4(6, 0, 0, 0), btgZero4(), box,
                                  BTG_BODY_DYNAMIC, 0.02f, 0.5f, 1);
    EXPECT_FLOAT_EQ(moving.lo.x, -0.52f);
    EXPECT_FLOAT_EQ(moving.hi.x, 3.52f);
    BtgAabb still = btgStockAabb(btgZero4(), btgMake4(0, 0, 0, 1), btgMake4(6, 0, 0, 0), btgZero4(), box,
                                 BTG_BODY_DYNAMIC, 0.02f, 0.5f, 0);
    EXPECT_FLOAT_EQ(still.hi.x, 0.52f);
    BtgAabb kinematic = btgStockAabb(btgZero4(), btgMake4(0, 0, 0, 1), btgMake4(6, 0, 0, 0), btgZero4(), box,
                                     BTG_BODY_KINEMATIC, 0.02f, 0.5f, 1);
    EXPECT_FLOAT_EQ(kinematic.hi.x, 0.52f);
}
