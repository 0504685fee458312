// soft_joint_turn_test.cpp — the soft step's linear joint rows turned with the bodies
// (btgSoftTurnLinearRows, kernels/shared/soft_joint_rows.h) against Bullet's own getInfo2 rows
// rebuilt at the turned poses: the turned pivot rows measure the joint's relative pivot velocity
// as Bullet's rows at those poses do; the start rows do not (the test can fail).
#include "joint_fixture.h"
#include "shared/soft_joint_rows.h"

#include <cstring>
#include <functional>

using namespace btgpu;
using namespace btgpu::jointtest;

namespace {

BtgJointRow deviceRow(const BulletRow& b)
{
    BtgJointRow r{};
    r.jacobian.linear = f4(b.linA);
    r.jacobian.angularA = f4(b.angA);
    r.jacobian.angularB = f4(b.angB);
    r.mass = b.mass;
    r.target = b.target;
    r.lower = b.lower;
    r.upper = b.upper;
    r.cfm = b.cfm;
    return r;
}

BtgSolverBody solverBody(const BulletBodies& bodies, int i)
{
    const ref::ContactBodies& r = bodies.rows;
    return btgMakeSolverBody(r.props[size_t(i)], r.invInertiaWorld[3 * size_t(i)], r.invInertiaWorld[3 * size_t(i) + 1],
                             r.invInertiaWorld[3 * size_t(i) + 2]);
}

// The relative velocity of the pivot the rows hold: sum over the linear rows of n (J v), for
// bodies moving at (vA, wA) and (vB, wB) (the linear rows of these joints are orthonormal).
btVector3 pivotVelocity(const std::vector<BtgJointRow>& rows, const btVector3& vA, const btVector3& wA, const btVector3& vB,
                        const btVector3& wB)
{
    const BtgBodyVel a = btgMakeBodyVel(1, f4(vA), f4(wA)), b = btgMakeBodyVel(1, f4(vB), f4(wB));
    btVector3 sum(0, 0, 0);
    for (const BtgJointRow& r : rows) {
        if (!btgSoftLinearRow(r.jacobian)) continue;
        const float v = btgRowVelocity(r.jacobian, a, b);
        sum += btVector3(r.jacobian.linear.x, r.jacobian.linear.y, r.jacobian.linear.z) * v;
    }
    return sum;
}

struct Case {
    const char* name;
    std::function<btTypedConstraint*(btRigidBody&, btRigidBody&)> make;
    float tolerance;  // m/s per m/s of the pivot's velocity
    bool aboutAxis;   // the bodies turn about the joint's axis (frame A's z in the world), not freely
};

}  // namespace

