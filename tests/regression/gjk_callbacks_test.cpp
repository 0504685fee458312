// gjk_callbacks_test.cpp — gContactAddedCallback beside support-function shapes (capsules) on the
// GPU path, against stock in the same test: the device's persistent manifold adds one point a
// step, as stock's convex–convex algorithm, and the callback is called for that point alone; a
// capsule bouncing on a trampoline through the callback's restitution, the added and processed
// counts on a capsule pile, and a capsule sliding over a mesh's internal edges through
// btAdjustInternalEdgeContacts. Each step asserts the GPU path.
#include "scenes/callback_scenes.h"
#include "callback_helpers.h"
#include "side_by_side.h"

#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>
#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

using namespace btgpu;
using namespace btgpu::test;

namespace {

struct Restore {
    ~Restore()
    {
        gContactAddedCallback = nullptr;
        gContactProcessedCallback = nullptr;
    }
};

long g_added = 0, g_processed = 0;
bool bouncy(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*, int, int)
{
    ++g_added;
    cp.m_combinedRestitution = btScalar(0.8);
    return true;
}
bool counted(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*, int, int)
{
    ++g_added;
    cp.m_combinedFriction = btScalar(0.3);
    return true;
}
bool processed(btManifoldPoint&, void*, void*)
{
    ++g_processed;
    return true;
}
long g_adjusted = 0;
bool edgeFix(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int, const btCollisionObjectWrapper* w1,
             int partId1, int index1)
{
    ++g_added;
    if (adjustInternalEdge(cp, w0, w1, partId1, index1)) ++g_adjusted;
    return true;
}


// The manifolds with points between the ground (body 0) and another body.
int groundPairs(Scene& s)
{
    int n = 0;
    btDispatcher* d = s.world().getDispatcher();
    for (int i = 0; i < d->getNumManifolds(); ++i) {
        const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
        n += m->getNumContacts() > 0 && (m->getBody0() == s.body(0) || m->getBody1() == s.body(0));
    }
    return n;
}

// Both worlds one step each, the callbacks' calls counted per world.
void stepCounting(SideBySide& sb, long* added, long* processedCalls)
{
    g_added = g_processed = 0;
    sb.stock->step();
    added[0] += g_added, processedCalls[0] += g_processed;
    g_added = g_processed = 0;
    sb.gpu->step();
    added[1] += g_added, processedCalls[1] += g_processed;
}

}  // namespace

// An upright capsule (restitution 0) bounces on the trampoline only through the callback's
// restitution: apexes as stock's within 5%, one call a step of contact on both.
TEST(GjkCallbacks, CapsuleTrampolineBouncesAsStock)
{
    Restore restore;
    gContactAddedCallback = bouncy;
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::capsuleTrampoline(k, c); });
    std::vector<double> ys, yg;
    long added[2] = {0, 0}, none[2] = {0, 0};
    for (int step = 0; step < 240; ++step) {
        stepCounting(sb, added, none);
        ASSERT_TRUE(sb.onGpu()) << step << " " << sb.gpu->report()->cpuPathReason;
        ASSERT_TRUE(hasStage(*sb.gpu, "contact_callbacks"));
        ys.push_back(sb.stockY(1));
        yg.push_back(sb.gpuY(1));
    }
    const std::vector<double> a = bounceApexes(ys), b = bounceApexes(yg);
    std::printf("apexes stock");
    for (double v : a) std::printf(" %.4f", v);
    std::printf(", btgpu");
    for (double v : b) std::printf(" %.4f", v);
    std::printf("; added calls %ld/%ld (stock/btgpu)\n", added[0], added[1]);
    ASSERT_GE(a.size(), 3u);
    ASSERT_GE(b.size(), 3u);
    const double rest = 0.8;  // the centre's height at rest (radius 0.3 + half height 0.5)
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_GT(a[i], rest + 0.3) << i;  // it bounces (restitution 0 without the callback)
        EXPECT_NEAR(b[i], a[i], 0.05 * (a[i] - rest)) << "apex " << i;
    }
    EXPECT_NEAR(double(added[1]), double(added[0]), 0.05 * double(added[0]) + 2);
}

// Capsules dropped in crossed layers onto a flagged ground, kept awake: the added calls (one per
// step per touching capsule–ground pair on stock: its GJK point) and the processed calls (every
// point its refresh keeps) per 100-step window, against stock.
TEST(GjkCallbacks, CapsulePileCountsAsStock)
{
    Restore restore;
    gContactAddedCallback = counted;
    gContactProcessedCallback = processed;
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::capsulePile(k, c); });
    // Awake throughout: stock collides no pair of two sleeping bodies (no calls), and when each
    // world's capsules fall asleep is the pile's own business, not the callbacks'.
    sb.both([](Scene& s) {
        for (btRigidBody* b : s.bodies())
            if (b->getInvMass() > 0) b->setActivationState(DISABLE_DEACTIVATION);
    });
    long added[2] = {0, 0}, processedCalls[2] = {0, 0}, touching[2] = {0, 0};
    for (int step = 0; step < 300; ++step) {
        stepCounting(sb, added, processedCalls);
        ASSERT_TRUE(sb.onGpu()) << step << " " << sb.gpu->report()->cpuPathReason;
        touching[0] += groundPairs(*sb.stock);
        touching[1] += groundPairs(*sb.gpu);
        if ((step + 1) % 100) continue;
        std::printf("steps %3d-%3d: added %ld/%ld processed %ld/%ld ground pair-steps %ld/%ld (stock/btgpu)\n", step - 99,
                    step, added[0], added[1], processedCalls[0], processedCalls[1], touching[0], touching[1]);
        EXPECT_GT(added[0], 50) << step;
        EXPECT_NEAR(double(added[1]), double(added[0]), 0.05 * double(added[0])) << step;
        EXPECT_NEAR(double(processedCalls[1]), double(processedCalls[0]), 0.08 * double(processedCalls[0])) << step;
        added[0] = added[1] = processedCalls[0] = processedCalls[1] = touching[0] = touching[1] = 0;
    }
}

// btInternalEdgeUtility through the callback with a capsule (a character's shape) sliding over a
// mesh's internal edges: as far as on stock (within 5%), no hop.
TEST(GjkCallbacks, CapsuleSlidesOverInternalEdgesAsStock)
{
    Restore restore;
    gContactAddedCallback = edgeFix;
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::capsuleEdgeSlide(k, c); });
    long added[2] = {0, 0}, none[2] = {0, 0};
    double highest = 0;
    for (int step = 0; step < 150; ++step) {
        stepCounting(sb, added, none);
        ASSERT_TRUE(sb.onGpu()) << step << " " << sb.gpu->report()->cpuPathReason;
        if (step > 10) highest = std::max(highest, sb.gpuY(1));
    }
    const double ds = sb.stock->body(1)->getWorldTransform().getOrigin().x() + 6;
    const double dg = sb.gpu->body(1)->getWorldTransform().getOrigin().x() + 6;
    std::printf("slid: stock %.4f m, btgpu %.4f m; calls %ld/%ld; normals adjusted %ld\n", ds, dg, added[0], added[1],
                g_adjusted);
    EXPECT_GT(ds, 2.0);
    EXPECT_NEAR(dg, ds, 0.05 * ds);
    EXPECT_LT(highest, 0.82);
    EXPECT_NEAR(sb.gpuY(1), sb.stockY(1), 0.01);
    EXPECT_GT(added[1], 0);
}
