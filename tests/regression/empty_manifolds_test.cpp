// empty_manifolds_test.cpp — the app's dispatcher holds stock's manifolds with and without points
// (one per pair stock's dispatcher has collided, per compound child pair), so getNumManifolds()
// is stock's count: by default from the device's leaf pairs (stage broadphase_leaves, which must
// run), with Config::stockEmptyManifolds from Bullet's own broadphase on the host; against stock
// in the same test, each step on the GPU path.
#include "callback_helpers.h"
#include "scenes/compound_scenes.h"
#include "scenes/stock_chaos.h"
#include "side_by_side.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <tuple>
#include <vector>

using namespace btgpu;
using namespace btgpu::test;

namespace {

struct Held {
    int manifolds = 0, touching = 0, points = 0;
};

Held held(Scene& s)
{
    Held h;
    btDispatcher* d = s.world().getDispatcher();
    h.manifolds = d->getNumManifolds();
    for (int i = 0; i < h.manifolds; ++i) {
        const int n = d->getManifoldByIndexInternal(i)->getNumContacts();
        h.touching += n > 0;
        h.points += n;
    }
    return h;
}

Config stockEmpties()
{
    Config c = Config::bulletMode();
    c.stockEmptyManifolds = true;
    return c;
}

// The default: stock's pairs from the device's leaves.
Config deviceEmpties() { return Config::bulletMode(); }

// The mode's stage ran on the btgpu world's last call (and the other mode's did not).
void expectMode(const Scene& gpu, const Config& c, int step)
{
    EXPECT_EQ(hasStage(gpu, "broadphase_leaves"), !c.stockEmptyManifolds) << step;
}

long g_started = 0, g_ended = 0;
void onStarted(btPersistentManifold* const&) { ++g_started; }
void onEnded(btPersistentManifold* const&) { ++g_ended; }

}  // namespace

// Stock's own chaos per step for the manifold count: the lowest and highest of its nudged runs.
struct Band {
    std::vector<int> lo, hi;
    long sumLo = 0, sumHi = 0;  // the least and most any run summed over the compared steps
    long startedLo = 0, startedHi = 0, endedLo = 0, endedHi = 0;  // contact events over all steps
};
Band stockBand(const std::function<ScenePtr(WorldKind, const Config&)>& make, int steps, int first)
{
    Band band{std::vector<int>(size_t(steps)), std::vector<int>(size_t(steps))};
    for (int run = 0; run < tol::kChaosRuns; ++run) {
        ScenePtr s = make(WorldKind::Stock, stockEmpties());
        scenes::nudge(*s, 1000u + unsigned(run), tol::kChaosNudge);
        long sum = 0;
        g_started = g_ended = 0;
        gContactStartedCallback = onStarted;
        gContactEndedCallback = onEnded;
        for (int step = 0; step < steps; ++step) {
            s->step();
            const int m = held(*s).manifolds;
            if (step >= first) sum += m;
            if (run == 0 || m < band.lo[size_t(step)]) band.lo[size_t(step)] = m;
            if (run == 0 || m > band.hi[size_t(step)]) band.hi[size_t(step)] = m;
        }
        gContactStartedCallback = nullptr;
        gContactEndedCallback = nullptr;
        if (run == 0 || sum < band.sumLo) band.sumLo = sum;
        if (run == 0 || sum > band.sumHi) band.sumHi = sum;
        if (run == 0 || g_started < band.startedLo) band.startedLo = g_started;
        if (run == 0 || g_started > band.startedHi) band.startedHi = g_started;
        if (run == 0 || g_ended < band.endedLo) band.endedLo = g_ended;
        if (run == 0 || g_ended > band.endedHi) band.endedHi = g_ended;
    }
    return band;
}

