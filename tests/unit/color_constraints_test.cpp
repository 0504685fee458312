// color_constraints_test.cpp — the batching stage on the constraint graph: colors exactly the
// reference's, no dynamic body twice in a parallel color (static and kinematic ones may be),
// every edge colored, and the result the same when run again.
#include "contact_fixture.h"
#include "shared/coloring.h"
#include "stages/color_constraints.h"
#include "test_device.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <random>
#include <set>

using namespace btgpu;

namespace {

struct Graph {
    ref::ContactBodies bodies;
    std::vector<BtgEdge> edges;
};

Graph randomGraph(int numBodies, int numEdges, unsigned seed)
{
    std::mt19937 rng(seed);
    Graph g;
    for (int i = 0; i < numBodies; ++i) {
        uint flags = i < 6 ? BTG_BODY_STATIC : (i == 6 ? BTG_BODY_KINEMATIC : BTG_BODY_DYNAMIC);
        test::addBody(g.bodies, btgZero4(), flags == BTG_BODY_DYNAMIC ? 1.0f : 0.0f, btgMake4(1, 1, 1, 0), flags);
    }
    for (int i = 0; i < numEdges; ++i) {
        BtgEdge e{};
        // Static rows are popular partners, as a ground is.
        e.bodyA = 6 + int(rng() % (numBodies - 6));
        e.bodyB = (rng() % 3 == 0) ? int(rng() % 7) : 6 + int(rng() % (numBodies - 6));
        if (e.bodyB == e.bodyA) e.bodyB = 0;
        g.edges.push_back(e);
    }
    return g;
}

// fused: the one-work-group launch small scenes take (chosen by the last contact count).
// resident: the one-launch batching over resident groups (Auto: GPUs); *status gets the
// status word after the batching.
// levels: the last levels.size() edges are ordered joints (the bullet mode's batching), the
// edges before them contacts.
std::vector<int> runDevice(const Graph& g, int maxColors, bool fused = false,
                           DeviceWorld::Resident resident = DeviceWorld::Resident::Auto, uint* status = nullptr,
                           const std::vector<int>& levels = {})
{
    DeviceWorld w(test::context());
    w.resident = resident;
    w.lastContactCount = fused ? 0 : (1 << 30);
    test::uploadWorld(w, g.bodies, {}, 0, {}, g.edges.size() + 8);
    w.edgeCapacity = g.edges.size() + 8;
    w.edges.reserve(w.ctx, w.edgeCapacity);
    w.edges.upload(w.ctx, g.edges);
    w.edgeColor.upload(w.ctx, std::vector<int>(w.edgeCapacity, 1234));  // the stage must overwrite stale colors
    std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    counters[kEdgeCount] = uint(g.edges.size());
    counters[kContactCount] = uint(g.edges.size() - levels.size());
    w.counters.upload(w.ctx, counters);
    w.colorRounds = maxColors - 1;
    if (!levels.empty()) {
        // the joints' edges end the edge slots, as prepare_joints appends them after the contacts
        w.edgeCapacity = g.edges.size();
        w.numJoints = int(levels.size());
        w.jointLevels.upload(w.ctx, levels);
        w.maxJointLevel = *std::max_element(levels.begin(), levels.end());
    }
    colorConstraints(w, maxColors, !levels.empty());
    EXPECT_EQ(w.numColors, maxColors);
    std::vector<uint> after = w.counters.download(w.ctx, kNumCounters);
    if (status) *status = after[kStatus];
    if (after[kStatus] & BTG_STATUS_GRID_BARRIER_TIMEOUT) return {};  // nothing to check: redone
    std::vector<int> colors = w.edgeColor.download(w.ctx, g.edges.size());
    int leftovers = 0, used = 0;
    for (int c : colors) {
        leftovers += c == maxColors - 1;
        used = std::max(used, c < maxColors - 1 ? c + 1 : 0);
    }
    EXPECT_EQ(after[kLeftovers], uint(leftovers));
    EXPECT_EQ(after[kColorsUsed], uint(used));
    return colors;
}

}  // namespace

