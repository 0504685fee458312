// joints_test.cpp — btPoint2PointConstraint on the GPU path against stock Bullet in the same
// process (the btgpu world asserted on the GPU path after every step): a pendulum's period, a
// hanging chain's stretch (and with more joint iterations), a breaking threshold breaking on
// stock's step, applied impulse and joint feedback, setEnabled and a moved pivot between steps,
// a jointed pair falling asleep and waking as one, and the joints that keep the CPU path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <BulletDynamics/ConstraintSolver/btGearConstraint.h>

#include "scenes/joint_scenes.h"
#include "scenes/stock_chaos.h"
#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

bool has(const Report& r, const std::string& stage)
{
    return std::find(r.stages.begin(), r.stages.end(), stage) != r.stages.end();
}

// Steps both worlds, asserting the GPU path after each step.
#define STEP_ON_GPU(s, n)                                                                       \
    for (int step_ = 0; step_ < (n); ++step_) {                                                 \
        (s).step();                                                                             \
        ASSERT_TRUE((s).onGpu()) << "step " << step_ << ": " << (s).gpu->report()->cpuPathReason; \
    }

// Times (s) at which the bob crosses x = 0 moving towards -x, linearly interpolated.
struct Crossings {
    std::vector<double> t;
    double lastX = 0.0;
    void add(double time, double x, double dt)
    {
        if (lastX > 0.0 && x <= 0.0) t.push_back(time - dt * x / (x - lastX));
        lastX = x;
    }
    double period() const { return t.size() < 2 ? 0.0 : (t.back() - t.front()) / double(t.size() - 1); }
};

}  // namespace

TEST(Joints, PendulumPeriodMatchesStock)
{
    // At Bullet's 10 iterations the bob's three world-axis rows (one stiff along the arm, two
    // that mostly spin the light sphere) are far from converged: stock's own period is 9 %
    // longer than physics and its arm stretches 4 cm. Against stock there; against physics with
    // 100 joint iterations (setOverrideNumSolverIterations), where stock converges too.
    for (int override : {0, 100}) {
        SCOPED_TRACE(override);
        SideBySide s([](WorldKind k, const Config& c) { return scenes::pendulum(k, c, 30.0); });
        s.both([&](Scene& sc) { sc.joint(0)->setOverrideNumSolverIterations(override); });
        Crossings stock, gpu;
        stock.lastX = gpu.lastX = s.stock->body(0)->getWorldTransform().getOrigin().x();
        double gpuArm = 0.0, stockArm = 0.0;  // largest error of the arm's length
        const btVector3 pivot(0, btScalar(scenes::kPendulumPivotY), 0);
        for (int i = 0; i < 600; ++i) {  // 10 s: about 5 periods
            s.step();
            ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
            const double t = (i + 1) * double(kStep);
            const btVector3 ps = s.stock->body(0)->getWorldTransform().getOrigin();
            const btVector3 pg = s.gpu->body(0)->getWorldTransform().getOrigin();
            stock.add(t, ps.x(), kStep);
            gpu.add(t, pg.x(), kStep);
            stockArm = std::max(stockArm, std::fabs((ps - pivot).length() - scenes::kPendulumLength));
            gpuArm = std::max(gpuArm, std::fabs((pg - pivot).length() - scenes::kPendulumLength));
        }
        std::printf("pendulum, %d joint iterations: period stock %.4f s, btgpu %.4f s; arm error stock %.4f m, "
                    "btgpu %.4f m\n",
                    override ? override : 10, stock.period(), gpu.period(), stockArm, gpuArm);
        const Report& r = *s.gpu->report();
        EXPECT_TRUE(has(r, "prepare_joints"));
        EXPECT_TRUE(has(r, "finish_joints"));
        EXPECT_TRUE(has(r, "solve_constraints"));
        EXPECT_FALSE(has(r, "narrowphase"));  // one body, no contacts: no collision stages
        ASSERT_GE(stock.t.size(), 4u);
        ASSERT_EQ(gpu.t.size(), stock.t.size());
        EXPECT_NEAR(gpu.period(), stock.period(), tol::kPendulumPeriodRel * stock.period());
        EXPECT_NEAR(gpuArm, stockArm, tol::kJointPosition + 0.05 * stockArm);
        if (!override) continue;
        // Physics: a physical pendulum (a sphere of radius 0.1 on a 1 m arm) at 30 degrees,
        // T = 2 pi sqrt(I / (m g L)) (1 + theta^2 / 16), g = 10.
        const double theta = 30.0 * M_PI / 180.0;
        const double inertia = 1.0 + 0.4 * 0.1 * 0.1;
        const double physical = 2.0 * M_PI * std::sqrt(inertia / 10.0) * (1.0 + theta * theta / 16.0);
        EXPECT_NEAR(gpu.period(), physical, tol::kPendulumPhysicsRel * physical);
        EXPECT_LT(gpuArm, tol::kJointDrift);
    }
}

TEST(Joints, HangingChainStretchMatchesStock)
{
    for (int override : {0, 40}) {
        SCOPED_TRACE(override ? "override 40 iterations" : "default iterations");
        SideBySide s([](WorldKind k, const Config& c) { return scenes::chain(k, c, 20); });
        if (override) s.both([&](Scene& sc) {
            for (int j = 0; j < sc.numJoints(); ++j) sc.joint(j)->setOverrideNumSolverIterations(override);
        });
        const int last = 21;  // bodies: ground, anchor, 20 links
        const double start = s.stockY(last);
        STEP_ON_GPU(s, 180);
        const double stockStretch = start - s.stockY(last), gpuStretch = start - s.gpuY(last);
        std::printf("chain of 20, joint iterations %d: stretch stock %.5f m, btgpu %.5f m\n", override ? override : 10,
                    stockStretch, gpuStretch);
        EXPECT_GT(stockStretch, 0.0);
        EXPECT_NEAR(gpuStretch, stockStretch, tol::kChainStretchRel * stockStretch + tol::kChainStretchAbs);
        // Hanging still: no link swings or stretches further.
        for (int i = 2; i <= last; ++i) {
            EXPECT_LT(s.gpu->body(i)->getLinearVelocity().length(), tol::kChainStillSpeed) << "link " << i;
            EXPECT_LT(std::fabs(s.gpu->body(i)->getWorldTransform().getOrigin().x()), 1e-4) << "link " << i;
        }
        EXPECT_TRUE(has(*s.gpu->report(), "prepare_joints"));
        EXPECT_TRUE(has(*s.gpu->report(), "narrowphase"));  // the ground: contacts and joints together
    }
}

