// prepare_joints_test.cpp — the joint stages: btPoint2PointConstraint rows on the device against
// the CPU reference and against Bullet's own getInfo1/getInfo2 and convertJoint arithmetic for
// the same bodies (ERP/CFM set by setParam, impulse clamp, damping, breaking bounds, the fixed
// body, a static row); the solve of joints with contacts against the reference in both launch
// shapes; finish_joints' applied impulse, feedback and breaking.
#include "contact_fixture.h"
#include "joint_fixture.h"
#include "reference/joint_reference.h"
#include "stages/color_constraints.h"
#include "stages/contact_cache.h"
#include "stages/prepare_contacts.h"
#include "stages/prepare_joints.h"
#include "stages/solve_constraints.h"
#include "test_device.h"
#include "tolerances.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <memory>

using namespace btgpu;
using namespace btgpu::jointtest;

TEST(PrepareJoints, Point2PointRowsMatchBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    btRigidBody* ground = s.add(0.0f, btVector3(0, -1, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0),
                                btVector3(0, 0, 0));
    // A plain pair; one with its own ERP/CFM, clamp, damping and breaking threshold; one on the
    // fixed body; one on a static row.
    btPoint2PointConstraint plain(*a, *b, btVector3(0.2f, -0.4f, 0.1f), btVector3(-0.1f, 0.5f, 0.0f));
    btPoint2PointConstraint tuned(*a, *b, btVector3(-0.3f, 0.1f, 0.4f), btVector3(0.2f, 0.3f, -0.2f));
    tuned.setParam(BT_CONSTRAINT_ERP, 0.6f);
    tuned.setParam(BT_CONSTRAINT_CFM, 0.01f);
    tuned.m_setting.m_impulseClamp = 0.05f;
    tuned.m_setting.m_damping = 0.7f;
    tuned.setBreakingImpulseThreshold(0.03f);
    btPoint2PointConstraint fixed(*b, btVector3(0.0f, 0.3f, 0.1f));
    btPoint2PointConstraint onStatic(*ground, *a, btVector3(0.5f, 1.5f, 0.0f), btVector3(0.1f, 0.1f, 0.1f));
    ref::JointTables t;
    t.joints = {p2pRow(0, 1, plain, 0), p2pRow(0, 1, tuned, 3), p2pRow(1, BTG_JOINT_FIXED_BODY, fixed, 6),
                p2pRow(2, 0, onStatic, 9)};
    t.joints[1].flags |= BTG_JOINT_OWN_ERP | BTG_JOINT_OWN_CFM;
    t.joints[1].erp = 0.6f;
    t.joints[1].cfm = 0.01f;
    t.state.assign(t.joints.size(), BtgJointState{});
    t.rows.assign(12, BtgJointRow{});
    const BtgJointStepParams p = jointParams(int(t.joints.size()));
    ref::JointTables expect = t;
    std::vector<BtgEdge> expectEdges = ref::prepareJoints(expect, s.rows, p);
    DeviceJoints got = runPrepare(s.rows, t, p);
    ASSERT_EQ(got.edgeCount, t.joints.size());  // no contacts: the joints' edges from 0
    btTypedConstraint* bullet[] = {&plain, &tuned, &fixed, &onStatic};
    for (size_t j = 0; j < t.joints.size(); ++j) {
        EXPECT_EQ(got.state[j].numRows, 3) << j;
        EXPECT_EQ(expect.state[j].numRows, 3) << j;
        EXPECT_EQ(got.edges[j].bodyA, expectEdges[j].bodyA) << j;
        EXPECT_EQ(got.edges[j].bodyB, expectEdges[j].bodyB) << j;
        std::vector<BulletRow> br = bulletRows(*bullet[j], p.dt, p.erp);
        ASSERT_EQ(br.size(), 3u);
        for (int k = 0; k < 3; ++k) {
            const BtgJointRow &g = got.rows[t.joints[j].firstRow + k], &e = expect.rows[t.joints[j].firstRow + k];
            const std::string what = "joint " + std::to_string(j) + " row " + std::to_string(k);
            // Device against reference.
            expectNear(g.mass, e.mass, what + " mass (ref)");
            expectNear(g.target, e.target, what + " target (ref)");
            expectNear3(g.jacobian.angularA, btVector3(e.jacobian.angularA.x, e.jacobian.angularA.y, e.jacobian.angularA.z),
                        what + " angularA (ref)");
            // Device against Bullet's getInfo2 and convertJoint.
            expectNear3(g.jacobian.linear, br[k].linA, what + " linA");
            expectNear3(-g.jacobian.linear, br[k].linB, what + " linB");
            expectNear3(g.jacobian.angularA, br[k].angA, what + " angA");
            expectNear3(g.jacobian.angularB, br[k].angB, what + " angB");
            expectNear(g.mass, br[k].mass, what + " mass");
            expectNear(g.target, br[k].target, what + " target");
            expectNear(g.cfm, br[k].cfm, what + " cfm");
            EXPECT_EQ(g.lower, br[k].lower) << what;
            EXPECT_EQ(g.upper, br[k].upper) << what;
            EXPECT_EQ(g.impulse, 0.0f) << what;
        }
    }
    // The clamp and the breaking threshold bound the tuned joint's rows; the fixed body's
    // edge claims only its one body.
    EXPECT_EQ(got.rows[3].upper, 0.03f);
    EXPECT_EQ(got.rows[3].lower, -0.03f);
    EXPECT_EQ(got.edges[2].bodyA, 1);
    EXPECT_EQ(got.edges[2].bodyB, 1);
}