TEST(ColorConstraints, MatchesReferenceAndIsAValidColoring)
{
    // dense (80 bodies, 600 edges) and sparse (3,000 bodies, 9,000 edges: most edges colored in
    // the first sub-round, the later ones' few candidates)
    for (int maxColors : {1, 4, 12, 24}) {
        Graph g = maxColors == 24 ? randomGraph(3000, 9000, 8) : randomGraph(80, 600, 5);
        std::vector<int> got = runDevice(g, maxColors);
        std::vector<int> want = ref::colorConstraints(g.edges, g.bodies, maxColors);
        ASSERT_EQ(got.size(), g.edges.size());
        std::vector<std::set<int>> used(maxColors);
        for (size_t i = 0; i < got.size(); ++i) {
            ASSERT_EQ(got[i], want[i]) << "edge " << i << " maxColors " << maxColors;
            ASSERT_GE(got[i], 0);
            ASSERT_LT(got[i], maxColors);
            if (got[i] == maxColors - 1) continue;  // the serial color may repeat bodies
            for (int b : {g.edges[i].bodyA, g.edges[i].bodyB}) {
                if (!btgIsSolverDynamic(g.bodies.props[b].flags)) continue;
                EXPECT_TRUE(used[got[i]].insert(b).second) << "body " << b << " twice in color " << got[i];
            }
        }
        EXPECT_EQ(runDevice(g, maxColors), got);  // deterministic
    }
}

TEST(ColorConstraints, SparseSceneNeedsFewSerialContacts)
{
    // 150 edges on 74 dynamic bodies (degree about 4): 15 rounds leave little for the serial color.
    Graph g = randomGraph(80, 150, 6);
    std::vector<int> got = runDevice(g, 16);
    size_t serial = size_t(std::count(got.begin(), got.end(), 15));
    EXPECT_LT(serial, got.size() / 10);
}

TEST(ColorConstraints, OneWorkGroupLaunchColorsTheSame)
{
    for (int maxColors : {1, 4, 12, 32}) {
        Graph g = randomGraph(80, 600, 9);
        EXPECT_EQ(runDevice(g, maxColors, true), runDevice(g, maxColors, false)) << "maxColors " << maxColors;
    }
}

// The one-launch batching over resident work-groups (grid barriers between rounds) colors
// exactly as one launch per round. A device that does not keep the groups resident may time
// out instead (the world then redoes the step); a GPU must not.
TEST(ColorConstraints, OneResidentLaunchColorsTheSame)
{
    using Resident = DeviceWorld::Resident;
    for (int maxColors : {4, 24}) {
        Graph g = randomGraph(3000, 9000, 11);  // several groups' worth of work per round
        uint status = 0;
        std::vector<int> resident = runDevice(g, maxColors, false, Resident::On, &status);
        if (status & BTG_STATUS_GRID_BARRIER_TIMEOUT) {
            EXPECT_FALSE(test::context().device().isGpu) << "a GPU must keep one group per compute unit resident";
            continue;
        }
        EXPECT_EQ(resident, runDevice(g, maxColors, false, Resident::Off)) << "maxColors " << maxColors;
    }
}

TEST(ColorConstraints, EnoughColorsLeaveNoLeftovers)
{
    // 80 bodies, 600 edges: ~15 edges per body. Filled colors need about the largest
    // degree (plus a few), far below 64, so nothing is left for the slow serial pass.
    Graph g = randomGraph(80, 600, 3);
    std::vector<int> got = runDevice(g, 64);
    EXPECT_EQ(std::count(got.begin(), got.end(), 63), 0);
}

