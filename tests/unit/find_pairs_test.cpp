// find_pairs_test.cpp — the device broadphase (grid + large + planes + pair sort) returns exactly
// the brute-force reference's sorted pair list on random scenes, including one where the grid
// matters (5000 bodies) and one with more than 65536 rows (the two-pass pair sort), grouped by
// kind exactly as the reference groups it (or, for a plan of one kind, left in place); an
// undersized pair buffer raises the overflow flag and still reports the full count.
#include "broadphase_scene.h"
#include "reference/find_pairs.h"
#include "stages/find_pairs.h"
#include "stages/update_aabbs.h"
#include "test_device.h"

#include <gtest/gtest.h>

using namespace btgpu;

namespace {
constexpr float kThreshold = 0.02f;

using Result = test::PairsRun;

Result runDevice(DeviceWorld& w, const test::BroadphaseScene& s, size_t capacity)
{
    return test::runFindPairs(w, Broadphase::UniformGrid, s.maxSmallExtent + 2 * kThreshold, capacity);
}

std::vector<BtgPair> reference(DeviceWorld& w, const test::BroadphaseScene& s)
{
    size_t n = s.pos.size();
    return ref::findPairs(w.aabbMin.download(w.ctx, n), w.aabbMax.download(w.ctx, n), s.props, s.shapes, s.pos, s.rot);
}

void checkScene(const test::BroadphaseScene& s, size_t minPairs)
{
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    std::vector<BtgPair> expected = reference(w, s);
    ASSERT_GE(expected.size(), minPairs) << "scene too sparse to test anything";
    Result r = runDevice(w, s, expected.size() + 100);
    EXPECT_EQ(r.status & BTG_STATUS_PAIR_OVERFLOW, 0u);
    ASSERT_EQ(r.count, expected.size());
    for (size_t i = 0; i < expected.size(); ++i)
        ASSERT_TRUE(r.pairs[i] == expected[i]) << "pair " << i << ": got (" << r.pairs[i].a << ", " << r.pairs[i].b
                                               << ") expected (" << expected[i].a << ", " << expected[i].b << ")";
    // Grouped by kind exactly as the reference groups the sorted list: (kind, a, b).
    ref::PairKindGroups groups = ref::groupPairsByKind(expected, s.props, s.shapes);
    EXPECT_EQ(r.kindRanges, groups.ranges);
    EXPECT_EQ(r.kindOrder, groups.order);
    // Same input, same list: the atomically appended order does not leak out.
    Result again = runDevice(w, s, expected.size() + 100);
    EXPECT_TRUE(again.pairs == r.pairs);
    EXPECT_EQ(again.kindOrder, r.kindOrder);
}
}  // namespace

TEST(FindPairs, SmallSceneMatchesReference)
{
    checkScene(test::makeBroadphaseScene(300, 8.0f, 3, true, 37), 50);
}

TEST(FindPairs, GridSceneMatchesReference)
{
    test::BroadphaseScene s = test::makeBroadphaseScene(5000, 30.0f, 4);
    checkScene(s, 1000);
}

TEST(FindPairs, PairKindsArePresent)
{
    // The reference must itself contain plane, large and large-large pairs, or the comparison
    // above would not cover those passes.
    test::BroadphaseScene s = test::makeBroadphaseScene(5000, 30.0f, 4);
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    std::vector<BtgPair> expected = reference(w, s);
    auto isLarge = [&](int i) { return (s.props[size_t(i)].flags & BTG_BODY_LARGE) != 0; };
    size_t plane = 0, large = 0, largeLarge = 0;
    for (const BtgPair& p : expected) {
        plane += p.a == 0;
        large += isLarge(p.a) || isLarge(p.b);
        largeLarge += isLarge(p.a) && isLarge(p.b);
    }
    EXPECT_GT(plane, 10u);
    EXPECT_GT(large, 10u);
    EXPECT_GT(largeLarge, 0u);
}

