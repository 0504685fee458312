// prepare_joints_cone_motor_test.cpp — btConeTwistConstraint with its motor on, on the device
// against the CPU reference and against Bullet's own getInfo1/getInfo2 for the same bodies
// (compat's jointRow converting each): targets set in world and constraint space, clamped by
// the limits, the impulse bound (set, unbounded, normalized), angular-only and damping (read by
// the obsolete solve only), spans below the fix threshold, the fixed body, a target reached.
#include "joint_fixture.h"

using namespace btgpu;
using namespace btgpu::jointtest;

TEST(PrepareJoints, ConeTwistMotorRowsMatchBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const RowMap map = s.rowsOf(a, b);
    const btTransform fa = frameInA(), fb = frameInB();
    const btQuaternion target(btVector3(0.3f, -1.0f, 0.5f).normalized(), 0.6f);
    std::vector<std::unique_ptr<btConeTwistConstraint>> c;
    auto add = [&](btConeTwistConstraint* k) {
        k->enableMotor(true);
        c.emplace_back(k);
        return k;
    };
    add(new btConeTwistConstraint(*a, *b, fa, fb))->setMotorTargetInConstraintSpace(target);  // unbounded (-1)
    btConeTwistConstraint* bounded = add(new btConeTwistConstraint(*a, *b, fa, fb));
    bounded->setLimit(0.5f, 0.3f, 0.4f);  // the target is clamped into these by Bullet's setter
    bounded->setMaxMotorImpulse(0.05f);
    bounded->setMotorTarget(btQuaternion(btVector3(0, 0, 1), 1.2f));
    btConeTwistConstraint* normalized = add(new btConeTwistConstraint(*a, *b, fa, fb));
    normalized->setMaxMotorImpulseNormalized(0.7f);  // getInfo2 reads it raw
    normalized->setAngularOnly(true);                // read by the obsolete solve only
    normalized->setDamping(0.5f);
    normalized->setParam(BT_CONSTRAINT_CFM, 0.02f, 3);
    normalized->setMotorTargetInConstraintSpace(btQuaternion(btVector3(1, 0, 0), -0.4f));
    btConeTwistConstraint* locked = add(new btConeTwistConstraint(*a, *b, fa, fb));
    locked->setLimit(0.0f, 0.0f, 0.3f);  // both spans below the fix threshold: two swing rows
    locked->setMotorTargetInConstraintSpace(target);
    btConeTwistConstraint* toFixed = add(new btConeTwistConstraint(*b, fb));
    toFixed->setMaxMotorImpulse(1.0f);
    toFixed->setMotorTargetInConstraintSpace(target);
    // The target the joint stands at: nothing left to turn, no swing row (three point rows).
    btConeTwistConstraint* reached = add(new btConeTwistConstraint(*a, *b, fa, fb));
    const btQuaternion qA = (a->getWorldTransform() * fa).getRotation(), qB = (b->getWorldTransform() * fb).getRotation();
    reached->setMotorTargetInConstraintSpace(qB.inverse() * qA);
    const RowKinds kinds = expectRowsAsBullet(s, map, c, BTG_JOINT_CONE_TWIST);
    EXPECT_EQ(kinds.firstRows0, 4);  // three point rows and the motor's swing row
    EXPECT_GE(kinds.bounded, 1);     // the unbounded motor's swing row: [0, infinity)
    EXPECT_GE(kinds.motors, 3);      // the others' [0, m_maxMotorImpulse]
}