// The pile lands at slightly different moments on the two worlds (the GPU path's speculative
// contacts stop a falling layer a step or two before stock's detector sees it penetrate), and
// the pairs follow the bodies: the counts are compared once it is down (from `first`), per step
// within 5% of stock's count or stock's own chaos (3x its nudged runs' spread plus a floor)
// where that is wider; summed, within 2% of stock's sum or of its nudged runs' sums.
Band expectCountsAsStock(const std::function<ScenePtr(WorldKind, const Config&)>& make, int steps, int first, long* sums,
                         const Config& mode,
                         const std::function<void(SideBySide&)>& stepBoth = [](SideBySide& sb) { sb.step(); })
{
    const Band band = stockBand(make, steps, first);
    SideBySide sb(make, mode);
    int empties = 0;
    for (int step = 0; step < steps; ++step) {
        stepBoth(sb);
        EXPECT_TRUE(sb.onGpu()) << step;
        if (!sb.onGpu()) return band;
        expectMode(*sb.gpu, mode, step);
        const Held a = held(*sb.stock), b = held(*sb.gpu);
        empties = std::max(empties, b.manifolds - b.touching);
        if (step % 30 == 29 || step == steps - 1)
            std::printf("step %d: manifolds %d/%d (stock's chaos %d-%d) touching %d/%d points %d/%d (stock/btgpu)\n",
                        step, a.manifolds, b.manifolds, band.lo[size_t(step)], band.hi[size_t(step)], a.touching,
                        b.touching, a.points, b.points);
        if (step < first) continue;
        const double chaos = band.hi[size_t(step)] - band.lo[size_t(step)];
        EXPECT_NEAR(b.manifolds, a.manifolds,
                    std::max(0.05 * a.manifolds, tol::kChaosFactor * chaos + tol::kChaosContactsFloor))
            << step;
        sums[0] += a.manifolds;
        sums[1] += b.manifolds;
    }
    const double lo = 0.98 * double(std::min(sums[0], band.sumLo)), hi = 1.02 * double(std::max(sums[0], band.sumHi));
    EXPECT_GE(double(sums[1]), lo);
    EXPECT_LE(double(sums[1]), hi);
    EXPECT_GT(empties, 10);  // pairs without points are held
    return band;
}

// BasicDemo (125 boxes falling onto a ground box, landing, coming to rest and sleeping): every
// manifold, empty or not, against stock's count.
void basicDemoCountsAsStock(const Config& mode)
{
    long sums[2] = {0, 0};
    // The lattice collapses until about step 55 (stock's own runs agree to a few manifolds there).
    expectCountsAsStock([](WorldKind k, const Config& c) { return scenes::basicDemo(k, c); }, 300, 60, sums, mode);
    std::printf("manifolds summed over steps 60-299: %ld/%ld (stock/btgpu)\n", sums[0], sums[1]);
}
TEST(EmptyManifolds, BasicDemoCountsAsStock) { basicDemoCountsAsStock(deviceEmpties()); }
TEST(EmptyManifolds, BasicDemoCountsAsStockHostBroadphase) { basicDemoCountsAsStock(stockEmpties()); }

// A 4x4x4 box pile: the counts through landing, settling and sleep; the manifold events as
// stock's (a contact starts when an empty manifold gets its first point, ends when it loses its
// last).
void boxPileCountsAndEventsAsStock(const Config& mode)
{
    struct Restore {
        ~Restore() { gContactStartedCallback = nullptr, gContactEndedCallback = nullptr; }
    } restore;
    long started[2] = {0, 0}, ended[2] = {0, 0}, sums[2] = {0, 0};
    auto stepBoth = [&](SideBySide& sb) {
        gContactStartedCallback = onStarted;
        gContactEndedCallback = onEnded;
        g_started = g_ended = 0;
        sb.stock->step();
        started[0] += g_started, ended[0] += g_ended;
        g_started = g_ended = 0;
        sb.gpu->step();
        started[1] += g_started, ended[1] += g_ended;
        gContactStartedCallback = nullptr;
        gContactEndedCallback = nullptr;
    };
    const Band band =
        expectCountsAsStock([](WorldKind k, const Config& c) { return scenes::cubes(k, 4, 4, 4, c); }, 240, 40, sums, mode,
                            stepBoth);
    std::printf("manifolds summed over steps 40-239 %ld/%ld, started %ld/%ld, ended %ld/%ld (stock/btgpu)\n", sums[0],
                sums[1], started[0], started[1], ended[0], ended[1]);
    std::printf("stock's nudged runs: started %ld-%ld, ended %ld-%ld\n", band.startedLo, band.startedHi, band.endedLo,
                band.endedHi);
    // Within 5% of stock's count, or stock's own chaos where wider (the floor: a few pairs of the
    // pile's edge that touch and part near rest).
    auto bound = [](long stock, long lo, long hi) {
        return std::max(0.05 * double(stock), tol::kChaosFactor * double(hi - lo) + tol::kChaosContactsFloor) + 10;
    };
    EXPECT_NEAR(started[1], started[0], bound(started[0], band.startedLo, band.startedHi));
    EXPECT_NEAR(ended[1], ended[0], bound(ended[0], band.endedLo, band.endedHi));
    EXPECT_GT(started[0], 100);
}
TEST(EmptyManifolds, BoxPileCountsAndEventsAsStock) { boxPileCountsAndEventsAsStock(deviceEmpties()); }
TEST(EmptyManifolds, BoxPileCountsAndEventsAsStockHostBroadphase) { boxPileCountsAndEventsAsStock(stockEmpties()); }

