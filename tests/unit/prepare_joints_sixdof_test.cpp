// prepare_joints_sixdof_test.cpp — btGeneric6DofSpring2Constraint rows (and btFixedConstraint's)
// on the device against the CPU reference and against Bullet's own getInfo1/getInfo2 for the
// same bodies, each joint converted by compat's jointRow (the table the GPU path uploads): a
// fixed joint, mixed locked/limited/free axes with a motor in each rotation order, setParam
// stop/motor ERP and CFM, bounce at a hit limit, and the fixed body.
#include "joint_fixture.h"

#include "../../compat/joint_rows.h"
#include "../../compat/row_map.h"

using namespace btgpu;
using namespace btgpu::jointtest;


TEST(PrepareJoints, SixDofSpring2RowsMatchBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const RowMap map = s.rowsOf(a, b);
    const btTransform fa = frameInA(), fb = frameInB();
    std::vector<std::unique_ptr<btGeneric6DofSpring2Constraint>> c;
    c.emplace_back(new btFixedConstraint(*a, *b, fa, fb));
    // Mixed axes with a motor, in every rotation order: x locked, y limited (hit), z free;
    // angular x limited wide with a motor, y locked, z limited (hit, with bounce).
    for (int order = 0; order < 6; ++order) {
        auto* k = new btGeneric6DofSpring2Constraint(*a, *b, fa, fb, RotateOrder(order));
        k->setLinearLowerLimit(btVector3(0.05f, -0.1f, 1.0f));
        k->setLinearUpperLimit(btVector3(0.05f, 0.1f, -1.0f));
        k->setAngularLowerLimit(btVector3(-2.5f, 0.0f, 0.1f));
        k->setAngularUpperLimit(btVector3(2.5f, 0.0f, 0.2f));
        k->enableMotor(3, true);
        k->setTargetVelocity(3, 1.5f);
        k->setMaxMotorForce(3, 4.0f);
        k->enableMotor(2, true);  // a motor on the free linear axis
        k->setTargetVelocity(2, -0.7f);
        k->setMaxMotorForce(2, 9.0f);
        k->setBounce(5, 0.6f);
        k->setBounce(1, 0.4f);
        c.emplace_back(k);
    }
    // setParam: own stop ERP/CFM and motor ERP/CFM; the first row's own CFM then becomes what
    // the axes without their own read as info->cfm[0].
    auto* tuned = new btGeneric6DofSpring2Constraint(*a, *b, fa, fb);
    tuned->setLimit(3, -0.3f, 0.3f);
    tuned->setLimit(4, 0.0f, 0.0f);
    tuned->setLimit(5, 1.0f, -1.0f);
    tuned->setParam(BT_CONSTRAINT_STOP_CFM, 0.05f, 3);
    tuned->setParam(BT_CONSTRAINT_STOP_ERP, 0.7f, 4);
    tuned->setParam(BT_CONSTRAINT_STOP_CFM, 0.02f, 0);
    tuned->setParam(BT_CONSTRAINT_STOP_ERP, 0.4f, 1);
    tuned->enableMotor(5, true);
    tuned->setTargetVelocity(5, 2.0f);
    tuned->setMaxMotorForce(5, 1.0f);
    tuned->setParam(BT_CONSTRAINT_CFM, 0.03f, 5);
    tuned->setParam(BT_CONSTRAINT_ERP, 0.3f, 5);
    c.emplace_back(tuned);
    // On the fixed body (body A), frame A where b's frame stands, all locked.
    c.emplace_back(new btFixedConstraint(btTypedConstraint::getFixedBody(), *b, b->getWorldTransform() * fb, fb));
    BtgJoint last;
    ASSERT_TRUE(jointRow(*c.back(), map, 10, &last));
    EXPECT_EQ(last.bodyA, BTG_JOINT_FIXED_BODY);
    const RowKinds kinds = expectRowsAsBullet(s, map, c, BTG_JOINT_SIXDOF2);
    EXPECT_EQ(kinds.firstRows0, 6);      // a fixed joint: three angular, three linear rows
    EXPECT_GE(kinds.bounded, 6 * 6);     // one-sided rows of ranged axes were built
    EXPECT_GE(kinds.motors, 6 * 2 + 1);  // the motor rows
}

