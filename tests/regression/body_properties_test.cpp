// body_properties_test.cpp — per-body settings an app sets on btRigidBody, on stock Bullet and
// on btgpu side by side: damping, linear and angular factors, per-body gravity,
// CF_NO_CONTACT_RESPONSE, an applied torque, additional damping, the gyroscopic terms. Each must
// move its body as stock does.
#include <gtest/gtest.h>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {
// Bodies 1..5 of a row of boxes, each with one setting changed; all but the no-response box
// fly high above the ground, so what is compared is the setting, not a landing.
ScenePtr settingsRow(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "settings_row");
    scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    for (int i = 0; i < 5; ++i) scene->addBody(box, 1, btVector3(btScalar(3 * i), i == 3 ? 2 : 20, 0));
    btRigidBody* damped = scene->body(1);
    damped->setDamping(btScalar(.5), btScalar(.5));
    damped->setLinearVelocity(btVector3(4, 0, 0));
    damped->setAngularVelocity(btVector3(0, 3, 0));
    scene->body(2)->setLinearFactor(btVector3(1, 0, 1));  // cannot fall
    scene->body(2)->setLinearVelocity(btVector3(0, 0, 1));
    scene->body(3)->setAngularFactor(btVector3(0, 0, 0));  // cannot turn
    scene->body(3)->setGravity(btVector3(0, 5, 0));        // falls up
    btRigidBody* ghostly = scene->body(4);
    ghostly->setCollisionFlags(ghostly->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
    return scene;
}
}  // namespace

TEST(BodyProperties, SettingsMoveBodiesAsStock)
{
    SideBySide s(settingsRow);
    for (int i = 0; i < 90; ++i) {
        s.both([](Scene& scene) {
            scene.body(3)->applyTorqueImpulse(btVector3(0, 0, btScalar(.5)));  // angular factor 0: no turn
            scene.body(5)->applyTorque(btVector3(0, 2, 0));                   // spins up about y
        });
        s.step();
    }
    for (int b = 1; b <= 5; ++b) EXPECT_LT(s.distance(b), tol::kFreeFallPosition) << "body " << b;
    EXPECT_NEAR(s.gpuY(2), 20.0, 1e-5) << "linear factor 0 on y: the box must not fall";
    EXPECT_GT(s.gpuY(3), 20.5) << "per-body gravity points up";
    EXPECT_LT(s.gpuY(4), -1.0) << "no contact response: falls through the ground";
    const btQuaternion q3 = s.gpu->body(3)->getOrientation();
    EXPECT_NEAR(q3.getAngle(), 0.0, 1e-6) << "angular factor 0: no rotation";
    const double w5 = s.gpu->body(5)->getAngularVelocity().y(), k5 = s.stock->body(5)->getAngularVelocity().y();
    EXPECT_NEAR(w5, k5, 1e-4 * std::max(1.0, std::fabs(k5)));
    const double w1 = s.gpu->body(1)->getAngularVelocity().y(), k1 = s.stock->body(1)->getAngularVelocity().y();
    EXPECT_NEAR(w1, k1, 1e-4) << "angular damping";
    EXPECT_TRUE(s.onGpu());
}

// btRigidBodyConstructionInfo::m_additionalDamping (ragdoll and game code set it): a slow body is
// scaled by the factor each step, one slower than its damping coefficient cut by 5 mm/s a step,
// as applyDamping does; fast bodies and bodies without it are left alone. Weightless boxes far
// apart, so only damping acts.
TEST(BodyProperties, AdditionalDampingAsStock)
{
    struct Case {
        btVector3 v, w;
        float linDamp, angDamp;
        bool additional;
    };
    const Case cases[] = {
        {btVector3(0.05f, 0, 0), btVector3(0, 0.05f, 0), 0.0f, 0.0f, true},   // below both thresholds: scaled to rest
        {btVector3(0.5f, 0, 0), btVector3(0, 0, 0.4f), 0.6f, 0.5f, true},     // slower than its damping: cut
        {btVector3(2.0f, 0, 0), btVector3(0, 3.0f, 0), 0.1f, 0.1f, true},     // fast: plain damping only
        {btVector3(0.05f, 0, 0), btVector3(0, 0.05f, 0), 0.0f, 0.0f, false},  // without it: keeps moving
        {btVector3(0.004f, 0, 0), btVector3(0, 0, 0.003f), 0.2f, 0.2f, true}, // slower than the cut: stopped
    };
    auto make = [&](WorldKind k, const Config& c) {
        auto scene = std::make_unique<Scene>(k, c, "additional_damping");
        btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
        btVector3 inertia;
        box->calculateLocalInertia(1, inertia);
        for (int i = 0; i < int(std::size(cases)); ++i) {
            btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, box, inertia);
            info.m_additionalDamping = cases[i].additional;
            info.m_linearDamping = cases[i].linDamp;
            info.m_angularDamping = cases[i].angDamp;
            btTransform t;
            t.setIdentity();
            t.setOrigin(btVector3(btScalar(10 * i), 0, 0));
            btRigidBody* b = scene->addBody(info, t);
            b->setGravity(btVector3(0, 0, 0));
            b->setLinearVelocity(cases[i].v);
            b->setAngularVelocity(cases[i].w);
            b->setActivationState(DISABLE_DEACTIVATION);
        }
        return ScenePtr(std::move(scene));
    };
    SideBySide s(make);
    for (int step = 0; step < 60; ++step) {
        s.step();
        ASSERT_TRUE(s.onGpu()) << step;
        for (int i = 0; i < int(std::size(cases)); ++i) {
            const btRigidBody *g = s.gpu->body(i), *k = s.stock->body(i);
            EXPECT_LT((g->getLinearVelocity() - k->getLinearVelocity()).length(), 1e-5) << "body " << i << " step " << step;
            EXPECT_LT((g->getAngularVelocity() - k->getAngularVelocity()).length(), 1e-5) << "body " << i << " step " << step;
        }
    }
    for (int i = 0; i < int(std::size(cases)); ++i) EXPECT_LT(s.distance(i), 1e-5) << "body " << i;
    // What applyDamping does: the slow one at rest at once; the cut one at 0.5 - 0.005 a step
    // (less its plain damping); the one without the setting still moving.
    EXPECT_EQ(s.gpu->body(0)->getLinearVelocity().length(), 0.0f);
    EXPECT_LT(s.gpu->body(1)->getLinearVelocity().length(), 0.5 - 60 * 0.005);
    EXPECT_GT(s.gpu->body(2)->getLinearVelocity().length(), 1.0);
    EXPECT_NEAR(s.gpu->body(3)->getLinearVelocity().length(), 0.05, 1e-6);
    EXPECT_EQ(s.gpu->body(4)->getAngularVelocity().length(), 0.0f);
}

