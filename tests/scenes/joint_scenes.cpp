// joint_scenes.cpp — the joint scenes of joint_scenes.h.
#include "scenes/joint_scenes.h"

#include "scenes/scene_specs.h"

#include <cmath>

namespace btgpu::scenes {

namespace {
btVector3 bobStart(double degrees)
{
    const double a = degrees * M_PI / 180.0;
    return btVector3(btScalar(kPendulumLength * std::sin(a)), btScalar(kPendulumPivotY - kPendulumLength * std::cos(a)),
                     0);
}
}  // namespace

ScenePtr pendulum(WorldKind kind, const Config& config, double degrees)
{
    auto s = std::make_unique<Scene>(kind, config, "pendulum");
    const btVector3 start = bobStart(degrees);
    btRigidBody* bob = s->addBody(s->sphereShape(0.1f), 1.0f, start);
    bob->setActivationState(DISABLE_DEACTIVATION);
    // The pivot in the bob's frame, and the fixed body's world pivot.
    s->addJoint(new btPoint2PointConstraint(*bob, btVector3(0, btScalar(kPendulumPivotY), 0) - start));
    return s;
}

ScenePtr chain(WorldKind kind, const Config& config, int links)
{
    auto s = std::make_unique<Scene>(kind, config, "chain");
    s->addBody(s->boxShape(btVector3(5, 0.5f, 5)), 0.0f, btVector3(0, -0.5f, 0));
    btRigidBody* above = s->addBody(s->boxShape(btVector3(0.1f, 0.1f, 0.1f)), 0.0f, btVector3(0, btScalar(kChainAnchorY), 0));
    btSphereShape* ball = s->sphereShape(0.05f);
    const btScalar half = btScalar(kChainPitch / 2);
    for (int i = 0; i < links; ++i) {
        const btScalar y = btScalar(kChainAnchorY - kChainPitch * (i + 1));
        btRigidBody* link = s->addBody(ball, 1.0f, btVector3(0, y, 0));
        link->setActivationState(DISABLE_DEACTIVATION);
        s->addJoint(new btPoint2PointConstraint(*above, *link, btVector3(0, -half, 0), btVector3(0, half, 0)));
        above = link;
    }
    return s;
}

ScenePtr breakingPendulum(WorldKind kind, const Config& config, double threshold)
{
    ScenePtr s = pendulum(kind, config, 90.0);
    s->joint(0)->setBreakingImpulseThreshold(btScalar(threshold));
    return s;
}

ScenePtr jointedPair(WorldKind kind, const Config& config)
{
    auto s = std::make_unique<Scene>(kind, config, "jointed_pair");
    s->addBody(s->boxShape(btVector3(10, 0.5f, 10)), 0.0f, btVector3(0, -0.5f, 0));
    btBoxShape* box = s->boxShape(btVector3(0.5f, 0.5f, 0.5f));
    btRigidBody* a = s->addBody(box, 1.0f, btVector3(-0.5f, 0.51f, 0));
    btRigidBody* b = s->addBody(box, 1.0f, btVector3(0.5f, 0.51f, 0));
    s->addJoint(new btPoint2PointConstraint(*a, *b, btVector3(0.5f, 0, 0), btVector3(-0.5f, 0, 0)));
    return s;
}

ScenePtr hingeDoor(WorldKind kind, const Config& config, double speed, double maxImpulse, double lower, double upper)
{
    auto s = std::make_unique<Scene>(kind, config, "hinge_door");
    s->addBody(s->boxShape(btVector3(5, 0.5f, 5)), 0.0f, btVector3(0, -0.5f, 0));
    btRigidBody* door = s->addBody(s->boxShape(btVector3(0.5f, 1.0f, 0.05f)), 5.0f, btVector3(0.5f, 1.05f, 0));
    door->setActivationState(DISABLE_DEACTIVATION);
    auto* hinge = s->addJoint(new btHingeConstraint(*door, btVector3(-0.5f, 0, 0), btVector3(0, 1, 0)));
    if (upper >= lower) hinge->setLimit(btScalar(lower), btScalar(upper));
    hinge->enableAngularMotor(true, btScalar(speed), btScalar(maxImpulse));
    return s;
}

ScenePtr gearPair(WorldKind kind, const Config& config, double ratio, double speed)
{
    auto s = std::make_unique<Scene>(kind, config, "gear_pair");
    btCollisionShape* wheel = s->ownShape(new btCylinderShape(btVector3(0.5f, 0.1f, 0.5f)));
    btRigidBody* a = s->addBody(wheel, 2.0f, btVector3(-1.0f, 2.0f, 0));
    btRigidBody* b = s->addBody(wheel, 2.0f, btVector3(1.2f, 2.0f, 0));
    for (btRigidBody* w : {a, b}) w->setActivationState(DISABLE_DEACTIVATION);
    auto* hingeA = s->addJoint(new btHingeConstraint(*a, btVector3(0, 0, 0), btVector3(0, 1, 0)));
    s->addJoint(new btHingeConstraint(*b, btVector3(0, 0, 0), btVector3(0, 1, 0)));
    if (speed != 0.0) hingeA->enableAngularMotor(true, btScalar(speed), 1.0f);
    else a->setAngularVelocity(btVector3(0, 3, 0));
    s->addJoint(new btGearConstraint(*a, *b, btVector3(0, 1, 0), btVector3(0, 1, 0), btScalar(ratio)));
    return s;
}

ScenePtr ragdolls(WorldKind kind, const Config& config, int count)
{
    auto s = std::make_unique<Scene>(kind, config, "ragdolls");
    const spec::Scene data = spec::makeRagdolls(count);
    std::vector<btRigidBody*> bodies;
    for (const spec::BodySpec& b : data.bodies) {
        btCollisionShape* shape = b.shape == spec::ShapeKind::Capsule
                                      ? static_cast<btCollisionShape*>(s->ownShape(new btCapsuleShape(b.radius, 2 * b.half[1])))
                                      : s->boxShape(btVector3(b.half[0], b.half[1], b.half[2]));
        btTransform xf(btQuaternion(b.rot[0], b.rot[1], b.rot[2], b.rot[3]), btVector3(b.pos[0], b.pos[1], b.pos[2]));
        btRigidBody* body = s->addBody(shape, b.mass, xf, Material{b.friction, b.restitution});
        body->setDamping(b.linearDamping, b.angularDamping);
        bodies.push_back(body);
    }
    auto frame = [](const float* f) {
        return btTransform(btQuaternion(f[3], f[4], f[5], f[6]), btVector3(f[0], f[1], f[2]));
    };
    for (const spec::JointSpec& j : data.joints) {
        btRigidBody& a = *bodies[size_t(j.a)];
        btRigidBody& b = *bodies[size_t(j.b)];
        if (j.kind == spec::JointSpec::Kind::Hinge) {
            auto* h = s->addJoint(new btHingeConstraint(a, b, frame(j.frameA), frame(j.frameB)), true);
            h->setLimit(j.limit[0], j.limit[1]);
        } else {
            auto* c = s->addJoint(new btConeTwistConstraint(a, b, frame(j.frameA), frame(j.frameB)), true);
            c->setLimit(j.limit[0], j.limit[1], j.limit[2]);
        }
    }
    return s;
}


ScenePtr fixedBoxes(WorldKind kind, const Config& config)
{
    auto s = std::make_unique<Scene>(kind, config, "fixed_boxes");
    s->addBody(s->boxShape(btVector3(5, 0.5f, 5)), 0.0f, btVector3(0, -0.5f, 0));
    btBoxShape* cube = s->boxShape(btVector3(0.2f, 0.2f, 0.2f));
    btRigidBody* anchor = s->addBody(cube, 0.0f, btVector3(0, 3, 0));
    btRigidBody* arm = s->addBody(cube, 2.0f, btVector3(0.6f, 3, 0));
    arm->setActivationState(DISABLE_DEACTIVATION);
    s->addJoint(new btFixedConstraint(*anchor, *arm, btTransform(btQuaternion::getIdentity(), btVector3(0.3f, 0, 0)),
                                      btTransform(btQuaternion::getIdentity(), btVector3(-0.3f, 0, 0))),
                true);
    btRigidBody* left = s->addBody(cube, 1.0f, btVector3(-2.0f, 0.7f, 0));
    btRigidBody* right = s->addBody(cube, 3.0f, btVector3(-1.6f, 0.7f, 0));
    left->setActivationState(DISABLE_DEACTIVATION);
    right->setActivationState(DISABLE_DEACTIVATION);
    s->addJoint(new btFixedConstraint(*left, *right, btTransform(btQuaternion::getIdentity(), btVector3(0.2f, 0, 0)),
                                      btTransform(btQuaternion::getIdentity(), btVector3(-0.2f, 0, 0))),
                true);
    return s;
}

ScenePtr sixDofMotors(WorldKind kind, const Config& config, double spin, int order)
{
    auto s = std::make_unique<Scene>(kind, config, "sixdof_motors");
    btRigidBody* box = s->addBody(s->boxShape(btVector3(0.3f, 0.1f, 0.2f)), 2.0f, btVector3(0, 2, 0));
    box->setActivationState(DISABLE_DEACTIVATION);
    auto* d = s->addJoint(new btGeneric6DofSpring2Constraint(*box, btTransform::getIdentity(), RotateOrder(order)));
    d->setLinearLowerLimit(btVector3(-0.3f, 0, 0));
    d->setLinearUpperLimit(btVector3(0.3f, 0, 0));
    d->setAngularLowerLimit(btVector3(0, 0, 1));
    d->setAngularUpperLimit(btVector3(0, 0, -1));
    d->enableMotor(0, true);
    d->setTargetVelocity(0, 0.5f);
    d->setMaxMotorForce(0, 40.0f);
    d->enableMotor(5, true);
    d->setTargetVelocity(5, btScalar(spin));
    d->setMaxMotorForce(5, 3.0f);
    return s;
}

ScenePtr sixDofSprings(WorldKind kind, const Config& config, double linStiffness, double angStiffness, bool limited)
{
    auto s = std::make_unique<Scene>(kind, config, "sixdof_springs");
    btBoxShape* shape = s->boxShape(btVector3(0.3f, 0.1f, 0.2f));
    const btVector3 at[2] = {btVector3(0, 2, 0), btVector3(2, 2, 0)};
    for (int k = 0; k < 2; ++k) {
        btRigidBody* box = s->addBody(shape, 2.0f, at[k]);
        box->setActivationState(DISABLE_DEACTIVATION);
        auto* d = s->addJoint(new btGeneric6DofSpring2Constraint(btTypedConstraint::getFixedBody(), *box,
                                                                 btTransform(btQuaternion::getIdentity(), at[k]),
                                                                 btTransform::getIdentity()));
        for (int axis = 0; axis < 6; ++axis) d->setLimit(axis, 0, 0);
        const int axis = k == 0 ? 1 : 5;
        d->setLimit(axis, 1, -1);  // free
        d->enableSpring(axis, true);
        d->setStiffness(axis, btScalar(k == 0 ? linStiffness : angStiffness), limited);
        d->setDamping(axis, k == 0 ? 0.2f : 0.005f, limited);
        d->setEquilibriumPoint(axis, k == 0 ? -0.3f : 0.8f);
    }
    return s;
}

ScenePtr sixDofServos(WorldKind kind, const Config& config, double angle)
{
    auto s = std::make_unique<Scene>(kind, config, "sixdof_servos");
    btRigidBody* box = s->addBody(s->boxShape(btVector3(0.3f, 0.1f, 0.2f)), 2.0f, btVector3(0, 2, 0));
    box->setActivationState(DISABLE_DEACTIVATION);
    auto* d = s->addJoint(new btGeneric6DofSpring2Constraint(*box, btTransform::getIdentity()));
    d->setLinearLowerLimit(btVector3(-0.5f, 0, 0));
    d->setLinearUpperLimit(btVector3(0.5f, 0, 0));
    d->setAngularLowerLimit(btVector3(0, 0, 1));
    d->setAngularUpperLimit(btVector3(0, 0, -1));
    d->enableMotor(0, true);
    d->setServo(0, true);
    d->setServoTarget(0, 0.2f);
    d->setTargetVelocity(0, 0.5f);
    d->setMaxMotorForce(0, 40.0f);
    d->enableMotor(5, true);
    d->setServo(5, true);
    d->setServoTarget(5, btScalar(angle));
    d->setTargetVelocity(5, 2.0f);
    d->setMaxMotorForce(5, 3.0f);
    return s;
}

ScenePtr hinge2Wheels(WorldKind kind, const Config& config)
{
    auto s = std::make_unique<Scene>(kind, config, "hinge2_wheels");
    s->addBody(s->boxShape(btVector3(5, 0.5f, 5)), 0.0f, btVector3(0, -0.5f, 0));
    const btScalar wheelY = 0.25f, chassisY = wheelY + 0.6f;
    btRigidBody* chassis = s->addBody(s->boxShape(btVector3(1, 0.1f, 0.5f)), 4.0f, btVector3(0, chassisY, 0));
    chassis->setActivationState(DISABLE_DEACTIVATION);
    btSphereShape* wheel = s->sphereShape(0.25f);
    for (int k = 0; k < 4; ++k) {
        btVector3 at((k & 1) ? 0.8f : -0.8f, wheelY, (k & 2) ? 0.5f : -0.5f);
        btRigidBody* w = s->addBody(wheel, 0.5f, at);
        w->setActivationState(DISABLE_DEACTIVATION);
        btVector3 up(0, 1, 0), axle(0, 0, 1);
        auto* h = s->addJoint(new btHinge2Constraint(*chassis, *w, at, up, axle), true);
        h->setDamping(2, 1.0f);  // the suspension's damper (as constructed: 0.01, rings for a minute)
    }
    return s;
}

ScenePtr generic6DofMotors(WorldKind kind, const Config& config, double spin, bool frameOffset)
{
    auto s = std::make_unique<Scene>(kind, config, "generic6dof_motors");
    btRigidBody* box = s->addBody(s->boxShape(btVector3(0.3f, 0.1f, 0.2f)), 2.0f, btVector3(0, 2, 0));
    box->setActivationState(DISABLE_DEACTIVATION);
    auto* d = s->addJoint(new btGeneric6DofConstraint(*box, btTransform::getIdentity(), true));
    d->setUseFrameOffset(frameOffset);
    d->setLinearLowerLimit(btVector3(-0.3f, 0, 0));
    d->setLinearUpperLimit(btVector3(0.3f, 0, 0));
    d->setAngularLowerLimit(btVector3(0, 0, 1));
    d->setAngularUpperLimit(btVector3(0, 0, -1));
    btTranslationalLimitMotor* lin = d->getTranslationalLimitMotor();
    lin->m_enableMotor[0] = true;
    lin->m_targetVelocity[0] = 0.5f;
    lin->m_maxMotorForce[0] = 40.0f;
    btRotationalLimitMotor* rot = d->getRotationalLimitMotor(2);
    rot->m_enableMotor = true;
    rot->m_targetVelocity = btScalar(spin);
    rot->m_maxMotorForce = 3.0f;
    return s;
}

ScenePtr universalPendulum(WorldKind kind, const Config& config)
{
    auto s = std::make_unique<Scene>(kind, config, "universal_pendulum");
    btRigidBody* anchor = s->addBody(s->boxShape(btVector3(0.1f, 0.1f, 0.1f)), 0.0f, btVector3(0, 3, 0));
    const btVector3 pivot(0, 2.9f, 0);
    const btQuaternion turn = btQuaternion(btVector3(1, 0, 0), 0.5f) * btQuaternion(btVector3(0, 0, 1), 0.3f);
    const btVector3 centre = pivot + quatRotate(turn, btVector3(0, -0.4f, 0));
    btRigidBody* bob = s->addBody(s->boxShape(btVector3(0.1f, 0.4f, 0.1f)), 1.0f, btTransform(turn, centre));
    bob->setActivationState(DISABLE_DEACTIVATION);
    bob->setAngularVelocity(quatRotate(turn, btVector3(0, 2.0f, 0)));
    btVector3 axis1(1, 0, 0), axis2(0, 0, 1);
    s->addJoint(new btUniversalConstraint(*anchor, *bob, pivot, axis1, axis2), true);
    return s;
}

ScenePtr generic6DofSprings(WorldKind kind, const Config& config, double linStiffness, double angStiffness,
                            double damping)
{
    auto s = std::make_unique<Scene>(kind, config, "generic6dof_springs");
    s->world().setGravity(btVector3(0, 0, 0));
    btBoxShape* shape = s->boxShape(btVector3(0.3f, 0.1f, 0.2f));
    const btVector3 at[2] = {btVector3(0, 2, 0), btVector3(2, 2, 0)};
    for (int k = 0; k < 2; ++k) {
        btRigidBody* box = s->addBody(shape, 2.0f, at[k]);
        box->setActivationState(DISABLE_DEACTIVATION);
        auto* d = s->addJoint(new btGeneric6DofSpringConstraint(btTypedConstraint::getFixedBody(), *box,
                                                                btTransform(btQuaternion::getIdentity(), at[k]),
                                                                btTransform::getIdentity(), true));
        for (int axis = 0; axis < 6; ++axis) d->setLimit(axis, 0, 0);
        const int axis = k == 0 ? 1 : 5;
        d->setLimit(axis, 1, -1);  // free
        d->enableSpring(axis, true);
        d->setStiffness(axis, btScalar(k == 0 ? linStiffness : angStiffness));
        d->setDamping(axis, btScalar(damping));
        d->setEquilibriumPoint(axis, k == 0 ? -0.3f : 0.8f);
    }
    return s;
}

btQuaternion coneMotorTarget()
{
    return btQuaternion(btVector3(0, 0, 1), 0.4f) * btQuaternion(btVector3(1, 0, 0), 0.3f);
}

ScenePtr coneTwistMotor(WorldKind kind, const Config& config, int variant)
{
    auto s = std::make_unique<Scene>(kind, config, "cone_twist_motor");
    s->world().setGravity(btVector3(0, 0, 0));
    btRigidBody* anchor = s->addBody(s->boxShape(btVector3(0.1f, 0.1f, 0.1f)), 0.0f, btVector3(0, 3, 0));
    btRigidBody* cube = s->addBody(s->boxShape(btVector3(0.2f, 0.2f, 0.2f)), 2.0f, btVector3(0, 2.7f, 0));
    cube->setActivationState(DISABLE_DEACTIVATION);
    const btQuaternion down(btVector3(0, 0, 1), btScalar(-M_PI / 2));  // frame x along -y
    auto* c = s->addJoint(new btConeTwistConstraint(*anchor, *cube, btTransform(down, btVector3(0, -0.1f, 0)),
                                                    btTransform(down, btVector3(0, 0.2f, 0))),
                          true);
    c->setLimit(0.8f, 0.8f, 0.5f);
    if (variant == 1) {
        c->setMaxMotorImpulseNormalized(0.02f);
        c->setAngularOnly(true);
        c->setDamping(0.2f);
    } else {
        c->setMaxMotorImpulse(0.02f);
    }
    c->setMotorTargetInConstraintSpace(coneMotorTarget());
    c->enableMotor(true);
    return s;
}

ScenePtr bench3Ragdolls(WorldKind kind, const Config& config, int rows)
{
    auto s = std::make_unique<Scene>(kind, config, "bench3_ragdolls");
    s->world().getSolverInfo().m_numIterations = 5;
    s->addBody(s->boxShape(btVector3(250, 50, 250)), 0.0f, btVector3(0, -50, 0));
    const float scale = 3.5f;
    spec::RagdollPart parts[11];
    spec::JointSpec joints[10];
    spec::ragdollLayout(scale, parts, joints);
    btCapsuleShape* shapes[11];
    for (int i = 0; i < 11; ++i) shapes[i] = s->ownShape(new btCapsuleShape(parts[i].radius, parts[i].height));
    auto frame = [](const float* f) {
        return btTransform(btQuaternion(f[3], f[4], f[5], f[6]), btVector3(f[0], f[1], f[2]));
    };
    btVector3 pos(0, 1, 0);
    for (int size = rows; size > 0; --size) {
        const float offset = -float(size) * 6.0f * 0.5f;
        for (int i = 0; i < size; ++i) {
            pos[0] = offset + float(i) * 6.0f;
            btRigidBody* body[11];
            for (int k = 0; k < 11; ++k) {
                const spec::RagdollPart& p = parts[k];
                const btTransform xf(btQuaternion(btVector3(0, 0, 1), p.roll), pos + btVector3(p.x, p.y, 0));
                body[k] = s->addBody(shapes[k], 1.0f, xf);
                body[k]->setDamping(0.05f, 0.85f);
                body[k]->setDeactivationTime(0.8f);
                body[k]->setSleepingThresholds(1.6f, 2.5f);
            }
            for (const spec::JointSpec& j : joints) {
                btRigidBody& a = *body[j.a];
                btRigidBody& b = *body[j.b];
                if (j.kind == spec::JointSpec::Kind::Hinge) {
                    auto* h = s->addJoint(new btHingeConstraint(a, b, frame(j.frameA), frame(j.frameB)), true);
                    h->setLimit(j.limit[0], j.limit[1]);
                } else {
                    auto* c = s->addJoint(new btConeTwistConstraint(a, b, frame(j.frameA), frame(j.frameB)), true);
                    c->setLimit(j.limit[0], j.limit[1], j.limit[2]);
                }
            }
        }
        pos[1] += 7.0f;
        pos[2] -= 2.0f;
    }
    return s;
}

ScenePtr newtonsCradle(WorldKind kind, const Config& config, int count)
{
    auto s = std::make_unique<Scene>(kind, config, "newtons_cradle");
    s->world().setGravity(btVector3(0, -10, 0));
    btSphereShape* sphere = s->sphereShape(1);
    btVector3 position(0, 15, 0);
    for (int i = 0; i < count; ++i) {
        btRigidBody* top = s->addBody(sphere, 1, position);
        btRigidBody* bottom = s->addBody(sphere, 1, position - btVector3(0, 8, 0));
        bottom->setFriction(0);
        bottom->setRestitution(1);
        top->setActivationState(DISABLE_DEACTIVATION);
        bottom->setActivationState(DISABLE_DEACTIVATION);
        s->addJoint(new btPoint2PointConstraint(*top, btVector3(0, 0, 0)), true);
        // the slider's axis (x in its frames) turned onto y, the pivot at the top sphere's centre
        btQuaternion turn;
        turn.setEuler(0, 0, -SIMD_HALF_PI);
        btTransform inTop(turn), inBottom(turn);
        inBottom.setOrigin(bottom->getWorldTransform().inverse()(top->getWorldTransform().getOrigin()));
        auto* rod = s->addJoint(new btSliderConstraint(*top, *bottom, inTop, inBottom, true), true);
        rod->setLowerLinLimit(0);
        rod->setUpperLinLimit(0);
        rod->setLowerAngLimit(0);
        rod->setUpperAngLimit(0);
        position.setX(position.x() - btScalar(2.1));
    }
    return s;
}

}  // namespace btgpu::scenes