// btGearConstraint: its one angular row from each body's axis and the ratio (any sign), on the
// device against the reference and Bullet's getInfo1/getInfo2 for the same bodies.
TEST(PrepareJoints, GearRowMatchesBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const RowMap map = s.rowsOf(a, b);
    std::vector<std::unique_ptr<btGearConstraint>> c;
    c.emplace_back(new btGearConstraint(*a, *b, btVector3(0, 1, 0), btVector3(0, 1, 0)));
    c.emplace_back(new btGearConstraint(*a, *b, btVector3(0.3f, -0.8f, 0.5f).normalized(), btVector3(1, 0, 0), 2.5f));
    c.emplace_back(new btGearConstraint(*b, *a, btVector3(0, 0, 1), btVector3(0.6f, 0.0f, -0.8f), -0.4f));
    c.back()->setBreakingImpulseThreshold(0.02f);
    const RowKinds kinds = expectRowsAsBullet(s, map, c, BTG_JOINT_GEAR);
    EXPECT_EQ(kinds.firstRows0, 1);
    EXPECT_EQ(kinds.motors, 1);  // the last bounded on both sides by its breaking threshold
}

TEST(PrepareJoints, HingeRowsMatchBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const btVector3 pa(0.2f, -0.4f, 0.1f), pb(-0.1f, 0.5f, 0.0f), axA(0, 0, 1), axB = btVector3(1, 1, 0).normalized();
    std::vector<std::unique_ptr<btHingeConstraint>> h;
    struct Setup {
        float sign = 1, low = 1, high = -1, bias = 0.3f, relaxation = 1.0f;
        int bodyB = 1;
    };
    std::vector<Setup> setup;
    auto add = [&](btHingeConstraint* c, Setup st) {
        h.emplace_back(c);
        setup.push_back(st);
        return c;
    };
    add(new btHingeConstraint(*a, *b, pa, pb, axA, axB), {});  // plain, frame offset (Bullet's default)
    Setup lim;
    lim.low = -0.1f;
    lim.high = 0.1f;
    lim.bias = 0.5f;
    lim.relaxation = 0.8f;
    add(new btHingeConstraint(*a, *b, pa, pb, axA, axB), lim)->setLimit(-0.1f, 0.1f, 0.9f, 0.5f, 0.8f);
    Setup wide;
    wide.low = -3.0f;
    wide.high = 3.0f;
    add(new btHingeConstraint(*a, *b, pa, pb, axA, axB), wide)->setLimit(-3.0f, 3.0f);
    h.back()->enableAngularMotor(true, 2.0f, 0.5f);
    Setup fixedSetup = lim;
    fixedSetup.bodyB = BTG_JOINT_FIXED_BODY;
    add(new btHingeConstraint(*b, pb, axB), fixedSetup)->setLimit(-0.1f, 0.1f, 0.9f, 0.5f, 0.8f);
    add(new btHingeConstraint(*a, *b, pa, pb, axA, axB), lim)->setLimit(-0.1f, 0.1f, 0.9f, 0.5f, 0.8f);
    h.back()->setUseFrameOffset(false);
    add(new btHingeConstraint(*a, *b, pa, pb, axA, axB), {})->setAngularOnly(true);
    Setup refA = wide;
    refA.sign = -1;
    add(new btHingeConstraint(*a, *b, pa, pb, axA, axB, true), refA)->setLimit(-3.0f, 3.0f);
    h.back()->enableAngularMotor(true, -1.5f, 0.2f);
    Setup tuned = lim;
    btHingeConstraint* t = add(new btHingeConstraint(*a, *b, pa, pb, axA, axB), tuned);
    t->setLimit(-0.1f, 0.1f, 0.9f, 0.5f, 0.8f);
    t->setParam(BT_CONSTRAINT_ERP, 0.4f);
    t->setParam(BT_CONSTRAINT_STOP_ERP, 0.6f);
    t->setParam(BT_CONSTRAINT_STOP_CFM, 0.05f);
    t->setBreakingImpulseThreshold(0.2f);
    Setup motorAtLimit = lim;
    add(new btHingeConstraint(*a, *b, pa, pb, axA, axB), motorAtLimit)->setLimit(-0.1f, 0.1f, 0.9f, 0.5f, 0.8f);
    h.back()->enableAngularMotor(true, 1.0f, 1.0f);
    h.back()->setParam(BT_CONSTRAINT_CFM, 0.02f);

    ref::JointTables tables;
    for (size_t i = 0; i < h.size(); ++i) {
        const Setup& st = setup[i];
        const int bodyA = st.bodyB == BTG_JOINT_FIXED_BODY ? 1 : 0;
        BtgJoint j = hingeRow(bodyA, st.bodyB, *h[i], int(6 * i), st.sign, st.low, st.high, st.bias, st.relaxation);
        const int flags = h[i]->getFlags();
        if (flags & BT_HINGE_FLAGS_ERP_NORM) j.flags |= BTG_JOINT_OWN_ERP, j.erp = h[i]->getParam(BT_CONSTRAINT_ERP, 5);
        if (flags & BT_HINGE_FLAGS_CFM_NORM) j.flags |= BTG_JOINT_OWN_CFM, j.cfm = h[i]->getParam(BT_CONSTRAINT_CFM, 5);
        if (flags & BT_HINGE_FLAGS_ERP_STOP)
            j.flags |= BTG_JOINT_OWN_STOP_ERP, j.stopErp = h[i]->getParam(BT_CONSTRAINT_STOP_ERP, 5);
        if (flags & BT_HINGE_FLAGS_CFM_STOP)
            j.flags |= BTG_JOINT_OWN_STOP_CFM, j.stopCfm = h[i]->getParam(BT_CONSTRAINT_STOP_CFM, 5);
        tables.joints.push_back(j);
    }
    tables.state.assign(h.size(), BtgJointState{});
    tables.rows.assign(6 * h.size(), BtgJointRow{});
    const BtgJointStepParams p = jointParams(int(h.size()));
    ref::JointTables expect = tables;
    ref::prepareJoints(expect, s.rows, p);
    DeviceJoints got = runPrepare(s.rows, tables, p);
    int withLimitRow = 0;
    for (size_t j = 0; j < h.size(); ++j) {
        std::vector<BulletRow> br = bulletRows(*h[j], p.dt, p.erp);
        ASSERT_EQ(got.state[j].numRows, int(br.size())) << "joint " << j;
        ASSERT_EQ(expect.state[j].numRows, int(br.size())) << "joint " << j;
        withLimitRow += br.size() == 6;
        for (size_t k = 0; k < br.size(); ++k) {
            const BtgJointRow &g = got.rows[tables.joints[j].firstRow + k], &e = expect.rows[tables.joints[j].firstRow + k];
            expectRowAsBullet(g, e, br[k], "hinge " + std::to_string(j) + " row " + std::to_string(k));
        }
    }
    EXPECT_GE(withLimitRow, 5);  // limits hit, motors on: the sixth row is exercised
}

