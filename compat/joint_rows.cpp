// joint_rows.cpp — btTypedConstraint → BtgJoint, the per-step comparison and upload of the
// joint table, and the write-back of applied impulses, feedback and breaks.
#include "joint_rows.h"
#include "joint_order.h"

#include "parallel_rows.h"
#include "private_member.h"
#include "shared/generic6dof_rows.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <typeinfo>
#include <unordered_set>

#include <cxxabi.h>

namespace btgpu {

// The joints' private state that has no getter (private_member.h; tags at namespace scope, as its
// explicit instantiations must be): the hinge's reference sign (fixed by the constructor;
// setUseReferenceFrameA does not change it), its limit's centre, the setParam values and the
// obsolete-solve flags.
BTGPU_PRIVATE_MEMBER(HingeReferenceSign, btHingeConstraint, btScalar, m_referenceSign);
BTGPU_PRIVATE_MEMBER(HingeLimit, btHingeConstraint, btAngularLimit, m_limit);
BTGPU_PRIVATE_MEMBER(HingeNormalCfm, btHingeConstraint, btScalar, m_normalCFM);
BTGPU_PRIVATE_MEMBER(HingeNormalErp, btHingeConstraint, btScalar, m_normalERP);
BTGPU_PRIVATE_MEMBER(HingeStopCfm, btHingeConstraint, btScalar, m_stopCFM);
BTGPU_PRIVATE_MEMBER(HingeStopErp, btHingeConstraint, btScalar, m_stopERP);
BTGPU_PRIVATE_MEMBER(HingeObsolete, btHingeConstraint, bool, m_useSolveConstraintObsolete);
BTGPU_PRIVATE_MEMBER(LimitCenter, btAngularLimit, btScalar, m_center);
BTGPU_PRIVATE_MEMBER(ConeLinErp, btConeTwistConstraint, btScalar, m_linERP);
BTGPU_PRIVATE_MEMBER(ConeLinCfm, btConeTwistConstraint, btScalar, m_linCFM);
BTGPU_PRIVATE_MEMBER(ConeAngCfm, btConeTwistConstraint, btScalar, m_angCFM);
BTGPU_PRIVATE_MEMBER(ConeObsolete, btConeTwistConstraint, bool, m_useSolveConstraintObsolete);
BTGPU_PRIVATE_MEMBER(SliderObsolete, btSliderConstraint, bool, m_useSolveConstraintObsolete);
BTGPU_PRIVATE_MEMBER(SliderCfmDirLin, btSliderConstraint, btScalar, m_cfmDirLin);
BTGPU_PRIVATE_MEMBER(SliderCfmDirAng, btSliderConstraint, btScalar, m_cfmDirAng);
BTGPU_PRIVATE_MEMBER(SliderCfmLimLin, btSliderConstraint, btScalar, m_cfmLimLin);
BTGPU_PRIVATE_MEMBER(SliderCfmLimAng, btSliderConstraint, btScalar, m_cfmLimAng);
BTGPU_PRIVATE_MEMBER(SliderCfmOrthoLin, btSliderConstraint, btScalar, m_cfmOrthoLin);
BTGPU_PRIVATE_MEMBER(SliderCfmOrthoAng, btSliderConstraint, btScalar, m_cfmOrthoAng);
BTGPU_PRIVATE_MEMBER(SixDofFlags, btGeneric6DofSpring2Constraint, int, m_flags);

namespace {

std::string typeName(const std::type_info& t)
{
    int status = 0;
    char* name = abi::__cxa_demangle(t.name(), nullptr, nullptr, &status);
    std::string out = status == 0 && name ? name : t.name();
    std::free(name);
    return out;
}

BtgFloat4 vec4(const btVector3& v) { return btgMake4(v.x(), v.y(), v.z(), 0.0f); }

int bodyRow(const btRigidBody& b, const RowMap& rows)
{
    if (&b == &btTypedConstraint::getFixedBody()) return BTG_JOINT_FIXED_BODY;
    return rows.rowOf(&b);
}


// btGeneric6DofConstraint by exact type, and the two Bullet classes that derive from it and add
// nothing to its rows but their construction (btUniversalConstraint) or their springs
// (btGeneric6DofSpringConstraint).
bool isGeneric6Dof(const std::type_info& t)
{
    return t == typeid(btGeneric6DofConstraint) || t == typeid(btUniversalConstraint) ||
           t == typeid(btGeneric6DofSpringConstraint);
}

bool isSixDof2(const std::type_info& t)
{
    return t == typeid(btGeneric6DofSpring2Constraint) || t == typeid(btFixedConstraint) ||
           t == typeid(btHinge2Constraint);
}

// A 6-DoF spring2 axis's motor, servo and spring switches as BtgSixDofAxis.mode.
uint sixDofMode(bool motor, bool servo, bool spring, bool stiffLimited, bool dampLimited)
{
    return (motor ? BTG_SIXDOF_MOTOR : 0u) | (servo ? BTG_SIXDOF_SERVO : 0u) | (spring ? BTG_SIXDOF_SPRING : 0u) |
           (stiffLimited ? BTG_SIXDOF_STIFF_LIMITED : 0u) | (dampLimited ? BTG_SIXDOF_DAMP_LIMITED : 0u);
}

// A hinge: btHingeConstraint, or Bullet's btHingeAccumulatedAngleConstraint, whose rows are the
// hinge's (it overrides getInfo1 only, to track its angle across the -pi/pi boundary).
bool isHinge(const std::type_info& t)
{
    return t == typeid(btHingeConstraint) || t == typeid(btHingeAccumulatedAngleConstraint);
}

// The exact types the GPU path takes (whether this one's settings are served is served()).
bool isServedType(const std::type_info& t)
{
    return t == typeid(btPoint2PointConstraint) || isHinge(t) || t == typeid(btConeTwistConstraint) ||
           t == typeid(btSliderConstraint) || isGeneric6Dof(t) || isSixDof2(t) || t == typeid(btGearConstraint);
}

bool served(const btTypedConstraint& c)
{
    if (isSixDof2(typeid(c)) || typeid(c) == typeid(btGearConstraint)) return true;  // no obsolete solve
    if (typeid(c) == typeid(btPoint2PointConstraint))
        return !static_cast<const btPoint2PointConstraint&>(c).m_useSolveConstraintObsolete;
    if (isHinge(typeid(c))) return !(static_cast<const btHingeConstraint&>(c).*member(HingeObsolete()));
    if (typeid(c) == typeid(btConeTwistConstraint)) {
        const auto& k = static_cast<const btConeTwistConstraint&>(c);
        return !(k.*member(ConeObsolete()));
    }
    if (typeid(c) == typeid(btSliderConstraint))
        return !(static_cast<const btSliderConstraint&>(c).*member(SliderObsolete()));
    if (isGeneric6Dof(typeid(c))) return !static_cast<const btGeneric6DofConstraint&>(c).m_useSolveConstraintObsolete;
    return false;
}

void setFrame(const btTransform& t, BtgFloat4* origin, BtgFloat4* axes)
{
    *origin = vec4(t.getOrigin());
    for (int c = 0; c < 3; ++c) axes[c] = vec4(t.getBasis().getColumn(c));
}

// A btGeneric6DofConstraint (or btUniversalConstraint, btGeneric6DofSpringConstraint) as the
// device row: BtgSixDofAxis per axis with the getInfo2 fields (m_normalCFM as motorCfm). A
// spring axis's motor target and force are left 0: the device computes them each substep from
// the pose, as internalUpdateSprings does in getInfo2 (Bullet writes them into the constraint).
void generic6DofRow(btGeneric6DofConstraint& k, BtgJoint* out)
{
    BtgJoint& j = *out;
    j.type = BTG_JOINT_SIXDOF;
    setFrame(k.getFrameOffsetA(), &j.pivotA, j.axesA);
    setFrame(k.getFrameOffsetB(), &j.pivotB, j.axesB);
    const int flags = k.getFlags();
    const btTranslationalLimitMotor* lin = k.getTranslationalLimitMotor();
    const auto* spring = typeid(k) == typeid(btGeneric6DofSpringConstraint)
                             ? static_cast<const btGeneric6DofSpringConstraint*>(&k)
                             : nullptr;
    for (int i = 0; i < 6; ++i) {
        BtgSixDofAxis& x = j.sixdof.axis[i];
        x.flags = uint(flags >> (i * BT_6DOF_FLAGS_AXIS_SHIFT)) & 7u;
        bool motor;
        if (i < 3) {
            x.lo = lin->m_lowerLimit[i];
            x.hi = lin->m_upperLimit[i];
            x.stopErp = lin->m_stopERP[i];
            x.stopCfm = lin->m_stopCFM[i];
            x.motorCfm = lin->m_normalCFM[i];
            x.targetVelocity = lin->m_targetVelocity[i];
            x.maxMotorForce = lin->m_maxMotorForce[i];
            motor = lin->m_enableMotor[i];
        } else {
            const btRotationalLimitMotor* r = k.getRotationalLimitMotor(i - 3);
            x.lo = r->m_loLimit;
            x.hi = r->m_hiLimit;
            x.bounce = r->m_bounce;
            // Without the flag these are overwritten from info->erp/cfm[0] every getInfo2:
            // stored only when the flag makes them the app's own (so the table stays put).
            x.stopErp = (x.flags & BTG_G6DOF_ERP_STOP) ? r->m_stopERP : 0.0f;
            x.stopCfm = (x.flags & BTG_G6DOF_CFM_STOP) ? r->m_stopCFM : 0.0f;
            x.motorCfm = (x.flags & BTG_G6DOF_CFM_NORM) ? r->m_normalCFM : 0.0f;
            x.targetVelocity = r->m_targetVelocity;
            x.maxMotorForce = r->m_maxMotorForce;
            motor = r->m_enableMotor;
        }
        x.mode = motor ? BTG_SIXDOF_MOTOR : 0u;
        if (spring && spring->isSpringEnabled(i)) {
            x.mode |= BTG_SIXDOF_SPRING;
            x.stiffness = spring->getStiffness(i);
            x.damping = spring->getDamping(i);
            x.equilibrium = spring->getEquilibriumPoint(i);
            x.targetVelocity = 0.0f;
            x.maxMotorForce = 0.0f;
        }
    }
    j.sixdof.options = k.getUseFrameOffset() ? BTG_SIXDOF_FRAME_OFFSET : 0u;
}

// What stock's getInfo1/getInfo2 leave in a btGeneric6DofSpringConstraint each step: its
// calculated frames (calculateTransforms) and, from internalUpdateSprings, the spring axes'
// motor target velocity and force, here from the poses the call starts from (stock: its last
// substep's). Only these members change, as on stock; the device computes its own per substep.
struct SpringAccess : btGeneric6DofSpringConstraint {
    using btGeneric6DofSpringConstraint::internalUpdateSprings;
};
void mirrorSprings(btTypedConstraint& c, const btContactSolverInfo& info)
{
    if (typeid(c) != typeid(btGeneric6DofSpringConstraint) || info.m_timeStep <= 0) return;
    auto& k = static_cast<btGeneric6DofSpringConstraint&>(c);
    k.calculateTransforms();
    btTypedConstraint::btConstraintInfo2 info2;
    info2.fps = btScalar(1) / info.m_timeStep;
    info2.m_numIterations = info.m_numIterations;
    void (btGeneric6DofSpringConstraint::*update)(btTypedConstraint::btConstraintInfo2*) =
        &SpringAccess::internalUpdateSprings;
    (k.*update)(&info2);
}

// Stock's solve calls getInfo1 on every enabled joint at each internal step with the poses the
// step starts from, and that call leaves state the app reads: the angles and offsets of the
// 6-DoF family (getAngle, getRelativePivotPosition, btUniversalConstraint's and
// btHinge2Constraint's getAngle1/2, the limit motors' m_currentPosition and m_currentLimit), a
// slider's getLinearPos / getAngularPos and limit flags, a cone-twist's twist angle and swing
// state, a hinge's limit state, and a btHingeAccumulatedAngleConstraint's m_accumulatedAngle.
// The device solves its own rows, so these stayed as the joint was built (a 6-DoF servo arm's
// getAngle read 0 at every angle): the same call here, at upload (the step's start poses), after
// the joint's rows were read from it. With several internal steps in one device call the values
// are the call's first step's, where stock's are its last's (an accumulated-angle hinge makes
// each internal step its own call: tracksAnglesEachStep).
void refreshAsStocksSolveDoes(btTypedConstraint& c)
{
    if (!c.isEnabled()) return;
    const std::type_info& t = typeid(c);
    if (t == typeid(btPoint2PointConstraint) || t == typeid(btGearConstraint)) return;  // nothing cached
    btTypedConstraint::btConstraintInfo1 info;
    c.getInfo1(&info);
}

}  // namespace

bool tracksAnglesEachStep(const btDiscreteDynamicsWorld& world)
{
    for (int i = 0; i < world.getNumConstraints(); ++i)
        if (typeid(*world.getConstraint(i)) == typeid(btHingeAccumulatedAngleConstraint)) return true;
    return false;
}

std::string jointsStructureReason(const btDiscreteDynamicsWorld& world)
{
    if (world.getNumConstraints() == 0) return "";
    std::unordered_set<const btCollisionObject*> inWorld;
    const btCollisionObjectArray& objs = world.getCollisionObjectArray();
    for (int i = 0; i < objs.size(); ++i) inWorld.insert(objs[i]);
    const btRigidBody* fixed = &btTypedConstraint::getFixedBody();
    for (int i = 0; i < world.getNumConstraints(); ++i) {
        const btTypedConstraint* c = world.getConstraint(i);
        if (&c->getRigidBodyA() != fixed && !inWorld.count(&c->getRigidBodyA()))
            return "joint " + std::to_string(i) + " links a body that is not in the world (its body A)";
        if (&c->getRigidBodyB() != fixed && !inWorld.count(&c->getRigidBodyB()))
            return "joint " + std::to_string(i) + " links a body that is not in the world (its body B)";
        const std::type_info& t = typeid(*c);
        if (isSixDof2(t) || t == typeid(btGearConstraint)) continue;
        if (t == typeid(btPoint2PointConstraint) || isHinge(t) || t == typeid(btConeTwistConstraint) ||
            t == typeid(btSliderConstraint) || isGeneric6Dof(t)) {
            if (!served(*c))
                return "joint " + std::to_string(i) + " (" + typeName(t) +
                       ") uses Bullet's obsolete solve (m_useSolveConstraintObsolete)";
            continue;
        }
        return "joint " + std::to_string(i) + " of type " + typeName(t) +
               " is not on the GPU path (served, by exact type: btPoint2PointConstraint, btHingeConstraint, "
               "btHingeAccumulatedAngleConstraint, "
               "btConeTwistConstraint, btSliderConstraint, btGeneric6DofConstraint, btUniversalConstraint, "
               "btGeneric6DofSpringConstraint, btGeneric6DofSpring2Constraint, btFixedConstraint, btHinge2Constraint, "
               "btGearConstraint)";
    }
    return "";
}

std::string jointsStepReason(const btDiscreteDynamicsWorld& world)
{
    if (world.getNumConstraints() == 0) return "";
    const btRigidBody& fixed = btTypedConstraint::getFixedBody();
    const btTransform& t = fixed.getCenterOfMassTransform();
    if (!(t.getOrigin() == btVector3(0, 0, 0)) || !(t.getBasis() == btMatrix3x3::getIdentity()) ||
        fixed.getInvMass() != btScalar(0) || !(fixed.getLinearVelocity() == btVector3(0, 0, 0)) ||
        !(fixed.getAngularVelocity() == btVector3(0, 0, 0)))
        return "Bullet's shared fixed body (btTypedConstraint::getFixedBody) was moved or given mass";
    // Settings the app may turn on after adding the joint and that no row here builds: checked
    // every step, so a joint is never uploaded half-described.
    for (int i = 0; i < world.getNumConstraints(); ++i) {
        const btTypedConstraint* c = world.getConstraint(i);
        const std::type_info& t = typeid(*c);
        // The obsolete solve switched on after the add (the structure check saw it off).
        if (isServedType(t) && !served(*c))
            return "joint " + std::to_string(i) + " (" + typeName(t) +
                   ") uses Bullet's obsolete solve (m_useSolveConstraintObsolete)";
    }
    return "";
}

bool jointRow(const btTypedConstraint& c, const RowMap& rows, int numIterations, BtgJoint* out)
{
    if (!served(c)) return false;
    BtgJoint j;
    std::memset(&j, 0, sizeof(j));
    j.bodyA = bodyRow(c.getRigidBodyA(), rows);
    j.bodyB = bodyRow(c.getRigidBodyB(), rows);
    j.flags = (c.isEnabled() ? BTG_JOINT_ENABLED : 0u) | (c.getJointFeedback() ? BTG_JOINT_FEEDBACK : 0u);
    j.iterations = c.getOverrideNumSolverIterations() > 0 ? c.getOverrideNumSolverIterations() : numIterations;
    j.breakingThreshold = c.getBreakingImpulseThreshold();
    if (typeid(c) == typeid(btPoint2PointConstraint)) {
        const auto& p = static_cast<const btPoint2PointConstraint&>(c);
        j.type = BTG_JOINT_POINT2POINT;
        j.pivotA = vec4(p.getPivotInA());
        j.pivotB = vec4(p.getPivotInB());
        const int flags = const_cast<btPoint2PointConstraint&>(p).getFlags();
        if (flags & BT_P2P_FLAGS_ERP) {
            j.flags |= BTG_JOINT_OWN_ERP;
            j.erp = p.getParam(BT_CONSTRAINT_ERP, -1);
        }
        if (flags & BT_P2P_FLAGS_CFM) {
            j.flags |= BTG_JOINT_OWN_CFM;
            j.cfm = p.getParam(BT_CONSTRAINT_CFM, -1);
        }
        j.damping = p.m_setting.m_damping;
        j.impulseClamp = p.m_setting.m_impulseClamp;
    } else if (typeid(c) == typeid(btGearConstraint)) {
        // getInfo2 reads the axes and the ratio afresh each step: the table follows setAxisA/B
        // and setRatio through the per-step comparison.
        const auto& g = static_cast<const btGearConstraint&>(c);
        j.type = BTG_JOINT_GEAR;
        j.axesA[0] = vec4(g.getAxisA());
        j.axesB[0] = vec4(g.getAxisB());
        j.gearRatio = g.getRatio();
    } else if (isHinge(typeid(c))) {
        auto& h = const_cast<btHingeConstraint&>(static_cast<const btHingeConstraint&>(c));
        j.type = BTG_JOINT_HINGE;
        setFrame(h.getAFrame(), &j.pivotA, j.axesA);
        setFrame(h.getBFrame(), &j.pivotB, j.axesB);
        const int flags = h.getFlags();
        if (flags & BT_HINGE_FLAGS_ERP_NORM) j.flags |= BTG_JOINT_OWN_ERP;
        if (flags & BT_HINGE_FLAGS_CFM_NORM) j.flags |= BTG_JOINT_OWN_CFM;
        if (flags & BT_HINGE_FLAGS_ERP_STOP) j.flags |= BTG_JOINT_OWN_STOP_ERP;
        if (flags & BT_HINGE_FLAGS_CFM_STOP) j.flags |= BTG_JOINT_OWN_STOP_CFM;
        j.erp = h.*member(HingeNormalErp());
        j.cfm = h.*member(HingeNormalCfm());
        j.stopErp = h.*member(HingeStopErp());
        j.stopCfm = h.*member(HingeStopCfm());
        if (h.getAngularOnly()) j.flags |= BTG_JOINT_ANGULAR_ONLY;
        if (h.getUseFrameOffset()) j.flags |= BTG_JOINT_FRAME_OFFSET;
        if (h.getEnableAngularMotor()) j.flags |= BTG_JOINT_MOTOR;
        j.motorVelocity = h.getMotorTargetVelocity();
        j.motorMaxImpulse = h.getMaxMotorImpulse();
        j.referenceSign = h.*member(HingeReferenceSign());
        const btAngularLimit& limit = h.*member(HingeLimit());
        j.limitHalfRange = limit.getHalfRange();
        j.limitCenter = limit.*member(LimitCenter());
        j.limitBias = limit.getBiasFactor();
        j.limitRelaxation = limit.getRelaxationFactor();
    } else if (typeid(c) == typeid(btConeTwistConstraint)) {
        auto& k = const_cast<btConeTwistConstraint&>(static_cast<const btConeTwistConstraint&>(c));
        j.type = BTG_JOINT_CONE_TWIST;
        setFrame(k.getAFrame(), &j.pivotA, j.axesA);
        setFrame(k.getBFrame(), &j.pivotB, j.axesB);
        const btQuaternion qa = k.getAFrame().getRotation(), qb = k.getBFrame().getRotation();
        j.frameRotA = btgMake4(qa.x(), qa.y(), qa.z(), qa.w());
        j.frameRotB = btgMake4(qb.x(), qb.y(), qb.z(), qb.w());
        const int flags = k.getFlags();
        if (flags & BT_CONETWIST_FLAGS_LIN_ERP) j.flags |= BTG_JOINT_OWN_ERP;
        if (flags & BT_CONETWIST_FLAGS_LIN_CFM) j.flags |= BTG_JOINT_OWN_CFM;
        if (flags & BT_CONETWIST_FLAGS_ANG_CFM) j.flags |= BTG_JOINT_OWN_STOP_CFM;
        j.erp = k.*member(ConeLinErp());
        j.cfm = k.*member(ConeLinCfm());
        j.stopCfm = k.*member(ConeAngCfm());
        j.swingSpan1 = k.getSwingSpan1();
        j.swingSpan2 = k.getSwingSpan2();
        j.twistSpan = k.getTwistSpan();
        j.limitSoftness = k.getLimitSoftness();
        j.limitBias = k.getBiasFactor();
        j.limitRelaxation = k.getRelaxationFactor();
        j.fixThresh = k.getFixThresh();
        if (k.isMotorEnabled()) {
            // getInfo2 reads the target as set (setMotorTarget* clamp it) and m_maxMotorImpulse
            // raw, normalized or not; only the obsolete solve scales it.
            j.flags |= BTG_JOINT_MOTOR;
            const btQuaternion& t = k.getMotorTarget();
            j.motorTarget = btgMake4(t.x(), t.y(), t.z(), t.w());
            j.motorMaxImpulse = k.getMaxMotorImpulse();
        }
    } else if (typeid(c) == typeid(btSliderConstraint)) {
        auto& k = const_cast<btSliderConstraint&>(static_cast<const btSliderConstraint&>(c));
        j.type = BTG_JOINT_SLIDER;
        setFrame(k.getFrameOffsetA(), &j.pivotA, j.axesA);
        setFrame(k.getFrameOffsetB(), &j.pivotB, j.axesB);
        BtgSliderParams& sp = j.slider;
        sp.lowerLin = k.getLowerLinLimit();
        sp.upperLin = k.getUpperLinLimit();
        sp.lowerAng = k.getLowerAngLimit();
        sp.upperAng = k.getUpperAngLimit();
        sp.softnessOrthoAng = k.getSoftnessOrthoAng();
        sp.softnessOrthoLin = k.getSoftnessOrthoLin();
        sp.softnessLimLin = k.getSoftnessLimLin();
        sp.softnessLimAng = k.getSoftnessLimAng();
        sp.dampingLimLin = k.getDampingLimLin();
        sp.dampingLimAng = k.getDampingLimAng();
        sp.cfmOrthoAng = k.*member(SliderCfmOrthoAng());
        sp.cfmOrthoLin = k.*member(SliderCfmOrthoLin());
        sp.cfmDirLin = k.*member(SliderCfmDirLin());
        sp.cfmLimLin = k.*member(SliderCfmLimLin());
        sp.cfmDirAng = k.*member(SliderCfmDirAng());
        sp.cfmLimAng = k.*member(SliderCfmLimAng());
        sp.linMotorVelocity = k.getTargetLinMotorVelocity();
        sp.linMotorMaxForce = k.getMaxLinMotorForce();
        sp.angMotorVelocity = k.getTargetAngMotorVelocity();
        sp.angMotorMaxForce = k.getMaxAngMotorForce();
        sp.flags = uint(k.getFlags());
        sp.options = (k.getUseLinearReferenceFrameA() ? BTG_SLIDER_LINEAR_REFERENCE_A : 0u) |
                     (k.getUseFrameOffset() ? BTG_SLIDER_FRAME_OFFSET : 0u) |
                     (k.getPoweredLinMotor() ? BTG_SLIDER_LIN_MOTOR : 0u) |
                     (k.getPoweredAngMotor() ? BTG_SLIDER_ANG_MOTOR : 0u);
    } else if (isGeneric6Dof(typeid(c))) {
        generic6DofRow(const_cast<btGeneric6DofConstraint&>(static_cast<const btGeneric6DofConstraint&>(c)), &j);
    } else if (isSixDof2(typeid(c))) {
        auto& k = const_cast<btGeneric6DofSpring2Constraint&>(static_cast<const btGeneric6DofSpring2Constraint&>(c));
        j.type = BTG_JOINT_SIXDOF2;
        setFrame(k.getFrameOffsetA(), &j.pivotA, j.axesA);
        setFrame(k.getFrameOffsetB(), &j.pivotB, j.axesB);
        const int flags = k.*member(SixDofFlags());
        const btTranslationalLimitMotor2* lin = k.getTranslationalLimitMotor();
        for (int i = 0; i < 6; ++i) {
            BtgSixDofAxis& x = j.sixdof.axis[i];
            x.flags = uint(flags >> (i * BT_6DOF_FLAGS_AXIS_SHIFT2)) & 15u;
            if (i < 3) {
                x.lo = lin->m_lowerLimit[i];
                x.hi = lin->m_upperLimit[i];
                x.bounce = lin->m_bounce[i];
                x.stopErp = lin->m_stopERP[i];
                x.stopCfm = lin->m_stopCFM[i];
                x.motorErp = lin->m_motorERP[i];
                x.motorCfm = lin->m_motorCFM[i];
                x.targetVelocity = lin->m_targetVelocity[i];
                x.maxMotorForce = lin->m_maxMotorForce[i];
                x.mode = sixDofMode(lin->m_enableMotor[i], lin->m_servoMotor[i], lin->m_enableSpring[i],
                                    lin->m_springStiffnessLimited[i], lin->m_springDampingLimited[i]);
                x.servoTarget = lin->m_servoTarget[i];
                x.stiffness = lin->m_springStiffness[i];
                x.damping = lin->m_springDamping[i];
                x.equilibrium = lin->m_equilibriumPoint[i];
            } else {
                const btRotationalLimitMotor2* r = k.getRotationalLimitMotor(i - 3);
                x.lo = r->m_loLimit;
                x.hi = r->m_hiLimit;
                x.bounce = r->m_bounce;
                // Without the flag these are overwritten from info->erp/cfm[0] every getInfo2:
                // stored only when the flag makes them the app's own (so the table stays put).
                x.stopErp = (x.flags & 2u) ? r->m_stopERP : 0.0f;
                x.stopCfm = (x.flags & 1u) ? r->m_stopCFM : 0.0f;
                x.motorErp = (x.flags & 8u) ? r->m_motorERP : 0.0f;
                x.motorCfm = (x.flags & 4u) ? r->m_motorCFM : 0.0f;
                x.targetVelocity = r->m_targetVelocity;
                x.maxMotorForce = r->m_maxMotorForce;
                x.mode = sixDofMode(r->m_enableMotor, r->m_servoMotor, r->m_enableSpring, r->m_springStiffnessLimited,
                                    r->m_springDampingLimited);
                x.servoTarget = r->m_servoTarget;
                x.stiffness = r->m_springStiffness;
                x.damping = r->m_springDamping;
                x.equilibrium = r->m_equilibriumPoint;
            }
        }
        j.sixdof.rotateOrder = int(k.getRotationOrder());
        j.sixdof.options = (flags & BT_6DOF_FLAGS_USE_INFINITE_ERROR) ? BTG_SIXDOF_INFINITE_ERROR : 0u;
    }
    *out = j;
    return true;
}

void JointSync::upload(btDiscreteDynamicsWorld& world, const RowMap& rows, DeviceWorld& w)
{
    const int n = world.getNumConstraints();
    const int numIterations = world.getSolverInfo().m_numIterations;
    std::vector<BtgJoint> table(static_cast<size_t>(n));
    m_constraints.resize(size_t(n));
    // Every joint every step (the app may change any of them): built in parallel chunks, with
    // stock's getInfo1 each (about 0.2 us a joint on PoCL's host: 1,000 ragdoll joints took
    // sync-in from 0.43 to 0.63 ms), so chunks of 1,024.
    forEachChunk(size_t(n), 1024, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) {
            btTypedConstraint* c = world.getConstraint(int(i));
            m_constraints[i] = c;
            jointRow(*c, rows, numIterations, &table[i]);
            mirrorSprings(*c, world.getSolverInfo());
            refreshAsStocksSolveDoes(*c);
        }
    });
    int nextRow = 0, iterations = 0, springs = 0;
    for (BtgJoint& j : table) {
        j.firstRow = nextRow;
        nextRow += j.type == BTG_JOINT_SIXDOF2 ? btgSixDofMaxRows(j.sixdof) : btgJointMaxRows(j.type);
        iterations = std::max(iterations, j.iterations);
        if (j.type == BTG_JOINT_SIXDOF2 || j.type == BTG_JOINT_SIXDOF)
            for (const BtgSixDofAxis& x : j.sixdof.axis) springs += (x.mode & BTG_SIXDOF_SPRING) != 0u;
    }
    w.numJoints = n;
    w.jointSprings = springs;
    w.jointIterations = iterations;
    if (n == 0) {
        m_uploaded.clear();
        m_state.clear();
        return;
    }
    const bool resized = m_uploaded.size() != table.size();
    m_state.resize(size_t(n));
    // Compared in parallel chunks; each joint that changed starts unbroken on the device.
    const size_t minPerThread = 4096;
    std::vector<std::vector<size_t>> found(size_t(chunkCount(size_t(n), minPerThread)));
    std::vector<char> anyFeedback(found.size(), 0);
    forEachChunk(size_t(n), minPerThread, [&](size_t begin, size_t end, int chunk) {
        for (size_t i = begin; i < end; ++i) {
            if (table[i].flags & BTG_JOINT_FEEDBACK) anyFeedback[size_t(chunk)] = 1;
            if (!resized && std::memcmp(&table[i], &m_uploaded[i], sizeof(BtgJoint)) == 0) continue;
            found[size_t(chunk)].push_back(i);
            std::memset(&m_state[i], 0, sizeof(BtgJointState));
            m_state[i].appliedImpulse = m_constraints[i]->getAppliedImpulse();
        }
    });
    m_anyFeedback = std::find(anyFeedback.begin(), anyFeedback.end(), 1) != anyFeedback.end();
    std::vector<size_t> changed;
    for (const std::vector<size_t>& list : found) changed.insert(changed.end(), list.begin(), list.end());
    uploadLevels(world, w, resized || !changed.empty());
    if (changed.empty()) return;
    // The device keeps what it last wrote (a joint whose island sleeps keeps its feedback, as
    // stock's); a joint new to the table starts at zero.
    m_feedback.resize(size_t(n), BtgJointFeedback{});
    w.jointRows.reserveExact(w.ctx, size_t(std::max(nextRow, 1)));
    if (resized || changed.size() > size_t(n) / 8) {
        w.joints.upload(w.ctx, table);
        w.jointState.upload(w.ctx, m_state);
        w.jointFeedback.upload(w.ctx, m_feedback);
    } else {
        // A few joints changed (a motor target set every step): only they travel.
        for (size_t i : changed) {
            w.joints.upload(w.ctx, &table[i], 1, i);
            w.jointState.upload(w.ctx, &m_state[i], 1, i);
        }
    }
    m_uploaded = std::move(table);
}

