// broadphase_scene.h — random body sets for the update_aabbs, find_pairs and sort_sweep unit
// tests: spheres and boxes of similar (or, mixed, widely different) size in a cube, a few large
// boxes, a ground plane, and rows that are static, sleeping, excluded, no-response or filtered
// by group/mask. Host columns plus an upload.
#pragma once
#include "shared/math.h"
#include "stages/find_pairs.h"
#include "world/device_world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace btgpu::test {

struct BroadphaseScene {
    std::vector<BtgFloat4> pos, rot;
    std::vector<BtgBodyProps> props;
    std::vector<BtgShape> shapes;  // 0: sphere r 0.5, 1: box half 0.4, 2: plane y = 0, 3: large box
    std::vector<int> large, planes;
    float maxSmallExtent = 0;      // m: largest AABB side of a small body before the threshold

    void upload(DeviceWorld& w) const
    {
        w.numBodies = int(pos.size());
        w.pos.upload(w.ctx, pos);
        w.rot.upload(w.ctx, rot);
        w.props.upload(w.ctx, props);
        w.shapes.upload(w.ctx, shapes);
        w.numShapes = int(shapes.size());
        w.largeBodies.reserve(w.ctx, large.size() + 1);
        w.largeBodies.upload(w.ctx, large);
        w.numLarge = int(large.size());
        w.planeBodies.reserve(w.ctx, planes.size() + 1);
        w.planeBodies.upload(w.ctx, planes);
        w.numPlanes = int(planes.size());
        w.counters.zero(w.ctx, kNumCounters);
    }
};

inline BtgShape makeBoxShape(float hx, float hy, float hz)
{
    BtgShape s{};
    s.type = BTG_SHAPE_HULL;
    s.localAabbMin = btgMake4(-hx, -hy, -hz, 0);
    s.localAabbMax = btgMake4(hx, hy, hz, 0);
    return s;
}

// n bodies in a cube of side `side` m (density sets how many touch); every `largeEvery`-th body
// is a large box, and body 0 is a plane when withPlane is set.
inline BroadphaseScene makeBroadphaseScene(int n, float side, unsigned seed, bool withPlane = true, int largeEvery = 97)
{
    BroadphaseScene s;
    BtgShape sphere{};
    sphere.type = BTG_SHAPE_SPHERE;
    sphere.param = btgMake4(0.5f, 0, 0, 0);
    sphere.localAabbMin = btgMake4(-0.5f, -0.5f, -0.5f, 0);
    sphere.localAabbMax = btgMake4(0.5f, 0.5f, 0.5f, 0);
    BtgShape plane{};
    plane.type = BTG_SHAPE_PLANE;
    plane.param = btgMake4(0, 1, 0, 0.25f);  // y = 0.25 in the plane body's frame
    s.shapes = {sphere, makeBoxShape(0.4f, 0.3f, 0.35f), plane, makeBoxShape(3.0f, 0.5f, 2.0f)};
    // A box of half extents h rotated arbitrarily spans at most 2|h| per axis.
    s.maxSmallExtent = std::fmax(1.0f, 2.0f * std::sqrt(0.4f * 0.4f + 0.3f * 0.3f + 0.35f * 0.35f));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < n; ++i) {
        BtgBodyProps p{};
        p.flags = BTG_BODY_DYNAMIC;
        p.group = 1;
        p.mask = -1;
        p.shape = (rng() % 2) ? 0 : 1;
        BtgFloat4 q = btgQuatNormalize(btgMake4(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
        BtgFloat4 x = btgMake4(u(rng) * side, u(rng) * side - 0.3f, u(rng) * side, 0);
        if (withPlane && i == 0) {
            p.shape = 2;
            p.flags = BTG_BODY_STATIC;
            // Tilted a little and lifted so that some bodies reach below it and some do not.
            q = btgQuatNormalize(btgMake4(0.05f, 0, 0.03f, 1));
            x = btgMake4(0, 0.5f, 0, 0);
            s.planes.push_back(i);
        } else if (largeEvery > 0 && i % largeEvery == 5) {
            p.shape = 3;
            p.flags = BTG_BODY_LARGE | (i % 2 ? BTG_BODY_STATIC : BTG_BODY_DYNAMIC);
            s.large.push_back(i);
        } else {
            unsigned r = rng() % 40;
            if (r == 0) p.flags = BTG_BODY_STATIC;
            else if (r == 1) p.flags = BTG_BODY_DYNAMIC | BTG_BODY_SLEEPING;
            else if (r == 2) { p.flags = BTG_BODY_EXCLUDED; p.shape = -1; }  // an empty row
            else if (r == 3) p.flags = BTG_BODY_DYNAMIC | BTG_BODY_NO_RESPONSE;
            else if (r == 4) p.flags = BTG_BODY_KINEMATIC;
            else if (r == 5) { p.group = 2; p.mask = ~2; }  // collides with nothing else of group 2
            else if (r == 6) { p.group = 2; p.mask = ~2; }
        }
        s.pos.push_back(x);
        s.rot.push_back(q);
        s.props.push_back(p);
    }
    return s;
}

// The scene above with the small bodies' sizes spread widely: each takes one of `kinds` shapes,
// boxes and spheres of half extent / radius drawn from [0.05, 1.2] m.
inline BroadphaseScene makeMixedSizeScene(int n, float side, unsigned seed, bool withPlane = true, int largeEvery = 97)
{
    BroadphaseScene s = makeBroadphaseScene(n, side, seed, withPlane, largeEvery);
    std::mt19937 rng(seed + 1000u);
    std::uniform_real_distribution<float> size(0.05f, 1.2f);
    const int first = int(s.shapes.size()), kinds = 24;
    s.maxSmallExtent = 0.0f;
    for (int k = 0; k < kinds; ++k) {
        if (k % 2) {
            float hx = size(rng), hy = size(rng), hz = size(rng);
            s.shapes.push_back(makeBoxShape(hx, hy, hz));
            s.maxSmallExtent = std::fmax(s.maxSmallExtent, 2.0f * std::sqrt(hx * hx + hy * hy + hz * hz));
        } else {
            float r = size(rng);
            BtgShape sphere{};
            sphere.type = BTG_SHAPE_SPHERE;
            sphere.param = btgMake4(r, 0, 0, 0);
            sphere.localAabbMin = btgMake4(-r, -r, -r, 0);
            sphere.localAabbMax = btgMake4(r, r, r, 0);
            s.shapes.push_back(sphere);
            s.maxSmallExtent = std::fmax(s.maxSmallExtent, 2.0f * r);
        }
    }
    for (BtgBodyProps& p : s.props)
        if (p.shape == 0 || p.shape == 1) p.shape = first + int(rng() % unsigned(kinds));
    return s;
}

}  // namespace btgpu::test