namespace {
BtgJoint coneRow(int a, int b, btConeTwistConstraint& c, int firstRow)
{
    BtgJoint j{};
    j.type = BTG_JOINT_CONE_TWIST;
    j.bodyA = a;
    j.bodyB = b;
    j.flags = BTG_JOINT_ENABLED;
    j.firstRow = firstRow;
    j.iterations = 10;
    j.breakingThreshold = c.getBreakingImpulseThreshold();
    j.pivotA = f4(c.getAFrame().getOrigin());
    j.pivotB = f4(c.getBFrame().getOrigin());
    for (int k = 0; k < 3; ++k) {
        j.axesA[k] = f4(c.getAFrame().getBasis().getColumn(k));
        j.axesB[k] = f4(c.getBFrame().getBasis().getColumn(k));
    }
    const btQuaternion qa = c.getAFrame().getRotation(), qb = c.getBFrame().getRotation();
    j.frameRotA = btgMake4(qa.x(), qa.y(), qa.z(), qa.w());
    j.frameRotB = btgMake4(qb.x(), qb.y(), qb.z(), qb.w());
    const int flags = c.getFlags();
    if (flags & BT_CONETWIST_FLAGS_LIN_ERP) j.flags |= BTG_JOINT_OWN_ERP, j.erp = c.getParam(BT_CONSTRAINT_ERP, 0);
    if (flags & BT_CONETWIST_FLAGS_LIN_CFM) j.flags |= BTG_JOINT_OWN_CFM, j.cfm = c.getParam(BT_CONSTRAINT_CFM, 0);
    if (flags & BT_CONETWIST_FLAGS_ANG_CFM) j.flags |= BTG_JOINT_OWN_STOP_CFM, j.stopCfm = c.getParam(BT_CONSTRAINT_CFM, 3);
    j.swingSpan1 = c.getSwingSpan1();
    j.swingSpan2 = c.getSwingSpan2();
    j.twistSpan = c.getTwistSpan();
    j.limitSoftness = c.getLimitSoftness();
    j.limitBias = c.getBiasFactor();
    j.limitRelaxation = c.getRelaxationFactor();
    j.fixThresh = c.getFixThresh();
    return j;
}
}  // namespace

