// soft_step_joints_test.cpp — the library's default solver (the soft step) on joints against
// stock Bullet in the same process, the btgpu world asserted on the GPU path after every step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

// Three boxes (half extents 0.5, 0.1, 0.1; 1 kg) in a horizontal chain from Bullet's fixed body
// at (0, 5, 0), joined end to end by btPoint2PointConstraints, released from rest; no ground.
ScenePtr boxChain(WorldKind kind, const Config& config)
{
    auto s = std::make_unique<Scene>(kind, config, "box_chain");
    btBoxShape* box = s->boxShape(btVector3(0.5f, 0.1f, 0.1f));
    btRigidBody* above = nullptr;
    for (int i = 0; i < 3; ++i) {
        btRigidBody* b = s->addBody(box, 1.0f, btVector3(-0.5f - float(i), 5.0f, 0.0f));
        b->setActivationState(DISABLE_DEACTIVATION);
        if (!above) s->addJoint(new btPoint2PointConstraint(*b, btVector3(0.5f, 0, 0)));
        else s->addJoint(new btPoint2PointConstraint(*above, *b, btVector3(-0.5f, 0, 0), btVector3(0.5f, 0, 0)));
        above = b;
    }
    return s;
}

// Kinetic and potential energy of the chain (the scene's gravity, y up), J.
double energy(const Scene& s)
{
    double e = 0;
    const double g = -double(s.world().getGravity().y());
    for (int i = 0; i < 3; ++i) {
        const btRigidBody* b = s.body(i);
        const btVector3 v = b->getLinearVelocity(), w = b->getAngularVelocity();
        e += 0.5 / double(b->getInvMass()) * double(v.length2()) + 0.5 * double(w.dot(b->getInvInertiaTensorWorld().inverse() * w)) +
             g / double(b->getInvMass()) * double(b->getWorldTransform().getOrigin().y());
    }
    return e;
}

}  // namespace

// A chain of point-to-point joints keeps its energy on the soft step: the relax drives those rows
// without their position correction's bias (as Box2D's relax does). With the bias in the relax
// too it gained 6 % in 20 s and 11 % in 60 s (150 to 167 J); stock, damped by its own
// correction, loses (140 J at 20 s). Bounded here: within 2 % of the start, never above it by
// more, over 20 s.
TEST(SoftStepJoints, PointToPointChainKeepsItsEnergy)
{
    SideBySide s(boxChain, Config());
    const double start = energy(*s.gpu);
    double high = start;
    for (int i = 0; i < 1200; ++i) {
        s.step();
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
        high = std::max(high, energy(*s.gpu));
    }
    EXPECT_EQ(s.gpu->report()->solver, SolverKind::SoftStep);
    const double end = energy(*s.gpu), stockEnd = energy(*s.stock);
    std::printf("p2p chain of 3 boxes, 20 s: energy from %.3f J to btgpu (soft step) %.3f J (highest %.3f), stock %.3f J\n",
                start, end, high, stockEnd);
    EXPECT_LT(stockEnd, start);  // stock's own correction damps it (the scene moves: not vacuous)
    EXPECT_NEAR(end, start, 0.02 * std::fabs(start));
    EXPECT_LE(high, start + 0.02 * std::fabs(start));
}

// KNOWN DEFECT, disabled until it is fixed (README, Known differences of the default): a rod
// (0.1 x 1 x 0.1 m, 1 kg) hanging from a point-to-point joint or a hinge at its top end, released
// 10 degrees out, keeps its swing energy on stock (96 % after 20 s) but gains it on the soft step:
// 7.3 times in 20 s through a point-to-point joint, 8.2 through a hinge (30 degrees: 3.4 and 5.4).
// With one substep it loses (28 %) as stock does; more substeps gain faster (2: 2.2x, 4: 4.9x,
// 10: 7.3x, 20: 8.2x). The rows keep the step's start lever arms through the substeps; a
// prototype that turns them with the bodies and gathers the warm start passes this test (98 and
// 99.5 %) but leaves capsule ragdolls jittering (branch wip/soft-joint-turned-arms; README).
// Enable with --gtest_also_run_disabled_tests.
TEST(SoftStepJoints, DISABLED_ARodPendulumKeepsItsEnergy)
{
    for (bool hinge : {false, true}) {
        SCOPED_TRACE(hinge ? "hinge" : "point-to-point");
        auto make = [&](WorldKind kind, const Config& config) {
            auto s = std::make_unique<Scene>(kind, config, "rod_pendulum");
            s->world().setGravity(btVector3(0, btScalar(-9.81), 0));
            const btQuaternion q(btVector3(0, 0, 1), btScalar(10 * M_PI / 180));
            const btVector3 com = btVector3(0, 2, 0) + quatRotate(q, btVector3(0, btScalar(-0.5), 0));
            btRigidBody* rod = s->addBody(s->boxShape(btVector3(btScalar(0.05), btScalar(0.5), btScalar(0.05))), 1,
                                          btTransform(q, com));
            rod->setActivationState(DISABLE_DEACTIVATION);
            if (hinge) s->addJoint(new btHingeConstraint(*rod, btVector3(0, btScalar(0.5), 0), btVector3(0, 0, 1)));
            else s->addJoint(new btPoint2PointConstraint(*rod, btVector3(0, btScalar(0.5), 0)));
            return s;
        };
        ScenePtr stock = make(WorldKind::Stock, Config::bulletMode());
        ScenePtr soft = make(WorldKind::Gpu, Config{});
        auto swing = [](const Scene& s) {  // above the rod's lowest, J
            const btRigidBody* b = s.body(0);
            const btVector3 w = b->getAngularVelocity();
            return 9.81 * (double(b->getWorldTransform().getOrigin().y()) - 1.5) + 0.5 * double(b->getLinearVelocity().length2()) +
                   0.5 * double(w.dot(b->getInvInertiaTensorWorld().inverse() * w));
        };
        const double start = swing(*soft);
        for (int i = 0; i < 1200; ++i) {
            stock->step();
            soft->step();
            ASSERT_TRUE(soft->gpuWorld()->isGpuPath()) << "step " << i;
        }
        std::printf("rod pendulum (%s), 10 degrees, 20 s: swing energy %.1f %% of the start (stock %.1f %%)\n",
                    hinge ? "hinge" : "point-to-point", 100 * swing(*soft) / start, 100 * swing(*stock) / start);
        EXPECT_GT(swing(*soft), 0.8 * start);
        EXPECT_LT(swing(*soft), 1.05 * start);
    }
}