TEST(FindPairs, KindRangesCoverEveryKind)
{
    // The scene has every convex kind of the table but plane–plane (never a pair): each range
    // is non-empty, and the ranges tile the kind order. It has no mesh (the mesh kinds' ranges,
    // empty here, are walked in midphase_test).
    test::BroadphaseScene s = test::makeBroadphaseScene(2000, 18.0f, 21);
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    std::vector<BtgPair> expected = reference(w, s);
    Result r = runDevice(w, s, expected.size() + 10);
    ASSERT_EQ(r.kindOrder.size(), expected.size());
    uint next = 0;
    for (int kind = 0; kind < BTG_NUM_PAIR_KINDS; ++kind) {
        EXPECT_EQ(r.kindRanges[BTG_KIND_RANGE_START(kind)], next);
        next = r.kindRanges[BTG_KIND_RANGE_END(kind)];
        const PairKindRow* row = pairKindRow(kind);
        const bool inScene = row && row->shapeA != BTG_SHAPE_CONVEX && row->shapeB != BTG_SHAPE_CONVEX &&
                             row->shapeA != BTG_SHAPE_BOX && row->shapeB != BTG_SHAPE_BOX &&
                             kind < BTG_FIRST_MESH_PAIR_KIND;
        if (inScene) EXPECT_GT(next, r.kindRanges[BTG_KIND_RANGE_START(kind)]) << "kind " << kind;
    }
    EXPECT_EQ(next, expected.size());
}

TEST(FindPairs, OneKindSortsNothing)
{
    // A plan of one kind: its range is every pair in place, the other kinds' are empty.
    test::BroadphaseScene s = test::makeBroadphaseScene(600, 10.0f, 3, false, 0);
    for (BtgBodyProps& p : s.props)
        if (p.shape == 0) p.shape = 1;  // boxes only
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    std::vector<BtgPair> expected = reference(w, s);
    ASSERT_GT(expected.size(), 50u);
    PairKinds hulls;
    hulls.add(BTG_PAIR_HULL_HULL);
    Result r = test::runFindPairs(w, Broadphase::UniformGrid, s.maxSmallExtent + 2 * kThreshold, expected.size(), hulls);
    EXPECT_FALSE(w.pairKindsIndirect);
    EXPECT_TRUE(r.pairs == expected);
    for (int kind = 0; kind < BTG_NUM_PAIR_KINDS; ++kind) {
        EXPECT_EQ(r.kindRanges[BTG_KIND_RANGE_START(kind)], 0u);
        EXPECT_EQ(r.kindRanges[BTG_KIND_RANGE_END(kind)], kind == BTG_PAIR_HULL_HULL ? expected.size() : 0u);
    }
}

TEST(FindPairs, ManyRowsUseTwoPassSort)
{
    // 70000 rows (row numbers need 17 bits, so (a, b) no longer packs into one key); all but
    // ~3000 are excluded so the brute-force reference stays quick.
    test::BroadphaseScene s = test::makeBroadphaseScene(70000, 12.0f, 9, true, 0);
    for (size_t i = 1; i < s.props.size(); ++i)
        if (i % 23 != 0 && i < 69000) s.props[i].flags = BTG_BODY_EXCLUDED;
    checkScene(s, 200);
}

TEST(FindPairs, OverflowIsFlaggedAndCounted)
{
    test::BroadphaseScene s = test::makeBroadphaseScene(1000, 12.0f, 5);
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    std::vector<BtgPair> expected = reference(w, s);
    ASSERT_GT(expected.size(), 20u);
    test::expectOverflowThenRedo(w, Broadphase::UniformGrid, s.maxSmallExtent + 2 * kThreshold, expected);
}

TEST(FindPairs, EmptyWorld)
{
    test::BroadphaseScene s;
    DeviceWorld w(test::context());
    s.upload(w);
    w.counters.zero(w.ctx, kNumCounters);
    Result r = runDevice(w, s, 8);
    EXPECT_EQ(r.count, 0u);
    EXPECT_EQ(r.status, 0u);
}