// Global so that std::vector's == finds it for the global BtgPair.
inline bool operator==(const BtgPair& x, const BtgPair& y) { return x.a == y.a && x.b == y.b; }

namespace btgpu::test {

// One find_pairs run on an uploaded world with AABBs: the pairs (up to capacity), the full
// count the kernels found and the status word.
struct PairsRun {
    std::vector<BtgPair> pairs;
    uint count = 0;
    uint status = 0;
    std::vector<uint> kindOrder;   // pairOrder after the kind pass (empty unless indirect)
    std::vector<uint> kindRanges;  // BTG_KIND_RANGES_SIZE
};

// Every kind of the pair-kind table.
inline PairKinds allPairKinds()
{
    PairKinds k;
    for (int r = 0; r < kNumPairKindRows; ++r) k.add(kPairKindRows[r].kind);
    return k;
}

inline PairsRun runFindPairs(DeviceWorld& w, Broadphase kind, float cellSize, size_t capacity,
                             PairKinds kinds = allPairKinds())
{
    w.pairs.reserve(w.ctx, capacity);
    w.pairCapacity = capacity;
    w.counters.zero(w.ctx, kNumCounters);
    findPairs(w, kinds, kind, cellSize);
    std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    PairsRun r;
    r.count = counters[kPairCount];
    r.status = counters[kStatus];
    const size_t stored = std::min<size_t>(r.count, capacity);
    r.pairs = w.pairs.download(w.ctx, stored);
    if (w.pairKindsIndirect) r.kindOrder = w.pairOrder.download(w.ctx, stored);
    r.kindRanges = w.pairKindRanges.download(w.ctx, BTG_KIND_RANGES_SIZE);
    return r;
}

// A pair buffer of 16 overflows: the status says so and the count is the full one; grown to
// that count, the redo fits and gives exactly `expected`.
inline void expectOverflowThenRedo(DeviceWorld& w, Broadphase kind, float cellSize, const std::vector<BtgPair>& expected)
{
    PairsRun r = runFindPairs(w, kind, cellSize, 16);
    EXPECT_NE(r.status & BTG_STATUS_PAIR_OVERFLOW, 0u);
    EXPECT_EQ(r.count, expected.size());
    PairsRun redo = runFindPairs(w, kind, cellSize, r.count);
    EXPECT_EQ(redo.status & BTG_STATUS_PAIR_OVERFLOW, 0u);
    EXPECT_TRUE(redo.pairs == expected);
}

}  // namespace btgpu::test