// Springs (linear and angular; stiffness and damping limited or not; with Bullet's infinite
// error flag), servos (linear and angular, free and limited, a target across the angle's wrap)
// and btHinge2Constraint as constructed (its suspension spring on linear z).
TEST(PrepareJoints, SixDofSpringAndServoRowsMatchBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const RowMap map = s.rowsOf(a, b);
    const btTransform fa = frameInA(), fb = frameInB();
    std::vector<std::unique_ptr<btGeneric6DofSpring2Constraint>> c;
    for (int order = 0; order < 6; ++order) {
        for (int limited = 0; limited < 2; ++limited) {
            auto* k = new btGeneric6DofSpring2Constraint(*a, *b, fa, fb, RotateOrder(order));
            k->setLinearLowerLimit(btVector3(1.0f, -0.5f, 0.0f));  // x free, y ranged, z locked
            k->setLinearUpperLimit(btVector3(-1.0f, 0.5f, 0.0f));
            k->setAngularLowerLimit(btVector3(1.0f, -0.4f, 0.2f));  // x free, y ranged, z ranged
            k->setAngularUpperLimit(btVector3(-1.0f, 0.4f, 0.9f));
            // Stiff enough that limiting (0.25 < omega dt, kd dt > m) changes them.
            for (int axis : {0, 1, 3, 4}) {
                k->enableSpring(axis, true);
                k->setStiffness(axis, axis < 3 ? 9000.0f : 300.0f, limited != 0);
                k->setDamping(axis, axis < 3 ? 400.0f : 50.0f, limited != 0);
            }
            k->setEquilibriumPoint();              // the current pose
            k->setEquilibriumPoint(0, 0.3f);       // and an own value on linear x
            k->setEquilibriumPoint(4, -0.2f);
            k->enableMotor(2, true);               // a linear servo on the locked axis
            k->setServo(2, true);
            k->setServoTarget(2, 0.1f);
            k->setTargetVelocity(2, 0.8f);
            k->setMaxMotorForce(2, 30.0f);
            k->enableMotor(3, true);               // an angular servo on the free axis, across the wrap
            k->setServo(3, true);
            k->setServoTarget(3, order % 2 ? 3.0f : -3.0f);
            k->setTargetVelocity(3, 2.0f);
            k->setMaxMotorForce(3, 5.0f);
            k->enableMotor(5, true);               // an angular servo inside its limits
            k->setServo(5, true);
            k->setServoTarget(5, 0.5f);
            k->setTargetVelocity(5, 1.0f);
            k->setMaxMotorForce(5, 2.0f);
            k->enableMotor(1, true);               // a plain velocity motor beside a spring
            k->setTargetVelocity(1, -0.3f);
            k->setMaxMotorForce(1, 7.0f);
            c.emplace_back(k);
        }
    }
    // Bullet's infinite error: the spring rows' target is +-infinity, the bounds do the work.
    auto* inf = new btGeneric6DofSpring2Constraint(*a, *b, fa, fb);
    for (int axis : {0, 5}) {
        inf->enableSpring(axis, true);
        inf->setStiffness(axis, 50.0f);
        inf->setDamping(axis, 2.0f);
    }
    inf->setEquilibriumPoint(0, 0.4f);
    inf->setEquilibriumPoint(5, -0.4f);
    inf->setParam(BT_CONSTRAINT_STOP_CFM, 0.1f, 4);  // a first row's own cfm the later rows read as cfm[0]
    struct Flags : btGeneric6DofSpring2Constraint {
        using btGeneric6DofSpring2Constraint::m_flags;
    };
    int btGeneric6DofSpring2Constraint::*flags = &Flags::m_flags;
    inf->*flags |= BT_6DOF_FLAGS_USE_INFINITE_ERROR;
    c.emplace_back(inf);
    // A spring to Bullet's fixed body (m is the one body's), and a servo with it.
    auto* toFixed = new btGeneric6DofSpring2Constraint(btTypedConstraint::getFixedBody(), *b, b->getWorldTransform() * fb, fb);
    for (int axis = 0; axis < 6; ++axis) toFixed->setLimit(axis, 1.0f, -1.0f);
    for (int axis : {1, 3}) {
        toFixed->enableSpring(axis, true);
        toFixed->setStiffness(axis, 120.0f);
        toFixed->setDamping(axis, 0.5f, false);
    }
    toFixed->setEquilibriumPoint(1, -0.25f);
    toFixed->enableMotor(4, true);
    toFixed->setServo(4, true);
    toFixed->setServoTarget(4, 0.7f);
    toFixed->setTargetVelocity(4, 1.5f);
    toFixed->setMaxMotorForce(4, 3.0f);
    c.emplace_back(toFixed);
    // btHinge2Constraint as constructed, stretched off its suspension's rest length.
    btVector3 anchor = b->getWorldTransform().getOrigin() + btVector3(0.0f, 0.1f, 0.05f), axis1(0, 1, 0), axis2(1, 0, 0);
    c.emplace_back(new btHinge2Constraint(*a, *b, anchor, axis1, axis2));
    const RowKinds kinds = expectRowsAsBullet(s, map, c, BTG_JOINT_SIXDOF2);
    EXPECT_GE(kinds.motors, 12 * 8);  // springs, servos and the motor: bounded on both sides
}

