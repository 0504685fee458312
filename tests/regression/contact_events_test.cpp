// contact_events_test.cpp — the manifold events on the GPU path against stock in the same test:
// gContactProcessed/Started/Ended/Destroyed callback counts on a box pile, a point's
// m_userPersistentData kept across steps and destroyed as stock's, and the events beside a
// trigger ghost. Each step asserts the GPU path.
#include "btgpu/btGpuDynamicsWorld.h"
#include "scenes/callback_scenes.h"
#include "scenes/compound_scenes.h"
#include "scenes/ghost_scenes.h"
#include "scenes/stock_chaos.h"
#include "side_by_side.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <vector>

using namespace btgpu;
using namespace btgpu::test;

namespace {

struct EventCounts {
    long started = 0, ended = 0, processed = 0, added = 0, destroyed = 0;
    long addedKept = 0;  // added calls for a point apart (distance > 0) that continues one
};
EventCounts g_events;
long g_allocated = 0;
void onStarted(btPersistentManifold* const&) { ++g_events.started; }
void onEnded(btPersistentManifold* const&) { ++g_events.ended; }
bool onProcessed(btManifoldPoint&, void*, void*)
{
    ++g_events.processed;
    return true;
}
bool onAdded(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*, int, int)
{
    ++g_events.added;
    if (cp.getDistance() > 0 && cp.getLifeTime() > 0) ++g_events.addedKept;
    return true;
}
// The usual user-data pattern: a point gets its own record the first time it is processed, the
// destroyed callback frees it.
bool tagPoint(btManifoldPoint& cp, void*, void*)
{
    ++g_events.processed;
    if (!cp.m_userPersistentData) {
        cp.m_userPersistentData = new long(++g_allocated);
    }
    return true;
}
bool freePoint(void* data)
{
    ++g_events.destroyed;
    delete static_cast<long*>(data);
    return true;
}
// The points of the app's manifolds whose pair has an awake body (stock's refresh processes them).
long heldPoints(Scene& s)
{
    long n = 0;
    btDispatcher* d = s.world().getDispatcher();
    for (int i = 0; i < d->getNumManifolds(); ++i) {
        const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
        if (m->getBody0()->isActive() || m->getBody1()->isActive()) n += m->getNumContacts();
    }
    return n;
}
struct Events {
    ~Events()
    {
        gContactStartedCallback = nullptr;
        gContactEndedCallback = nullptr;
        gContactProcessedCallback = nullptr;
        gContactDestroyedCallback = nullptr;
        gContactAddedCallback = nullptr;
    }
};

}  // namespace

