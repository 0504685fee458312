// extreme_test.cpp — extreme scenes on stock Bullet and on btgpu: deep initial overlap, a fast
// small sphere against a thin wall, very small and very large boxes, a pile far from the origin,
// and "beyond reason" inputs that only have to end without NaN or crash and with a clear status.
#include <cmath>
#include <limits>

#include "stability/stability.h"

using namespace btgpu;
using namespace btgpu::stability;
namespace st = btgpu::scenes::stability;

namespace {

constexpr double kUnjudged = std::numeric_limits<double>::infinity();

// The btgpu runs each case takes: the bullet mode (its rows labelled "btgpu", as runEngines's)
// and the default solver.
struct EngineRun {
    const char* label;
    bool bulletMode;
    Config config() const { return bulletMode ? Config::bulletMode() : Config(); }
};
const EngineRun kGpuRuns[] = {{"btgpu", true}, {"btgpu default", false}};

// Beyond reason: measured (penetration and speed recorded) but judged only on finiteness, and
// for btgpu on a clear status: the GPU path ran, or the world said why not, or an issue names
// the problem (a NaN with an issue reported is a clear status).
// `measure`: penetration at the end (contactPairTest on every overlapping pair: too slow for
// millions of pairs). `withStock`: stock Bullet can hold the scene in memory at all.
void beyondReason(const std::string& caseName, const Builder& make, double seconds, bool measure = true,
                  bool withStock = true)
{
    const Config config = Config::bulletMode();
    Criteria c;
    c.seconds = seconds;
    c.speed = kUnjudged;
    c.penetration = measure ? kUnjudged : -1;
    c.measureFrom = seconds;
    Outcome stock;
    if (withStock) {
        stock = run(make, WorldKind::Stock, c, config);
        record(caseName, stock, figure(stock));
    } else {
        // Not a result: stock Bullet's pair cache would need n (n - 1) / 2 manifolds.
        appendRowNotRun(caseName, "stock", "not run: stock's pair cache cannot hold n(n-1)/2 pairs");
    }
    for (const EngineRun& e : kGpuRuns) {
        ScenePtr gpuScene = make(WorldKind::Gpu, e.config());
        Outcome gpu = run(*gpuScene, c);
        const Report* r = gpuScene->report();
        const bool clearStatus = r->gpuPath || !r->cpuPathReason.empty() || !r->issues.empty();
        if (!gpu.finite && gpu.issues > 0) {
            gpu.pass = clearStatus;
            gpu.why = clearStatus ? "" : "no status; ";
        } else if (!clearStatus) {
            gpu.pass = false;
            gpu.why += "no status; ";
        }
        std::string gpuFigure = figure(gpu);
        if (!r->gpuPath && !r->cpuPathReason.empty()) gpuFigure += " (cpu path: " + r->cpuPathReason + ")";
        recordAs(caseName, e.label, gpu, gpuFigure);
        // Beyond reason btgpu is judged on its own: no NaN without an issue, no crash, a status.
        EXPECT_TRUE(gpu.pass) << caseName << " (" << e.label << "): " << gpu.why;
    }
}

}  // namespace

TEST(DeepOverlap, PyramidOfFourSeparates)
{
    // Neighbours overlap by 25 % of the box size (pitch 0.75). Judged on speed (< 5 m/s), and
    // on being separated after 3 s (penetration <= 1 cm over the last second).
    Criteria c;
    c.seconds = 3;
    c.speed = tol::kSeparationSpeed;
    c.penetration = tol::kPenetrationFraction;
    c.measureFrom = 2;
    runEngines("deep overlap 25 %, pyramid 4", [](WorldKind k, const Config& cf) { return st::pyramid(k, cf, 4, .75); },
            c);
}

TEST(FastSmall, SphereAgainstThinWall)
{
    // A sphere of radius 0.05 at 50 m/s moves 0.83 m per 1/60 s step, four times the wall's
    // thickness: without continuous collision it tunnels. Recorded on both; btgpu fails only
    // where stock stops it and btgpu does not.
    Criteria c;
    c.seconds = 0.5;
    Outcome out[3];
    for (int k = 0; k < 3; ++k) {
        const WorldKind kind = k == 0 ? WorldKind::Stock : WorldKind::Gpu;
        ScenePtr scene = st::bulletVsWall(kind, k == 0 ? Config::bulletMode() : kGpuRuns[k - 1].config());
        Outcome o = run(*scene, c);
        const double x = scene->body(1)->getWorldTransform().getOrigin().x();
        const bool tunnelled = x > 0.1;
        if (tunnelled) {
            o.pass = false;
            o.why += "tunnelled; ";
        }
        char f[160];
        std::snprintf(f, sizeof f, "%s, sphere ends at x = %.3g m, vmax %.3g m/s%s", tunnelled ? "tunnelled" : "stopped",
                      x, o.maxSpeed, kind == WorldKind::Gpu ? (o.gpuPath ? ", gpu path" : ", CPU fallback") : "");
        recordAs("sphere r 0.05 at 50 m/s vs wall 0.2", k == 0 ? "stock" : kGpuRuns[k - 1].label, o, f);
        out[k] = o;
    }
    for (int k = 1; k < 3; ++k) {
        if (out[0].pass) EXPECT_TRUE(out[k].pass) << "stock stops the sphere, " << kGpuRuns[k - 1].label << " lets it through";
        EXPECT_TRUE(out[k].gpuPath) << kGpuRuns[k - 1].label;
    }
}

