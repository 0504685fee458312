// joint_fixture.h — what the joint stage tests share: Bullet bodies mirrored as body rows,
// Bullet's own getInfo1/getInfo2 rows finished as convertJoint does, the stage run on the
// device, and the stage tolerances (tests/tolerances.h) as comparisons.
#pragma once
#include "../../compat/joint_rows.h"
#include "../../compat/row_map.h"
#include "contact_fixture.h"
#include "reference/joint_reference.h"
#include "stages/prepare_joints.h"
#include "test_device.h"
#include "tolerances.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <memory>
#include <string>
#include <vector>

namespace btgpu {
namespace jointtest {

inline BtgFloat4 f4(const btVector3& v) { return btgMake4(v.x(), v.y(), v.z(), 0.0f); }

// Bullet bodies and the same bodies as rows.
struct BulletBodies {
    btBoxShape shape{btVector3(0.3f, 0.2f, 0.5f)};
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    ref::ContactBodies rows;

    // The rows compat's jointRow reads bodies a and b through: a then b.
    static RowMap rowsOf(btRigidBody* a, btRigidBody* b)
    {
        btAlignedObjectArray<btCollisionObject*> objects;
        objects.push_back(a);
        objects.push_back(b);
        RowMap map;
        map.reset(objects);
        return map;
    }