TEST(Joints, MoreJointIterationsStretchLess)
{
    // setOverrideNumSolverIterations above m_numIterations makes Bullet iterate the joints
    // longer: the chain stretches less, on both.
    double stretch[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
        ScenePtr gpu = scenes::chain(WorldKind::Gpu, Config::bulletMode(), 20);
        for (int j = 0; j < gpu->numJoints(); ++j) gpu->joint(j)->setOverrideNumSolverIterations(k ? 60 : 0);
        const double start = gpu->body(21)->getWorldTransform().getOrigin().y();
        for (int i = 0; i < 120; ++i) {
            gpu->step();
            ASSERT_TRUE(gpu->gpuWorld()->isGpuPath());
        }
        stretch[k] = start - gpu->body(21)->getWorldTransform().getOrigin().y();
    }
    EXPECT_LT(stretch[1], 0.5 * stretch[0]);
}

TEST(Joints, BreakingThresholdBreaksOnStocksStep)
{
    for (double threshold : {0.3, 0.45, 5.0}) {
        SCOPED_TRACE(threshold);
        SideBySide s([=](WorldKind k, const Config& c) { return scenes::breakingPendulum(k, c, threshold); });
        int stockBreak = -1, gpuBreak = -1;
        for (int i = 0; i < 90 && (stockBreak < 0 || gpuBreak < 0); ++i) {
            s.step();
            ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
            if (stockBreak < 0 && !s.stock->joint(0)->isEnabled()) stockBreak = i;
            if (gpuBreak < 0 && !s.gpu->joint(0)->isEnabled()) gpuBreak = i;
        }
        EXPECT_EQ(gpuBreak, stockBreak);
        std::printf("breaking threshold %.2f N s: breaks at step %d on stock, %d on btgpu\n", threshold, stockBreak,
                    gpuBreak);
        if (threshold > 1.0) EXPECT_EQ(stockBreak, -1);  // holds: the scene's load is below it
        else EXPECT_GE(stockBreak, 0);
        // After the break the bob flies free on both.
        s.step(10);
        EXPECT_LT(s.distance(0), tol::kJointPosition);
    }
}

TEST(Joints, AppliedImpulseAndFeedbackMatchStock)
{
    SideBySide s([](WorldKind k, const Config& c) { return scenes::pendulum(k, c, 60.0); });
    btJointFeedback fbStock, fbGpu;
    s.stock->joint(0)->setJointFeedback(&fbStock);
    s.gpu->joint(0)->setJointFeedback(&fbGpu);
    s.stock->joint(0)->enableFeedback(true);
    s.gpu->joint(0)->enableFeedback(true);
    double maxForce = 0.0;
    for (int i = 0; i < 120; ++i) {
        s.step();
        ASSERT_TRUE(s.onGpu());
        const double applied = s.stock->joint(0)->getAppliedImpulse();
        EXPECT_NEAR(s.gpu->joint(0)->getAppliedImpulse(), applied, tol::kJointImpulseRel * std::fabs(applied) + 1e-4)
            << "step " << i;
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(fbGpu.m_appliedForceBodyA[k], fbStock.m_appliedForceBodyA[k],
                        tol::kJointImpulseRel * fbStock.m_appliedForceBodyA.length() + 1e-2)
                << "step " << i;
            EXPECT_NEAR(fbGpu.m_appliedTorqueBodyA[k], fbStock.m_appliedTorqueBodyA[k],
                        tol::kJointImpulseRel * fbStock.m_appliedTorqueBodyA.length() + 1e-2)
                << "step " << i;
            EXPECT_NEAR(fbGpu.m_appliedForceBodyB[k], fbStock.m_appliedForceBodyB[k],
                        tol::kJointImpulseRel * fbStock.m_appliedForceBodyB.length() + 1e-2)
                << "step " << i;
        }
        maxForce = std::max(maxForce, double(fbStock.m_appliedForceBodyA.length()));
        EXPECT_LT(s.distance(0), tol::kJointPosition) << "step " << i;
    }
    // The arm carries tension: m g at rest, more through the swing.
    EXPECT_GT(maxForce, 10.0);
}

TEST(Joints, EnabledAndPivotChangesBetweenStepsTakeEffect)
{
    SideBySide s([](WorldKind k, const Config& c) { return scenes::pendulum(k, c, 30.0); });
    STEP_ON_GPU(s, 20);
    s.both([](Scene& sc) { sc.joint(0)->setEnabled(false); });
    const double before = s.stockY(0);
    STEP_ON_GPU(s, 30);  // falls free: at least g t^2 / 2 = 1.25 m in 0.5 s
    EXPECT_LT(s.stockY(0), before - 1.2);
    EXPECT_LT(s.distance(0), tol::kJointPosition);
    // Back on, with the world pivot moved to where the bob is now plus 0.5 m up: it hangs there.
    s.both([](Scene& sc) {
        auto* p = static_cast<btPoint2PointConstraint*>(sc.joint(0));
        p->setPivotA(btVector3(0, 0.5f, 0));
        p->setPivotB(sc.body(0)->getWorldTransform().getOrigin() + btVector3(0, 0.5f, 0));
        p->setParam(BT_CONSTRAINT_ERP, 0.8f);
        sc.joint(0)->setEnabled(true);
    });
    STEP_ON_GPU(s, 60);
    EXPECT_LT(s.distance(0), tol::kJointPosition);
    EXPECT_TRUE(s.gpu->joint(0)->isEnabled());
}

