// solver_features_test.cpp — btContactSolverInfo settings and body materials beyond the defaults
// that the GPU path serves as btSequentialImpulseConstraintSolver does: each scene run on stock
// and on btgpu in the same test, the btgpu world on the GPU path on every step (scenes in
// tests/scenes/solver_feature_scenes.h).
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "scenes/solver_feature_scenes.h"
#include "scenes/stability_scenes.h"
#include "scenes/stock_chaos.h"
#include "feature_builders.h"
#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;
namespace features = btgpu::scenes::features;

namespace {


// A stock world and a soft-step one side by side, `steps` steps, the GPU path asserted after
// every step.
void stepBesideStock(Scene& stock, Scene& soft, int steps)
{
    for (int i = 0; i < steps; ++i) {
        stock.step();
        soft.step();
        ASSERT_TRUE(soft.report()->gpuPath) << "step " << i << ": " << soft.report()->cpuPathReason;
    }
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


// The aggregates a pile is judged by against stock's chaos, stock's band of each over `steps`
// steps of `make`'s scene, and the check of btgpu's against them.
std::vector<double> pileAggregates(const Scene& s)
{
    scenes::Aggregates a = scenes::aggregates(s);
    return std::vector<double>{a.meanHeight, a.spread, a.kineticEnergy};
}
std::vector<scenes::ChaosBand> pileBands(const SceneBuilder& make, int steps)
{
    return scenes::stockChaos([&](WorldKind k) { return make(k, Config::bulletMode()); }, steps, pileAggregates,
                              {"mean height", "spread", "kinetic energy"},
                              {tol::kChaosHeightFloor, tol::kChaosSpreadFloor, tol::kChaosEnergyFloor});
}
void expectWithinBands(const std::vector<scenes::ChaosBand>& bands, const Scene& gpu)
{
    const std::vector<double> v = pileAggregates(gpu);
    for (size_t k = 0; k < bands.size(); ++k)
        EXPECT_TRUE(bands[k].admits(v[k])) << bands[k].name << ": btgpu " << v[k] << ", stock " << bands[k].stockMean
                                           << " +- " << bands[k].bound();
}

// A 4 x 4 x 4 box pile with m_solverMode bits `bits` on both worlds, 3 s: btgpu on the GPU
// path every step and within stock's chaos (mean height, spread, kinetic energy).
void expectPileWithinStocksChaos(int bits)
{
    const int steps = 180;
    auto make = with([](WorldKind k, const Config& c) { return features::boxPile(k, c, 4); }, solverMode(bits));
    const std::vector<scenes::ChaosBand> bands = pileBands(make, steps);
    SideBySide s(make);
    stepOnGpu(s, steps);
    expectWithinBands(bands, *s.gpu);
}

// The sliding box with m_solverMode bits `mode` on both worlds, 1.5 s on the GPU path: its
// travel within 5% of stock's; returns stock's.
btVector3 expectSlideAsStock(int mode)
{
    SideBySide s(with(features::slidingBox, solverMode(mode)));
    const btVector3 start = s.stock->body(1)->getWorldTransform().getOrigin();
    stepOnGpu(s, 90);
    const btVector3 stock = travel(*s.stock, 1, start), gpu = travel(*s.gpu, 1, start);
    EXPECT_LT((gpu - stock).length(), tol::kRollDistanceRel * stock.length())
        << "stock (" << stock.x() << ", " << stock.z() << "), btgpu (" << gpu.x() << ", " << gpu.z() << ")";
    return stock;
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
        ScenePtr plain = features::boxPile(WorldKind::Stock, Config::bulletMode(), 4);
        ScenePtr cached = features::boxPile(WorldKind::Stock, Config::bulletMode(), 4);
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
    expectPileWithinStocksChaos(SOLVER_ENABLE_FRICTION_DIRECTION_CACHING);
}

// SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS: each velocity iteration one sweep, each
// point's friction rows right after its normal row (device against reference: unit
// SolveConstraints.InterleavedMatchesReferenceAndDiffers). With the bit on both worlds, on the
// GPU path every step: the box pile within stock's chaos (mean height, spread, kinetic energy
// after 3 s), and the sliding box's travel within 5% of stock's, with one and two friction
// directions.
TEST(SolverFeatures, InterleavedFrictionAsStock)
{
    expectPileWithinStocksChaos(SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS);
    for (int mode : {int(SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS),
                     SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS | SOLVER_USE_2_FRICTION_DIRECTIONS}) {
        SCOPED_TRACE(mode);
        expectSlideAsStock(mode);
    }
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
        const btVector3 stock = expectSlideAsStock(mode);
        if (!(mode & SOLVER_USE_2_FRICTION_DIRECTIONS)) {
            // the mode's own signature: x stopped early, z slid on
            EXPECT_GT(stock.z(), 1.2 * stock.x());
        }
    }
}

// The default (soft step) bounds each point's friction by a cone, not by its two tangents apart:
// sliding_box's box (friction 0.3 x 0.3), sent along the ground at 2.83 m/s along x, along the
// diagonal and between, slides to a stop as far as stock's in the throw's direction (within 5%;
// the analytic answer 8 / (2 x 0.09 x 10) = 4.44 m) and stays on its line (within 1 cm). Each
// tangent clamped on its own gave the diagonal sqrt 2 times the friction (3.1 m) and bent the
// slide toward the nearer axis (README, solver modes).
TEST(SolverFeatures, SoftStepFrictionIsACone)
{
    for (const double angle : {0.0, 0.5, M_PI / 4}) {
        SCOPED_TRACE(testing::Message() << "angle " << angle);
        const btVector3 dir(btScalar(std::cos(angle)), 0, btScalar(std::sin(angle)));
        ScenePtr stock = features::slidingBox(WorldKind::Stock, Config{});
        ScenePtr soft = features::slidingBox(WorldKind::Gpu, Config{});
        for (Scene* s : {stock.get(), soft.get()}) s->body(1)->setLinearVelocity(dir * btScalar(2 * std::sqrt(2.0)));
        const btVector3 start = stock->body(1)->getWorldTransform().getOrigin();
        stepBesideStock(*stock, *soft, 240);
        const btVector3 a = travel(*stock, 1, start), b = travel(*soft, 1, start);
        std::printf("sliding at %.2f rad: stock %.4f m along, %.4f across; default %.4f along, %.4f across\n", angle,
                    a.dot(dir), (a - dir * a.dot(dir)).length(), b.dot(dir), (b - dir * b.dot(dir)).length());
        EXPECT_NEAR(b.dot(dir), a.dot(dir), tol::kRollDistanceRel * a.dot(dir));
        EXPECT_LT((b - dir * b.dot(dir)).length(), 0.01);
    }
}

// ... and a box sliding down a slope whose fall line lies across the tangents (0.4 rad, turned
// 0.5 rad about the vertical; friction 0.5 x 0.5) slides as the physics has it, g (sin 0.4 -
// 0.25 cos 0.4) = 1.591 m/s^2: 0.796 m in 1 s, within 2% and within 1 degree of the fall line.
// On the rows' own masses the cone's step did not point against the slip: 4% fast, 3 degrees off;
// clamped each on its own, 0.59 m at 10 degrees off.
TEST(SolverFeatures, SoftStepSlidesDownTheFallLine)
{
    Scene s(WorldKind::Gpu, Config{}, "slope_across");
    const btQuaternion q = btQuaternion(btVector3(0, 1, 0), btScalar(0.5)) * btQuaternion(btVector3(0, 0, 1), btScalar(0.4));
    s.addBody(s.boxShape(btVector3(20, btScalar(0.5), 20)), 0, btTransform(q, btVector3(0, 0, 0)));
    const btVector3 up = quatRotate(q, btVector3(0, 1, 0));
    btRigidBody* box = s.addBody(s.boxShape(btVector3(btScalar(.25), btScalar(.25), btScalar(.25))), 1,
                                 btTransform(q, up * btScalar(0.75)));
    box->setActivationState(DISABLE_DEACTIVATION);
    const btVector3 start = box->getWorldTransform().getOrigin();
    for (int i = 0; i < 60; ++i) {
        s.step();
        ASSERT_TRUE(s.gpuWorld()->isGpuPath()) << "step " << i;
    }
    const btVector3 fall = (btVector3(0, -1, 0) - up * up.dot(btVector3(0, -1, 0))).normalized();
    const btVector3 d = box->getWorldTransform().getOrigin() - start;
    const double expected = 0.5 * 10 * (std::sin(0.4) - 0.25 * std::cos(0.4));
    std::printf("box down a slope across the tangents: %.4f m in 1 s (the physics %.4f), %.2f degrees off the fall line\n",
                d.length(), expected, double(d.angle(fall)) * 180 / M_PI);
    EXPECT_NEAR(d.length(), expected, 0.02 * expected);
    EXPECT_LT(d.angle(fall), btScalar(M_PI / 180));
}

// ... and a box spinning flat on the ground (0.5 m, 5 rad/s about the vertical, friction 0.5 x
// 0.5) spins down as its four corners' friction has it: torque 0.25 m g |r| with |r| = 0.354 m on
// I = m / 24, 21.2 rad/s^2, so it turns 25 / 42.4 = 0.59 rad in 0.24 s (within 5%; stock turns
// 0.55 in as many steps). Each corner slips across both tangents: clamped each on its own they
// stopped it at 0.42 rad.
TEST(SolverFeatures, SoftStepSpinsABoxDownAsItsCorners)
{
    Scene s(WorldKind::Gpu, Config{}, "spinning_box");
    s.addBody(s.boxShape(btVector3(50, 1, 50)), 0, btVector3(0, -1, 0));
    btRigidBody* box = s.addBody(s.boxShape(btVector3(btScalar(.25), btScalar(.25), btScalar(.25))), 1,
                                 btVector3(0, btScalar(.25), 0));
    box->setAngularVelocity(btVector3(0, 5, 0));
    int stopped = -1;
    for (int i = 0; i < 60 && stopped < 0; ++i) {
        s.step();
        ASSERT_TRUE(s.gpuWorld()->isGpuPath()) << "step " << i;
        if (box->getAngularVelocity().length() < 0.01) stopped = i;
    }
    const double turned = box->getWorldTransform().getRotation().getAngle();
    const double r = 0.25 * std::sqrt(2.0), alpha = 0.25 * 10 * r / ((0.5 * 0.5 + 0.5 * 0.5) / 12);
    std::printf("box spinning down: turned %.4f rad by step %d (the physics %.4f rad in %.3f s)\n", turned, stopped,
                25 / (2 * alpha), 5 / alpha);
    EXPECT_GT(stopped, 0);
    EXPECT_NEAR(turned, 25 / (2 * alpha), 0.05 * 25 / (2 * alpha));
}

namespace {

// The depth body 1 (a unit box) rests at after `steps` steps: 0.5 m less its centre's height.
double restDepth(const Scene& s) { return 0.5 - s.body(1)->getWorldTransform().getOrigin().y(); }

}  // namespace

// Soft contacts (setContactStiffnessAndDamping: CF_HAS_CONTACT_STIFFNESS_DAMPING): the pair's
// points take erp = dt k / (dt k + d) and cfm = 1 / (dt k + d) (setupContactConstraint), so a
// box settles into the ground; the depth it rests at within 5% of stock's, for two stiffnesses
// (about 5 and 2.5 mm; a hard contact rests at well under 1 mm).
TEST(SolverFeatures, SoftContactRestsAtStockDepth)
{
    for (btScalar k : {btScalar(500), btScalar(1000)}) {
        SCOPED_TRACE(k);
        SideBySide s([k](WorldKind kind, const Config& c) { return features::softBox(kind, c, k); });
        stepOnGpu(s, 120);
        const double stock = restDepth(*s.stock), gpu = restDepth(*s.gpu);
        RecordProperty(std::string("stock_depth_") + std::to_string(int(k)), std::to_string(stock));
        RecordProperty(std::string("btgpu_depth_") + std::to_string(int(k)), std::to_string(gpu));
        EXPECT_GT(stock, 0.002);  // soft: a hard contact rests at well under this
        EXPECT_NEAR(gpu, stock, tol::kSoftDepthRel * stock);
    }
}

// The soft step serves them as its own spring of the pair's stiffness k and damping c
// (soft_rows.h): the same box rests where its load is k times its depth, at stock's depth
// within 5% as the bullet mode does; and deeper for the softer spring (about twice).
TEST(SolverFeatures, SoftStepContactSpringRestsAtStockDepth)
{
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    std::vector<double> depths;
    for (btScalar k : {btScalar(500), btScalar(1000)}) {
        SCOPED_TRACE(k);
        auto make = [k](WorldKind kind, const Config& c) { return features::softBox(kind, c, k); };
        ScenePtr stock = make(WorldKind::Stock, Config::bulletMode()), gpu = make(WorldKind::Gpu, soft);
        stepBesideStock(*stock, *gpu, 120);
        const double stockDepth = restDepth(*stock), gpuDepth = restDepth(*gpu);
        RecordProperty(std::string("soft_step_depth_") + std::to_string(int(k)), std::to_string(gpuDepth));
        EXPECT_GT(stockDepth, 0.002);
        EXPECT_NEAR(gpuDepth, stockDepth, tol::kSoftDepthRel * stockDepth);
        depths.push_back(gpuDepth);
    }
    EXPECT_NEAR(depths[0], 2 * depths[1], 0.1 * depths[0]);
}

// m_globalCfm on the contacts: a resting box sinks to where the cfm's give balances its weight,
// at stock's depth within 5%.
TEST(SolverFeatures, GlobalCfmRestsAtStockDepth)
{
    SideBySide s(with([](WorldKind k, const Config& c) { return scenes::restingBox(k, c); },
                      [](Scene& sc) { sc.world().getSolverInfo().m_globalCfm = btScalar(0.05); }));
    stepOnGpu(s, 120);
    const double stock = restDepth(*s.stock), gpu = restDepth(*s.gpu);
    RecordProperty("stock_depth", std::to_string(stock));
    RecordProperty("btgpu_depth", std::to_string(gpu));
    EXPECT_GT(stock, 0.002);
    EXPECT_NEAR(gpu, stock, tol::kSoftDepthRel * stock);
}

// The soft step serves m_globalCfm as the contacts' spring of the same give (btgSoftCfmSpring:
// k = m_erp2 / (dt cfm), d = (1 - m_erp2) / cfm): the resting box at stock's depth within 5%
// after 5 s (its relax takes out the spring's ringing: it creeps to the depth with a time
// constant of about 0.6 s here, 3% short at 2 s, where stock's has settled).
TEST(SolverFeatures, SoftStepGlobalCfmRestsAtStockDepth)
{
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    auto make = with([](WorldKind k, const Config& c) { return scenes::restingBox(k, c); },
                     [](Scene& sc) { sc.world().getSolverInfo().m_globalCfm = btScalar(0.05); });
    ScenePtr stock = make(WorldKind::Stock, Config::bulletMode()), gpu = make(WorldKind::Gpu, soft);
    stepBesideStock(*stock, *gpu, 300);
    const double stockDepth = restDepth(*stock), gpuDepth = restDepth(*gpu);
    RecordProperty("soft_step_depth", std::to_string(gpuDepth));
    EXPECT_GT(stockDepth, 0.002);
    EXPECT_NEAR(gpuDepth, stockDepth, tol::kSoftDepthRel * stockDepth) << "stock " << stockDepth;
}

// m_sor (setupContactConstraint's relaxation, on the normal and friction rows): three boxes
// dropped from 3 m, under-relaxed (0.3) with 4 iterations, sink deeper on landing and recover
// as stock's do, where stock's own default run differs by 3 cm. Without warm starting every
// box's height is within 1 mm of stock's on every step (1 um here). With it, within 5 mm (4
// here): so under-relaxed, the warm start carries much of each step's impulse, and which old
// point warm-starts which new one during the landing (stock's persistent manifold against the
// GPU path's matching) shows; the same scene at m_sor 1 stays within 0.03 mm. (A stack is no
// yardstick: with so few iterations, so under-relaxed, its result follows the order rows are
// solved in, which the batched solver does not share with stock's sequential one.)
TEST(SolverFeatures, SorLandingAsStock)
{
    for (bool warm : {false, true}) {
        SCOPED_TRACE(warm ? "warm start" : "no warm start");
        auto sor = [warm](Scene& sc) {
            sc.world().getSolverInfo().m_sor = btScalar(0.3);
            sc.world().getSolverInfo().m_numIterations = 4;
            if (!warm) sc.world().getSolverInfo().m_solverMode &= ~SOLVER_USE_WARMSTARTING;
        };
        SideBySide s(with([](WorldKind k, const Config& c) { return scenes::dropRow(k, c); }, sor));
        ScenePtr plain = scenes::dropRow(WorldKind::Stock, Config::bulletMode());
        plain->world().getSolverInfo().m_numIterations = 4;
        double apart = 0, worst = 0;
        for (int i = 0; i < 90; ++i) {
            s.step();
            plain->step();
            ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
            for (int b = 1; b <= 3; ++b) {
                worst = std::max(worst, std::fabs(s.gpuY(b) - s.stockY(b)));
                apart = std::max(apart, std::fabs(s.stockY(b) - plain->body(b)->getWorldTransform().getOrigin().y()));
            }
        }
        RecordProperty(std::string(warm ? "warm_" : "cold_") + "btgpu_vs_stock_max", std::to_string(worst));
        RecordProperty(std::string(warm ? "warm_" : "cold_") + "stock_sor_vs_default_max", std::to_string(apart));
        EXPECT_LT(worst, warm ? 5e-3 : 1e-3);
        EXPECT_GT(apart, 0.02);  // the setting matters here
    }
}

// Anisotropic friction (setAnisotropicFriction, CF_ANISOTROPIC_FRICTION): a box turned 30
// degrees about y with friction scaled to 0.1 along its own z axis, sliding diagonally, slides
// further along that axis than across it, as on stock: its travel within 5% of stock's, with
// one and with two friction directions; and the isotropic box's travel is well apart.
TEST(SolverFeatures, AnisotropicFrictionSlidesAsStock)
{
    for (int mode : {0, int(SOLVER_USE_2_FRICTION_DIRECTIONS)}) {
        SCOPED_TRACE(mode);
        SideBySide s(with(features::anisotropicBox, solverMode(mode)));
        ScenePtr plain = features::anisotropicBox(WorldKind::Stock, Config::bulletMode());
        solverMode(mode)(*plain);
        plain->body(1)->setAnisotropicFriction(btVector3(1, 1, 1));
        const btVector3 start = s.stock->body(1)->getWorldTransform().getOrigin();
        stepOnGpu(s, 90);
        for (int i = 0; i < 90; ++i) plain->step();
        const btVector3 stock = travel(*s.stock, 1, start), gpu = travel(*s.gpu, 1, start),
                        iso = travel(*plain, 1, start);
        RecordProperty(std::string("mode") + std::to_string(mode) + "_stock", std::to_string(stock.length()));
        RecordProperty(std::string("mode") + std::to_string(mode) + "_btgpu", std::to_string(gpu.length()));
        RecordProperty(std::string("mode") + std::to_string(mode) + "_isotropic", std::to_string(iso.length()));
        EXPECT_LT((gpu - stock).length(), tol::kRollDistanceRel * stock.length())
            << "stock (" << stock.x() << ", " << stock.z() << "), btgpu (" << gpu.x() << ", " << gpu.z() << ")";
        EXPECT_GT((stock - iso).length(), 0.2 * stock.length());  // the setting matters here
        // further along the box's low-friction axis (its z, turned 30 degrees) than across it
        const btVector3 lowAxis = s.stock->body(1)->getWorldTransform().getBasis().getColumn(2);
        const btVector3 highAxis = s.stock->body(1)->getWorldTransform().getBasis().getColumn(0);
        EXPECT_GT(std::fabs(stock.dot(lowAxis)), std::fabs(stock.dot(highAxis)));
    }
}

// Anisotropic friction on both bodies of a pair: convertContact scales by body 0's anisotropy,
// then body 1's, body 0 being the one of the lower proxy id. The ground is removed and added
// back first, so the world's object order (the GPU path's rows: slider, slab, ground) is not
// the proxy order (slab, slider, ground): the device must take Bullet's. The box slides as far
// as stock's (within 5%), and the slab's anisotropy matters (without it stock's box goes
// elsewhere).
TEST(SolverFeatures, AnisotropicFrictionOnBothBodiesAsStock)
{
    for (int mode : {0, int(SOLVER_USE_2_FRICTION_DIRECTIONS)}) {
        SCOPED_TRACE(mode);
        auto reorder = [](Scene& s) {
            s.world().removeRigidBody(s.body(0));
            s.world().addRigidBody(s.body(0));
        };
        SideBySide s(with(features::anisotropicPair, solverMode(mode)));
        s.both(reorder);
        ASSERT_EQ(s.gpu->world().getCollisionObjectArray()[0], s.gpu->body(2));  // the rows' order is not the proxies'
        ScenePtr plain = features::anisotropicPair(WorldKind::Stock, Config::bulletMode());
        solverMode(mode)(*plain);
        reorder(*plain);
        plain->body(1)->setAnisotropicFriction(btVector3(1, 1, 1), btCollisionObject::CF_ANISOTROPIC_FRICTION_DISABLED);
        const btVector3 start = s.stock->body(2)->getWorldTransform().getOrigin();
        stepOnGpu(s, 60);
        for (int i = 0; i < 60; ++i) plain->step();
        const btVector3 stock = travel(*s.stock, 2, start), gpu = travel(*s.gpu, 2, start),
                        one = travel(*plain, 2, start);
        std::printf("both anisotropic, mode %d: stock (%.4f, %.4f), btgpu (%.4f, %.4f), slab isotropic (%.4f, %.4f)\n",
                    mode, stock.x(), stock.z(), gpu.x(), gpu.z(), one.x(), one.z());
        EXPECT_LT((gpu - stock).length(), tol::kRollDistanceRel * stock.length());
        EXPECT_GT((stock - one).length(), 0.05 * stock.length());  // the slab's anisotropy matters
    }
}

namespace {
// Contact points the app sees in the dispatcher's manifolds, and how many of them lie farther
// apart than `threshold`.
struct SeenPoints {
    int points = 0;
    int beyond = 0;
};
SeenPoints seenPoints(Scene& s, btScalar threshold)
{
    SeenPoints seen;
    btDispatcher* d = s.world().getDispatcher();
    for (int m = 0; m < d->getNumManifolds(); ++m) {
        const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
        for (int k = 0; k < pm->getNumContacts(); ++k) {
            ++seen.points;
            seen.beyond += pm->getContactPoint(k).getDistance() > threshold;
        }
    }
    return seen;
}
double gap(const Scene& s) { return s.body(2)->getWorldTransform().getOrigin().y() - s.body(1)->getWorldTransform().getOrigin().y() - 1; }
}  // namespace

// setContactProcessingThreshold: convertContacts solves a manifold's points only while they are
// no farther apart than the smaller of its bodies' thresholds. A sphere dropped 5 cm onto a box
// with a 1 mm threshold: the point it finds on the way down (up to the breaking threshold apart,
// which would slow it before it touches) is not solved, it lands and rests as stock's, step for
// step within 1 mm; the unsolved points stay in the manifolds the app reads, as many as stock's.
// (Box pairs find penetrating points only: the box on box below.)
TEST(SolverFeatures, ProcessingThresholdLandsAsStock)
{
    const btScalar threshold = btScalar(0.001);
    SideBySide s(
        [&](WorldKind k, const Config& c) { return features::thresholdStack(k, c, threshold, btScalar(0.05), true); });
    ScenePtr plain = features::thresholdStack(WorldKind::Stock, Config::bulletMode(), btScalar(BT_LARGE_FLOAT), btScalar(0.05), true);
    int beyondSeen = 0;
    double apart = 0, plainApart = 0;
    for (int i = 0; i < 90; ++i) {
        s.step();
        plain->step();
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
        EXPECT_NEAR(s.gpuY(2), s.stockY(2), tol::kRestHeight) << "step " << i;
        apart = std::max(apart, std::fabs(s.gpuY(2) - s.stockY(2)));
        plainApart = std::max(plainApart, std::fabs(plain->body(2)->getWorldTransform().getOrigin().y() - s.stockY(2)));
        const SeenPoints gpu = seenPoints(*s.gpu, threshold), stock = seenPoints(*s.stock, threshold);
        EXPECT_EQ(gpu.points, stock.points) << "step " << i;
        beyondSeen += gpu.beyond;
    }
    EXPECT_GT(beyondSeen, 0);  // the scene did have unsolved points to keep
    // the threshold changes stock's landing by more than the bound the GPU path keeps
    EXPECT_GT(plainApart, tol::kRestHeight) << "btgpu within " << apart << " m";
    EXPECT_NEAR(gap(*s.gpu), gap(*s.stock), tol::kRestHeight);
}

// A threshold below zero leaves the box's points unsolved until they are that deep: the box sinks
// about 1 cm into the one below on stock (against under 1 mm without it), and as deep on the GPU
// path (within 1 mm after 2 s).
TEST(SolverFeatures, NegativeProcessingThresholdSinksAsStock)
{
    const btScalar threshold = btScalar(-0.01);
    SideBySide s([&](WorldKind k, const Config& c) { return features::thresholdStack(k, c, threshold); });
    ScenePtr plain = features::thresholdStack(WorldKind::Stock, Config::bulletMode(), btScalar(BT_LARGE_FLOAT));
    for (int i = 0; i < 120; ++i) {
        s.step();
        plain->step();
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
    }
    EXPECT_LT(gap(*s.stock), -0.005) << "stock's box sinks";
    EXPECT_GT(gap(*plain), -0.001) << "without the threshold it does not";
    EXPECT_NEAR(gap(*s.gpu), gap(*s.stock), tol::kRestHeight)
        << "stock " << gap(*s.stock) << ", without the threshold " << gap(*plain);
    EXPECT_EQ(seenPoints(*s.gpu, threshold).points, seenPoints(*s.stock, threshold).points);
}

// The soft step leaves the points beyond the threshold unsolved as well: with -1 cm the box rests
// as deep in the one below as stock's (without the threshold the soft step's box rests under 2 mm
// deep), on the GPU path every step, the app seeing as many points. Both boxes rattle about the
// threshold (their points solved only below it: stock's between 8 and 12.5 mm deep from step to
// step), so the depths compared are the means over the second second, within 1 mm.
TEST(SolverFeatures, SoftStepNegativeProcessingThresholdSinksAsStock)
{
    const btScalar threshold = btScalar(-0.01);
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    ScenePtr stock = features::thresholdStack(WorldKind::Stock, Config::bulletMode(), threshold);
    ScenePtr gpu = features::thresholdStack(WorldKind::Gpu, soft, threshold);
    ScenePtr plain = features::thresholdStack(WorldKind::Gpu, soft, btScalar(BT_LARGE_FLOAT));
    double stockMean = 0, gpuMean = 0, plainMean = 0;
    for (int i = 0; i < 120; ++i) {
        stock->step();
        gpu->step();
        plain->step();
        ASSERT_TRUE(gpu->report()->gpuPath) << "step " << i << ": " << gpu->report()->cpuPathReason;
        ASSERT_TRUE(plain->report()->gpuPath) << "step " << i << ": " << plain->report()->cpuPathReason;
        if (i < 60) continue;
        stockMean += gap(*stock) / 60;
        gpuMean += gap(*gpu) / 60;
        plainMean += gap(*plain) / 60;
    }
    EXPECT_LT(stockMean, -0.005) << "stock's box sinks";
    EXPECT_GT(plainMean, -0.002) << "without the threshold the soft step's does not";
    EXPECT_NEAR(gpuMean, stockMean, tol::kRestHeight) << "stock " << stockMean << ", without the threshold " << plainMean;
    EXPECT_EQ(seenPoints(*gpu, threshold).points, seenPoints(*stock, threshold).points);
}

// CF_HAS_FRICTION_ANCHOR: btManifoldResult flags the box's points, replaceContactPoint keeps an
// old point while its lateral impulse lies inside the friction cone (a sliding point's, clamped
// to the cone's edge, is inside: 3.24's eps is 0), and setupFrictionConstraint pulls each anchor
// back along the friction directions (m_frictionERP). A box at rest on a slab tilted just inside
// its friction cone (0.24 rad of 0.245) creeps 0.661 mm in 4 s with anchors on stock and on the
// GPU path alike (0.761 mm without). A box sliding at 1 m/s, on the flat slab and down one tilted
// 0.2 rad, keeps its anchors while it slides and stops 10.7 mm and 25.6 mm sooner on stock: the
// GPU path with anchors stops within 1 mm of stock's, and its anchors change its own slide by
// more than five times that.
TEST(SolverFeatures, FrictionAnchorsHoldAndSlideAsStock)
{
    for (auto [angle, speed] : std::vector<std::pair<btScalar, btScalar>>{{0.24f, 0.0f}, {0.0f, 1.0f}, {0.2f, 1.0f}}) {
        SCOPED_TRACE(testing::Message() << "angle " << angle << ", speed " << speed);
        SideBySide s([&](WorldKind k, const Config& c) { return features::anchorSlope(k, c, angle, true, speed); });
        ScenePtr plain = features::anchorSlope(WorldKind::Stock, Config::bulletMode(), angle, false, speed);
        ScenePtr plainGpu = features::anchorSlope(WorldKind::Gpu, Config::bulletMode(), angle, false, speed);
        const btVector3 start = s.stock->body(2)->getWorldTransform().getOrigin();
        for (int i = 0; i < 240; ++i) {
            s.step();
            plain->step();
            plainGpu->step();
            ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
            ASSERT_TRUE(plainGpu->gpuWorld()->isGpuPath());
        }
        const double stock = downhill(*s.stock, start, angle), gpu = downhill(*s.gpu, start, angle);
        const double without = downhill(*plain, start, angle), gpuWithout = downhill(*plainGpu, start, angle);
        if (speed == 0) {
            EXPECT_NEAR(gpu, stock, tol::kAnchorCreep) << "without anchors: stock " << without << ", btgpu " << gpuWithout;
            continue;
        }
        EXPECT_NEAR(gpu, stock, tol::kAnchorSlide) << "without anchors: stock " << without << ", btgpu " << gpuWithout;
        EXPECT_GT(std::fabs(without - stock), 5 * tol::kAnchorSlide) << "stock " << stock << ", without " << without;
        EXPECT_GT(std::fabs(gpuWithout - gpu), 5 * tol::kAnchorSlide) << "btgpu " << gpu << ", without " << gpuWithout;
    }
}

// SOLVER_RANDMIZE_ORDER: stock shuffles its row pools every iteration with its own btRandInt2
// stream; the batched solver permutes its own solve order (each sweep's colours, each contact's
// points) by a stream of its own at the same iterations. A pyramid of 10 (55 boxes) and a
// collapsing 4x4x4 pile with the bit on both: btgpu stays on the GPU path and within stock's own
// chaos with the bit (mean height, spread, kinetic energy after 3 s); the bit is not a no-op (the
// state differs from the same world's without it), and two worlds with it step bitwise alike.
TEST(SolverFeatures, RandomizedOrderPyramidAndPileLikeStock)
{
    const int steps = 180;
    const std::vector<std::pair<std::string, SceneBuilder>> scenesToRun = {
        {"pyramid", [](WorldKind k, const Config& c) { return scenes::stability::pyramid(k, c, 10); }},
        {"pile", [](WorldKind k, const Config& c) { return features::boxPile(k, c, 4); }}};
    for (const auto& [name, plainMake] : scenesToRun) {
        SCOPED_TRACE(name);
        auto make = with(plainMake, solverMode(SOLVER_RANDMIZE_ORDER));
        const std::vector<scenes::ChaosBand> bands = pileBands(make, steps);
        SideBySide s(make);
        ScenePtr twin = make(WorldKind::Gpu, Config::bulletMode());
        ScenePtr inOrder = plainMake(WorldKind::Gpu, Config::bulletMode());
        bool differs = false;
        for (int i = 0; i < steps; ++i) {
            s.step();
            twin->step();
            inOrder->step();
            ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
            ASSERT_EQ(s.gpu->gpuWorld()->stateHash(), twin->gpuWorld()->stateHash()) << "step " << i;
            differs = differs || s.gpu->gpuWorld()->stateHash() != inOrder->gpuWorld()->stateHash();
        }
        EXPECT_TRUE(differs) << "the bit changed nothing";
        expectWithinBands(bands, *s.gpu);
    }
}

// The soft step serves SOLVER_RANDMIZE_ORDER (each substep's solve and relax sweeps take their
// colours and points in an order of their own, from the world's order stream) and
// SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS (the relax's friction rows point by point
// after the normal row): a pyramid of base 10, 3 s, on the GPU path every step, step for step
// as a twin world, not as the plain soft step, and standing (no box 5 cm from its start).
TEST(SolverFeatures, SoftStepServesTheOrderBits)
{
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    for (int bits : {int(SOLVER_RANDMIZE_ORDER), int(SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS)}) {
        SCOPED_TRACE(bits);
        auto make = with([](WorldKind k, const Config& c) { return scenes::stability::pyramid(k, c, 10); },
                         solverMode(bits));
        ScenePtr gpu = make(WorldKind::Gpu, soft), twin = make(WorldKind::Gpu, soft);
        ScenePtr plain = scenes::stability::pyramid(WorldKind::Gpu, soft, 10);
        std::vector<btVector3> start;
        for (btRigidBody* b : gpu->bodies()) start.push_back(b->getWorldTransform().getOrigin());
        bool differs = false;
        for (int i = 0; i < 180; ++i) {
            gpu->step();
            twin->step();
            plain->step();
            ASSERT_TRUE(gpu->report()->gpuPath) << "step " << i << ": " << gpu->report()->cpuPathReason;
            ASSERT_EQ(gpu->gpuWorld()->stateHash(), twin->gpuWorld()->stateHash()) << "step " << i;
            differs = differs || gpu->gpuWorld()->stateHash() != plain->gpuWorld()->stateHash();
        }
        EXPECT_TRUE(differs) << "the bit changed nothing";
        double farthest = 0;
        for (size_t i = 0; i < start.size(); ++i)
            farthest = std::max(farthest, double((gpu->bodies()[i]->getWorldTransform().getOrigin() - start[i]).length()));
        EXPECT_LT(farthest, 0.05) << "a box left its place";
    }
}
