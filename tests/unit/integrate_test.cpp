// integrate_test.cpp — the integrate stage against its CPU reference, and against physics:
// free fall follows x = x0 + v t + g t^2 / 2 in Bullet's symplectic form, damping decays as
// (1 - d)^t, a torque-free spin about a principal axis keeps its rate.
#include "reference/integrate.h"
#include "shared/integrate.h"
#include "stages/integrate.h"
#include "stages/sync_bodies.h"
#include "test_device.h"
#include "tolerances.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <gtest/gtest.h>
#include <random>

using namespace btgpu;

namespace {

reference::Bodies randomBodies(int n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    reference::Bodies b;
    for (int i = 0; i < n; ++i) {
        b.pos.push_back(btgMake4(10 * u(rng), 10 * u(rng), 10 * u(rng), 0));
        b.rot.push_back(btgQuatNormalize(btgMake4(u(rng), u(rng), u(rng), u(rng) + 2.0f)));
        b.linVel.push_back(btgMake4(u(rng), u(rng), u(rng), 0));
        b.angVel.push_back(btgMake4(3 * u(rng), 3 * u(rng), 3 * u(rng), 0));
        b.extForce.push_back(i % 3 == 0 ? btgMake4(u(rng), u(rng), u(rng), 0) : btgZero4());
        b.extTorque.push_back(i % 5 == 0 ? btgMake4(u(rng), u(rng), u(rng), 0) : btgZero4());
        b.pushLin.push_back(i % 4 == 0 ? btgMake4(0.1f * u(rng), 0.1f * u(rng), 0, 0) : btgZero4());
        b.pushAng.push_back(i % 4 == 0 ? btgMake4(0.1f * u(rng), 0, 0.1f * u(rng), 0) : btgZero4());
        BtgBodyProps p{};
        p.invInertiaLocal = btgMake4(1.0f + u(rng) * 0.5f, 2.0f, 1.5f, 0);
        p.invMass = 0.5f;
        p.linearFactor = btgMake4(1, 1, 1, 0);
        p.angularFactor = btgMake4(1, 1, 1, 0);
        p.linearDamping = i % 2 ? 0.1f : 0.0f;
        p.angularDamping = i % 2 ? 0.2f : 0.0f;
        p.gravity = btgMake4(0, -10, 0, 0);
        p.friction = 0.5f;
        p.flags = (i % 7 == 0) ? BTG_BODY_STATIC : BTG_BODY_DYNAMIC | (i % 2 ? BTG_BODY_GYRO : 0u);
        if (i % 5 == 2) p.flags |= BTG_BODY_GYRO_EXPLICIT;
        if (i % 4 == 3) p.flags |= BTG_BODY_GYRO_WORLD;
        if (i % 3 == 1) {
            // Additional damping with thresholds that catch some of these velocities and a
            // damping coefficient above some speeds (applyDamping's cut).
            p.flags |= BTG_BODY_ADDITIONAL_DAMPING;
            p.additionalDampingFactor = 0.005f;
            p.additionalLinearThresholdSqr = 1.0f;
            p.additionalAngularThresholdSqr = 4.0f;
            p.linearDamping = 0.9f;
            p.angularDamping = 0.9f;
        }
        b.props.push_back(p);
    }
    return b;
}

void upload(DeviceWorld& w, const reference::Bodies& b)
{
    cl::Context& c = w.ctx;
    resizeBodies(w, int(b.props.size()));
    w.pos.upload(c, b.pos);
    w.rot.upload(c, b.rot);
    w.linVel.upload(c, b.linVel);
    w.angVel.upload(c, b.angVel);
    w.extForce.upload(c, b.extForce);
    w.extTorque.upload(c, b.extTorque);
    w.props.upload(c, b.props);
    std::vector<uint> counters(kNumCounters, 0);
    counters[kNanBody] = 0xffffffffu;
    w.counters.upload(c, counters);
}

void expectNear4(BtgFloat4 a, BtgFloat4 b, float tol, int row, const char* what)
{
    EXPECT_NEAR(a.x, b.x, tol) << what << " row " << row;
    EXPECT_NEAR(a.y, b.y, tol) << what << " row " << row;
    EXPECT_NEAR(a.z, b.z, tol) << what << " row " << row;
}

}  // namespace