// Everything a btGeneric6DofSpring2Constraint, btFixedConstraint or btHinge2Constraint sets is
// served; a subclass of them is not (named by its type).
TEST(PrepareJoints, SixDofSpringsServosAndHinge2AreServed)
{
    BulletBodies s;
    btRigidBody* a = s.add(2.0f, btVector3(0, 2, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    btRigidBody* b = s.add(3.0f, btVector3(0, 1, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    const RowMap map = s.rowsOf(a, b);
    BtgJoint j;
    btGeneric6DofSpring2Constraint spring(*a, *b, btTransform::getIdentity(), btTransform::getIdentity());
    spring.enableSpring(1, true);
    spring.setStiffness(1, 10.0f, false);
    ASSERT_TRUE(jointRow(spring, map, 10, &j));
    EXPECT_EQ(j.sixdof.axis[1].mode, BTG_SIXDOF_SPRING);  // setStiffness(.., false); no setDamping
    EXPECT_EQ(j.sixdof.axis[1].stiffness, 10.0f);
    btGeneric6DofSpring2Constraint servo(*a, *b, btTransform::getIdentity(), btTransform::getIdentity());
    servo.enableMotor(4, true);
    servo.setServo(4, true);
    servo.setServoTarget(4, 7.0f);  // Bullet wraps it into [-pi, pi)
    ASSERT_TRUE(jointRow(servo, map, 10, &j));
    EXPECT_EQ(j.sixdof.axis[4].mode, BTG_SIXDOF_MOTOR | BTG_SIXDOF_SERVO);
    EXPECT_NEAR(j.sixdof.axis[4].servoTarget, 7.0f - 2.0f * SIMD_PI, 1e-5f);
    btVector3 anchor(0, 1, 0), axis1(0, 1, 0), axis2(1, 0, 0);
    btHinge2Constraint hinge2(*a, *b, anchor, axis1, axis2);
    ASSERT_TRUE(jointRow(hinge2, map, 10, &j));
    EXPECT_TRUE(j.sixdof.axis[2].mode & BTG_SIXDOF_SPRING);
    EXPECT_NEAR(j.sixdof.axis[2].stiffness, SIMD_PI * SIMD_PI * 4.0f, 1e-4f);
    struct Derived : btGeneric6DofSpring2Constraint {
        using btGeneric6DofSpring2Constraint::btGeneric6DofSpring2Constraint;
    };
    Derived derived(*a, *b, btTransform::getIdentity(), btTransform::getIdentity());
    EXPECT_FALSE(jointRow(derived, map, 10, &j));
}

// A rotational spring whose partner is asleep while the other body moves (btgpu wakes it a step
// later than Bullet, which wakes the island first): the sleeping body counts as static for the
// spring's mass, never a zero inertia (inf / inf), and the rows stay finite.
TEST(PrepareJoints, SixDofSpringBesideASleepingBodyStaysFinite)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const RowMap map = s.rowsOf(a, b);
    btGeneric6DofSpring2Constraint k(*a, *b, frameInA(), frameInB());
    for (int axis = 0; axis < 6; ++axis) {
        k.setLimit(axis, 1.0f, -1.0f);
        k.enableSpring(axis, true);
        k.setStiffness(axis, 50.0f);
        k.setDamping(axis, 1.0f);
    }
    ref::JointTables tables;
    BtgJoint j;
    ASSERT_TRUE(jointRow(k, map, 10, &j));
    tables.joints.push_back(j);
    tables.state.assign(1, BtgJointState{});
    tables.rows.assign(size_t(btgSixDofMaxRows(j.sixdof)), BtgJointRow{});
    s.rows.props[1].flags |= BTG_BODY_SLEEPING;
    const BtgJointStepParams p = jointParams(1);
    ref::JointTables expect = tables;
    ref::prepareJoints(expect, s.rows, p);
    DeviceJoints got = runPrepare(s.rows, tables, p);
    ASSERT_EQ(got.state[0].numRows, 6);
    for (int r = 0; r < 6; ++r) {
        EXPECT_TRUE(std::isfinite(got.rows[size_t(r)].target)) << r;
        EXPECT_TRUE(std::isfinite(got.rows[size_t(r)].lower) && std::isfinite(got.rows[size_t(r)].upper)) << r;
        // Not bitwise: OpenCL lets a device contract a * b + c (NVIDIA's does; it failed there
        // by its last bits), so the reference's float order is matched within a few ulps.
        const float want = expect.rows[size_t(r)].target;
        EXPECT_NEAR(got.rows[size_t(r)].target, want, 1e-5f * std::max(1.0f, std::fabs(want))) << r;
    }
}
