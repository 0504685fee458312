// app_changes_test.cpp — what an app does between steps, done to stock Bullet and to
// btGpuDynamicsWorld alike: remove and add bodies, change gravity, apply impulses, drive a
// kinematic body, teleport a body, step with substeps and interpolation.
#include <gtest/gtest.h>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

TEST(AppChanges, RemoveAndAddBodyMidRun)
{
    SideBySide s(scenes::dropRow);
    s.step(20);
    s.both([](Scene& scene) {
        scene.removeBody(scene.body(2));  // the middle box, while falling
        scene.addBody(scene.sphereShape(.5), 1, btVector3(0, 3, 0));
    });
    for (int i = 0; i < 130; ++i) {
        s.step();
        for (int b = 1; b <= 3; ++b) ASSERT_LT(s.distance(b), tol::kRestHeight) << "step " << i << " body " << b;
    }
    EXPECT_TRUE(s.onGpu());
}

TEST(AppChanges, GravityChangedMidRun)
{
    SideBySide s(scenes::freeFall);
    s.step(30);
    s.both([](Scene& scene) {
        // Bullet's setGravity sets the gravity of the bodies in the world now; a body added
        // later takes the world's gravity in addRigidBody; a body's own setGravity holds until
        // the world's next setGravity.
        scene.world().setGravity(btVector3(1, -2, 0));
        scene.addBody(scene.boxShape(btVector3(.5, .5, .5)), 1, btVector3(5, 30, 0));
    });
    for (int i = 0; i < 30; ++i) {
        s.step();
        ASSERT_LT(s.distance(1), tol::kFreeFallPosition) << "step " << i;
        ASSERT_LT(s.distance(2), tol::kFreeFallPosition) << "step " << i;
    }
    s.both([](Scene& scene) { scene.body(2)->setGravity(btVector3(0, -5, 0)); });
    for (int i = 0; i < 30; ++i) {
        s.step();
        ASSERT_LT(s.distance(1), tol::kFreeFallPosition) << "step " << i;
        ASSERT_LT(s.distance(2), tol::kFreeFallPosition) << "step " << i;
    }
    // The change reached the bodies: box 1 has drifted +x under the new gravity.
    EXPECT_GT(s.gpu->body(1)->getWorldTransform().getOrigin().x(), 0.1);
}

TEST(AppChanges, CentralImpulseBetweenSteps)
{
    SideBySide s(scenes::freeFall);
    s.step(10);
    s.both([](Scene& scene) {
        scene.body(1)->activate();
        scene.body(1)->applyCentralImpulse(btVector3(1, 5, btScalar(.5)));
    });
    for (int i = 0; i < 60; ++i) {
        s.step();
        ASSERT_LT(s.distance(1), tol::kFreeFallPosition) << "step " << i;
    }
}

TEST(AppChanges, ImpulseLiftsRestingBox)
{
    SideBySide s(scenes::restingBox);
    s.step(20);
    // Straight up: it rises ~0.45 m and lands flat again.
    s.both([](Scene& scene) {
        scene.body(1)->activate();
        scene.body(1)->applyCentralImpulse(btVector3(0, 3, 0));
    });
    s.step(10);
    EXPECT_GT(s.gpuY(1), 0.7) << "the impulse did not reach the GPU world";
    s.step(110);
    // Back at rest at stock's height; sideways, no more drift than stock's own landing has.
    const btVector3 g = s.gpu->body(1)->getWorldTransform().getOrigin();
    const btVector3 k = s.stock->body(1)->getWorldTransform().getOrigin();
    EXPECT_NEAR(g.y(), k.y(), tol::kRestHeight);
    EXPECT_LE(btVector3(g.x(), 0, g.z()).length(), btVector3(k.x(), 0, k.z()).length() + tol::kExtraDrift);
}

TEST(AppChanges, KinematicBoxPushesBoxes)
{
    SideBySide s(scenes::kinematicPush);
    s.step(240);  // 4 s: the pusher has travelled 4 m and pushed the row
    ASSERT_GT(s.stock->body(1)->getWorldTransform().getOrigin().x(), 0.5) << "stock pushed nothing: scene is wrong";
    for (int b = 1; b <= 3; ++b) EXPECT_LT(s.distance(b), tol::kPushedPosition) << "box " << b;
    // The pusher follows its motion state exactly on both.
    EXPECT_LT(s.distance(4), tol::kFreeFallPosition);
    EXPECT_TRUE(s.onGpu());
}

TEST(AppChanges, TeleportedBody)
{
    SideBySide s(scenes::restingBox);
    s.step(20);
    s.both([](Scene& scene) {
        btTransform t(btQuaternion(btVector3(0, 1, 0), btScalar(.3)), btVector3(2, 3, 1));
        btRigidBody* box = scene.body(1);
        box->setWorldTransform(t);
        box->getMotionState()->setWorldTransform(t);
        box->activate();
    });
    s.step();
    EXPECT_LT(s.distance(1), tol::kFreeFallPosition);
    EXPECT_GT(s.gpuY(1), 2.9) << "the GPU world did not take the new transform";
    s.step(120);
    EXPECT_LT(s.distance(1), tol::kRestHeight);
}

TEST(AppChanges, SubstepsAndInterpolation)
{
    SideBySide s(scenes::freeFall);
    // A cube's inertia is isotropic, so Bullet's (default) gyroscopic term is zero and the spin
    // stays constant: the interpolated orientation is pure integration.
    s.both([](Scene& scene) { scene.body(1)->setAngularVelocity(btVector3(0, 2, 1)); });
    for (int i = 0; i < 100; ++i) {
        // 1/100 s per call with a 1/60 s fixed step: some calls run no substep and only
        // interpolate, others run one; the motion state must carry the interpolated transform.
        s.stock->step(btScalar(1) / 100, 10, kStep);
        s.gpu->step(btScalar(1) / 100, 10, kStep);
        btTransform a, b;
        s.stock->body(1)->getMotionState()->getWorldTransform(a);
        s.gpu->body(1)->getMotionState()->getWorldTransform(b);
        ASSERT_LT((a.getOrigin() - b.getOrigin()).length(), tol::kInterpolatedTransform) << "call " << i;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(a.getBasis()[r][c], b.getBasis()[r][c], tol::kInterpolatedTransform)
                    << "call " << i << " basis " << r << "," << c;
    }
}
