// soft_step_friction_test.cpp — friction in the soft step (SolverKind::SoftStep) against stock:
// anisotropic friction along Bullet's scaled directions, a box and a stack of two held on a
// slope, and the Bullet friction features it sends to the CPU path. Each soft world asserted on
// the GPU path (or off it, with its reason) at every step (scenes in
// tests/scenes/solver_feature_scenes.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "scenes/solver_feature_scenes.h"
#include "scenes/stability_scenes.h"
#include "feature_builders.h"

using namespace btgpu;
using namespace btgpu::test;
namespace features = btgpu::scenes::features;

// Anisotropic friction in the soft step: each point's friction rows run along the directions
// prepare_contacts scaled (as the bullet mode's), so the turned box of
// AnisotropicFrictionSlidesAsStock slides along its low-friction axis as on stock, and the box on
// the anisotropic slab of AnisotropicFrictionOnBothBodiesAsStock goes where stock's goes
// (tol::kSoftSlideDistanceRel of stock's travel, with one friction direction and with two); both
// stay on the GPU path in the soft step every step.
TEST(SolverFeatures, SoftStepAnisotropicFrictionAsStock)
{
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    const std::vector<std::pair<std::string, SceneBuilder>> scenes = {{"box", SceneBuilder(features::anisotropicBox)},
                                                                      {"pair", SceneBuilder(features::anisotropicPair)}};
    // one friction direction along the slip (Bullet's default: the soft step then solves that
    // row alone), and two
    for (int mode : {0, int(SOLVER_USE_2_FRICTION_DIRECTIONS)})
        for (const auto& [name, base] : scenes) {
            SCOPED_TRACE(name + " mode " + std::to_string(mode));
            const SceneBuilder make = with(base, solverMode(mode));
            ScenePtr stock = make(WorldKind::Stock, Config::bulletMode()), gpu = make(WorldKind::Gpu, soft);
            ScenePtr plain = make(WorldKind::Gpu, soft);
            const int moving = name == "box" ? 1 : 2;
            for (int b = 1; b <= moving; ++b)
                plain->body(b)->setAnisotropicFriction(btVector3(1, 1, 1), btCollisionObject::CF_ANISOTROPIC_FRICTION_DISABLED);
            const btVector3 start = stock->body(moving)->getWorldTransform().getOrigin();
            for (int i = 0; i < 90; ++i) {
                stock->step();
                gpu->step();
                plain->step();
                ASSERT_TRUE(gpu->report()->gpuPath) << "step " << i << ": " << gpu->report()->cpuPathReason;
                ASSERT_EQ(SolverKind::SoftStep, gpu->report()->solver);
            }
            const btVector3 s = travel(*stock, moving, start), g = travel(*gpu, moving, start),
                            iso = travel(*plain, moving, start);
            std::printf("soft step, anisotropic %s, mode %d: stock (%.4f, %.4f), soft step (%.4f, %.4f), isotropic soft "
                        "step (%.4f, %.4f)\n",
                        name.c_str(), mode, s.x(), s.z(), g.x(), g.z(), iso.x(), iso.z());
            RecordProperty(name + "_mode" + std::to_string(mode) + "_stock", std::to_string(s.length()));
            RecordProperty(name + "_mode" + std::to_string(mode) + "_soft_step", std::to_string(g.length()));
            EXPECT_LT((g - s).length(), tol::kSoftSlideDistanceRel * s.length());
            EXPECT_GT((g - iso).length(), 0.2 * s.length());  // the anisotropy matters in the soft step too
        }
}