// A 4 x 4 x 4 box pile falling onto a flagged ground, per 100-step window against stock:
// processed calls (the points in the manifolds, refreshed) within 5% over the 200 steps and 8% a
// window (measured +0.2% and -0.3%); started and ended within 5% plus 10 (the landing's 171
// starts equal; later a few a window come and go, as the pile's chaos has it). Added calls: as
// stock's, box pairs run stock's box–box detector into a persistent manifold
// (kernels/shared/box_box.h), so only the points it reports (penetrating, distance <= 0) are
// added and called; a point kept from an earlier step is not. Measured +9.3% in the first window
// and +7.6% in the second (+8.4% over the 200 steps) against the unnudged stock run; stock's own
// chaos is as wide: its 8 nudged runs make 4,621-4,891 and 5,663-6,189 calls a window (10,320-
// 11,080 in all: a resting box's corner just above or just below zero decides a call), so the
// bound is stock's chaos (the nudged runs' mean, 3 x their largest distance plus a floor) where
// wider than 5%: measured 419 off the mean against 810, 500 against 1,578, 919 against 2,280.
// After 200 steps stock's pile sleeps earlier than the GPU path's (no calls for a
// pair of sleeping bodies on either), so the windows stop there.
TEST(Callbacks, EventCountsOnABoxPileAsStock)
{
    Events restore;
    gContactStartedCallback = onStarted;
    gContactEndedCallback = onEnded;
    gContactProcessedCallback = onProcessed;
    gContactAddedCallback = onAdded;
    auto make = [](WorldKind k, const Config&) {
        ScenePtr s = scenes::cubes(k, 4, 4, 4, Config::bulletMode());
        btRigidBody* ground = s->body(0);
        ground->setCollisionFlags(ground->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
        return s;
    };
    // Stock's own chaos of the added calls: per window and over the run, the nudged runs' mean
    // and largest distance.
    double chaosMean[3] = {0, 0, 0}, chaosLo[3] = {1e30, 1e30, 1e30}, chaosHi[3] = {0, 0, 0};
    for (int run = 0; run < tol::kChaosRuns; ++run) {
        ScenePtr s = make(WorldKind::Stock, Config::bulletMode());
        scenes::nudge(*s, 1000u + unsigned(run), tol::kChaosNudge);
        double counts[3] = {0, 0, 0};
        for (int step = 0; step < 200; ++step) {
            g_events = EventCounts();
            s->step();
            counts[step / 100] += double(g_events.added);
            counts[2] += double(g_events.added);
        }
        for (int k = 0; k < 3; ++k) {
            chaosMean[k] += counts[k] / tol::kChaosRuns;
            chaosLo[k] = std::min(chaosLo[k], counts[k]);
            chaosHi[k] = std::max(chaosHi[k], counts[k]);
        }
    }
    auto expectAddedAsStock = [&](double gpuCount, double stockCount, int k) {
        const double chaos = tol::kChaosFactor * (chaosHi[k] - chaosLo[k]) + tol::kChaosContactsFloor;
        std::printf("added %s: btgpu %.0f, stock %.0f, stock's nudged runs %.0f-%.0f (mean %.0f): %.0f off, bound %.0f\n",
                    k < 2 ? (k ? "steps 100-199" : "steps 0-99") : "over 200 steps", gpuCount, stockCount, chaosLo[k],
                    chaosHi[k], chaosMean[k], std::fabs(gpuCount - chaosMean[k]), std::max(0.05 * stockCount, chaos));
        if (std::fabs(gpuCount - stockCount) <= 0.05 * stockCount) return;
        EXPECT_NEAR(gpuCount, chaosMean[k], chaos) << "added calls, " << k;
    };
    SideBySide sb(make);
    const int window = 100;
    EventCounts stock, gpu;
    long stockProcessed = 0, gpuProcessed = 0, stockAdded = 0, gpuAdded = 0;
    for (int step = 0; step < 200; ++step) {
        g_events = EventCounts();
        sb.stock->step();
        EventCounts a = g_events;
        g_events = EventCounts();
        sb.gpu->step();
        EventCounts b = g_events;
        ASSERT_TRUE(sb.onGpu()) << step << " " << sb.gpu->report()->cpuPathReason;
        for (auto [sum, one] : {std::pair<EventCounts*, EventCounts*>{&stock, &a}, {&gpu, &b}}) {
            sum->started += one->started;
            sum->ended += one->ended;
            sum->processed += one->processed;
            sum->added += one->added;
        }
        EXPECT_EQ(a.addedKept, 0) << step;  // stock's box–box detector reports penetrating points only
        EXPECT_EQ(b.addedKept, 0) << step;
        // Each refreshed point is processed once: as many calls as the app's manifolds of pairs
        // with an awake body hold, on both.
        EXPECT_EQ(a.processed, heldPoints(*sb.stock)) << step;
        EXPECT_EQ(b.processed, heldPoints(*sb.gpu)) << step;
        if ((step + 1) % window) continue;
        std::printf("steps %3d-%3d: started %ld/%ld ended %ld/%ld processed %ld/%ld added %ld/%ld (stock/gpu)\n",
                    step + 1 - window, step, stock.started, gpu.started, stock.ended, gpu.ended, stock.processed,
                    gpu.processed, stock.added, gpu.added);
        EXPECT_NEAR(gpu.processed, stock.processed, 0.08 * double(stock.processed)) << step;
        stockProcessed += stock.processed;
        gpuProcessed += gpu.processed;
        EXPECT_NEAR(gpu.started, stock.started, 0.05 * double(stock.started) + 10) << step;
        EXPECT_NEAR(gpu.ended, stock.ended, 0.05 * double(stock.ended) + 10) << step;
        expectAddedAsStock(double(gpu.added), double(stock.added), step / window);
        stockAdded += stock.added;
        gpuAdded += gpu.added;
        EXPECT_GT(stock.processed, 0);
        stock = gpu = EventCounts();
    }
    EXPECT_NEAR(gpuProcessed, stockProcessed, 0.05 * double(stockProcessed));
    expectAddedAsStock(double(gpuAdded), double(stockAdded), 2);
    std::printf("added over 200 steps: stock %ld gpu %ld\n", stockAdded, gpuAdded);
}

namespace {
// The ground's contacts get the callback's friction and restitution (not the bodies' 0.5 x 0.5
// and 0); the processed callback counts the points that are apart and were added in an earlier
// step (on stock: kept by its refresh; on the GPU path: not called again, see above).
bool groundMaterial(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*, int, int)
{
    ++g_events.added;
    if (cp.getDistance() > 0 && cp.getLifeTime() > 0) ++g_events.addedKept;
    cp.m_combinedFriction = btScalar(0.3);
    cp.m_combinedRestitution = btScalar(0.05);
    return true;
}
bool countKept(btManifoldPoint& cp, void* body0, void* body1)
{
    const int flags = static_cast<btCollisionObject*>(body0)->getCollisionFlags() |
                      static_cast<btCollisionObject*>(body1)->getCollisionFlags();
    if (!(flags & btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK)) return true;
    ++g_events.processed;
    if (cp.getDistance() > 0 && cp.getLifeTime() > 1) ++g_events.destroyed;  // here: kept points
    return true;
}

struct KeptRun {
    long added[2] = {0, 0}, kept[2] = {0, 0}, checked[2] = {0, 0};
};
// Steps a scene whose body 0 (a box ground) is flagged with groundMaterial, on both worlds: no
// added call for an apart point that continues one, every point of a ground manifold with the
// callback's friction and restitution after every step, the GPU path on every step.
KeptRun keptRun(const std::function<ScenePtr(WorldKind)>& scene, int steps)
{
    gContactAddedCallback = groundMaterial;
    gContactProcessedCallback = countKept;
    SideBySide sb([&](WorldKind k, const Config&) {
        ScenePtr s = scene(k);
        btRigidBody* ground = s->body(0);
        ground->setCollisionFlags(ground->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
        return s;
    });
    KeptRun r;
    for (int step = 0; step < steps; ++step) {
        int w = 0;
        for (Scene* s : {sb.stock.get(), sb.gpu.get()}) {
            g_events = EventCounts();
            s->step();
            EXPECT_EQ(g_events.addedKept, 0) << step << " " << w;
            r.added[w] += g_events.added;
            r.kept[w] += g_events.destroyed;
            btDispatcher* d = s->world().getDispatcher();
            for (int i = 0; i < d->getNumManifolds(); ++i) {
                const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
                if (m->getBody0() != s->body(0) && m->getBody1() != s->body(0)) continue;
                for (int j = 0; j < m->getNumContacts(); ++j) {
                    EXPECT_FLOAT_EQ(m->getContactPoint(j).m_combinedFriction, 0.3f) << step << " " << w;
                    EXPECT_FLOAT_EQ(m->getContactPoint(j).m_combinedRestitution, 0.05f) << step << " " << w;
                    ++r.checked[w];
                }
            }
            ++w;
        }
        EXPECT_TRUE(sb.onGpu()) << step << " " << sb.gpu->report()->cpuPathReason;
        if (!sb.onGpu()) break;
    }
    std::printf("ground points checked stock %ld gpu %ld; added stock %ld gpu %ld; kept (apart, not added "
                "again) stock %ld gpu %ld\n",
                r.checked[0], r.checked[1], r.added[0], r.added[1], r.kept[0], r.kept[1]);
    return r;
}
}  // namespace

// A ground box's added callback: the points stock's box–box detector does not add (apart, kept
// from an earlier step) keep on both what the callback gave them when added, in the step's solve
// (one friction a device manifold: no fallback) and in the app's manifolds. On a box pile, and
// under tables (compounds: stock's child algorithms are box–box too, one per leg).
TEST(Callbacks, KeptBoxPointsKeepTheCallbacksMaterialAsStock)
{
    Events restore;
    const KeptRun pile = keptRun([](WorldKind k) { return scenes::cubes(k, 4, 4, 4, Config::bulletMode()); }, 90);
    EXPECT_GT(pile.checked[1], 64 * 60);
    EXPECT_GT(pile.kept[0], 0);
    EXPECT_GT(pile.kept[1], 0);  // the path is taken on the GPU path too
    const KeptRun tables = keptRun([](WorldKind k) { return scenes::tableStack(k, Config::bulletMode(), 3); }, 90);
    EXPECT_GT(tables.checked[1], 4 * 60);
    EXPECT_GT(tables.added[1], 0);
}

// On compounds stock calls the processed callback twice a step for a point that continues one
// (the compound's algorithm refreshes every child manifold before the children collide, then
// each child's algorithm refreshes its own): a stack of three tables on a box. Measured per
// 30-step window (stock/GPU) 2376/2832, 2572/2880, 2548/2880, 2664/2880, +12.9% over the 120
// steps (before: about half of stock's): stock's table-on-table points are often replaced by
// new ones (lifetimes of 2 or 3 at step 100), which its first refresh does not see; the GPU
// path's stay (96 calls a step: 48 points, twice). Bound: 15% over the steps.
TEST(Callbacks, ProcessedTwiceOnCompoundsAsStock)
{
    // With trees and, btCompoundShape(false), without (stock's nested compound algorithms refresh
    // a table–table leaf pair three times a step).
    for (bool trees : {true, false}) {
        SCOPED_TRACE(trees ? "with trees" : "without trees");
        Events restore;
        gContactProcessedCallback = onProcessed;
        SideBySide sb([=](WorldKind k, const Config& c) { return scenes::tableStack(k, c, 3, trees); });
        long processed[2] = {0, 0}, total[2] = {0, 0};
        for (int step = 0; step < 120; ++step) {
            int w = 0;
            for (Scene* s : {sb.stock.get(), sb.gpu.get()}) {
                g_events = EventCounts();
                s->step();
                processed[w] += g_events.processed;
                total[w++] += g_events.processed;
            }
            ASSERT_TRUE(sb.onGpu()) << step << " " << sb.gpu->report()->cpuPathReason;
            if ((step + 1) % 30) continue;
            std::printf("steps %3d-%3d: processed %ld/%ld (stock/gpu)\n", step - 29, step, processed[0], processed[1]);
            processed[0] = processed[1] = 0;
        }
        std::printf("tables (%s trees): processed %ld/%ld\n", trees ? "with" : "without", total[0], total[1]);
        EXPECT_GT(total[0], 120 * 48 * 3 / 2);  // stock's own: more than once a point
        EXPECT_NEAR(total[1], total[0], 0.15 * double(total[0]));
    }
}

// m_userPersistentData set in the processed callback persists on the app's manifold points as
// stock's (one record a point while the box rests), and each record reaches the destroyed
// callback when the contact goes (the box lifted away): the counts equal stock's.
TEST(Callbacks, UserDataPersistsAndIsDestroyedAsStock)
{
    Events restore;
    gContactProcessedCallback = tagPoint;
    gContactDestroyedCallback = freePoint;
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::restingBox(k, c); });
    long allocated[2] = {0, 0}, destroyed[2] = {0, 0};
    auto stepBoth = [&](int n) {
        for (int i = 0; i < n; ++i) {
            int w = 0;
            for (Scene* s : {sb.stock.get(), sb.gpu.get()}) {
                g_allocated = 0;
                g_events = EventCounts();
                s->step();
                allocated[w] += g_allocated;
                destroyed[w] += g_events.destroyed;
                ++w;
            }
            ASSERT_TRUE(sb.onGpu()) << sb.gpu->report()->cpuPathReason;
        }
    };
    stepBoth(60);
    std::printf("resting 60 steps: records stock %ld gpu %ld\n", allocated[0], allocated[1]);
    EXPECT_EQ(allocated[1], allocated[0]);
    EXPECT_GT(allocated[0], 0);
    EXPECT_LE(allocated[0], 8);  // one a point, not one a step
    // The app's points hold them as stock's.
    auto held = [](Scene& s) {
        long n = 0;
        btDispatcher* d = s.world().getDispatcher();
        for (int i = 0; i < d->getNumManifolds(); ++i)
            for (int j = 0; j < d->getManifoldByIndexInternal(i)->getNumContacts(); ++j)
                n += d->getManifoldByIndexInternal(i)->getContactPoint(j).m_userPersistentData != nullptr;
        return n;
    };
    EXPECT_EQ(held(*sb.gpu), held(*sb.stock));
    EXPECT_EQ(destroyed[1] + held(*sb.gpu), allocated[1]);
    // Lifted 3 m: the contact goes, every record is destroyed.
    sb.both([](Scene& s) {
        btTransform t = s.body(1)->getWorldTransform();
        t.getOrigin() += btVector3(0, 3, 0);
        s.body(1)->setWorldTransform(t);
        s.body(1)->activate();
    });
    stepBoth(5);
    std::printf("lifted: destroyed stock %ld gpu %ld of %ld / %ld\n", destroyed[0], destroyed[1], allocated[0], allocated[1]);
    EXPECT_EQ(destroyed[0], allocated[0]);
    EXPECT_EQ(destroyed[1], destroyed[0]);
}