    btRigidBody* add(btScalar mass, const btVector3& pos, const btQuaternion& q, const btVector3& v, const btVector3& w)
    {
        btVector3 inertia(0, 0, 0);
        if (mass > 0) shape.calculateLocalInertia(mass, inertia);
        btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, &shape, inertia);
        ci.m_startWorldTransform = btTransform(q, pos);
        bodies.emplace_back(new btRigidBody(ci));
        btRigidBody* b = bodies.back().get();
        b->setLinearVelocity(v);
        b->setAngularVelocity(w);
        BtgBodyProps p{};
        p.invInertiaLocal = f4(b->getInvInertiaDiagLocal());
        p.linearFactor = f4(b->getLinearFactor());
        p.angularFactor = f4(b->getAngularFactor());
        p.invMass = b->getInvMass();
        p.flags = mass > 0 ? BTG_BODY_DYNAMIC : BTG_BODY_STATIC;
        rows.props.push_back(p);
        rows.pos.push_back(f4(pos));
        btQuaternion r = b->getOrientation();
        rows.rot.push_back(btgMake4(r.x(), r.y(), r.z(), r.w()));
        rows.linVel.push_back(f4(v));
        rows.angVel.push_back(f4(w));
        rows.linVel0.push_back(f4(v));
        rows.angVel0.push_back(f4(w));  // no forces: the velocities before and after them agree
        for (auto* col : {&rows.pushLin, &rows.pushAng}) col->push_back(btgZero4());
        const btMatrix3x3& I = b->getInvInertiaTensorWorld();
        for (int k = 0; k < 3; ++k) rows.invInertiaWorld.push_back(f4(I[k]));
        return b;
    }
    // The two moving bodies every row test joins: turned, moving and spinning arbitrarily.
    btRigidBody* addBodyA()
    {
        return add(2.0f, btVector3(0.1f, 2.0f, -0.3f), btQuaternion(btVector3(1, 2, 3).normalized(), 0.7f),
                   btVector3(0.5f, -1.0f, 0.2f), btVector3(0.3f, 0.1f, -2.0f));
    }
    btRigidBody* addBodyB()
    {
        return add(3.0f, btVector3(0.4f, 1.1f, 0.2f), btQuaternion(btVector3(-1, 0, 2).normalized(), 1.9f),
                   btVector3(-0.2f, 0.4f, 0.0f), btVector3(1.0f, -0.5f, 0.25f));
    }
};

// Joint frames in A's and B's body frames that the row tests share: neither at the centre nor aligned.
inline btTransform frameInA() { return btTransform(btQuaternion(btVector3(0, 0, 1), 0.3f), btVector3(0.2f, -0.4f, 0.1f)); }
inline btTransform frameInB() { return btTransform(btQuaternion(btVector3(0, 1, 0), -0.6f), btVector3(-0.1f, 0.5f, 0.0f)); }

inline BtgJoint p2pRow(int a, int b, const btPoint2PointConstraint& c, int firstRow)
{
    BtgJoint j{};
    j.type = BTG_JOINT_POINT2POINT;
    j.bodyA = a;
    j.bodyB = b;
    j.flags = c.isEnabled() ? BTG_JOINT_ENABLED : 0u;
    j.firstRow = firstRow;
    j.iterations = 10;
    j.breakingThreshold = c.getBreakingImpulseThreshold();
    j.pivotA = f4(c.getPivotInA());
    j.pivotB = f4(c.getPivotInB());
    j.damping = c.m_setting.m_damping;
    j.impulseClamp = c.m_setting.m_impulseClamp;
    return j;
}

// The device row of a hinge as compat/joint_rows.cpp builds it, from the hinge's getters and
// what the test set (the private reference sign and limit are passed in).
inline BtgJoint hingeRow(int a, int b, btHingeConstraint& h, int firstRow, float referenceSign, float low, float high,
                  float bias, float relaxation)
{
    BtgJoint j{};
    j.type = BTG_JOINT_HINGE;
    j.bodyA = a;
    j.bodyB = b;
    j.flags = BTG_JOINT_ENABLED;
    j.firstRow = firstRow;
    j.iterations = 10;
    j.breakingThreshold = h.getBreakingImpulseThreshold();
    j.pivotA = f4(h.getAFrame().getOrigin());
    j.pivotB = f4(h.getBFrame().getOrigin());
    for (int c = 0; c < 3; ++c) {
        j.axesA[c] = f4(h.getAFrame().getBasis().getColumn(c));
        j.axesB[c] = f4(h.getBFrame().getBasis().getColumn(c));
    }
    if (h.getAngularOnly()) j.flags |= BTG_JOINT_ANGULAR_ONLY;
    if (h.getUseFrameOffset()) j.flags |= BTG_JOINT_FRAME_OFFSET;
    if (h.getEnableAngularMotor()) j.flags |= BTG_JOINT_MOTOR;
    j.motorVelocity = h.getMotorTargetVelocity();
    j.motorMaxImpulse = h.getMaxMotorImpulse();
    j.referenceSign = referenceSign;
    if (high >= low) {
        j.limitHalfRange = (high - low) / 2.0f;
        j.limitCenter = btNormalizeAngle(low + j.limitHalfRange);
    } else {
        j.limitHalfRange = -1.0f;
    }
    j.limitBias = bias;
    j.limitRelaxation = relaxation;
    return j;
}

inline BtgJointStepParams jointParams(int n)
{
    BtgJointStepParams p{};
    p.dt = 1.0f / 60.0f;
    p.erp = 0.2f;
    p.globalCfm = 0.0f;
    p.damping = 1.0f;
    p.numJoints = n;
    p.numIterations = 10;  // bulletRows' info2.m_numIterations
    return p;
}

// Bullet's getInfo2 rows for constraint c, finished as convertJoint does (mass, rhs as target).
struct BulletRow {
    btVector3 linA, angA, linB, angB;
    float mass, target, lower, upper, cfm;
};
inline std::vector<BulletRow> bulletRows(btTypedConstraint& c, float dt, float erp)
{
    btTypedConstraint::btConstraintInfo1 info1;
    c.getInfo1(&info1);
    const int n = info1.m_numConstraintRows, skip = 16;
    std::vector<btScalar> j1l(n * skip, 0), j1a(n * skip, 0), j2l(n * skip, 0), j2a(n * skip, 0);
    std::vector<btScalar> err(n * skip, 0), cfm(n * skip, 0), lo(n * skip, -SIMD_INFINITY), hi(n * skip, SIMD_INFINITY);
    btTypedConstraint::btConstraintInfo2 info2;
    info2.fps = 1.f / dt;
    info2.erp = erp;
    info2.m_J1linearAxis = j1l.data();
    info2.m_J1angularAxis = j1a.data();
    info2.m_J2linearAxis = j2l.data();
    info2.m_J2angularAxis = j2a.data();
    info2.rowskip = skip;
    info2.m_constraintError = err.data();
    info2.cfm = cfm.data();
    info2.m_lowerLimit = lo.data();
    info2.m_upperLimit = hi.data();
    info2.m_damping = 1.0f;
    info2.m_numIterations = 10;
    c.getInfo2(&info2);
    std::vector<BulletRow> out;
    const btRigidBody &a = c.getRigidBodyA(), &b = c.getRigidBodyB();
    for (int k = 0; k < n; ++k) {
        BulletRow r;
        auto v = [&](std::vector<btScalar>& arr) { return btVector3(arr[k * skip], arr[k * skip + 1], arr[k * skip + 2]); };
        r.linA = v(j1l);
        r.angA = v(j1a);
        r.linB = v(j2l);
        r.angB = v(j2a);
        r.lower = std::max<float>(lo[k * skip], -c.getBreakingImpulseThreshold());
        r.upper = std::min<float>(hi[k * skip], c.getBreakingImpulseThreshold());
        float sum = (r.linA * a.getInvMass()).dot(r.linA) + (a.getInvInertiaTensorWorld() * r.angA).dot(r.angA) +
                    (r.linB * b.getInvMass()).dot(r.linB) + (b.getInvInertiaTensorWorld() * r.angB).dot(r.angB);
        r.mass = 1.0f / sum;
        float relVel = r.linA.dot(a.getLinearVelocity()) + r.angA.dot(a.getAngularVelocity()) +
                       r.linB.dot(b.getLinearVelocity()) + r.angB.dot(b.getAngularVelocity());
        float rhs = err[k * skip] * r.mass + (0.0f - relVel * info2.m_damping) * r.mass;
        r.target = rhs / r.mass + relVel;
        r.cfm = cfm[k * skip] * r.mass;
        out.push_back(r);
    }
    return out;
}

inline void expectNear(float got, float want, const std::string& what)
{
    if (std::fabs(want) > 1e30f) {  // a spring's USE_INFINITE_ERROR target (SIMD_INFINITY, plus J v0)
        EXPECT_NEAR(got / want, 1.0f, 1e-6f) << what;
        return;
    }
    EXPECT_NEAR(got, want, tol::kStageAbs + tol::kStageRel * std::fabs(want)) << what;
}
inline void expectNear3(BtgFloat4 got, const btVector3& want, const std::string& what)
{
    expectNear(got.x, want.x(), what + ".x");
    expectNear(got.y, want.y(), what + ".y");
    expectNear(got.z, want.z(), what + ".z");
}

struct DeviceJoints {
    std::vector<BtgJointRow> rows;
    std::vector<BtgJointState> state;
    std::vector<BtgEdge> edges;
    uint edgeCount = 0;
};

inline DeviceJoints runPrepare(const ref::ContactBodies& b, const ref::JointTables& t, const BtgJointStepParams& p)
{
    DeviceWorld w(test::context());
    test::uploadWorld(w, b, {}, 0, {}, 4);
    w.numJoints = int(t.joints.size());
    w.joints.upload(w.ctx, t.joints);
    w.jointState.upload(w.ctx, t.state);
    w.jointRows.reserve(w.ctx, t.rows.size());
    prepareJoints(w, p);
    DeviceJoints d;
    d.rows = w.jointRows.download(w.ctx, t.rows.size());
    d.state = w.jointState.download(w.ctx, t.state.size());
    d.edgeCount = w.counters.download(w.ctx, kNumCounters)[kEdgeCount];
    d.edges = w.edges.download(w.ctx, d.edgeCount);
    return d;
}

// One joint's row k on the device against the CPU reference's and Bullet's own getInfo2 row.
inline void expectRowAsBullet(const BtgJointRow& g, const BtgJointRow& e, const BulletRow& b, const std::string& what)
{
    expectNear(g.mass, e.mass, what + " mass (ref)");
    expectNear(g.target, e.target, what + " target (ref)");
    expectNear(g.cfm, e.cfm, what + " cfm (ref)");
    expectNear3(g.jacobian.linear, b.linA, what + " linA");
    expectNear3(-g.jacobian.linear, b.linB, what + " linB");
    expectNear3(g.jacobian.angularA, b.angA, what + " angA");
    expectNear3(g.jacobian.angularB, b.angB, what + " angB");
    expectNear(g.mass, b.mass, what + " mass");
    expectNear(g.target, b.target, what + " target");
    expectNear(g.cfm, b.cfm, what + " cfm");
    // Unbounded sides are exact; the others (0, a motor's force per step, a spring's step of
    // force from the pose) within the stage tolerance.
    if (std::fabs(b.lower) > 1e30f) EXPECT_EQ(g.lower, b.lower) << what;
    else expectNear(g.lower, b.lower, what + " lower");
    if (std::fabs(b.upper) > 1e30f) EXPECT_EQ(g.upper, b.upper) << what;
    else expectNear(g.upper, b.upper, what + " upper");
}

// Counts of the rows seen: one-sided (bounded on one side), bounded on both (motors, servos, springs).
struct RowKinds {
    int bounded = 0, motors = 0, firstRows0 = 0;
};

// Each 6-DoF joint (of device type `type`) converted by compat's jointRow, prepared on the
// device and by the reference, and every row compared with Bullet's own getInfo2 row for the
// same bodies.
template <class C>
RowKinds expectRowsAsBullet(BulletBodies& s, const RowMap& map, std::vector<std::unique_ptr<C>>& c, int type)
{
    RowKinds kinds;
    ref::JointTables tables;
    int nextRow = 0;
    for (auto& k : c) {
        BtgJoint j;
        EXPECT_TRUE(jointRow(*k, map, 10, &j));
        EXPECT_EQ(j.type, type);
        j.firstRow = nextRow;
        nextRow += type == BTG_JOINT_SIXDOF2 ? btgSixDofMaxRows(j.sixdof) : btgJointMaxRows(type);
        tables.joints.push_back(j);
    }
    tables.state.assign(c.size(), BtgJointState{});
    tables.rows.assign(size_t(nextRow), BtgJointRow{});
    const BtgJointStepParams p = jointParams(int(c.size()));
    ref::JointTables expect = tables;
    ref::prepareJoints(expect, s.rows, p);
    DeviceJoints got = runPrepare(s.rows, tables, p);
    for (size_t j = 0; j < c.size(); ++j) {
        std::vector<BulletRow> br = bulletRows(*c[j], p.dt, p.erp);
        EXPECT_EQ(got.state[j].numRows, int(br.size())) << "6dof " << j;
        EXPECT_EQ(expect.state[j].numRows, int(br.size())) << "6dof " << j;
        EXPECT_LE(int(br.size()), type == BTG_JOINT_SIXDOF2 ? btgSixDofMaxRows(tables.joints[j].sixdof) : btgJointMaxRows(type))
            << "6dof " << j;
        if (got.state[j].numRows != int(br.size())) continue;
        if (j == 0) kinds.firstRows0 = int(br.size());
        for (size_t k = 0; k < br.size(); ++k) {
            const BtgJointRow &g = got.rows[tables.joints[j].firstRow + k], &e = expect.rows[tables.joints[j].firstRow + k];
            expectRowAsBullet(g, e, br[k], "6dof " + std::to_string(j) + " row " + std::to_string(k));
            // Unbounded sides arrive clamped to the breaking threshold (SIMD_INFINITY).
            const bool bigLo = std::fabs(br[k].lower) > 1e30f, bigHi = std::fabs(br[k].upper) > 1e30f;
            if (bigLo != bigHi) ++kinds.bounded;
            if (!bigLo && !bigHi) ++kinds.motors;
        }
    }
    return kinds;
}


}  // namespace jointtest
}  // namespace btgpu