TEST(PrepareJoints, ConeTwistRowsMatchBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const btTransform fa = frameInA(), fb = frameInB();
    std::vector<std::unique_ptr<btConeTwistConstraint>> c;
    std::vector<int> bodyB;
    auto add = [&](btConeTwistConstraint* k, int b2 = 1) {
        c.emplace_back(k);
        bodyB.push_back(b2);
        return k;
    };
    add(new btConeTwistConstraint(*a, *b, fa, fb));  // no limits (Bullet's default spans)
    add(new btConeTwistConstraint(*a, *b, fa, fb))->setLimit(0.5f, 0.3f, 0.4f);  // elliptic cone, twist
    add(new btConeTwistConstraint(*a, *b, fa, fb))->setLimit(0.0f, 0.0f, 0.0f);  // locked: fixed swing rows
    add(new btConeTwistConstraint(*a, *b, fa, fb))->setLimit(0.01f, 0.8f, 0.3f);  // hinge about y
    add(new btConeTwistConstraint(*a, *b, fa, fb))->setLimit(0.8f, 0.01f, 0.3f);  // hinge about z
    btConeTwistConstraint* tuned = add(new btConeTwistConstraint(*a, *b, fa, fb));
    tuned->setLimit(0.4f, 0.6f, 0.2f, 0.8f, 0.5f, 0.9f);
    tuned->setParam(BT_CONSTRAINT_ERP, 0.5f, 0);
    tuned->setParam(BT_CONSTRAINT_CFM, 0.01f, 0);
    tuned->setParam(BT_CONSTRAINT_CFM, 0.02f, 3);
    add(new btConeTwistConstraint(*b, fb), BTG_JOINT_FIXED_BODY)->setLimit(0.3f, 0.3f, 0.1f);  // on the fixed body
    ref::JointTables tables;
    for (size_t i = 0; i < c.size(); ++i)
        tables.joints.push_back(coneRow(bodyB[i] == BTG_JOINT_FIXED_BODY ? 1 : 0, bodyB[i], *c[i], int(6 * i)));
    tables.state.assign(c.size(), BtgJointState{});
    tables.rows.assign(6 * c.size(), BtgJointRow{});
    const BtgJointStepParams p = jointParams(int(c.size()));
    ref::JointTables expect = tables;
    ref::prepareJoints(expect, s.rows, p);
    DeviceJoints got = runPrepare(s.rows, tables, p);
    int limitRows = 0;
    for (size_t j = 0; j < c.size(); ++j) {
        std::vector<BulletRow> br = bulletRows(*c[j], p.dt, p.erp);
        ASSERT_EQ(got.state[j].numRows, int(br.size())) << "cone " << j;
        ASSERT_EQ(expect.state[j].numRows, int(br.size())) << "cone " << j;
        limitRows += int(br.size()) - 3;
        for (size_t k = 0; k < br.size(); ++k) {
            const BtgJointRow &g = got.rows[tables.joints[j].firstRow + k], &e = expect.rows[tables.joints[j].firstRow + k];
            expectRowAsBullet(g, e, br[k], "cone " + std::to_string(j) + " row " + std::to_string(k));
        }
    }
    EXPECT_GE(limitRows, 8);  // swing and twist rows of every kind were built
}

namespace {
BtgJoint sliderRow(int a, int b, btSliderConstraint& c, int firstRow)
{
    BtgJoint j{};
    j.type = BTG_JOINT_SLIDER;
    j.bodyA = a;
    j.bodyB = b;
    j.flags = BTG_JOINT_ENABLED;
    j.firstRow = firstRow;
    j.iterations = 10;
    j.breakingThreshold = c.getBreakingImpulseThreshold();
    j.pivotA = f4(c.getFrameOffsetA().getOrigin());
    j.pivotB = f4(c.getFrameOffsetB().getOrigin());
    for (int k = 0; k < 3; ++k) {
        j.axesA[k] = f4(c.getFrameOffsetA().getBasis().getColumn(k));
        j.axesB[k] = f4(c.getFrameOffsetB().getBasis().getColumn(k));
    }
    BtgSliderParams& sp = j.slider;
    sp.lowerLin = c.getLowerLinLimit();
    sp.upperLin = c.getUpperLinLimit();
    sp.lowerAng = c.getLowerAngLimit();
    sp.upperAng = c.getUpperAngLimit();
    sp.softnessOrthoAng = c.getSoftnessOrthoAng();
    sp.softnessOrthoLin = c.getSoftnessOrthoLin();
    sp.softnessLimLin = c.getSoftnessLimLin();
    sp.softnessLimAng = c.getSoftnessLimAng();
    sp.dampingLimLin = c.getDampingLimLin();
    sp.dampingLimAng = c.getDampingLimAng();
    sp.cfmDirLin = c.getParam(BT_CONSTRAINT_CFM, 0);
    sp.cfmDirAng = c.getParam(BT_CONSTRAINT_CFM, 3);
    sp.cfmLimLin = c.getParam(BT_CONSTRAINT_STOP_CFM, 0);
    sp.cfmOrthoLin = c.getParam(BT_CONSTRAINT_STOP_CFM, 1);
    sp.cfmLimAng = c.getParam(BT_CONSTRAINT_STOP_CFM, 3);
    sp.cfmOrthoAng = c.getParam(BT_CONSTRAINT_STOP_CFM, 4);
    sp.linMotorVelocity = c.getTargetLinMotorVelocity();
    sp.linMotorMaxForce = c.getMaxLinMotorForce();
    sp.angMotorVelocity = c.getTargetAngMotorVelocity();
    sp.angMotorMaxForce = c.getMaxAngMotorForce();
    sp.flags = uint(c.getFlags());
    sp.options = (c.getUseLinearReferenceFrameA() ? BTG_SLIDER_LINEAR_REFERENCE_A : 0u) |
                 (c.getUseFrameOffset() ? BTG_SLIDER_FRAME_OFFSET : 0u) |
                 (c.getPoweredLinMotor() ? BTG_SLIDER_LIN_MOTOR : 0u) | (c.getPoweredAngMotor() ? BTG_SLIDER_ANG_MOTOR : 0u);
    return j;
}
}  // namespace