namespace {
void nearAsStock(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info)
{
    btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}
}  // namespace

// A resting stack sent to the CPU path for 10 steps (an app's near callback, which the GPU path
// leaves to Bullet) and back: its contacts go on through both switches as they do on stock,
// which has no switch — no started or ended event, no user data destroyed, the same records
// held (the GPU path's manifolds handed to stock's algorithms on the way out, stock's taken back
// on the way in: ManifoldSync::handToStock, takeFromStock). Before, each switch ended and
// started every contact (stock's algorithms made their manifolds anew, and freed them on the
// way back) and destroyed and remade every record.
TEST(Callbacks, CpuPathExcursionContinuesContactsAsStock)
{
    Events restore;
    gContactStartedCallback = onStarted;
    gContactEndedCallback = onEnded;
    gContactProcessedCallback = tagPoint;
    gContactDestroyedCallback = freePoint;
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::boxStack(k, c, 4); });
    EventCounts sum[2];
    long allocated[2] = {0, 0};
    auto stepBoth = [&](int n, bool count) {
        for (int i = 0; i < n; ++i) {
            int w = 0;
            for (Scene* s : {sb.stock.get(), sb.gpu.get()}) {
                g_events = EventCounts();
                g_allocated = 0;
                s->step();
                if (count) {
                    sum[w].started += g_events.started;
                    sum[w].ended += g_events.ended;
                    sum[w].destroyed += g_events.destroyed;
                    allocated[w] += g_allocated;
                }
                ++w;
            }
        }
    };
    stepBoth(30, false);
    ASSERT_TRUE(sb.onGpu());
    auto setNear = [](btNearCallback cb) {
        return [cb](Scene& s) { static_cast<btCollisionDispatcher*>(s.world().getDispatcher())->setNearCallback(cb); };
    };
    sb.both(setNear(nearAsStock));
    stepBoth(10, true);
    EXPECT_FALSE(sb.onGpu());
    sb.both(setNear(btCollisionDispatcher::defaultNearCallback));
    stepBoth(30, true);
    ASSERT_TRUE(sb.onGpu());
    std::printf("excursion: started %ld/%ld ended %ld/%ld destroyed %ld/%ld new records %ld/%ld (stock/gpu)\n",
                sum[0].started, sum[1].started, sum[0].ended, sum[1].ended, sum[0].destroyed, sum[1].destroyed,
                allocated[0], allocated[1]);
    EXPECT_EQ(sum[1].started, sum[0].started);
    EXPECT_EQ(sum[1].ended, sum[0].ended);
    // Stock's own resting stack replaces a point now and then (measured 2 records destroyed and
    // remade in these 40 steps, the GPU path's none): within one manifold's points of stock's.
    // Without the hand-overs: 8 started, 4 ended, 32 destroyed and remade.
    EXPECT_NEAR(sum[1].destroyed, sum[0].destroyed, 4);
    EXPECT_NEAR(allocated[1], allocated[0], 4);
    // The same excursion on a second btgpu world (other addresses, so the manifold map keeps
    // another order): bitwise the same bodies — the hand-overs follow the pair cache's order.
    ScenePtr again = scenes::boxStack(WorldKind::Gpu, Config::bulletMode(), 4);
    auto near = [&](btNearCallback cb) { static_cast<btCollisionDispatcher*>(again->world().getDispatcher())->setNearCallback(cb); };
    for (int i = 0; i < 30; ++i) again->step();
    near(nearAsStock);
    for (int i = 0; i < 10; ++i) again->step();
    near(btCollisionDispatcher::defaultNearCallback);
    for (int i = 0; i < 30; ++i) again->step();
    for (size_t i = 0; i < again->bodies().size(); ++i) {
        const btTransform& x = again->body(int(i))->getWorldTransform();
        const btTransform& y = sb.gpu->body(int(i))->getWorldTransform();
        EXPECT_EQ(std::memcmp(&x, &y, sizeof(btTransform)), 0) << "body " << i;
    }
}

