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
    btAlignedObjectArray<btCollisionObject*> objects;
    objects.push_back(a);
    objects.push_back(b);
    RowMap map;
    map.reset(objects);
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
    ref::JointTables tables;
    int nextRow = 0;
    for (auto& k : c) {
        BtgJoint j;
        ASSERT_TRUE(jointRow(*k, map, 10, &j));
        ASSERT_EQ(j.type, BTG_JOINT_SIXDOF2);
        j.firstRow = nextRow;
        nextRow += btgSixDofMaxRows(j.sixdof);
        tables.joints.push_back(j);
    }
    EXPECT_EQ(tables.joints.back().bodyA, BTG_JOINT_FIXED_BODY);
    tables.state.assign(c.size(), BtgJointState{});
    tables.rows.assign(size_t(nextRow), BtgJointRow{});
    const BtgJointStepParams p = jointParams(int(c.size()));
    ref::JointTables expect = tables;
    ref::prepareJoints(expect, s.rows, p);
    DeviceJoints got = runPrepare(s.rows, tables, p);
    int bounded = 0, motors = 0;
    for (size_t j = 0; j < c.size(); ++j) {
        std::vector<BulletRow> br = bulletRows(*c[j], p.dt, p.erp);
        ASSERT_EQ(got.state[j].numRows, int(br.size())) << "6dof " << j;
        ASSERT_EQ(expect.state[j].numRows, int(br.size())) << "6dof " << j;
        ASSERT_LE(int(br.size()), btgSixDofMaxRows(tables.joints[j].sixdof)) << "6dof " << j;
        for (size_t k = 0; k < br.size(); ++k) {
            const BtgJointRow &g = got.rows[tables.joints[j].firstRow + k], &e = expect.rows[tables.joints[j].firstRow + k];
            expectRowAsBullet(g, e, br[k], "6dof " + std::to_string(j) + " row " + std::to_string(k));
            // Unbounded sides arrive clamped to the breaking threshold (SIMD_INFINITY = FLT_MAX).
            const bool bigLo = std::fabs(br[k].lower) > 1e30f, bigHi = std::fabs(br[k].upper) > 1e30f;
            if (bigLo != bigHi) ++bounded;
            if (!bigLo && !bigHi) ++motors;
        }
    }
    EXPECT_EQ(got.state[0].numRows, 6);  // a fixed joint: three angular, three linear rows
    EXPECT_GE(bounded, 6 * 6);           // one-sided rows of ranged axes were built
    EXPECT_GE(motors, 6 * 2 + 1);        // the motor rows
}

TEST(PrepareJoints, SixDofSpringsAndServosAreNotServed)
{
    BulletBodies s;
    btRigidBody* a = s.add(2.0f, btVector3(0, 2, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    btRigidBody* b = s.add(3.0f, btVector3(0, 1, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    btAlignedObjectArray<btCollisionObject*> objects;
    objects.push_back(a);
    objects.push_back(b);
    RowMap map;
    map.reset(objects);
    BtgJoint j;
    btGeneric6DofSpring2Constraint spring(*a, *b, btTransform::getIdentity(), btTransform::getIdentity());
    EXPECT_TRUE(jointRow(spring, map, 10, &j));
    spring.enableSpring(1, true);
    EXPECT_FALSE(jointRow(spring, map, 10, &j));
    btGeneric6DofSpring2Constraint servo(*a, *b, btTransform::getIdentity(), btTransform::getIdentity());
    servo.enableMotor(4, true);
    EXPECT_TRUE(jointRow(servo, map, 10, &j));
    servo.setServo(4, true);
    EXPECT_FALSE(jointRow(servo, map, 10, &j));
    // btHinge2Constraint's suspension is a spring on linear z.
    btVector3 anchor(0, 1, 0), axis1(0, 1, 0), axis2(1, 0, 0);
    btHinge2Constraint hinge2(*a, *b, anchor, axis1, axis2);
    EXPECT_FALSE(jointRow(hinge2, map, 10, &j));
}