TEST(Joints, JointedPairSleepsAndWakesAsOne)
{
    SideBySide s(scenes::jointedPair);
    int stockAsleep = -1, gpuAsleep = -1;
    for (int i = 0; i < 600 && (stockAsleep < 0 || gpuAsleep < 0); ++i) {
        s.step();
        ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        // The two bodies of the pair change state in the same step (one island).
        EXPECT_EQ(s.gpu->body(1)->isActive(), s.gpu->body(2)->isActive()) << "step " << i;
        if (stockAsleep < 0 && !s.stock->body(1)->isActive()) stockAsleep = i;
        if (gpuAsleep < 0 && !s.gpu->body(1)->isActive()) gpuAsleep = i;
    }
    ASSERT_GE(stockAsleep, 0);
    ASSERT_GE(gpuAsleep, 0);
    EXPECT_NEAR(gpuAsleep, stockAsleep, tol::kSleepStepSlack);
    EXPECT_LT(s.distance(1), tol::kRestHeight);
    EXPECT_LT(s.distance(2), tol::kRestHeight);
    // Waking one wakes the other through the joint.
    s.both([](Scene& sc) {
        sc.body(1)->activate();
        sc.body(1)->applyCentralImpulse(btVector3(0, 2, 0));
    });
    s.step();
    s.step();
    EXPECT_TRUE(s.stock->body(2)->isActive());
    EXPECT_TRUE(s.gpu->body(2)->isActive());
}

TEST(Joints, UnservedJointsKeepTheCpuPathNamingThem)
{
    struct AppJoint : btPoint2PointConstraint {
        using btPoint2PointConstraint::btPoint2PointConstraint;
    };
    {
        ScenePtr s = scenes::pendulum(WorldKind::Gpu);
        s->addJoint(new AppJoint(*s->body(0), btVector3(0, 1, 0)));
        s->step();
        EXPECT_FALSE(s->gpuWorld()->isGpuPath());
        EXPECT_NE(s->report()->cpuPathReason.find("AppJoint"), std::string::npos) << s->report()->cpuPathReason;
    }
    {
        // An app's subclass of Bullet's accumulated-angle hinge is not that type either.
        struct AppHinge : btHingeAccumulatedAngleConstraint {
            using btHingeAccumulatedAngleConstraint::btHingeAccumulatedAngleConstraint;
        };
        ScenePtr s = scenes::chain(WorldKind::Gpu, Config::bulletMode(), 2);
        s->addJoint(new AppHinge(*s->body(2), btVector3(0, 0, 0), btVector3(0, 1, 0)));
        s->step();
        EXPECT_FALSE(s->gpuWorld()->isGpuPath());
        EXPECT_NE(s->report()->cpuPathReason.find("AppHinge"), std::string::npos) << s->report()->cpuPathReason;
    }
    {
        Config c = Config::bulletMode();
        c.solver = SolverKind::JacobiMassSplitting;
        ScenePtr s = scenes::pendulum(WorldKind::Gpu, c);
        s->step();
        EXPECT_FALSE(s->gpuWorld()->isGpuPath());
        EXPECT_NE(s->report()->cpuPathReason.find("Jacobi"), std::string::npos) << s->report()->cpuPathReason;
    }
}

// btGearConstraint: a wheel driven by its hinge motor turns a geared one at -w / ratio, and a
// wheel spun free shares its spin through the gear, as on stock, both ratios' signs.
TEST(Joints, GearTurnsTheSecondWheelAsOnStock)
{
    for (double ratio : {2.0, -0.5}) {
        SideBySide s([=](WorldKind k, const Config& c) { return scenes::gearPair(k, c, ratio, 2.0); });
        STEP_ON_GPU(s, 120);
        const double stockA = s.stock->body(0)->getAngularVelocity().y(), gpuA = s.gpu->body(0)->getAngularVelocity().y();
        const double stockB = s.stock->body(1)->getAngularVelocity().y(), gpuB = s.gpu->body(1)->getAngularVelocity().y();
        std::printf("gear ratio %.1f, motor 2 rad/s after 2 s: wheel 0 stock %.4f btgpu %.4f, wheel 1 stock %.4f btgpu %.4f\n",
                    ratio, stockA, gpuA, stockB, gpuB);
        EXPECT_NEAR(gpuA, 2.0, tol::kMotorSpeedRel * 2.0);
        EXPECT_NEAR(gpuB, -gpuA / ratio, tol::kMotorSpeedRel * std::fabs(gpuA / ratio));
        EXPECT_NEAR(gpuA, stockA, tol::kMotorSpeedRel * std::fabs(stockA));
        EXPECT_NEAR(gpuB, stockB, tol::kMotorSpeedRel * std::fabs(stockB));
        EXPECT_LT(s.distance(0), tol::kJointPosition * 10);
        EXPECT_LT(s.distance(1), tol::kJointPosition * 10);
        EXPECT_TRUE(has(*s.gpu->report(), "prepare_joints"));
    }
    {
        // Free: wheel 0 starts at 3 rad/s; the gear's impulse shares it (equal inertias, ratio 2:
        // w0 = 3 / (1 + 1/4) = 2.4, w1 = -1.2), the hinges' rows leaving the spin axis alone.
        SideBySide s([](WorldKind k, const Config& c) { return scenes::gearPair(k, c, 2.0, 0.0); });
        STEP_ON_GPU(s, 60);
        const double gpuA = s.gpu->body(0)->getAngularVelocity().y(), gpuB = s.gpu->body(1)->getAngularVelocity().y();
        const double stockA = s.stock->body(0)->getAngularVelocity().y(), stockB = s.stock->body(1)->getAngularVelocity().y();
        std::printf("gear ratio 2, free after 1 s: wheel 0 stock %.4f btgpu %.4f, wheel 1 stock %.4f btgpu %.4f\n", stockA,
                    gpuA, stockB, gpuB);
        EXPECT_NEAR(gpuA, 2.4, 0.02 * 2.4);
        EXPECT_NEAR(gpuB, -1.2, 0.02 * 1.2);
        EXPECT_NEAR(gpuA, stockA, tol::kMotorSpeedRel * std::fabs(stockA));
        EXPECT_NEAR(gpuB, stockB, tol::kMotorSpeedRel * std::fabs(stockB));
    }
}