// Contact events beside a trigger ghost (CF_NO_CONTACT_RESPONSE): stock's dispatcher collides the
// ghost with the bodies inside it, and its callbacks see those points; so do btgpu's, on the GPU
// path (the trigger is a device row that is never solved).
TEST(Callbacks, EventsBesideATriggerGhostAsStock)
{
    static int processed[2], started[2];
    static int which = 0;
    gContactProcessedCallback = [](btManifoldPoint&, void*, void*) {
        ++processed[which];
        return true;
    };
    gContactStartedCallback = [](btPersistentManifold* const&) { ++started[which]; };
    processed[0] = processed[1] = started[0] = started[1] = 0;
    auto stock = scenes::triggerFall(WorldKind::Stock);
    auto gpu = scenes::triggerFall(WorldKind::Gpu);
    for (int step = 0; step < 180; ++step) {
        which = 0;
        stock->scene->step();
        which = 1;
        gpu->scene->step();
        ASSERT_TRUE(gpu->scene->gpuWorld()->isGpuPath()) << step << " " << gpu->scene->report()->cpuPathReason;
    }
    gContactProcessedCallback = nullptr;
    gContactStartedCallback = nullptr;
    printf("beside a trigger ghost: processed %d / %d, started %d / %d (stock / btgpu)\n", processed[0], processed[1],
           started[0], started[1]);
    EXPECT_GE(started[0], 8);  // measured: 8 on both, processed 371 and 372
    EXPECT_NEAR(started[1], started[0], 2);
    EXPECT_NEAR(processed[1], processed[0], 0.15 * processed[0]);
}