TEST(PrepareJoints, SliderRowsMatchBulletAndReference)
{
    BulletBodies s;
    btRigidBody* a = s.addBodyA();
    btRigidBody* b = s.addBodyB();
    const btTransform fa = frameInA(), fb = frameInB();
    std::vector<std::unique_ptr<btSliderConstraint>> c;
    std::vector<int> bodyB;
    auto add = [&](btSliderConstraint* k, int b2 = 1) {
        c.emplace_back(k);
        bodyB.push_back(b2);
        return k;
    };
    add(new btSliderConstraint(*a, *b, fa, fb, true));  // Bullet's default limits (lin [1, -1]: free; ang 0)
    btSliderConstraint* lim = add(new btSliderConstraint(*a, *b, fa, fb, true));
    lim->setLowerLinLimit(-0.1f);
    lim->setUpperLinLimit(0.1f);
    lim->setLowerAngLimit(-0.2f);
    lim->setUpperAngLimit(0.2f);
    lim->setDampingLimLin(0.3f);  // bounce 0.7
    lim->setDampingLimAng(0.5f);
    btSliderConstraint* motor = add(new btSliderConstraint(*a, *b, fa, fb, false));
    motor->setLowerLinLimit(-3.0f);
    motor->setUpperLinLimit(3.0f);
    motor->setLowerAngLimit(-3.0f);
    motor->setUpperAngLimit(3.0f);
    motor->setPoweredLinMotor(true);
    motor->setTargetLinMotorVelocity(0.8f);
    motor->setMaxLinMotorForce(20.0f);
    motor->setPoweredAngMotor(true);
    motor->setTargetAngMotorVelocity(-1.2f);
    motor->setMaxAngMotorForce(5.0f);
    btSliderConstraint* old = add(new btSliderConstraint(*a, *b, fa, fb, true));
    old->setUseFrameOffset(false);
    old->setLowerLinLimit(0.5f);
    old->setUpperLinLimit(0.5f);  // locked
    btSliderConstraint* tuned = add(new btSliderConstraint(*a, *b, fa, fb, true));
    tuned->setLowerLinLimit(-0.1f);
    tuned->setUpperLinLimit(0.1f);
    tuned->setParam(BT_CONSTRAINT_STOP_ERP, 0.7f, 0);
    tuned->setParam(BT_CONSTRAINT_STOP_ERP, 0.6f, 1);
    tuned->setParam(BT_CONSTRAINT_STOP_ERP, 0.5f, 4);
    tuned->setParam(BT_CONSTRAINT_STOP_CFM, 0.01f, 0);
    tuned->setParam(BT_CONSTRAINT_STOP_CFM, 0.02f, 1);
    tuned->setParam(BT_CONSTRAINT_STOP_CFM, 0.03f, 3);
    tuned->setParam(BT_CONSTRAINT_STOP_CFM, 0.04f, 4);
    // On the fixed body, built where body b stands (Bullet puts frame A at b's frame in world):
    // the angle and offset start exactly at zero, so limits that exclude zero, not a locked
    // range whose row appears or not with the last bit of rounding.
    btSliderConstraint* fixed = add(new btSliderConstraint(*b, fb, true), BTG_JOINT_FIXED_BODY);
    fixed->setLowerLinLimit(0.1f);
    fixed->setUpperLinLimit(0.2f);
    fixed->setLowerAngLimit(0.1f);
    fixed->setUpperAngLimit(0.3f);
    ref::JointTables tables;
    for (size_t i = 0; i < c.size(); ++i)
        tables.joints.push_back(sliderRow(bodyB[i] == BTG_JOINT_FIXED_BODY ? 1 : 0, bodyB[i], *c[i], int(6 * i)));
    // Bullet's fixed-body constructor puts the fixed body as A: mirror it.
    tables.joints.back().bodyA = BTG_JOINT_FIXED_BODY;
    tables.joints.back().bodyB = 1;
    tables.state.assign(c.size(), BtgJointState{});
    tables.rows.assign(6 * c.size(), BtgJointRow{});
    const BtgJointStepParams p = jointParams(int(c.size()));
    ref::JointTables expect = tables;
    ref::prepareJoints(expect, s.rows, p);
    DeviceJoints got = runPrepare(s.rows, tables, p);
    int extraRows = 0;
    for (size_t j = 0; j < c.size(); ++j) {
        std::vector<BulletRow> br = bulletRows(*c[j], p.dt, p.erp);
        ASSERT_EQ(got.state[j].numRows, int(br.size())) << "slider " << j;
        ASSERT_EQ(expect.state[j].numRows, int(br.size())) << "slider " << j;
        extraRows += int(br.size()) - 4;
        for (size_t k = 0; k < br.size(); ++k) {
            const BtgJointRow &g = got.rows[tables.joints[j].firstRow + k], &e = expect.rows[tables.joints[j].firstRow + k];
            expectRowAsBullet(g, e, br[k], "slider " + std::to_string(j) + " row " + std::to_string(k));
        }
    }
    EXPECT_GE(extraRows, 6);  // limit and motor rows of both kinds were built
}