// btHingeAccumulatedAngleConstraint: the hinge's rows, and its angle tracked across -pi/pi at
// each internal step as stock's getInfo1 tracks it. A wheel driven at 15 rad/s, three internal
// steps a call: 0.25 rad a step, within the 0.3 rad btShortestAngleUpdate follows (beyond it
// Bullet restarts from the folded angle), but 0.75 rad a call, which a call-by-call update
// would fold.
TEST(Joints, AccumulatedHingeAngleFollowsEveryTurnAsOnStock)
{
    auto wheel = [](WorldKind k, const Config& c) {
        auto s = std::make_unique<Scene>(k, c, "accumulated_hinge");
        btRigidBody* w = s->addBody(s->ownShape(new btCylinderShape(btVector3(0.5f, 0.1f, 0.5f))), 2.0f, btVector3(0, 2, 0));
        w->setActivationState(DISABLE_DEACTIVATION);
        auto* h = s->addJoint(new btHingeAccumulatedAngleConstraint(*w, btVector3(0, 0, 0), btVector3(0, 1, 0)));
        h->enableAngularMotor(true, 15.0f, 10.0f);
        return ScenePtr(std::move(s));
    };
    SideBySide s(wheel);
    double travelled = 0;  // the wheel's own spin, integrated
    for (int call = 0; call < 20; ++call) {
        s.step(1, btScalar(3.0 / 60.0), 3, btScalar(1.0 / 60.0));
        ASSERT_TRUE(s.onGpu()) << call;
        travelled += 3.0 / 60.0 * s.gpu->body(0)->getAngularVelocity().y();
    }
    auto angle = [](Scene& sc) { return double(static_cast<btHingeAccumulatedAngleConstraint*>(sc.joint(0))->getAccumulatedHingeAngle()); };
    const double stockAngle = angle(*s.stock), gpuAngle = angle(*s.gpu);
    std::printf("accumulated hinge angle after 1 s at 15 rad/s: stock %.4f, btgpu %.4f rad (spin integrated %.4f)\n",
                stockAngle, gpuAngle, travelled);
    EXPECT_GT(std::fabs(gpuAngle), 12.0);  // more than two turns, not folded into one
    EXPECT_NEAR(gpuAngle, stockAngle, 0.02 * std::fabs(stockAngle));
    EXPECT_NEAR(std::fabs(gpuAngle), std::fabs(travelled), 0.05 * std::fabs(travelled));
    EXPECT_TRUE(has(*s.gpu->report(), "prepare_joints"));
}

TEST(Joints, ScenesWithoutJointsBuildNoJointStage)
{
    ScenePtr s = scenes::basicDemo(WorldKind::Gpu);
    s->step();
    EXPECT_FALSE(has(*s->report(), "prepare_joints"));
    EXPECT_FALSE(has(*s->report(), "finish_joints"));
}

TEST(Joints, IgnoredCollisionChecksLeaveNoContacts)
{
    // setIgnoreCollisionCheck: the box falls through the ground on both.
    SideBySide s(scenes::restingBox);
    s.both([](Scene& sc) { sc.body(1)->setIgnoreCollisionCheck(sc.body(0), true); });
    STEP_ON_GPU(s, 30);
    EXPECT_LT(s.stockY(1), 0.0);
    EXPECT_LT(s.distance(1), tol::kFreeFallPosition);
    EXPECT_TRUE(has(*s.gpu->report(), "filter_pairs"));
    // Taken back: the plan drops the stage.
    s.both([](Scene& sc) { sc.body(1)->setIgnoreCollisionCheck(sc.body(0), false); });
    STEP_ON_GPU(s, 1);
    EXPECT_FALSE(has(*s.gpu->report(), "filter_pairs"));
}

TEST(Joints, DisableCollisionsBetweenLinkedBodies)
{
    // Two spheres (radius 0.3) overlapping by 0.2 m, joined at the midpoint, resting on the
    // ground: with collisions between them disabled they stay put; with them enabled the contact
    // pushes against the joint. Either way as on stock.
    for (bool disable : {true, false}) {
        SCOPED_TRACE(disable ? "disabled" : "enabled");
        SideBySide s([=](WorldKind k, const Config& c) {
            auto sc = std::make_unique<Scene>(k, c, "overlapping_pair");
            sc->addBody(sc->boxShape(btVector3(5, 0.5f, 5)), 0.0f, btVector3(0, -0.5f, 0));
            btSphereShape* ball = sc->sphereShape(0.3f);
            btRigidBody* a = sc->addBody(ball, 1.0f, btVector3(-0.2f, 0.3f, 0));
            btRigidBody* b = sc->addBody(ball, 1.0f, btVector3(0.2f, 0.3f, 0));
            sc->addJoint(new btPoint2PointConstraint(*a, *b, btVector3(0.2f, 0, 0), btVector3(-0.2f, 0, 0)), disable);
            return sc;
        });
        STEP_ON_GPU(s, 60);
        auto gap = [](Scene& sc) {
            return sc.body(2)->getWorldTransform().getOrigin().x() - sc.body(1)->getWorldTransform().getOrigin().x();
        };
        std::printf("overlapping jointed spheres, collisions %s: gap stock %.4f m, btgpu %.4f m\n",
                    disable ? "disabled" : "enabled", gap(*s.stock), gap(*s.gpu));
        EXPECT_LT(s.distance(1), disable ? tol::kRestHeight : tol::kJointContactFight);
        EXPECT_LT(s.distance(2), disable ? tol::kRestHeight : tol::kJointContactFight);
        if (disable) EXPECT_NEAR(gap(*s.gpu), 0.4, 1e-3);
        else EXPECT_GT(std::fabs(gap(*s.stock) - 0.4), 1e-3);
        EXPECT_EQ(has(*s.gpu->report(), "filter_pairs"), disable);
    }
}