// A table on the ground and a ball resting beside a leg, inside the leg's AABB but 6 cm from it:
// stock's compound algorithm holds an empty manifold for that leg–ball child pair (and none for
// the top or the other legs); rolled away, the ball's manifold goes at the step its AABB leaves
// the leg's.
void compoundChildPairsAsStock(const Config& mode)
{
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::tableBesideSphere(k, c); }, mode);
    int differ = 0;
    for (int step = 0; step < 100; ++step) {
        if (step == 60)
            sb.both([](Scene& s) {
                s.body(2)->setLinearVelocity(btVector3(2, 0, 2));
                s.body(2)->activate();
            });
        sb.step();
        ASSERT_TRUE(sb.onGpu()) << step;
        expectMode(*sb.gpu, mode, step);
        const Held a = held(*sb.stock), b = held(*sb.gpu);
        if (step == 59) {
            EXPECT_EQ(a.manifolds, 6);  // four legs and the ball on the ground, the leg beside the ball
            EXPECT_EQ(a.touching, 5);
            // The leg first: its child algorithm is the convex–convex one, in the compound's order.
            for (Scene* s : {sb.stock.get(), sb.gpu.get()}) {
                bool childEmpty = false;
                btDispatcher* d = s->world().getDispatcher();
                for (int i = 0; i < d->getNumManifolds(); ++i) {
                    const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
                    childEmpty |= m->getNumContacts() == 0 && m->getBody0() == s->body(1) && m->getBody1() == s->body(2);
                }
                EXPECT_TRUE(childEmpty) << (s == sb.stock.get() ? "stock" : "btgpu");
            }
            // Every manifold's bodies in stock's order (the ball second on the ground: the pair's order).
            auto order = [](Scene& s) {
                std::vector<std::tuple<int, int, int>> o;
                btDispatcher* d = s.world().getDispatcher();
                auto index = [&](const btCollisionObject* c) { return c == s.body(0) ? 0 : c == s.body(1) ? 1 : 2; };
                for (int i = 0; i < d->getNumManifolds(); ++i) {
                    const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
                    o.emplace_back(index(m->getBody0()), index(m->getBody1()), m->getNumContacts() > 0);
                }
                std::sort(o.begin(), o.end());
                return o;
            };
            EXPECT_EQ(order(*sb.gpu), order(*sb.stock));
        }
        if (a.manifolds != b.manifolds || a.touching != b.touching)
            std::printf("step %d: manifolds %d/%d touching %d/%d ball x %.3f/%.3f\n", step, a.manifolds, b.manifolds,
                        a.touching, b.touching, sb.stock->body(2)->getWorldTransform().getOrigin().x(),
                        sb.gpu->body(2)->getWorldTransform().getOrigin().x());
        differ += a.manifolds != b.manifolds || a.touching != b.touching;
        if (step < 60) EXPECT_EQ(b.manifolds, a.manifolds) << step;
    }
    EXPECT_EQ(held(*sb.stock).manifolds, 5);
    EXPECT_EQ(held(*sb.gpu).manifolds, 5);
    EXPECT_EQ(differ, 0);
}
TEST(EmptyManifolds, CompoundChildPairsAsStock) { compoundChildPairsAsStock(deviceEmpties()); }
TEST(EmptyManifolds, CompoundChildPairsAsStockHostBroadphase) { compoundChildPairsAsStock(stockEmpties()); }

// The same scene twice in the default mode: the same manifolds, in the same order with the same
// bodies and point counts, at every step (the leaf pairs are sorted by an integer key, the
// lazy removal and the fill's order follow from them).
TEST(EmptyManifolds, DeviceModeIsDeterministic)
{
    auto make = [] { return scenes::basicDemo(WorldKind::Gpu, deviceEmpties()); };
    ScenePtr x = make(), y = make();
    auto manifolds = [](Scene& s) {
        std::vector<std::tuple<int, int, int>> m;
        btDispatcher* d = s.world().getDispatcher();
        const btCollisionObjectArray& objs = s.world().getCollisionObjectArray();
        for (int i = 0; i < d->getNumManifolds(); ++i) {
            const btPersistentManifold* p = d->getManifoldByIndexInternal(i);
            m.emplace_back(objs.findLinearSearch(const_cast<btCollisionObject*>(p->getBody0())),
                           objs.findLinearSearch(const_cast<btCollisionObject*>(p->getBody1())), p->getNumContacts());
        }
        return m;
    };
    int empties = 0;
    for (int step = 0; step < 150; ++step) {
        x->step();
        y->step();
        ASSERT_TRUE(x->gpuWorld()->isGpuPath() && y->gpuWorld()->isGpuPath()) << step;
        ASSERT_TRUE(hasStage(*x, "broadphase_leaves"));
        const auto a = manifolds(*x), b = manifolds(*y);
        ASSERT_EQ(a, b) << step;
        empties = std::max(empties, int(std::count_if(a.begin(), a.end(), [](const auto& t) { return std::get<2>(t) == 0; })));
    }
    EXPECT_GT(empties, 100);
}

