// prepare_joints_generic6dof_test.cpp — btGeneric6DofConstraint rows (and btUniversalConstraint's,
// btGeneric6DofSpringConstraint's) on the device against the CPU reference and against Bullet's
// own getInfo1/getInfo2 for the same bodies, each joint converted by compat's jointRow: limits
// hit and locked, motors free and inside limits, bounce, setParam, the frame offset on and
// off, the fixed body, a universal joint, springs (their motor targets from the pose).
#include "joint_fixture.h"

using namespace btgpu;
using namespace btgpu::jointtest;

TEST(PrepareJoints, Generic6DofRowsMatchBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const RowMap map = s.rowsOf(a, b);
    const btTransform fa = frameInA(), fb = frameInB();
    std::vector<std::unique_ptr<btGeneric6DofConstraint>> c;
    for (int offset = 0; offset < 2; ++offset) {
        for (int refA = 0; refA < 2; ++refA) {
            // Linear x locked (off its value), y ranged and hit, z free with a motor; angular x
            // ranged wide with a motor, y locked, z ranged and hit with bounce.
            auto* k = new btGeneric6DofConstraint(*a, *b, fa, fb, refA != 0);
            k->setUseFrameOffset(offset != 0);
            k->setLinearLowerLimit(btVector3(0.05f, -0.1f, 1.0f));
            k->setLinearUpperLimit(btVector3(0.05f, 0.1f, -1.0f));
            k->setAngularLowerLimit(btVector3(-2.5f, 0.0f, 0.1f));
            k->setAngularUpperLimit(btVector3(2.5f, 0.0f, 0.2f));
            k->getRotationalLimitMotor(0)->m_enableMotor = true;
            k->getRotationalLimitMotor(0)->m_targetVelocity = 1.5f;
            k->getRotationalLimitMotor(0)->m_maxMotorForce = 4.0f;
            k->getRotationalLimitMotor(2)->m_bounce = 0.6f;
            k->getTranslationalLimitMotor()->m_enableMotor[2] = true;
            k->getTranslationalLimitMotor()->m_targetVelocity[2] = -0.7f;
            k->getTranslationalLimitMotor()->m_maxMotorForce[2] = 9.0f;
            c.emplace_back(k);
        }
    }
    // setParam: own CFM, stop ERP and stop CFM on linear and angular axes (the first row's own
    // cfm then becomes the later axes' info->cfm[0]); a motor inside a range that is not hit;
    // a motor on a locked axis (ineffective, as Bullet).
    auto* tuned = new btGeneric6DofConstraint(*a, *b, fa, fb, true);
    tuned->setLimit(3, -0.3f, 0.3f);
    tuned->setLimit(4, 0.0f, 0.0f);
    tuned->setLimit(5, -3.0f, 3.0f);
    tuned->setLimit(0, -2.0f, 2.0f);
    tuned->setLimit(1, 0.0f, 0.0f);
    tuned->setParam(BT_CONSTRAINT_STOP_CFM, 0.05f, 3);
    tuned->setParam(BT_CONSTRAINT_STOP_ERP, 0.7f, 4);
    tuned->setParam(BT_CONSTRAINT_CFM, 0.02f, 5);
    tuned->setParam(BT_CONSTRAINT_STOP_ERP, 0.4f, 1);
    tuned->setParam(BT_CONSTRAINT_STOP_CFM, 0.03f, 1);
    tuned->getRotationalLimitMotor(2)->m_enableMotor = true;
    tuned->getRotationalLimitMotor(2)->m_targetVelocity = -2.0f;
    tuned->getRotationalLimitMotor(2)->m_maxMotorForce = 1.0f;
    tuned->getTranslationalLimitMotor()->m_enableMotor[0] = true;
    tuned->getTranslationalLimitMotor()->m_targetVelocity[0] = 0.4f;
    tuned->getTranslationalLimitMotor()->m_maxMotorForce[0] = 3.0f;
    tuned->getTranslationalLimitMotor()->m_enableMotor[1] = true;
    tuned->getTranslationalLimitMotor()->m_targetVelocity[1] = 0.4f;
    c.emplace_back(tuned);
    // On the fixed body, every axis locked or ranged off its value (a static side: the lever
    // arms by mass; no value sits exactly on a limit, where rounding picks the row or not).
    auto* toFixed = new btGeneric6DofConstraint(*b, fb, true);
    toFixed->setLimit(0, 0.1f, 0.1f);
    toFixed->setLimit(1, -0.1f, -0.05f);
    toFixed->setLimit(2, 0.02f, 0.02f);
    toFixed->setLimit(3, 0.2f, 0.3f);
    toFixed->setLimit(4, -0.05f, -0.05f);
    toFixed->setLimit(5, -0.2f, -0.1f);
    c.emplace_back(toFixed);
    // Angular axes locked across the angle's wrap: the error is wrapped into +-pi.
    for (float lock : {3.0f, -3.0f}) {
        auto* w = new btGeneric6DofConstraint(*a, *b, fa, fb, true);
        for (int axis = 0; axis < 6; ++axis) w->setLimit(axis, 1.0f, -1.0f);
        w->setLimit(3, lock, lock);
        w->setLimit(5, -lock, -lock);
        c.emplace_back(w);
    }
    // btUniversalConstraint, turned off its axes.
    btVector3 anchor = b->getWorldTransform().getOrigin() + btVector3(0.1f, 0.3f, -0.2f);
    btVector3 axis1 = btVector3(0.2f, 1.0f, 0.1f).normalized(), axis2 = btVector3(1.0f, -0.2f, 0.0f).normalized();
    axis2 = (axis2 - axis1 * axis1.dot(axis2)).normalized();
    c.emplace_back(new btUniversalConstraint(*a, *b, anchor, axis1, axis2));
    // btGeneric6DofSpringConstraint: springs on free, ranged and locked axes (their motors'
    // targets from the pose), with and without the frame offset.
    for (int offset = 0; offset < 2; ++offset) {
        auto* sp = new btGeneric6DofSpringConstraint(*a, *b, fa, fb, true);
        sp->setUseFrameOffset(offset != 0);
        sp->setLimit(0, 1.0f, -1.0f);
        sp->setLimit(1, -0.5f, 0.5f);
        sp->setLimit(2, 0.0f, 0.0f);
        sp->setLimit(3, 1.0f, -1.0f);
        sp->setLimit(4, -0.1f, 0.1f);
        sp->setLimit(5, 1.0f, -1.0f);
        for (int axis : {0, 1, 3, 5}) {
            sp->enableSpring(axis, true);
            sp->setStiffness(axis, axis < 3 ? 80.0f : 12.0f);
            sp->setDamping(axis, axis == 5 ? 0.3f : 1.0f);
        }
        sp->setEquilibriumPoint();
        sp->setEquilibriumPoint(0, 0.25f);
        sp->setEquilibriumPoint(3, -0.4f);
        sp->setEquilibriumPoint(5, 0.9f);
        c.emplace_back(sp);
    }
    const RowKinds kinds = expectRowsAsBullet(s, map, c, BTG_JOINT_SIXDOF);
    EXPECT_GE(kinds.bounded, 4 * 2);  // one-sided rows of hit ranges
    EXPECT_GE(kinds.motors, 4 * 2 + 2 * 4);  // motor rows and the springs' motor rows
}

// Subclasses and the obsolete solve of the old 6-DoF family are not served.
TEST(PrepareJoints, Generic6DofSubclassesAndObsoleteSolveAreNotServed)
{
    BulletBodies s;
    btRigidBody* a = s.add(2.0f, btVector3(0, 2, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    btRigidBody* b = s.add(3.0f, btVector3(0, 1, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    const RowMap map = s.rowsOf(a, b);
    BtgJoint j;
    btGeneric6DofConstraint plain(*a, *b, btTransform::getIdentity(), btTransform::getIdentity(), true);
    EXPECT_TRUE(jointRow(plain, map, 10, &j));
    EXPECT_EQ(j.type, BTG_JOINT_SIXDOF);
    plain.m_useSolveConstraintObsolete = true;
    EXPECT_FALSE(jointRow(plain, map, 10, &j));
    struct Derived : btGeneric6DofSpringConstraint {
        using btGeneric6DofSpringConstraint::btGeneric6DofSpringConstraint;
    };
    Derived derived(*a, *b, btTransform::getIdentity(), btTransform::getIdentity(), true);
    EXPECT_FALSE(jointRow(derived, map, 10, &j));
}