// A box at rest on a slab tilted 0.1, 0.2 and 0.24 rad (the pair's friction 0.25: 0.24 rad is just
// inside its cone, 0.245) stays in the soft step as on stock: 4 s, its downhill travel within
// stock's plus tol::kSoftSlopeCreep, at rest at the end. The soft step warm-starts its friction
// across steps (BTG_SOLVER_WARM_FRICTION); started at zero each step as Bullet's are, each step's
// first substep let the box slide: 1.4, 3.3 and 17.5 mm in the 4 s (stock 0.01, 0.02, 0.77).
TEST(SolverFeatures, SoftStepHoldsABoxOnASlope)
{
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    for (btScalar angle : {btScalar(0.1), btScalar(0.2), btScalar(0.24)}) {
        SCOPED_TRACE(angle);
        ScenePtr stock = features::anchorSlope(WorldKind::Stock, Config::bulletMode(), angle, false, 0);
        ScenePtr gpu = features::anchorSlope(WorldKind::Gpu, soft, angle, false, 0);
        const btVector3 start = stock->body(2)->getWorldTransform().getOrigin();
        for (int i = 0; i < 240; ++i) {
            stock->step();
            gpu->step();
            ASSERT_TRUE(gpu->report()->gpuPath) << "step " << i << ": " << gpu->report()->cpuPathReason;
            ASSERT_EQ(SolverKind::SoftStep, gpu->report()->solver);
        }
        const double st = downhill(*stock, start, angle), g = downhill(*gpu, start, angle);
        RecordProperty("creep_mm_" + std::to_string(int(angle * 100)), std::to_string(1000 * g));
        EXPECT_LT(g, std::max(st, 0.0) + tol::kSoftSlopeCreep) << "stock " << st;
        EXPECT_LT(gpu->body(2)->getLinearVelocity().length(), 1e-3);
    }
}

// Two boxes stacked on that slope, 0.1 and 0.2 rad, 4 s: stock's slide (its friction along the
// slip, from zero each step: the top box 0.13 and 1.08 m); the soft step's creep, each box within
// tol::kSoftStackCreepOfStock of stock's travel. The friction between the two boxes starts at zero
// each step, so the top box still creeps (4.9 and 10.9 mm), far less than stock's.
TEST(SolverFeatures, SoftStepHoldsAStackOnASlope)
{
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    for (btScalar angle : {btScalar(0.1), btScalar(0.2)}) {
        SCOPED_TRACE(angle);
        ScenePtr stock = features::slopeStack(WorldKind::Stock, Config::bulletMode(), angle, 2);
        ScenePtr gpu = features::slopeStack(WorldKind::Gpu, soft, angle, 2);
        const btVector3 start[2] = {stock->body(2)->getWorldTransform().getOrigin(),
                                    stock->body(3)->getWorldTransform().getOrigin()};
        for (int i = 0; i < 240; ++i) {
            stock->step();
            gpu->step();
            ASSERT_TRUE(gpu->report()->gpuPath) << "step " << i << ": " << gpu->report()->cpuPathReason;
            ASSERT_EQ(SolverKind::SoftStep, gpu->report()->solver);
        }
        for (int k = 0; k < 2; ++k) {
            const double st = downhill(*stock, start[k], angle, 2 + k), g = downhill(*gpu, start[k], angle, 2 + k);
            RecordProperty("creep_mm_" + std::to_string(int(angle * 100)) + "_box" + std::to_string(k),
                           std::to_string(1000 * g));
            EXPECT_GT(st, 0.02) << "box " << k << ": stock's slides";
            EXPECT_LT(std::abs(g), tol::kSoftStackCreepOfStock * st) << "box " << k << ": stock " << st;
        }
    }
}

// The soft step builds none of the rows these Bullet features add to the bullet mode: with
// Config::solver = SoftStep each sends the world to the CPU path naming it (and back when unset).
TEST(SolverFeatures, SoftStepFallsBackForTheBulletModesContactFeatures)
{
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    const std::vector<std::pair<std::string, std::function<void(scenes::Scene&, bool)>>> cases = {
        {"m_sor",
         [](scenes::Scene& s, bool on) { s.world().getSolverInfo().m_sor = on ? btScalar(0.5) : btScalar(1); }},
    };
    for (const auto& [name, set] : cases) {
        scenes::ScenePtr gpu = scenes::boxStack(WorldKind::Gpu, soft, 2);
        gpu->step();
        ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << gpu->report()->cpuPathReason;
        set(*gpu, true);
        gpu->step();
        EXPECT_FALSE(gpu->gpuWorld()->isGpuPath()) << name;
        EXPECT_NE(gpu->report()->cpuPathReason.find(name), std::string::npos) << gpu->report()->cpuPathReason;
        EXPECT_NE(gpu->report()->cpuPathReason.find("SoftStep"), std::string::npos) << gpu->report()->cpuPathReason;
        set(*gpu, false);
        gpu->step();
        EXPECT_TRUE(gpu->gpuWorld()->isGpuPath()) << name << ": " << gpu->report()->cpuPathReason;
    }
}