TEST(Joints, HingeDoorMotorReachesItsSpeedAndStopsAtItsLimit)
{
    // Free door: the motor brings it to 1 rad/s within 1 s (the door's 0.42 kg m^2 about the
    // hinge at 0.5 N m s a step gets there in a few steps).
    {
        SideBySide s([](WorldKind k, const Config& c) { return scenes::hingeDoor(k, c, 1.0, 0.5); });
        STEP_ON_GPU(s, 60);
        const double stockW = s.stock->body(1)->getAngularVelocity().y();
        const double gpuW = s.gpu->body(1)->getAngularVelocity().y();
        std::printf("hinge door motor at 1 rad/s after 1 s: stock %.4f, btgpu %.4f rad/s\n", stockW, gpuW);
        EXPECT_NEAR(gpuW, 1.0, tol::kMotorSpeedRel * 1.0);
        EXPECT_NEAR(gpuW, stockW, tol::kMotorSpeedRel * std::fabs(stockW));
        EXPECT_LT(s.distance(1), tol::kJointPosition * 10);
        EXPECT_TRUE(has(*s.gpu->report(), "prepare_joints"));
    }
    // Limited to [-0.1, pi/2]: the motor drives it into the upper limit, where it stops.
    {
        const double upper = M_PI / 2;
        SideBySide s([=](WorldKind k, const Config& c) { return scenes::hingeDoor(k, c, 1.0, 0.5, -0.1, upper); });
        STEP_ON_GPU(s, 180);
        auto* hs = static_cast<btHingeConstraint*>(s.stock->joint(0));
        auto* hg = static_cast<btHingeConstraint*>(s.gpu->joint(0));
        const double stockAngle = hs->getHingeAngle(), gpuAngle = hg->getHingeAngle();
        std::printf("hinge door at its limit (%.4f rad) after 3 s: stock %.4f, btgpu %.4f rad\n", upper, stockAngle,
                    gpuAngle);
        EXPECT_NEAR(gpuAngle, upper, tol::kHingeLimitAngle);
        EXPECT_NEAR(gpuAngle, stockAngle, tol::kHingeLimitAngle);
        EXPECT_LT(std::fabs(s.gpu->body(1)->getAngularVelocity().y()), 0.05);
    }
}

TEST(Joints, HingePendulumWithABouncyLimitMatchesStock)
{
    // A hinged bar swinging about z from horizontal into a limit at -60 degrees with
    // relaxation 1 (bounce) and bias 0.3: the same swing and rebound as stock.
    SideBySide s([](WorldKind k, const Config& c) {
        auto sc = std::make_unique<Scene>(k, c, "hinge_limit");
        btRigidBody* bar = sc->addBody(sc->boxShape(btVector3(0.5f, 0.05f, 0.05f)), 1.0f, btVector3(0.5f, 3, 0));
        bar->setActivationState(DISABLE_DEACTIVATION);
        auto* h = sc->addJoint(new btHingeConstraint(*bar, btVector3(-0.5f, 0, 0), btVector3(0, 0, 1)));
        h->setLimit(btScalar(-M_PI / 3), btScalar(M_PI / 3), 0.9f, 0.3f, 1.0f);
        return sc;
    });
    double maxDiff = 0.0, minAngle = 0.0;
    for (int i = 0; i < 120; ++i) {
        s.step();
        ASSERT_TRUE(s.onGpu());
        const double a = static_cast<btHingeConstraint*>(s.gpu->joint(0))->getHingeAngle();
        const double b = static_cast<btHingeConstraint*>(s.stock->joint(0))->getHingeAngle();
        maxDiff = std::max(maxDiff, std::fabs(a - b));
        minAngle = std::min(minAngle, b);
    }
    std::printf("hinge with bouncy limit: largest angle difference %.5f rad, lowest stock angle %.4f rad\n", maxDiff,
                minAngle);
    EXPECT_LT(minAngle, -M_PI / 3 + 0.1);  // it reached the limit
    EXPECT_LT(maxDiff, tol::kHingeLimitAngle);
}

namespace {
// World distance between a joint's two frame origins (0 when the joint holds).
double pivotGap(btTypedConstraint* c)
{
    btTransform fa, fb;
    if (auto* h = dynamic_cast<btHingeConstraint*>(c)) {
        fa = h->getAFrame();
        fb = h->getBFrame();
    } else if (auto* k = dynamic_cast<btConeTwistConstraint*>(c)) {
        fa = k->getAFrame();
        fb = k->getBFrame();
    } else {
        return 0.0;
    }
    const btVector3 pa = c->getRigidBodyA().getCenterOfMassTransform() * fa.getOrigin();
    const btVector3 pb = c->getRigidBodyB().getCenterOfMassTransform() * fb.getOrigin();
    return (pa - pb).length();
}
}  // namespace

TEST(Joints, RagdollsFallOntoTheGroundAsOnStock)
{
    SideBySide s([](WorldKind k, const Config& c) { return scenes::ragdolls(k, c, 4); });
    double worstGap = 0.0, stockWorstGap = 0.0;
    for (int i = 0; i < 180; ++i) {
        s.step();
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
        for (int j = 0; j < s.gpu->numJoints(); ++j) {
            worstGap = std::max(worstGap, pivotGap(s.gpu->joint(j)));
            stockWorstGap = std::max(stockWorstGap, pivotGap(s.stock->joint(j)));
        }
    }
    const double stockMean = scenes::meanHeight(*s.stock), gpuMean = scenes::meanHeight(*s.gpu);
    const scenes::StateDifference d = scenes::positionDifference(*s.stock, *s.gpu);
    std::printf("4 ragdolls after 3 s: mean height stock %.4f, btgpu %.4f m; largest joint gap stock %.4f, btgpu %.4f m;"
                " body distance to stock mean %.4f, max %.4f m\n",
                stockMean, gpuMean, stockWorstGap, worstGap, d.meanPosition, d.maxPosition);
    EXPECT_TRUE(scenes::allFinite(*s.gpu));
    EXPECT_TRUE(has(*s.gpu->report(), "filter_pairs"));  // linked bodies do not collide
    EXPECT_NEAR(gpuMean, stockMean, tol::kRagdollMeanHeight);
    EXPECT_LT(worstGap, std::max(tol::kRagdollJointGap, 2.0 * stockWorstGap));
    EXPECT_GT(scenes::lowestHeight(*s.gpu), -0.05);  // on the ground, not through it
}

