// solver_features_test.cpp — btContactSolverInfo settings and body materials beyond the defaults
// that the GPU path serves as btSequentialImpulseConstraintSolver does: each scene run on stock
// and on btgpu in the same test, the btgpu world on the GPU path on every step (scenes in
// tests/scenes/solver_feature_scenes.h).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "scenes/solver_feature_scenes.h"
#include "scenes/stock_chaos.h"
#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;
namespace features = btgpu::scenes::features;

namespace {

// A builder that applies `change` to each world it makes (a btContactSolverInfo setting).
SceneBuilder with(const SceneBuilder& make, const std::function<void(Scene&)>& change)
{
    return [make, change](WorldKind kind, const Config& config) {
        ScenePtr scene = make(kind, config);
        change(*scene);
        return scene;
    };
}
std::function<void(Scene&)> solverMode(int bits)
{
    return [bits](Scene& s) { s.world().getSolverInfo().m_solverMode |= bits; };
}

// Steps both worlds `steps` times, asserting the GPU path after every step.
void stepOnGpu(SideBySide& s, int steps)
{
    for (int i = 0; i < steps; ++i) {
        s.step();
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
    }
}

bool sameTransforms(const Scene& a, const Scene& b)
{
    for (size_t i = 0; i < a.bodies().size(); ++i) {
        const btTransform& x = a.body(int(i))->getWorldTransform();
        const btTransform& y = b.body(int(i))->getWorldTransform();
        if (!(x.getOrigin() == y.getOrigin()) || !(x.getBasis() == y.getBasis())) return false;
    }
    return true;
}

btVector3 travel(const Scene& s, int body, const btVector3& start)
{
    return s.body(body)->getWorldTransform().getOrigin() - start;
}

}  // namespace

// SOLVER_ENABLE_FRICTION_DIRECTION_CACHING (BenchmarkDemo sets it) is served by following
// stock's own result: in 3.24 it changes nothing without anisotropic friction
// (cpu_path_rules.cpp says why). Stock with and without the bit, step for step bit for bit, on
// a pile: in the default mode and in the one mode where convertContact caches directions
// (two directions, velocity-independent).
TEST(SolverFeatures, FrictionDirectionCachingIsStockNoOp)
{
    for (int mode : {0, SOLVER_USE_2_FRICTION_DIRECTIONS | SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION}) {
        SCOPED_TRACE(mode);
        ScenePtr plain = features::boxPile(WorldKind::Stock, Config(), 4);
        ScenePtr cached = features::boxPile(WorldKind::Stock, Config(), 4);
        solverMode(mode)(*plain);
        solverMode(mode | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING)(*cached);
        for (int i = 0; i < 240; ++i) {
            plain->step();
            cached->step();
            ASSERT_TRUE(sameTransforms(*plain, *cached)) << "step " << i;
        }
    }
}

// The same pile with the bit on both worlds: btgpu stays on the GPU path and within stock's
// chaos (mean height, spread, kinetic energy after 3 s).
TEST(SolverFeatures, FrictionDirectionCachingPileLikeStock)
{
    const int steps = 180;
    auto make = with([](WorldKind k, const Config& c) { return features::boxPile(k, c, 4); },
                     solverMode(SOLVER_ENABLE_FRICTION_DIRECTION_CACHING));
    auto measure = [](const Scene& s) {
        scenes::Aggregates a = scenes::aggregates(s);
        return std::vector<double>{a.meanHeight, a.spread, a.kineticEnergy};
    };
    const std::vector<std::string> names = {"mean height", "spread", "kinetic energy"};
    std::vector<scenes::ChaosBand> bands = scenes::stockChaos(
        [&](WorldKind k) { return make(k, Config()); }, steps, measure, names,
        {tol::kChaosHeightFloor, tol::kChaosSpreadFloor, tol::kChaosEnergyFloor});
    SideBySide s(make);
    stepOnGpu(s, steps);
    std::vector<double> v = measure(*s.gpu);
    for (size_t k = 0; k < bands.size(); ++k)
        EXPECT_TRUE(bands[k].admits(v[k])) << bands[k].name << ": btgpu " << v[k] << ", stock " << bands[k].stockMean
                                           << " +- " << bands[k].bound();
}

// SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION: friction along btPlaneSpace1's axes
// whatever the slip. With one direction that is world x for the ground's normal: a box
// sliding diagonally stops along x and keeps going along z (with the default it stops along
// both). With two directions it stops along both, by other paths. Travel within 5% of stock's.
TEST(SolverFeatures, VelocityIndependentFrictionSlidesAsStock)
{
    for (int mode : {int(SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION),
                     SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION | SOLVER_USE_2_FRICTION_DIRECTIONS}) {
        SCOPED_TRACE(mode);
        SideBySide s(with(features::slidingBox, solverMode(mode)));
        const btVector3 start = s.stock->body(1)->getWorldTransform().getOrigin();
        stepOnGpu(s, 90);
        const btVector3 stock = travel(*s.stock, 1, start), gpu = travel(*s.gpu, 1, start);
        EXPECT_LT((gpu - stock).length(), tol::kRollDistanceRel * stock.length())
            << "stock (" << stock.x() << ", " << stock.z() << "), btgpu (" << gpu.x() << ", " << gpu.z() << ")";
        if (!(mode & SOLVER_USE_2_FRICTION_DIRECTIONS)) {
            // the mode's own signature: x stopped early, z slid on
            EXPECT_GT(stock.z(), 1.2 * stock.x());
        }
    }
}