// Spheres flying apart without contacts (the same motion on both worlds): every manifold is
// empty, and each goes when stock's lazy cleanup drops its pair, some steps after the leaves
// part (here every leaf parts from every other in one step, step 7). The device mode follows that
// timing: the round robin over the pair array (whose order is not stock's), m_newpairs counted in
// stock's update order, the pairs stock's pass meets on the way. Plain removal would drop all
// 1,036 at step 7. Measured residual: from step 8 btgpu holds 36 pairs more than stock (3.5% of
// the pairs at the start; both then lose 10% of what they hold a step); its cause is not found,
// so the bound is 5% of the starting pairs per step, and the sum within 20%.
TEST(EmptyManifolds, LazyPairRemovalAsStock)
{
    SideBySide sb([](WorldKind k, const Config& c) { return scenes::dispersingSpheres(k, c); }, deviceEmpties());
    long sums[2] = {0, 0};
    int worst = 0, start = 0, lastStock = -1, lastGpu = -1, atTen[2] = {0, 0};
    for (int step = 0; step < 90; ++step) {
        sb.step();
        ASSERT_TRUE(sb.onGpu()) << step;
        expectMode(*sb.gpu, deviceEmpties(), step);
        const Held a = held(*sb.stock), b = held(*sb.gpu);
        EXPECT_EQ(a.touching, 0);
        EXPECT_EQ(b.touching, 0);
        if (step == 0) start = a.manifolds;
        EXPECT_NEAR(b.manifolds, a.manifolds, std::max(3.0, 0.05 * start)) << step;
        worst = std::max(worst, std::abs(b.manifolds - a.manifolds));
        sums[0] += a.manifolds;
        sums[1] += b.manifolds;
        if (step == 10) atTen[0] = a.manifolds, atTen[1] = b.manifolds;
        if (a.manifolds > 0) lastStock = step;
        if (b.manifolds > 0) lastGpu = step;
    }
    std::printf("dispersing spheres: manifolds summed %ld/%ld (stock/btgpu), worst step %d, %d at the start, %d/%d at "
                "step 10, last held at step %d/%d\n",
                sums[0], sums[1], worst, start, atTen[0], atTen[1], lastStock, lastGpu);
    EXPECT_GT(start, 1000);  // the lattice's neighbours (and diagonal ones) start paired
    EXPECT_GT(atTen[0], start / 3);  // lazily: stock still holds many three steps after the leaves parted
    EXPECT_GT(atTen[1], start / 3);
    EXPECT_NEAR(double(sums[1]), double(sums[0]), 0.2 * double(sums[0]));
    EXPECT_NEAR(lastGpu, lastStock, 3);
}

// Above Config::deviceEmptyManifoldsUpTo collision objects the device mode stays off (its host
// cost grows with the world): no broadphase_leaves stage, and the dispatcher holds the manifolds
// with points only, as stock's with points; raised again, the stage and the empty ones come back.
TEST(EmptyManifolds, BigWorldsHoldPointsOnly)
{
    Config capped = Config::bulletMode();
    capped.deviceEmptyManifoldsUpTo = 100;  // BasicDemo has 126 collision objects
    ScenePtr s = scenes::basicDemo(WorldKind::Gpu, capped);
    for (int step = 0; step < 80; ++step) {
        s->step();
        ASSERT_TRUE(s->gpuWorld()->isGpuPath()) << step;
        ASSERT_FALSE(hasStage(*s, "broadphase_leaves")) << step;
        const Held h = held(*s);
        ASSERT_EQ(h.manifolds, h.touching) << step;
    }
    EXPECT_GT(held(*s).touching, 100);
    // Not silently: one Difference issue says so, naming the count and the setting.
    int said = 0;
    for (const Issue& i : s->gpuWorld()->report().issues)
        if (i.kind == Issue::Kind::Difference) {
            ++said;
            EXPECT_NE(i.message.find("126 collision objects"), std::string::npos) << i.message;
            EXPECT_NE(i.message.find("deviceEmptyManifoldsUpTo (100)"), std::string::npos) << i.message;
        }
    EXPECT_EQ(said, 1);
    ScenePtr open = scenes::basicDemo(WorldKind::Gpu, Config::bulletMode());
    for (int step = 0; step < 80; ++step) open->step();
    EXPECT_TRUE(hasStage(*open, "broadphase_leaves"));
    EXPECT_GT(held(*open).manifolds, held(*open).touching);
    for (const Issue& i : open->gpuWorld()->report().issues) EXPECT_NE(i.kind, Issue::Kind::Difference) << i.message;
}
