// sort_sweep_test.cpp — the sort-and-sweep broadphase finds exactly the uniform grid's pairs:
// on random mixed-size scenes (with large bodies, a plane and every filter case) the device's
// sorted pair list equals the grid's and the brute-force reference's; the small-body pass alone
// equals its CPU reference; the device picks the reference's axis; exact ties and touching
// AABBs (including -0 against +0) are kept; an undersized buffer overflows as the grid's does.
// Also the plan's choice between the two from body sizes.
#include "broadphase_scene.h"
#include "reference/find_pairs.h"
#include "reference/sort_sweep.h"
#include "shared/broadphase.h"
#include "stages/find_pairs.h"
#include "stages/update_aabbs.h"
#include "test_device.h"
#include "world/plan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace btgpu;

namespace {
constexpr float kThreshold = 0.02f;

using Result = test::PairsRun;

Result runDevice(DeviceWorld& w, Broadphase kind, float cellSize, size_t capacity)
{
    return test::runFindPairs(w, kind, cellSize, capacity);
}

struct Aabbs {
    std::vector<BtgFloat4> min, max;
};

Aabbs download(DeviceWorld& w)
{
    size_t n = size_t(w.numBodies);
    return {w.aabbMin.download(w.ctx, n), w.aabbMax.download(w.ctx, n)};
}

void expectSamePairs(const std::vector<BtgPair>& got, const std::vector<BtgPair>& expected, const char* what)
{
    ASSERT_EQ(got.size(), expected.size()) << what;
    for (size_t i = 0; i < expected.size(); ++i)
        ASSERT_TRUE(got[i] == expected[i]) << what << ", pair " << i << ": got (" << got[i].a << ", " << got[i].b
                                           << ") expected (" << expected[i].a << ", " << expected[i].b << ")";
}

// Sweep, grid and brute force agree on the whole find_pairs list; the sweep twice gives the same.
void checkAgainstGrid(DeviceWorld& w, const test::BroadphaseScene& s, float cellSize, size_t minPairs)
{
    Aabbs a = download(w);
    std::vector<BtgPair> expected = ref::findPairs(a.min, a.max, s.props, s.shapes, s.pos, s.rot);
    ASSERT_GE(expected.size(), minPairs) << "scene too sparse to test anything";
    size_t capacity = expected.size() + 100;
    Result sweep = runDevice(w, Broadphase::SortAndSweep, cellSize, capacity);
    EXPECT_EQ(sweep.status & BTG_STATUS_PAIR_OVERFLOW, 0u);
    EXPECT_EQ(sweep.count, expected.size());
    expectSamePairs(sweep.pairs, expected, "sort-and-sweep vs brute force");
    Result grid = runDevice(w, Broadphase::UniformGrid, cellSize, capacity);
    expectSamePairs(sweep.pairs, grid.pairs, "sort-and-sweep vs grid");
    Result again = runDevice(w, Broadphase::SortAndSweep, cellSize, capacity);
    EXPECT_TRUE(again.pairs == sweep.pairs) << "the appended order leaked out";
}

// Brute-force pairs between two rows the small-body pass takes.
std::vector<BtgPair> smallPairs(const std::vector<BtgPair>& all, const test::BroadphaseScene& s)
{
    std::vector<BtgPair> out;
    for (const BtgPair& p : all)
        if (btgGridded(s.props[size_t(p.a)], s.shapes.data()) && btgGridded(s.props[size_t(p.b)], s.shapes.data()))
            out.push_back(p);
    return out;
}
}  // namespace

TEST(SortSweep, MixedSizesMatchGridAndBruteForce)
{
    test::BroadphaseScene s = test::makeMixedSizeScene(4000, 22.0f, 11);
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    checkAgainstGrid(w, s, s.maxSmallExtent + 2 * kThreshold, 2000);
}