TEST(PrepareJoints, DisabledBrokenAndSleepingJointsBuildNoRows)
{
    BulletBodies s;
    btRigidBody* a = s.add(1.0f, btVector3(0, 1, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    btRigidBody* b = s.add(1.0f, btVector3(0, 2, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    btPoint2PointConstraint c(*a, *b, btVector3(0, 0.5f, 0), btVector3(0, -0.5f, 0));
    ref::JointTables t;
    t.joints = {p2pRow(0, 1, c, 0), p2pRow(0, 1, c, 3), p2pRow(0, 1, c, 6)};
    t.joints[0].flags = 0;  // setEnabled(false)
    t.state.assign(3, BtgJointState{});
    t.state[1].broken = 1;
    t.state[2].appliedImpulse = 5.0f;
    t.rows.assign(9, BtgJointRow{});
    s.rows.props[0].flags |= BTG_BODY_SLEEPING;
    s.rows.props[1].flags |= BTG_BODY_SLEEPING;  // an island asleep: joint 2 keeps its impulse
    DeviceJoints got = runPrepare(s.rows, t, jointParams(3));
    for (int j = 0; j < 3; ++j) {
        EXPECT_EQ(got.state[j].numRows, 0) << j;
        // A joint without rows links nothing: its edge is a self-edge.
        EXPECT_EQ(got.edges[j].bodyA, got.edges[j].bodyB) << j;
    }
    EXPECT_EQ(got.state[2].appliedImpulse, 5.0f);
    EXPECT_EQ(got.state[1].broken, 1);
}

namespace {

// Contacts of a stack plus joints between its bodies, through prepare, batching, solve and
// finish, on the device.
struct SolveResult {
    ref::ContactBodies bodies;
    ref::JointTables joints;
    std::vector<int> colors;
};

SolveResult runSolveDevice(const test::StackScene& s, const ref::JointTables& t, const BtgStepParams& p,
                           const BtgJointStepParams& jp, int iterations, int maxColors, bool fused,
                           DeviceWorld::Resident resident = DeviceWorld::Resident::Auto,
                           DeviceWorld::Resident flow = DeviceWorld::Resident::Off, uint* status = nullptr,
                           DeviceWorld::Resident local = DeviceWorld::Resident::Off)
{
    DeviceWorld w(test::context());
    w.resident = resident;
    w.pgsFlow = flow;
    w.pgsLocal = local;
    w.lastContactCount = fused ? 0 : (1 << 30);
    test::uploadWorld(w, s.bodies, s.manifolds, uint(s.manifolds.size()), {}, s.manifolds.size() + 4);
    w.numJoints = int(t.joints.size());
    w.jointIterations = 0;
    for (const BtgJoint& j : t.joints) w.jointIterations = std::max(w.jointIterations, j.iterations);
    w.joints.upload(w.ctx, t.joints);
    w.jointState.upload(w.ctx, t.state);
    w.jointRows.reserve(w.ctx, t.rows.size());
    w.jointFeedback.reserve(w.ctx, t.joints.size());
    buildContacts(w, p);
    prepareContacts(w, p);
    prepareJoints(w, jp);
    w.colorRounds = maxColors - 1;
    colorConstraints(w, maxColors);
    solveConstraints(w, p, iterations, w.numColors);
    finishJoints(w, jp);
    SolveResult r;
    r.bodies = s.bodies;
    const size_t n = s.bodies.props.size();
    r.bodies.linVel = w.linVel.download(w.ctx, n);
    r.bodies.angVel = w.angVel.download(w.ctx, n);
    r.joints = t;
    r.joints.rows = w.jointRows.download(w.ctx, t.rows.size());
    r.joints.state = w.jointState.download(w.ctx, t.state.size());
    r.joints.feedback = w.jointFeedback.download(w.ctx, t.state.size());
    const std::vector<uint> counters = w.counters.download(w.ctx, kNumCounters);
    r.colors = w.edgeColor.download(w.ctx, counters[kEdgeCount]);
    if (status) *status = counters[kStatus];
    return r;
}

ref::JointTables stackJoints(const test::StackScene& s)
{
    // Joints between neighbouring dynamic bodies of the stack (rows 1..), and one to the fixed
    // body; pivots at the midpoints, so the rows start near rest.
    ref::JointTables t;
    const int n = int(s.bodies.props.size());
    int row = 0;
    for (int i = 1; i + 1 < n; i += 2) {
        BtgJoint j{};
        j.type = BTG_JOINT_POINT2POINT;
        j.bodyA = i;
        j.bodyB = i + 1;
        j.flags = BTG_JOINT_ENABLED | BTG_JOINT_FEEDBACK;
        j.firstRow = row;
        j.iterations = (i % 4 == 1) ? 14 : 10;  // some override upwards
        j.breakingThreshold = (i == 3) ? 1e-3f : INFINITY;  // one breaks
        const BtgFloat4 mid = (s.bodies.pos[i] + s.bodies.pos[i + 1]) * 0.5f;
        j.pivotA = btgXyz(mid - s.bodies.pos[i]);
        j.pivotB = btgXyz(mid - s.bodies.pos[i + 1]) + btgMake4(0.01f, 0, 0, 0);
        j.damping = 1.0f;
        t.joints.push_back(j);
        row += BTG_JOINT_P2P_ROWS;
    }
    BtgJoint f{};
    f.type = BTG_JOINT_POINT2POINT;
    f.bodyA = 1;
    f.bodyB = BTG_JOINT_FIXED_BODY;
    f.flags = BTG_JOINT_ENABLED | BTG_JOINT_FEEDBACK;
    f.firstRow = row;
    f.iterations = 10;
    f.breakingThreshold = INFINITY;
    f.pivotB = s.bodies.pos[1] + btgMake4(0, 0.02f, 0, 0);
    f.damping = 1.0f;
    t.joints.push_back(f);
    row += BTG_JOINT_P2P_ROWS;
    t.state.assign(t.joints.size(), BtgJointState{});
    t.rows.assign(size_t(row), BtgJointRow{});
    return t;
}

}  // namespace

TEST(PrepareJoints, SolveWithContactsMatchesReference)
{
    test::StackScene s = test::stackScene(4, 2, 2);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    for (size_t i = 0; i < s.bodies.props.size(); ++i)
        if (s.bodies.props[i].flags & BTG_BODY_DYNAMIC) s.bodies.linVel[i] = btgMake4(0.1f * float(i % 3), -0.3f, 0, 0);
    ref::JointTables t = stackJoints(s);
    BtgJointStepParams jp = jointParams(int(t.joints.size()));
    const int iterations = 10, maxColors = 24;
    // Reference: the same stages on the host.
    ref::ContactBodies rb = s.bodies;
    std::vector<BtgContact> contacts = ref::buildContacts(s.manifolds, int(s.manifolds.size()), rb, {}, p);
    std::vector<BtgEdge> edges = ref::prepareContacts(contacts, rb, p);
    ref::JointTables rt = t;
    std::vector<BtgEdge> jointEdges = ref::prepareJoints(rt, rb, jp);
    edges.insert(edges.end(), jointEdges.begin(), jointEdges.end());
    std::vector<int> colors = ref::colorConstraints(edges, rb, maxColors);
    int jointIterations = 0;
    for (const BtgJoint& j : t.joints) jointIterations = std::max(jointIterations, j.iterations);
    ref::solveConstraints(contacts, rt, colors, rb, p, iterations, jointIterations, maxColors);
    ref::finishJoints(rt, rb, jp);
    ASSERT_GT(contacts.size(), 0u);
    for (bool fused : {false, true}) {
        SCOPED_TRACE(fused ? "one launch" : "per color");
        SolveResult d = runSolveDevice(s, t, p, jp, iterations, maxColors, fused);
        ASSERT_EQ(d.colors.size(), colors.size());
        for (size_t e = 0; e < colors.size(); ++e) EXPECT_EQ(d.colors[e], colors[e]) << "edge " << e;
        for (size_t i = 0; i < rb.props.size(); ++i) {
            const std::string what = "body " + std::to_string(i);
            expectNear3(d.bodies.linVel[i], btVector3(rb.linVel[i].x, rb.linVel[i].y, rb.linVel[i].z), what + " lin");
            expectNear3(d.bodies.angVel[i], btVector3(rb.angVel[i].x, rb.angVel[i].y, rb.angVel[i].z), what + " ang");
        }
        for (size_t j = 0; j < t.joints.size(); ++j) {
            const std::string what = "joint " + std::to_string(j);
            expectNear(d.joints.state[j].appliedImpulse, rt.state[j].appliedImpulse, what + " applied impulse");
            EXPECT_EQ(d.joints.state[j].broken, rt.state[j].broken) << what;
            const BtgJointFeedback &gf = d.joints.feedback[j], &ef = rt.feedback[j];
            expectNear3(gf.forceA, btVector3(ef.forceA.x, ef.forceA.y, ef.forceA.z), what + " forceA");
            expectNear3(gf.torqueA, btVector3(ef.torqueA.x, ef.torqueA.y, ef.torqueA.z), what + " torqueA");
            expectNear3(gf.forceB, btVector3(ef.forceB.x, ef.forceB.y, ef.forceB.z), what + " forceB");
            expectNear3(gf.torqueB, btVector3(ef.torqueB.x, ef.torqueB.y, ef.torqueB.z), what + " torqueB");
        }
    }
    // The scene exercises what it claims: the low threshold breaks its joint, the others hold,
    // and the fixed-body joint carries load.
    EXPECT_EQ(rt.state[1].broken, 1);
    EXPECT_EQ(rt.state[0].broken, 0);
    EXPECT_GT(std::fabs(rt.state.back().appliedImpulse), 0.0f);
}

// The resident solve's flow (per-body counts instead of a barrier per colour) with joints: the
// joints' list, iteration overrides above the contacts' count, a joint to the fixed body and one
// that breaks: bitwise what the per-colour launches give (on a CPU device in groups of one
// work-item, so it must not time out).
namespace {
// The jointed stack the launch-shape tests solve: its bodies moving, so every row has work.
test::StackScene movingStack()
{
    test::StackScene s = test::stackScene(4, 2, 2);
    for (size_t i = 0; i < s.bodies.props.size(); ++i)
        if (s.bodies.props[i].flags & BTG_BODY_DYNAMIC) s.bodies.linVel[i] = btgMake4(0.1f * float(i % 3), -0.3f, 0, 0);
    return s;
}
}  // namespace

TEST(PrepareJoints, SolveWithContactsFlowIsBitwiseTheSame)
{
    using Resident = DeviceWorld::Resident;
    const test::StackScene s = movingStack();
    const BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    const ref::JointTables t = stackJoints(s);
    const BtgJointStepParams jp = jointParams(int(t.joints.size()));
    uint perColorStatus = 0, flowStatus = 0;
    const SolveResult a = runSolveDevice(s, t, p, jp, 10, 24, false, Resident::Off, Resident::Off, &perColorStatus);
    const SolveResult b = runSolveDevice(s, t, p, jp, 10, 24, false, Resident::On, Resident::On, &flowStatus);
    EXPECT_EQ(perColorStatus & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u);
    ASSERT_EQ(flowStatus & BTG_STATUS_GRID_BARRIER_TIMEOUT, 0u) << "the flow timed out";
    const size_t n = a.bodies.linVel.size() * sizeof(BtgFloat4);
    EXPECT_EQ(0, std::memcmp(a.bodies.linVel.data(), b.bodies.linVel.data(), n));
    EXPECT_EQ(0, std::memcmp(a.bodies.angVel.data(), b.bodies.angVel.data(), n));
    ASSERT_EQ(a.joints.rows.size(), b.joints.rows.size());
    for (size_t k = 0; k < a.joints.rows.size(); ++k)
        EXPECT_EQ(0, std::memcmp(&a.joints.rows[k].impulse, &b.joints.rows[k].impulse, sizeof(float))) << "row " << k;
    for (size_t j = 0; j < t.joints.size(); ++j) EXPECT_EQ(a.joints.state[j].broken, b.joints.state[j].broken) << j;
}

// The one-group solve with local velocities (solve_local), joints with iterations overridden
// upwards included: bitwise the per-colour launches'.
TEST(PrepareJoints, SolveWithContactsLocalIsBitwiseTheSame)
{
    using Resident = DeviceWorld::Resident;
    const test::StackScene s = movingStack();
    const BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    const ref::JointTables t = stackJoints(s);
    const BtgJointStepParams jp = jointParams(int(t.joints.size()));
    const SolveResult a = runSolveDevice(s, t, p, jp, 10, 24, false, Resident::Off);
    const SolveResult b = runSolveDevice(s, t, p, jp, 10, 24, false, Resident::Off, Resident::Off, nullptr, Resident::On);
    const size_t n = a.bodies.linVel.size() * sizeof(BtgFloat4);
    EXPECT_EQ(0, std::memcmp(a.bodies.linVel.data(), b.bodies.linVel.data(), n));
    EXPECT_EQ(0, std::memcmp(a.bodies.angVel.data(), b.bodies.angVel.data(), n));
    ASSERT_EQ(a.joints.rows.size(), b.joints.rows.size());
    int loaded = 0;
    for (size_t k = 0; k < a.joints.rows.size(); ++k) {
        EXPECT_EQ(0, std::memcmp(&a.joints.rows[k].impulse, &b.joints.rows[k].impulse, sizeof(float))) << "row " << k;
        loaded += a.joints.rows[k].impulse != 0.0f;
    }
    EXPECT_GT(loaded, 0);
    for (size_t j = 0; j < t.joints.size(); ++j) EXPECT_EQ(a.joints.state[j].broken, b.joints.state[j].broken) << j;
}