TEST(Joints, SameRagdollSceneTwiceGivesSameHashes)
{
    ScenePtr a = scenes::ragdolls(WorldKind::Gpu, Config::bulletMode(), 4);
    ScenePtr b = scenes::ragdolls(WorldKind::Gpu, Config::bulletMode(), 4);
    for (int i = 0; i < 90; ++i) {
        a->step();
        b->step();
        ASSERT_TRUE(a->gpuWorld()->isGpuPath());
        ASSERT_EQ(a->gpuWorld()->stateHash(), b->gpuWorld()->stateHash()) << "step " << i;
    }
}

TEST(Joints, BreaksInsideSubstepsOnStocksCall)
{
    // Two substeps a call: the break happens inside a call; stock and btgpu report it after
    // the same call, and the bob flies on alike.
    SideBySide s([](WorldKind k, const Config& c) { return scenes::breakingPendulum(k, c, 0.3); });
    int stockBreak = -1, gpuBreak = -1;
    for (int i = 0; i < 45; ++i) {
        s.step(1, kStep * 2, 2, kStep);
        ASSERT_TRUE(s.onGpu());
        if (stockBreak < 0 && !s.stock->joint(0)->isEnabled()) stockBreak = i;
        if (gpuBreak < 0 && !s.gpu->joint(0)->isEnabled()) gpuBreak = i;
        EXPECT_LT(s.distance(0), tol::kJointPosition) << "call " << i;
    }
    EXPECT_GE(stockBreak, 0);
    EXPECT_EQ(gpuBreak, stockBreak);
}

TEST(Joints, BobHangingFromAKinematicBodyFollowsIt)
{
    SideBySide s([](WorldKind k, const Config& c) {
        auto sc = std::make_unique<Scene>(k, c, "kinematic_anchor");
        btTransform at = btTransform::getIdentity();
        at.setOrigin(btVector3(0, 5, 0));
        btRigidBody* anchor = sc->addKinematic(sc->boxShape(btVector3(0.1f, 0.1f, 0.1f)), at);
        btRigidBody* bob = sc->addBody(sc->sphereShape(0.1f), 1.0f, btVector3(0, 4, 0));
        bob->setActivationState(DISABLE_DEACTIVATION);
        sc->addJoint(new btPoint2PointConstraint(*anchor, *bob, btVector3(0, -0.5f, 0), btVector3(0, 0.5f, 0)));
        sc->beforeStep = [anchor](Scene&, double t) {
            btTransform x = btTransform::getIdentity();
            x.setOrigin(btVector3(btScalar(std::min(t, 1.0)), 5, 0));  // 1 m/s along x for 1 s
            anchor->getMotionState()->setWorldTransform(x);
        };
        return sc;
    });
    STEP_ON_GPU(s, 120);
    EXPECT_GT(s.gpu->body(1)->getWorldTransform().getOrigin().x(), 0.5);  // dragged along
    EXPECT_LT(s.distance(1), tol::kJointPosition * 10);
}

TEST(Joints, RemovingAJointMidRunLetsTheRestFall)
{
    SideBySide s([](WorldKind k, const Config& c) { return scenes::chain(k, c, 10); });
    STEP_ON_GPU(s, 30);
    s.both([](Scene& sc) { sc.world().removeConstraint(sc.joint(5)); });
    STEP_ON_GPU(s, 30);
    // Links below the removed joint (bodies 7..11) fall; those above hang. The chain's stretch
    // before the removal (within kChainStretch* of stock's) travels with the falling links.
    EXPECT_LT(s.stockY(11), scenes::kChainAnchorY - 0.2 * 10 - 1.0);
    EXPECT_LT(s.gpuY(11), scenes::kChainAnchorY - 0.2 * 10 - 1.0);
    for (int i = 2; i <= 11; ++i) EXPECT_LT(s.distance(i), 2.0 * tol::kChainStretchAbs) << "body " << i;
    // The scene still owns the removed joint; put it back so it is removed once at the end.
    s.both([](Scene& sc) { sc.world().addConstraint(sc.joint(5)); });
    STEP_ON_GPU(s, 1);
}

TEST(Joints, SliderMotorDrivesToItsLimit)
{
    // A box on a horizontal slider to the fixed body, limited to [-0.5, 0.5] m along x, its
    // linear motor pushing at 1 m/s: it stops at the upper limit, as on stock.
    SideBySide s([](WorldKind k, const Config& c) {
        auto sc = std::make_unique<Scene>(k, c, "slider");
        btRigidBody* box = sc->addBody(sc->boxShape(btVector3(0.2f, 0.2f, 0.2f)), 2.0f, btVector3(0, 2, 0));
        box->setActivationState(DISABLE_DEACTIVATION);
        auto* sl = sc->addJoint(new btSliderConstraint(*box, btTransform::getIdentity(), true));
        sl->setLowerLinLimit(-0.5f);
        sl->setUpperLinLimit(0.5f);
        sl->setPoweredLinMotor(true);
        sl->setTargetLinMotorVelocity(1.0f);
        sl->setMaxLinMotorForce(50.0f);
        return sc;
    });
    STEP_ON_GPU(s, 120);
    const double stockX = s.stock->body(0)->getWorldTransform().getOrigin().x();
    const double gpuX = s.gpu->body(0)->getWorldTransform().getOrigin().x();
    std::printf("slider at its 0.5 m limit after 2 s: stock x %.5f, btgpu x %.5f m; btgpu y %.5f m\n", stockX, gpuX,
                s.gpuY(0));
    EXPECT_NEAR(gpuX, 0.5, tol::kSliderLimit);
    EXPECT_NEAR(gpuX, stockX, tol::kSliderLimit);
    EXPECT_NEAR(s.gpuY(0), s.stockY(0), tol::kSliderLimit);  // held up against gravity by the ortho rows
}