// Two bodies joined by each joint type with a pivot, turned about their centres (A by 0.12 rad,
// B by 0.09 rad about other axes): the start rows turned by those rotations give the relative
// pivot velocity that Bullet's rows rebuilt at the turned poses give, for arbitrary velocities,
// to float rounding. The hinge's frames meet and its bodies turn about its axis, as a hinge
// lets them: its rows run along the bodies' axes blended by their masses, and its arms (relA,
// relB) take a share of the bodies' separation along that axis, which turns across the axis
// (which the hinge's rows stop) would change otherwise than by turning.
TEST(SoftJointTurn, TurnedRowsMeasureThePivotAsBulletsRowsAtTheTurnedPoses)
{
    const std::vector<Case> cases = {
        {"point-to-point",
         [](btRigidBody& a, btRigidBody& b) {
             return new btPoint2PointConstraint(a, b, frameInA().getOrigin(), frameInB().getOrigin());
         },
         1e-5f, false},
        {"cone twist", [](btRigidBody& a, btRigidBody& b) { return new btConeTwistConstraint(a, b, frameInA(), frameInB()); },
         1e-5f, false},
        {"6-DoF spring2",
         [](btRigidBody& a, btRigidBody& b) { return new btGeneric6DofSpring2Constraint(a, b, frameInA(), frameInB()); },
         1e-5f, false},
        {"hinge",  // its frames meeting, as a hinge holds them
         [](btRigidBody& a, btRigidBody& b) {
             const btTransform inB = b.getWorldTransform().inverse() * a.getWorldTransform() * frameInA();
             return new btHingeConstraint(a, b, frameInA(), inB);
         },
         1e-5f, true},
    };
    const btVector3 vA(0.4f, -1.2f, 0.7f), wA(2.0f, -0.5f, 1.5f), vB(-0.3f, 0.8f, 0.1f), wB(-1.0f, 2.5f, 0.4f);
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        BulletBodies bodies;
        btRigidBody* a = bodies.addBodyA();
        btRigidBody* b = bodies.addBodyB();
        std::unique_ptr<btTypedConstraint> joint(c.make(*a, *b));
        std::vector<BtgJointRow> rows;
        for (const BulletRow& r : bulletRows(*joint, 1.0f / 60.0f, 0.2f)) rows.push_back(deviceRow(r));
        const std::vector<BtgJointRow> start = rows;
        ASSERT_GE(rows.size(), 3u);

        const btTransform ta = a->getWorldTransform(), tb = b->getWorldTransform();
        const btVector3 axis = (ta.getBasis() * frameInA().getBasis()).getColumn(2);
        const btQuaternion turnA(c.aboutAxis ? axis : btVector3(1, -1, 2).normalized(), 0.12f);
        const btQuaternion turnB(c.aboutAxis ? axis : btVector3(0, 3, 1).normalized(), c.aboutAxis ? -0.09f : 0.09f);
        a->setWorldTransform(btTransform(turnA * ta.getRotation(), ta.getOrigin()));
        b->setWorldTransform(btTransform(turnB * tb.getRotation(), tb.getOrigin()));
        std::vector<BtgJointRow> turnedPose;
        for (const BulletRow& r : bulletRows(*joint, 1.0f / 60.0f, 0.2f)) turnedPose.push_back(deviceRow(r));

        const BtgMat3 dA = btgQuatToMat3(btgMake4(turnA.x(), turnA.y(), turnA.z(), turnA.w()));
        const BtgMat3 dB = btgQuatToMat3(btgMake4(turnB.x(), turnB.y(), turnB.z(), turnB.w()));
        BtgFloat4 spinA, spinB;
        btgSoftTurnLinearRows(rows.data(), 0, int(rows.size()), solverBody(bodies, 0), solverBody(bodies, 1), dA, dB, &spinA, &spinB);
        // the second sweep of a substep reads its arms back from the rows (BTG_JOINT_ROW_ARMS)
        std::vector<BtgJointRow> again = rows;
        btgSoftTurnLinearRows(again.data(), 0, int(again.size()), solverBody(bodies, 0), solverBody(bodies, 1), dA, dB, &spinA, &spinB);

        int turned = 0;
        for (const BtgJointRow& r : rows) turned += (r.flags & BTG_JOINT_ROW_TURNED) != 0;
        EXPECT_EQ(3, turned);
        EXPECT_NE(0, rows[0].flags & BTG_JOINT_ROW_ARMS);

        const btVector3 want = pivotVelocity(turnedPose, vA, wA, vB, wB);
        const btVector3 got = pivotVelocity(rows, vA, wA, vB, wB), got2 = pivotVelocity(again, vA, wA, vB, wB);
        const btVector3 stale = pivotVelocity(start, vA, wA, vB, wB);
        const float bound = c.tolerance * want.length();
        EXPECT_LE((got - want).length(), bound) << "turned " << (got - want).length() << " of " << want.length();
        EXPECT_LE((got2 - want).length(), bound);
        EXPECT_GT((stale - want).length(), 20.0f * bound) << "the start rows already agree: the test could not fail";
        // a turned row's mass is its Jacobian's, on the step's inverse inertia
        for (const BtgJointRow& r : rows) {
            if (!(r.flags & BTG_JOINT_ROW_TURNED)) continue;
            const BtgSolverBody sa = solverBody(bodies, 0), sb = solverBody(bodies, 1);
            const float k = sa.invMass + sb.invMass + btgDot3(btgMat3MulVec(sa.invI, r.jacobian.angularA), r.jacobian.angularA) +
                            btgDot3(btgMat3MulVec(sb.invI, r.jacobian.angularB), r.jacobian.angularB);
            EXPECT_NEAR(r.mass * k, 1.0f, 1e-5f);
        }
    }
}

// A hinge with the frame offset on a static body: Bullet scales its axial linear row's angular
// parts by the masses' factors (0 on the dynamic side), so that row is not the arms' and stays as
// built; the two rows across the axis turn.
TEST(SoftJointTurn, AHingesScaledAxialRowStaysAsBuilt)
{
    BulletBodies bodies;
    btRigidBody* a = bodies.addBodyA();
    btRigidBody* ground = bodies.add(0.0f, btVector3(0, 0, 0), btQuaternion::getIdentity(), btVector3(0, 0, 0), btVector3(0, 0, 0));
    btHingeConstraint hinge(*a, *ground, frameInA(), frameInB());
    ASSERT_TRUE(hinge.getUseFrameOffset());
    std::vector<BtgJointRow> rows;
    for (const BulletRow& r : bulletRows(hinge, 1.0f / 60.0f, 0.2f)) rows.push_back(deviceRow(r));
    const std::vector<BtgJointRow> start = rows;
    const BtgMat3 dA = btgQuatToMat3(btgMake4(0.0f, 0.0f, std::sin(0.05f), std::cos(0.05f)));
    const BtgMat3 still = btgQuatToMat3(btgMake4(0.0f, 0.0f, 0.0f, 1.0f));
    BtgFloat4 turnA, turnB;
    btgSoftTurnLinearRows(rows.data(), 0, int(rows.size()), solverBody(bodies, 0), solverBody(bodies, 1), dA, still, &turnA, &turnB);
    ASSERT_GE(rows.size(), 3u);
    EXPECT_NE(0, rows[0].flags & BTG_JOINT_ROW_TURNED);
    EXPECT_NE(0, rows[1].flags & BTG_JOINT_ROW_TURNED);
    EXPECT_EQ(0, rows[2].flags & BTG_JOINT_ROW_TURNED);
    EXPECT_EQ(0, std::memcmp(&rows[2].jacobian.angularA.x, &start[2].jacobian.angularA.x, 3 * sizeof(float)));
    EXPECT_EQ(rows[2].mass, start[2].mass);
    EXPECT_GT(std::fabs(rows[0].jacobian.angularA.x - start[0].jacobian.angularA.x) +
                  std::fabs(rows[0].jacobian.angularA.y - start[0].jacobian.angularA.y),
              1e-4f);
}
