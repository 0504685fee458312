// body_properties_test.cpp — per-body settings an app sets on btRigidBody, on stock Bullet and
// on btgpu side by side: damping, linear and angular factors, per-body gravity,
// CF_NO_CONTACT_RESPONSE, an applied torque. Each must move its body as stock does.
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