// The three gyroscopic terms (BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT, _IMPLICIT_WORLD, _IMPLICIT_BODY,
// each on its own body; a fourth without any): a weightless plate spun about its intermediate
// axis with a small wobble flips over (the Dzhanibekov effect) on stock and on btgpu alike, the
// explicit one bounded by m_maxGyroscopicForce. Without a term the spin stays put.
TEST(BodyProperties, GyroscopicTermsAsStock)
{
    const int flags[] = {BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT, BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD,
                         BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY, 0};
    auto make = [&](WorldKind k, const Config& c) {
        auto scene = std::make_unique<Scene>(k, c, "gyroscopic");
        btBoxShape* plate = scene->boxShape(btVector3(0.1f, 0.5f, 1.0f));
        for (int i = 0; i < 4; ++i) {
            btRigidBody* b = scene->addBody(plate, 2, btVector3(btScalar(5 * i), 0, 0));
            b->setFlags(flags[i]);
            b->setGravity(btVector3(0, 0, 0));
            b->setAngularVelocity(btVector3(0.02f, 6.0f, 0.02f));
            b->setActivationState(DISABLE_DEACTIVATION);
        }
        scene->world().getSolverInfo().m_maxGyroscopicForce = 50;
        return ScenePtr(std::move(scene));
    };
    SideBySide s(make);
    double lowest[4] = {1e9, 1e9, 1e9, 1e9};  // of the spin about the body's own intermediate axis
    for (int step = 0; step < 180; ++step) {
        s.step();
        ASSERT_TRUE(s.onGpu()) << step;
        for (int i = 0; i < 4; ++i) {
            const btRigidBody *g = s.gpu->body(i), *k = s.stock->body(i);
            const btVector3 dw = g->getAngularVelocity() - k->getAngularVelocity();
            EXPECT_LT(dw.length(), 1e-3 * 6.0) << "body " << i << " step " << step;
            const btVector3 local = g->getWorldTransform().getBasis().transpose() * g->getAngularVelocity();
            lowest[i] = std::min(lowest[i], double(local.y()));
        }
    }
    std::printf("gyroscopic: lowest spin about the intermediate axis over 3 s: explicit %.3f, world %.3f, body %.3f, none %.3f rad/s\n",
                lowest[0], lowest[1], lowest[2], lowest[3]);
    for (int i = 0; i < 3; ++i) EXPECT_LT(lowest[i], -3.0) << "body " << i << " flips over";
    EXPECT_NEAR(lowest[3], 6.0, 1e-3);  // no term: the spin keeps its axis
}

// A body made kinematic by its flag alone keeps its mass, which stock's solver moves it by: the
// bullet mode (stock's answers) leaves such a world to the CPU path (cpu_path_rules.cpp's rule);
// the default solver (judged on physics) holds it still as every kinematic body, and a kinematic
// body without mass is served in both.
TEST(CpuPathRules, KinematicBodyWithMassLeavesOnlyTheBulletMode)
{
    for (bool massless : {false, true})
        for (const Config& config : {Config(), Config::bulletMode()}) {
            const bool bullet = config.solver == SolverKind::BatchedPgs;
            SCOPED_TRACE(std::string(bullet ? "bullet mode" : "default") + (massless ? ", setMassProps(0)" : ""));
            scenes::ScenePtr scene = scenes::dropRow(WorldKind::Gpu, config);
            scene->step();
            btRigidBody* b = scene->body(2);
            b->setCollisionFlags(b->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
            if (massless) b->setMassProps(0, btVector3(0, 0, 0));
            scene->step();
            const Report& r = *scene->report();
            EXPECT_EQ(r.gpuPath, !bullet || massless) << r.cpuPathReason;
        }
}