TEST(Scale, CentimetreBoxes)
{
    Criteria c;
    c.seconds = 3;
    c.settleBy = 2;
    c.penetration = tol::kPenetrationFraction * 0.01;
    c.driftBody = 3;
    c.drift = tol::kTopDriftFraction * 0.01;
    c.drop = 3 * c.penetration;
    runEngines("3 boxes of 0.01 m resting", [](WorldKind k, const Config& cf) { return st::scaledStack(k, cf, btScalar(.01)); },
            c);
}

TEST(Scale, HundredMetreBoxes)
{
    Criteria c;
    c.seconds = 4;
    c.settleBy = 3;
    c.penetration = tol::kPenetrationFraction * 100;
    c.driftBody = 3;
    c.drift = tol::kTopDriftFraction * 100;
    c.drop = 3 * c.penetration;
    runEngines("3 boxes of 100 m resting", [](WorldKind k, const Config& cf) { return st::scaledStack(k, cf, 100); }, c);
}

TEST(FarFromOrigin, PileAt1e4BehavesAsAtOrigin)
{
    Criteria c;
    c.seconds = 3;
    c.settleBy = 2;
    c.penetration = tol::kPenetrationFraction;
    c.driftBody = 5;
    c.drift = tol::kTopDriftFraction;
    const btVector3 far(1e4, 0, 1e4);
    Outcome out[3];
    for (int k = 0; k < 3; ++k) {
        const WorldKind kind = k == 0 ? WorldKind::Stock : WorldKind::Gpu;
        const Config config = k == 0 ? Config::bulletMode() : kGpuRuns[k - 1].config();
        ScenePtr home = st::smallPile(kind, config, btVector3(0, 0, 0));
        ScenePtr away = st::smallPile(kind, config, far);
        run(*home, c);
        Outcome o = run(*away, c);
        double worst = 0;
        for (int i = 1; i <= 5; ++i) {
            const btVector3 a = away->body(i)->getWorldTransform().getOrigin();
            const btVector3 h = home->body(i)->getWorldTransform().getOrigin();
            const double dx = double(a.x()) - 1e4 - h.x(), dy = double(a.y()) - h.y(), dz = double(a.z()) - 1e4 - h.z();
            worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz));
        }
        if (o.finite && worst > tol::kFarPileAlike) {
            o.pass = false;
            o.why += "differs from the pile at the origin by " + std::to_string(worst) + " m; ";
        }
        char f[64];
        std::snprintf(f, sizeof f, "; vs origin %.3g mm", worst * 1000);
        recordAs("small pile at (1e4, 0, 1e4)", k == 0 ? "stock" : kGpuRuns[k - 1].label, o, figure(o) + f);
        out[k] = o;
    }
    for (int k = 1; k < 3; ++k) {
        if (out[0].pass) EXPECT_TRUE(out[k].pass) << "stock passes, " << kGpuRuns[k - 1].label << " fails: " << out[k].why;
        EXPECT_TRUE(out[k].gpuPath) << kGpuRuns[k - 1].label;
    }
}

TEST(FarFromOrigin, PileAt1e5StaysCalm)
{
    // Float spacing at 1e5 is ~8 mm: only calm is asked (finite, bounded, settled).
    Criteria c;
    c.seconds = 3;
    c.settleBy = 2;
    runEngines("small pile at (1e5, 0, 1e5)",
            [](WorldKind k, const Config& cf) { return st::smallPile(k, cf, btVector3(1e5, 0, 1e5)); }, c);
}

TEST(BeyondReason, MassRatioMillion)
{
    beyondReason("mass ratio 1e6:1", [](WorldKind k, const Config& c) { return st::massRatio(k, c, 1e6); }, 3);
}

TEST(BeyondReason, Velocity1e4)
{
    beyondReason("box at 1e4 m/s into ground", [](WorldKind k, const Config& c) { return st::fastDrop(k, c, 1e4); }, 1);
}

TEST(BeyondReason, ManyBodiesInOneSpot)
{
    // Every pair overlaps completely: n (n - 1) / 2 pairs, one step. Short mode (CI): 600 bodies
    // (1.8e5 pairs); 2,000 (2e6 pairs, run here: both finite, btgpu redoes the step once after
    // its buffers grow) cost stock ~30 s and btgpu ~40 s on 2 PoCL cores. Full mode: 1e5 bodies
    // (5e9 pairs) on btgpu only — stock Bullet cannot hold that many manifolds in memory.
    const int count = fullMode() ? 100000 : 600;
    beyondReason(std::to_string(count) + " bodies in one spot",
                 [count](WorldKind k, const Config& c) { return st::onePlace(k, c, count); }, 1.0 / 60, false,
                 !fullMode());
}