TEST(Integrate, MatchesReference)
{
    const int n = 300;
    const float dt = 1.0f / 60.0f;
    reference::Bodies ref = randomBodies(n, 7);
    DeviceWorld w(test::context());
    upload(w, ref);
    predictMotion(w, dt);
    applyForces(w, dt, 2.0f);  // a bound some explicit terms reach
    // The solver would fill the push velocities; the test sets them directly.
    w.pushLin.upload(w.ctx, ref.pushLin);
    w.pushAng.upload(w.ctx, ref.pushAng);
    integrateTransforms(w, dt, 0.1f);
    std::vector<BtgFloat4> iw;
    reference::predictMotion(ref, dt);
    reference::applyForces(ref, dt, iw, 2.0f);
    reference::integrateTransforms(ref, dt, 0.1f);
    auto pos = w.pos.download(w.ctx, n), rot = w.rot.download(w.ctx, n);
    auto lin = w.linVel.download(w.ctx, n), ang = w.angVel.download(w.ctx, n);
    auto iwDev = w.invInertiaWorld.download(w.ctx, 3 * n);
    for (int i = 0; i < n; ++i) {
        expectNear4(pos[i], ref.pos[i], tol::kStageAbs * 10, i, "pos");
        expectNear4(rot[i], ref.rot[i], tol::kStageAbs, i, "rot");
        EXPECT_NEAR(rot[i].w, ref.rot[i].w, tol::kStageAbs);
        expectNear4(lin[i], ref.linVel[i], tol::kStageAbs, i, "linVel");
        expectNear4(ang[i], ref.angVel[i], tol::kStageAbs, i, "angVel");
        for (int k = 0; k < 3; ++k) expectNear4(iwDev[3 * i + k], iw[3 * i + k], tol::kStageAbs, i, "invInertiaWorld");
    }
}

TEST(Integrate, FreeFallDampingAndSpin)
{
    const float dt = 1.0f / 60.0f;
    reference::Bodies b = randomBodies(3, 1);
    for (int i = 0; i < 3; ++i) {
        b.pos[i] = btgZero4();
        b.rot[i] = btgMake4(0, 0, 0, 1);
        b.linVel[i] = btgZero4();
        b.angVel[i] = btgZero4();
        b.extForce[i] = b.extTorque[i] = btgZero4();
        b.props[i].flags = BTG_BODY_DYNAMIC;
        b.props[i].linearDamping = 0.0f;
        b.props[i].angularDamping = 0.0f;
    }
    b.props[1].linearDamping = 0.5f;  // damped
    b.linVel[1] = btgMake4(1, 0, 0, 0);
    b.props[1].gravity = btgZero4();
    b.angVel[2] = btgMake4(0, 0, 2, 0);  // spin about a principal axis, no gyroscopic flag
    DeviceWorld w(test::context());
    upload(w, b);
    std::vector<BtgFloat4> zero(3, btgZero4());
    const int steps = 60;
    for (int s = 0; s < steps; ++s) {
        predictMotion(w, dt);
        applyForces(w, dt);
        integrateTransforms(w, dt, 0.1f);
    }
    auto pos = w.pos.download(w.ctx, 3), lin = w.linVel.download(w.ctx, 3), ang = w.angVel.download(w.ctx, 3);
    // Symplectic Euler: v_n = g n dt, x_n = g dt^2 n (n + 1) / 2.
    float expected = -10.0f * dt * dt * steps * (steps + 1) / 2.0f;
    EXPECT_NEAR(pos[0].y, expected, 1e-4f);
    EXPECT_NEAR(lin[0].y, -10.0f, 1e-4f);
    EXPECT_NEAR(lin[1].x, std::pow(0.5f, 1.0f), 1e-4f);  // (1 - 0.5)^(60 dt) after one second
    EXPECT_NEAR(ang[2].z, 2.0f, 1e-6f);
}