TEST(SortSweep, SmallPassMatchesReference)
{
    // No plane and no large body: find_pairs' list is the sweep's own.
    test::BroadphaseScene s = test::makeMixedSizeScene(3000, 18.0f, 12, false, 0);
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    Aabbs a = download(w);
    std::vector<BtgPair> expected = ref::sortSweepPairs(a.min, a.max, s.props, s.shapes);
    ASSERT_GT(expected.size(), 1000u);
    Result r = runDevice(w, Broadphase::SortAndSweep, 1.0f, expected.size() + 10);
    EXPECT_EQ(r.count, expected.size());
    expectSamePairs(r.pairs, expected, "device vs reference sweep");
    EXPECT_EQ(w.broadphase.sapAxis.download(w.ctx, 1)[0], ref::sortSweepAxis(a.min, a.max, s.props, s.shapes));
}

TEST(SortSweep, ReferenceMatchesBruteForce)
{
    test::BroadphaseScene s = test::makeMixedSizeScene(3000, 20.0f, 13);
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    Aabbs a = download(w);
    std::vector<BtgPair> brute = smallPairs(ref::findPairs(a.min, a.max, s.props, s.shapes, s.pos, s.rot), s);
    ASSERT_GT(brute.size(), 1000u);
    expectSamePairs(ref::sortSweepPairs(a.min, a.max, s.props, s.shapes), brute, "reference sweep vs brute force");
}

TEST(SortSweep, AxisIsTheWidestSpread)
{
    // Centres spread 4x wider along one axis: the device and the reference both pick it.
    for (uint wide = 0; wide < 3; ++wide) {
        test::BroadphaseScene s = test::makeMixedSizeScene(2000, 10.0f, 20 + wide, false, 0);
        for (BtgFloat4& p : s.pos) (wide == 0 ? p.x : wide == 1 ? p.y : p.z) *= 4.0f;
        DeviceWorld w(test::context());
        s.upload(w);
        updateAabbs(w, kThreshold);
        runDevice(w, Broadphase::SortAndSweep, 1.0f, 4096);
        Aabbs a = download(w);
        EXPECT_EQ(ref::sortSweepAxis(a.min, a.max, s.props, s.shapes), wide);
        EXPECT_EQ(w.broadphase.sapAxis.download(w.ctx, 1)[0], wide);
    }
}

TEST(SortSweep, TiesAndTouchingAabbsAreKept)
{
    // A 10x10x10 lattice of unit AABBs with shared faces, edges and corners: every neighbour
    // touches, every sweep key ties with 99 others, and the faces at 0 are -0 or +0 (mins)
    // and -0 (maxes). Touching counts as overlap, as in the grid.
    test::BroadphaseScene s = test::makeBroadphaseScene(1000, 1.0f, 30, false, 0);
    Aabbs a;
    for (int i = 0; i < 1000; ++i) {
        int c[3] = {i % 10 - 5, (i / 10) % 10 - 5, i / 100 - 5};
        float lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
            lo[k] = c[k] == 0 && i % 2 ? -0.0f : float(c[k]);
            hi[k] = c[k] + 1 == 0 ? -0.0f : float(c[k] + 1);
        }
        a.min.push_back(btgMake4(lo[0], lo[1], lo[2], 0));
        a.max.push_back(btgMake4(hi[0], hi[1], hi[2], 0));
        s.props[size_t(i)] = BtgBodyProps{};
        s.props[size_t(i)].flags = BTG_BODY_DYNAMIC;
        s.props[size_t(i)].group = 1;
        s.props[size_t(i)].mask = -1;
    }
    DeviceWorld w(test::context());
    s.upload(w);
    w.aabbMin.upload(w.ctx, a.min);
    w.aabbMax.upload(w.ctx, a.max);
    std::vector<BtgPair> expected = ref::findPairs(a.min, a.max, s.props, s.shapes, s.pos, s.rot);
    // Interior lattice: 26 neighbours each; in all 3 * 9 * 10 * 10 face + 6 * 9 * 9 * 10 edge
    // + 4 * 9 * 9 * 9 corner contacts.
    EXPECT_EQ(expected.size(), size_t(2700 + 4860 + 2916));
    EXPECT_EQ(ref::sortSweepPairs(a.min, a.max, s.props, s.shapes).size(), expected.size());
    checkAgainstGrid(w, s, 1.01f, expected.size());
}