TEST(Joints, OneJointOfManyChangedTravelsAlone)
{
    // One joint of twenty disabled, then moved and re-enabled: only that joint is uploaded
    // (compat's partial upload); the chain behaves as stock's.
    SideBySide s([](WorldKind k, const Config& c) { return scenes::chain(k, c, 20); });
    STEP_ON_GPU(s, 20);
    s.both([](Scene& sc) { sc.joint(12)->setEnabled(false); });
    STEP_ON_GPU(s, 10);
    EXPECT_LT(s.stockY(21), scenes::kChainAnchorY - 0.2 * 20 - 0.3);  // the lower links fell
    EXPECT_LT(s.gpuY(21), scenes::kChainAnchorY - 0.2 * 20 - 0.3);
    // The upper links recoil from the chain's 27 cm stretch: the same transient as the snap below.
    for (int i = 2; i <= 21; ++i) EXPECT_LT(s.distance(i), tol::kJointSnap) << "body " << i;
    s.both([](Scene& sc) {
        auto* p = static_cast<btPoint2PointConstraint*>(sc.joint(12));
        p->setPivotB(btVector3(0, 0.6f, 0));
        sc.joint(12)->setEnabled(true);
    });
    STEP_ON_GPU(s, 60);
    // The joint snaps its 0.5 m error shut within the iterations' reach: a violent transient in
    // which the batched order and stock's serial one part by centimetres; the joint holds on both.
    for (int i = 2; i <= 21; ++i) EXPECT_LT(s.distance(i), tol::kJointSnap) << "body " << i;
    auto gap = [](Scene& sc) {
        auto* p = static_cast<btPoint2PointConstraint*>(sc.joint(12));
        const btVector3 a = p->getRigidBodyA().getCenterOfMassTransform() * p->getPivotInA();
        const btVector3 b = p->getRigidBodyB().getCenterOfMassTransform() * p->getPivotInB();
        return double((a - b).length());
    };
    // Closed as far as the chain's own stretch lets it (about 1.3 cm a joint at 10 iterations).
    EXPECT_LT(gap(*s.stock), 0.05);
    EXPECT_LT(gap(*s.gpu), gap(*s.stock) + tol::kJointDrift);
}

// btConeTwistConstraint's motor (getInfo2's path, as 3.24 takes by default): the cube turns to
// its target as on stock; the normalized impulse, angular-only and damping, which only the
// obsolete solve reads, change nothing here, as on stock.
TEST(Joints, ConeTwistMotorReachesItsTargetAsOnStock)
{
    double stockEnd[2] = {0, 0};
    for (int variant = 0; variant < 2; ++variant) {
        SCOPED_TRACE(variant);
        SideBySide s([variant](WorldKind k, const Config& c) { return scenes::coneTwistMotor(k, c, variant); });
        // Left to go: frame A against frame B turned by the target (the motor drives it to 0).
        auto left = [](Scene& sc) {
            auto* c = static_cast<btConeTwistConstraint*>(sc.joint(0));
            const btQuaternion qA = (sc.body(0)->getWorldTransform() * c->getAFrame()).getRotation();
            const btQuaternion qB = (sc.body(1)->getWorldTransform() * c->getBFrame()).getRotation();
            return double((qB * c->getMotorTarget()).angleShortestPath(qA));
        };
        const double start = left(*s.gpu);
        double worst = 0, closest = start;
        for (int i = 0; i < 120; ++i) {
            s.step();
            ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
            worst = std::max<double>(worst, s.stock->body(1)->getOrientation().angleShortestPath(s.gpu->body(1)->getOrientation()));
            closest = std::min(closest, left(*s.gpu));
        }
        const Report& r = *s.gpu->report();
        for (const char* stage : {"prepare_joints", "solve_constraints", "finish_joints"})
            EXPECT_NE(std::find(r.stages.begin(), r.stages.end(), stage), r.stages.end()) << stage;
        std::printf("cone-twist motor variant %d after 2 s: left to turn stock %.5f, btgpu %.5f rad (from %.4f, "
                    "closest %.5f); largest difference in the cube's turn %.5f rad\n",
                    variant, left(*s.stock), left(*s.gpu), start, closest, worst);
        EXPECT_GT(start, 0.3);     // it had to turn
        // and got there: within 0.05 rad (its row pushes one way only, [0, max impulse], with no
        // damping: it swings through and back, 0.12 rad off at 2 s, on stock as here)
        EXPECT_LT(closest, 0.05);
        EXPECT_NEAR(left(*s.gpu), left(*s.stock), 2e-3);
        EXPECT_LT(worst, 1e-2);
        stockEnd[variant] = s.stockY(1);
    }
    EXPECT_DOUBLE_EQ(stockEnd[0], stockEnd[1]);  // stock: the variant's settings change nothing
}