// Bullet's integrateTransform: when the rotated quaternion's length overflows (a spin of
// 1e22 rad/s), the orientation is kept, never replaced by a zero quaternion.
TEST(Integrate, OverflowingSpinKeepsTheOrientation)
{
    const BtgFloat4 rot = btgQuatNormalize(btgMake4(0.1f, 0.2f, 0.3f, 0.9f));
    for (float w : {1e22f, 3e38f}) {
        BtgFloat4 q = btgIntegrateRotation(rot, btgMake4(w, 0, 0, 0), 1.0f / 60.0f);
        EXPECT_EQ(q.x, rot.x);
        EXPECT_EQ(q.y, rot.y);
        EXPECT_EQ(q.z, rot.z);
        EXPECT_EQ(q.w, rot.w);
    }
    // An ordinary spin still turns, and stays a unit quaternion.
    BtgFloat4 q = btgIntegrateRotation(rot, btgMake4(0, 3, 0, 0), 1.0f / 60.0f);
    EXPECT_NEAR(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, 1.0f, 1e-6f);
    EXPECT_GT(std::fabs(q.y - rot.y), 1e-3f);
}

// The three gyroscopic terms against Bullet's own btRigidBody functions for the same body
// (computeGyroscopicForceExplicit applied as convertBodies applies it, and the two implicit
// impulses), each alone and all together, on random anisotropic bodies.
TEST(Integrate, GyroscopicTermsAsBullet)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const float dt = 1.0f / 60.0f, maxGyro = 3.0f;
    btBoxShape shape(btVector3(0.1f, 0.5f, 1.0f));
    int bounded = 0;
    for (int i = 0; i < 200; ++i) {
        btVector3 inertia(0.2f + u(rng) * 0.1f, 1.0f + u(rng) * 0.5f, 3.0f + u(rng));
        btRigidBody::btRigidBodyConstructionInfo info(2.0f, nullptr, &shape, inertia);
        btRigidBody body(info);
        btQuaternion q(u(rng), u(rng), u(rng), 2.0f + u(rng));
        q.normalize();
        body.setWorldTransform(btTransform(q, btVector3(0, 0, 0)));
        body.updateInertiaTensor();
        const btVector3 w0(4 * u(rng), 4 * u(rng), 4 * u(rng));
        body.setAngularVelocity(w0);
        const btMatrix3x3& invIw = body.getInvInertiaTensorWorld();
        btVector3 gf = body.computeGyroscopicForceExplicit(maxGyro);
        bounded += gf.length() > maxGyro * 0.999f;
        const btVector3 expect[3] = {-(gf * invIw) * dt, body.computeGyroscopicImpulseImplicit_World(dt),
                                     body.computeGyroscopicImpulseImplicit_Body(dt)};
        const uint flags[3] = {BTG_BODY_GYRO_EXPLICIT, BTG_BODY_GYRO_WORLD, BTG_BODY_GYRO};
        BtgBodyProps p{};
        const btVector3 ii = body.getInvInertiaDiagLocal();
        p.invInertiaLocal = btgMake4(ii.x(), ii.y(), ii.z(), 0);
        const BtgFloat4 rot = btgMake4(q.x(), q.y(), q.z(), q.w()), w = btgMake4(w0.x(), w0.y(), w0.z(), 0);
        const BtgMat3 m = btgInvInertiaWorld(rot, p.invInertiaLocal);
        btVector3 all(0, 0, 0);
        for (int k = 0; k < 3; ++k) {
            p.flags = BTG_BODY_DYNAMIC | flags[k];
            const BtgFloat4 got = btgApplyAngularForces(w, btgZero4(), rot, m, p, dt, maxGyro) - w;
            const float scale = std::max(1e-3f, expect[k].length());
            EXPECT_NEAR(got.x, expect[k].x(), 2e-4f * scale + 1e-6f) << "body " << i << " term " << k;
            EXPECT_NEAR(got.y, expect[k].y(), 2e-4f * scale + 1e-6f) << "body " << i << " term " << k;
            EXPECT_NEAR(got.z, expect[k].z(), 2e-4f * scale + 1e-6f) << "body " << i << " term " << k;
            all += expect[k];
        }
        p.flags = BTG_BODY_DYNAMIC | BTG_BODY_GYRO | BTG_BODY_GYRO_EXPLICIT | BTG_BODY_GYRO_WORLD;
        const BtgFloat4 got = btgApplyAngularForces(w, btgZero4(), rot, m, p, dt, maxGyro) - w;
        const BtgFloat4 d = got - btgMake4(all.x(), all.y(), all.z(), 0);
        EXPECT_NEAR(std::sqrt(btgDot3(d, d)), 0.0f, 5e-4f * std::max(1e-3f, all.length()) + 1e-6f)
            << "body " << i;
    }
    EXPECT_GT(bounded, 10);  // the bound is exercised
}