void JointSync::uploadLevels(const btDiscreteDynamicsWorld& world, DeviceWorld& w, bool jointsChanged)
{
    // Stock's order of the joints that share a body (the bullet mode's batching reads it). It
    // moves when the app adds, removes, disables or re-links joints (the table changed) or the
    // world's objects change places (the island ids are places in its object array); else the
    // last levels hold, and the device keeps them.
    const int objects = world.getNumCollisionObjects();
    if (!jointsChanged && objects == m_levelObjects && m_levelsCurrent) return;
    m_levelObjects = objects;
    m_levelsCurrent = true;
    std::vector<int> levels = stockJointLevels(world);
    w.maxJointLevel = levels.empty() ? 0 : *std::max_element(levels.begin(), levels.end());
    if (levels.empty()) return;
    w.jointLevels.reserveExact(w.ctx, levels.size());
    w.jointLevels.upload(w.ctx, levels);
}

void JointSync::writeBack(DeviceWorld& w)
{
    const size_t n = m_uploaded.size();
    if (n == 0) return;
    w.jointState.download(w.ctx, m_state.data(), n);
    if (m_anyFeedback) w.jointFeedback.download(w.ctx, m_feedback.data(), n);
    for (size_t i = 0; i < n; ++i) {
        btTypedConstraint* c = m_constraints[i];
        const BtgJointState& s = m_state[i];
        c->internalSetAppliedImpulse(s.appliedImpulse);
        if (btJointFeedback* fb = c->getJointFeedback()) {
            if (m_uploaded[i].flags & BTG_JOINT_FEEDBACK) {
                const BtgJointFeedback& f = m_feedback[i];
                fb->m_appliedForceBodyA = btVector3(f.forceA.x, f.forceA.y, f.forceA.z);
                fb->m_appliedTorqueBodyA = btVector3(f.torqueA.x, f.torqueA.y, f.torqueA.z);
                fb->m_appliedForceBodyB = btVector3(f.forceB.x, f.forceB.y, f.forceB.z);
                fb->m_appliedTorqueBodyB = btVector3(f.torqueB.x, f.torqueB.y, f.torqueB.z);
            }
        }
        if (s.broken && c->isEnabled()) {
            // As stock's writeBackJoints; the device keeps it broken until the app changes it.
            c->setEnabled(false);
            m_uploaded[i].flags &= ~BTG_JOINT_ENABLED;
        }
    }
}

}  // namespace btgpu