TEST(SortSweep, OverflowIsFlaggedAndCounted)
{
    test::BroadphaseScene s = test::makeMixedSizeScene(1000, 12.0f, 14);
    DeviceWorld w(test::context());
    s.upload(w);
    updateAabbs(w, kThreshold);
    Aabbs a = download(w);
    std::vector<BtgPair> expected = ref::findPairs(a.min, a.max, s.props, s.shapes, s.pos, s.rot);
    ASSERT_GT(expected.size(), 100u);
    test::expectOverflowThenRedo(w, Broadphase::SortAndSweep, 1.0f, expected);
}

TEST(SortSweep, NothingToSweep)
{
    test::BroadphaseScene empty;
    DeviceWorld w(test::context());
    empty.upload(w);
    Result r = runDevice(w, Broadphase::SortAndSweep, 1.0f, 8);
    EXPECT_EQ(r.count, 0u);
    EXPECT_EQ(r.status, 0u);
    // Every row excluded or a plane: no key, no pair.
    test::BroadphaseScene s = test::makeBroadphaseScene(200, 5.0f, 15, true, 0);
    for (size_t i = 1; i < s.props.size(); ++i) s.props[i].flags = BTG_BODY_EXCLUDED;
    DeviceWorld w2(test::context());
    s.upload(w2);
    updateAabbs(w2, kThreshold);
    Result r2 = runDevice(w2, Broadphase::SortAndSweep, 1.0f, 8);
    EXPECT_EQ(r2.count, 0u);
    EXPECT_EQ(w2.broadphase.sapAxis.download(w2.ctx, 1)[0], 0u);
}

TEST(SortSweep, PlanChoosesFromSizes)
{
    // Alike: one size, or sizes within a factor of two, or one pebble among crates.
    EXPECT_EQ(chooseBroadphase(std::vector<float>(1000, 2.0f), 8.0f), Broadphase::UniformGrid);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<float> narrow, mixed;
    for (int i = 0; i < 1000; ++i) narrow.push_back(1.0f + u(rng));
    EXPECT_EQ(chooseBroadphase(narrow, 8.0f), Broadphase::UniformGrid);
    std::vector<float> pebble(1000, 2.0f);
    pebble[7] = 0.05f;
    EXPECT_EQ(chooseBroadphase(pebble, 8.0f), Broadphase::UniformGrid);
    // Boxes of half extents drawn from [0.1, 2.5] m each (the bench's mixed scene): the grid,
    // which measured faster there.
    for (int i = 0; i < 1000; ++i) {
        float h[3] = {0.1f + 2.4f * u(rng), 0.1f + 2.4f * u(rng), 0.1f + 2.4f * u(rng)};
        mixed.push_back(2.0f * std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]));
    }
    EXPECT_EQ(chooseBroadphase(mixed, 40.0f), Broadphase::UniformGrid);
    // Not alike: debris of 0.2-0.4 m among a few crates of 1.6 m: mostly empty cells, the sweep.
    std::vector<float> debris;
    for (int i = 0; i < 1000; ++i) debris.push_back(i % 100 == 0 ? 1.6f : 0.2f + 0.2f * u(rng));
    EXPECT_EQ(chooseBroadphase(debris, 4.0f), Broadphase::SortAndSweep);
    // Bodies above the large limit are paired apart and do not count: crates and ground boxes.
    std::vector<float> withGround(1000, 2.0f);
    withGround.push_back(700.0f);
    EXPECT_EQ(chooseBroadphase(withGround, 8.0f), Broadphase::UniformGrid);
    EXPECT_EQ(chooseBroadphase({}, 1.0f), Broadphase::UniformGrid);
}