// The batching's priorities are a bijection of the edge index (coloring.h): no two edges below
// four million tie. A tie between two edges of one body lets both take it in the same colour.
// (The int priority before 2026-12-06 tied 1,823 pairs here, the first at edges 88,337 and
// 112,962.) And the fix changed no coloring without a tie: its order is the old one's wherever
// the old priorities differ.
TEST(ColorPriority, UniqueOverFourMillionEdges)
{
    const int n = 4 << 20;
    std::vector<uint> p(size_t(n), 0u);
    for (int i = 0; i < n; ++i) p[size_t(i)] = btgColorPriority(i);
    EXPECT_NE(btgColorPriority(88337), btgColorPriority(112962));
    // the old priority: the hash's low 31 bits
    auto old = [](int i) { return int(((btgColorPriority(i) >> 1) | (btgColorPriority(i) << 31)) & 0x7fffffffu); };
    std::mt19937 rng(7);
    for (int k = 0; k < 100000; ++k) {
        const int i = int(rng() % uint(n)), j = int(rng() % uint(n));
        if (old(i) != old(j)) ASSERT_EQ(old(i) < old(j), p[size_t(i)] < p[size_t(j)]) << i << " " << j;
    }
    EXPECT_EQ(old(88337), old(112962));
    std::sort(p.begin(), p.end());
    EXPECT_EQ(std::adjacent_find(p.begin(), p.end()), p.end()) << "two edges share a priority";
}

// The bullet mode's ordered joints (stock's solve order, compat/joint_order.h): each joint takes
// the colour of its level, the contacts colour around them, exactly as the reference, on every
// launch shape; no dynamic body twice in a colour; levels past the rounds are leftovers.
TEST(ColorConstraints, OrderedJointsTakeTheirLevelsAsTheReference)
{
    Graph g = randomGraph(80, 400, 21);
    // 12 joints: a chain 10-11-...-16 (levels 0..5 in the chain's order), a chain of three
    // ending at a static body, and three on bodies of their own or shared with the chain's start
    std::vector<BtgEdge> joints;
    std::vector<int> levels;
    for (int k = 0; k < 6; ++k) {
        joints.push_back(BtgEdge{10 + k, 11 + k});
        levels.push_back(k);
    }
    joints.push_back(BtgEdge{40, 41});
    levels.push_back(0);
    joints.push_back(BtgEdge{41, 42});
    levels.push_back(1);
    joints.push_back(BtgEdge{42, 2});  // to a static body
    levels.push_back(2);
    joints.push_back(BtgEdge{50, 51});
    levels.push_back(0);
    joints.push_back(BtgEdge{10, 60});  // shares body 10 with the chain's first joint
    levels.push_back(1);
    joints.push_back(BtgEdge{61, 62});
    levels.push_back(0);
    const int firstJoint = int(g.edges.size());
    g.edges.insert(g.edges.end(), joints.begin(), joints.end());
    for (int maxColors : {4, 24}) {
        std::vector<int> want = ref::colorConstraints(g.edges, g.bodies, maxColors, levels, firstJoint);
        std::vector<int> got = runDevice(g, maxColors, false, DeviceWorld::Resident::Off, nullptr, levels);
        ASSERT_EQ(got, want) << "maxColors " << maxColors;
        EXPECT_EQ(runDevice(g, maxColors, true, DeviceWorld::Resident::Auto, nullptr, levels), want) << "one group";
        uint status = 0;
        std::vector<int> resident = runDevice(g, maxColors, false, DeviceWorld::Resident::On, &status, levels);
        if (!(status & BTG_STATUS_GRID_BARRIER_TIMEOUT)) EXPECT_EQ(resident, want) << "resident";
        for (size_t j = 0; j < levels.size(); ++j)
            EXPECT_EQ(got[size_t(firstJoint) + j], std::min(levels[j], maxColors - 1)) << "joint " << j;
        std::vector<std::set<int>> used(static_cast<size_t>(maxColors));
        for (size_t i = 0; i < got.size(); ++i) {
            if (got[i] == maxColors - 1) continue;  // the serial colour may repeat bodies
            for (int b : {g.edges[i].bodyA, g.edges[i].bodyB}) {
                if (!btgIsSolverDynamic(g.bodies.props[size_t(b)].flags)) continue;
                EXPECT_TRUE(used[size_t(got[i])].insert(b).second) << "body " << b << " twice in colour " << got[i];
            }
        }
    }
}