namespace {

// Bullet's bench 3 (BenchmarkDemo createTest3, `rows` rows of capsule ragdolls) on btgpu
// against stock's own chaos (tests/scenes/stock_chaos.h) on mean height, spread and kinetic
// energy at each of `times` (s); the GPU path asserted every step, the joint stages run.
void expectBench3WithinStocksChaos(int rows, const std::vector<int>& steps)
{
    auto measure = [](const scenes::Scene& scene) {
        scenes::Aggregates a = scenes::aggregates(scene);
        return std::vector<double>{a.meanHeight, a.spread, a.kineticEnergy};
    };
    scenes::ScenePtr gpu = scenes::bench3Ragdolls(WorldKind::Gpu, Config::bulletMode(), rows);
    int done = 0;
    for (int at : steps) {
        const auto bands = scenes::stockChaos([rows](WorldKind kind) { return scenes::bench3Ragdolls(kind, Config::bulletMode(), rows); },
                                              at, measure, {"mean height", "spread", "kinetic energy"},
                                              {tol::kChaosHeightFloor, tol::kChaosSpreadFloor, tol::kChaosEnergyFloor});
        for (; done < at; ++done) {
            gpu->step();
            ASSERT_TRUE(gpu->gpuWorld()->isGpuPath()) << "step " << done << ": " << gpu->report()->cpuPathReason;
        }
        const std::vector<double> got = measure(*gpu);
        for (size_t k = 0; k < bands.size(); ++k) {
            std::printf("bench 3 (%d rows) at %.1f s, %s: btgpu %.4f, stock %.4f +- %.4f\n", rows, at / 60.0,
                        bands[k].name.c_str(), got[k], bands[k].stockMean, bands[k].bound());
            EXPECT_TRUE(bands[k].admits(got[k])) << bands[k].name << " at step " << at << ": btgpu " << got[k]
                                                 << ", stock mean " << bands[k].stockMean << " +- " << bands[k].bound();
        }
    }
    const Report& r = *gpu->report();
    for (const char* stage : {"prepare_joints", "solve_constraints", "finish_joints", "filter_pairs"})
        EXPECT_NE(std::find(r.stages.begin(), r.stages.end(), stage), r.stages.end()) << stage;
    EXPECT_TRUE(scenes::allFinite(*gpu));
}

}  // namespace

// The CI variant: the pyramid's top 4 rows (10 ragdolls, 110 capsules) falling 22 m and landing.
TEST(Joints, Bench3RagdollsQuickWithinStocksChaos)
{
    expectBench3WithinStocksChaos(4, {90, 180});
}

// The full bench 3 (136 ragdolls, 1,496 capsules, 1,360 joints; the top row lands after about
// 5 s): 23 s on PoCL's 2 cores (8 stock runs and btgpu, twice), so kept out of CI; run it with
// --gtest_also_run_disabled_tests --gtest_filter=Joints.DISABLED_Bench3*.
TEST(Joints, DISABLED_Bench3RagdollsWithinStocksChaos)
{
    expectBench3WithinStocksChaos(16, {180, 360});
}

namespace {
// A robot arm: a static base and three 1 m links on hinges, each driven by setMotorTarget
// every step (a position servo, max motor impulse 2) towards 0.5 / -0.3 / 0.8 rad over 1 s.
ScenePtr servoArm(WorldKind kind, const Config& config, bool reversed)
{
    auto s = std::make_unique<Scene>(kind, config, "servo_arm");
    btRigidBody* base = s->addBody(s->boxShape(btVector3(0.2f, 0.2f, 0.2f)), 0, btVector3(0, 1, 0));
    btCollisionShape* link = s->boxShape(btVector3(0.5f, 0.05f, 0.05f));
    btRigidBody* links[3];
    for (int i = 0; i < 3; ++i) {
        links[i] = s->addBody(link, 1, btVector3(0.7f + btScalar(i), 1, 0));
        links[i]->setActivationState(DISABLE_DEACTIVATION);
    }
    btHingeConstraint* hinges[3];
    for (int i = 0; i < 3; ++i)
        hinges[i] = i == 0 ? new btHingeConstraint(*base, *links[0], btVector3(0.2f, 0, 0), btVector3(-0.5f, 0, 0),
                                                    btVector3(0, 0, 1), btVector3(0, 0, 1))
                           : new btHingeConstraint(*links[i - 1], *links[i], btVector3(0.5f, 0, 0),
                                                   btVector3(-0.5f, 0, 0), btVector3(0, 0, 1), btVector3(0, 0, 1));
    for (int k = 0; k < 3; ++k) {
        btHingeConstraint* h = hinges[reversed ? 2 - k : k];
        h->enableMotor(true);
        h->setMaxMotorImpulse(2.0f);
        s->addJoint(h, true);
    }
    return s;
}
}  // namespace

// The bullet mode solves joints that share a body in stock's order: stock sorts a copy of the
// world's joints by island with its (unstable) quickSort, which reverses three joints of one
// island, and the servo arm's answer depends on that order. Colouring the joints by hash (the
// order before) rested the arm at (0.5082, -0.3000, 0.8028) rad against stock's (0.5000,
// -0.2917, 0.8028), the tip 3 cm apart; in stock's order they agree to 1e-4. The joints added in
// the reverse order (another permutation, another answer on stock: 0.5082, -0.2972, 0.8000)
// agree too.
TEST(Joints, ServoArmRestsAsStockInTheBulletMode)
{
    for (bool reversed : {false, true}) {
        SCOPED_TRACE(reversed ? "joints added tip first" : "joints added base first");
        SideBySide s([=](WorldKind k, const Config& c) { return servoArm(k, c, reversed); });
        const btScalar dt = btScalar(1.0 / 60.0);
        const btScalar target[3] = {0.5f, -0.3f, 0.8f};
        auto hinge = [&](Scene& sc, int i) {  // the hinge from link i - 1 (the base) to link i
            return static_cast<btHingeConstraint*>(sc.joint(reversed ? 2 - i : i));
        };
        for (int step = 0; step < 180; ++step) {
            s.both([&](Scene& sc) {
                for (int i = 0; i < 3; ++i) hinge(sc, i)->setMotorTarget(target[i] * std::min(1.0f, step / 60.0f), dt);
            });
            s.step();
            ASSERT_TRUE(s.onGpu()) << step;
        }
        for (int i = 0; i < 3; ++i) {
            const double stock = hinge(*s.stock, i)->getHingeAngle(), gpu = hinge(*s.gpu, i)->getHingeAngle();
            std::printf("servo arm%s, hinge %d after 3 s: stock %.5f, btgpu %.5f rad\n", reversed ? " (reversed)" : "", i,
                        stock, gpu);
            EXPECT_NEAR(gpu, stock, 5e-4) << "hinge " << i << " (before: 0.008 rad apart)";
        }
        EXPECT_LT(s.distance(3), 0.002) << "the tip link, m (before: 3 cm)";
    }
}
