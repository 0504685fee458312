/* joint_rows.h — the joints' part of btSequentialImpulseConstraintSolver (issue 11), shared by
 * the prepare_joints and solve_constraints kernels and their CPU references: the joint table
 * the host uploads (BtgJoint), each joint type's rows from the current body poses as its
 * getInfo2 builds them, convertJoint's finishing of a row (breaking-threshold bounds, effective
 * mass, right-hand side), resolveSingleConstraintRowGeneric on it, and writeBackJoints'
 * applied impulse, joint feedback and breaking. */
#ifndef BTG_JOINT_ROWS_H
#define BTG_JOINT_ROWS_H
#include "prelude.h"
#include "types.h"
#include "math.h"
#include "solver_rows.h"

/* Joint types (BtgJoint.type), each an exact Bullet class. */
#define BTG_JOINT_POINT2POINT 1
#define BTG_JOINT_HINGE 2
#define BTG_JOINT_CONE_TWIST 3
#define BTG_JOINT_SLIDER 4
#define BTG_JOINT_SIXDOF2 5 /* btGeneric6DofSpring2Constraint, btFixedConstraint, btHinge2Constraint */
#define BTG_JOINT_SIXDOF 6  /* btGeneric6DofConstraint, btUniversalConstraint, btGeneric6DofSpringConstraint */
#define BTG_JOINT_GEAR 7    /* btGearConstraint */
/* Rows one joint of each type may build (getInfo1's maximum): its slots in the row table. */
#define BTG_JOINT_P2P_ROWS 3
#define BTG_JOINT_HINGE_ROWS 6
#define BTG_JOINT_CONE_TWIST_ROWS 6
#define BTG_JOINT_SLIDER_ROWS 6
#define BTG_JOINT_MAX_ROWS 6
#define BTG_JOINT_SIXDOF2_ROWS 24 /* per axis: two limit rows, a motor (or servo) row, a spring row */
#define BTG_JOINT_SIXDOF_ROWS 6   /* one row per axis (limit and motor share it) */
#define BTG_JOINT_GEAR_ROWS 1

/* BtgJoint.flags */
#define BTG_JOINT_ENABLED 1u   /* btTypedConstraint::isEnabled() as the app left it */
#define BTG_JOINT_FEEDBACK 2u  /* a btJointFeedback is attached (setJointFeedback) */
#define BTG_JOINT_OWN_ERP 4u   /* setParam(BT_CONSTRAINT_ERP): BT_P2P_FLAGS_ERP, BT_HINGE_FLAGS_ERP_NORM */
#define BTG_JOINT_OWN_CFM 8u   /* setParam(BT_CONSTRAINT_CFM): BT_P2P_FLAGS_CFM, BT_HINGE_FLAGS_CFM_NORM */
#define BTG_JOINT_OWN_STOP_ERP 16u  /* setParam(BT_CONSTRAINT_STOP_ERP): BT_HINGE_FLAGS_ERP_STOP */
#define BTG_JOINT_OWN_STOP_CFM 32u  /* setParam(BT_CONSTRAINT_STOP_CFM): BT_HINGE_FLAGS_CFM_STOP */
#define BTG_JOINT_ANGULAR_ONLY 64u  /* hinge: setAngularOnly */
#define BTG_JOINT_FRAME_OFFSET 128u /* hinge: setUseFrameOffset (Bullet's default: on) */
#define BTG_JOINT_MOTOR 256u        /* hinge: enableAngularMotor; cone-twist: enableMotor */

/* BtgSliderParams.options */
#define BTG_SLIDER_LINEAR_REFERENCE_A 1u /* useLinearReferenceFrameA */
#define BTG_SLIDER_FRAME_OFFSET 2u       /* setUseFrameOffset (Bullet's default: on) */
#define BTG_SLIDER_LIN_MOTOR 4u          /* setPoweredLinMotor */
#define BTG_SLIDER_ANG_MOTOR 8u          /* setPoweredAngMotor */

/* btSliderConstraint's settings (getters and setParam values). */
typedef struct {
    float lowerLin, upperLin; /* m */
    float lowerAng, upperAng; /* rad */
    float softnessOrthoAng, softnessOrthoLin, softnessLimLin, softnessLimAng;
    float dampingLimLin, dampingLimAng;
    float cfmOrthoAng, cfmOrthoLin, cfmDirLin, cfmLimLin, cfmDirAng, cfmLimAng;
    float linMotorVelocity, linMotorMaxForce; /* m/s, N */
    float angMotorVelocity, angMotorMaxForce; /* rad/s, N m */
    uint flags;   /* BT_SLIDER_FLAGS_* as Bullet numbers them */
    uint options; /* BTG_SLIDER_* */
    float pad0;
    float pad1;
} BtgSliderParams;

/* One axis of a btGeneric6DofSpring2Constraint (0..2 linear along frame A's axes, 3..5
 * angular), as btTranslationalLimitMotor2 / btRotationalLimitMotor2 hold it; also one of a
 * btGeneric6DofConstraint (btTranslationalLimitMotor / btRotationalLimitMotor: motorCfm is its
 * m_normalCFM, flags its 3 bits of BT_6DOF_FLAGS_*, servoTarget unused; a
 * btGeneric6DofSpringConstraint's springs in mode, stiffness, damping, equilibrium). */
typedef struct {
    float lo, hi;            /* m or rad; lo > hi: free, lo == hi: locked */
    float bounce;            /* m_bounce */
    float stopErp, stopCfm;  /* read when flags has BT_6DOF_FLAGS_ERP_STOP2 / CFM_STOP2 */
    float motorErp, motorCfm;/* read when flags has BT_6DOF_FLAGS_ERP_MOTO2 / CFM_MOTO2 */
    float targetVelocity;    /* m/s or rad/s */
    float maxMotorForce;     /* N or N m */
    uint flags;              /* the axis's 4 bits of m_flags (BT_6DOF_FLAGS_*2) */
    uint mode;               /* BTG_SIXDOF_* bits: motor, servo, spring and its limiting */
    float servoTarget;       /* m or rad (setServoTarget, already wrapped by Bullet) */
    float stiffness;         /* N/m or N m/rad (setStiffness) */
    float damping;           /* N s/m or N m s/rad (setDamping) */
    float equilibrium;       /* m or rad (setEquilibriumPoint) */
    float pad0;
} BtgSixDofAxis;

/* BtgSixDofAxis.mode */
#define BTG_SIXDOF_MOTOR 1u           /* m_enableMotor */
#define BTG_SIXDOF_SERVO 2u           /* m_servoMotor (a servo only with the motor on) */
#define BTG_SIXDOF_SPRING 4u          /* m_enableSpring */
#define BTG_SIXDOF_STIFF_LIMITED 8u   /* m_springStiffnessLimited (setStiffness's limitIfNeeded) */
#define BTG_SIXDOF_DAMP_LIMITED 16u   /* m_springDampingLimited (setDamping's limitIfNeeded) */

/* BtgSixDofParams.options */
#define BTG_SIXDOF_INFINITE_ERROR 1u  /* m_flags has BT_6DOF_FLAGS_USE_INFINITE_ERROR */

typedef struct {
    BtgSixDofAxis axis[6];
    int rotateOrder;         /* RotateOrder: RO_XYZ 0 .. RO_ZYX 5 */
    uint options;            /* BTG_SIXDOF_INFINITE_ERROR */
    int pad1, pad2;
} BtgSixDofParams;

/* A body of a joint without a row: Bullet's shared fixed body (btTypedConstraint::getFixedBody),
 * static at the identity transform. */
#define BTG_JOINT_FIXED_BODY -1

/* One joint as the app set it up; rewritten only when the app changes it. Pivots and frames
 * are in the bodies' centre-of-mass frames (Bullet's pivotInA/pivotInB, m_rbAFrame/m_rbBFrame). */
typedef struct {
    BtgFloat4 pivotA;         /* m, in A's frame (a frame's origin); w: 0 */
    BtgFloat4 pivotB;         /* m, in B's frame; w: 0 */
    BtgFloat4 axesA[3];       /* the joint frame's basis columns in A's frame (hinge: z is the axis) */
    BtgFloat4 axesB[3];
    BtgFloat4 frameRotA;      /* the joint frame's rotation in A's frame (m_rbAFrame.getRotation()) */
    BtgFloat4 frameRotB;
    BtgFloat4 motorTarget;    /* cone-twist: m_qTarget (the motor's target rotation in constraint space) */
    int type;                 /* BTG_JOINT_* */
    int bodyA;                /* body rows, or BTG_JOINT_FIXED_BODY */
    int bodyB;
    uint flags;               /* BTG_JOINT_* flags */
    int firstRow;             /* its rows in the row table: [firstRow, firstRow + max rows of its type) */
    int iterations;           /* velocity iterations its rows take part in (getOverrideNumSolverIterations,
                                 else m_numIterations) */
    float breakingThreshold;  /* N s: a row reaching it breaks the joint; bounds every row */
    float erp;                /* setParam(BT_CONSTRAINT_ERP), read with BTG_JOINT_OWN_ERP */
    float cfm;                /* setParam(BT_CONSTRAINT_CFM), read with BTG_JOINT_OWN_CFM */
    float damping;            /* btConstraintSetting::m_damping (p2p) */
    float impulseClamp;       /* N s, btConstraintSetting::m_impulseClamp; 0: none */
    float stopErp;            /* setParam(BT_CONSTRAINT_STOP_ERP), read with BTG_JOINT_OWN_STOP_ERP */
    float stopCfm;            /* setParam(BT_CONSTRAINT_STOP_CFM), read with BTG_JOINT_OWN_STOP_CFM */
    float limitCenter;        /* rad, btAngularLimit's centre (hinge) */
    float limitHalfRange;     /* rad; negative: no limit */
    float limitBias;          /* btAngularLimit's bias factor */
    float limitRelaxation;    /* btAngularLimit's relaxation factor (bounce) */
    float motorVelocity;      /* rad/s, the hinge motor's target velocity */
    float motorMaxImpulse;    /* N m s (cone-twist: m_maxMotorImpulse, negative: unbounded) */
    float referenceSign;      /* hinge: -1 with useReferenceFrameA as constructed, else 1 */
    float swingSpan1;         /* rad, cone-twist limits (setLimit) */
    float swingSpan2;
    float twistSpan;
    float limitSoftness;      /* cone-twist: the limits act from softness x span */
    float fixThresh;          /* cone-twist: spans below this lock the swing (m_fixThresh) */
    float gearRatio;          /* gear: m_ratio (its axes are axesA[0] and axesB[0]) */
    float pad1;
    float pad2;
    BtgSliderParams slider;   /* slider only */
    BtgSixDofParams sixdof;   /* 6-DoF spring2 only */
} BtgJoint;

/* One row of a joint in device memory (btSolverConstraint of the non-contact pool): the
 * BtgSolverRow fields and the row's constraint force mixing. */
typedef struct {
    BtgJacobian jacobian;
    float mass;    /* m_jacDiagABInv, kg (kg m^2 angular); 0: never solved */
    float target;  /* velocity J v is driven to (the rhs as a velocity), m/s or rad/s */
    float lower;   /* N s */
    float upper;
    float impulse; /* accumulated this substep, N s */
    float cfm;     /* m_cfm * m_jacDiagABInv: the impulse's own feedback (dimensionless) */
    int flags;     /* BTG_JOINT_ROW_* */
    float bias;    /* the share of target that corrects position error (BTG_JOINT_ROW_POSITION rows) */
} BtgJointRow;

/* BtgJointRow.flags: a spring's row (a 6-DoF spring2 spring row, get_limit_motor_info2's; the
 * row of a btGeneric6DofSpringConstraint axis whose spring drives its motor): its bounds are the
 * impulse of one step of the spring force from the step's start, which the soft step spends
 * over the step's substeps as one budget (btgSoftJointSolve), not as a force held each substep. */
#define BTG_JOINT_ROW_SPRING 1
/* BtgJointRow.flags: a row whose target's bias is only position error (a point-to-point row):
 * the soft step's relax drives it without (bias), as Box2D's relax does, so that the correction
 * leaves no velocity behind. */
#define BTG_JOINT_ROW_POSITION 2
/* BtgJointRow.flags (the soft step's; prepare_joints' rows start without them): the row's angular
 * parts follow its lever arms turned with the bodies (btgSoftTurnLinearRows); on a joint's first
 * row, the step's start arms are kept in its linear rows' w (soft_joint_rows.h). */
#define BTG_JOINT_ROW_TURNED 4
#define BTG_JOINT_ROW_ARMS 8

/* What the device keeps of each joint and the host reads back every call (writeBackJoints'
 * results of the last substep; a break holds until the host has disabled the joint). */
typedef struct {
    float appliedImpulse; /* N s: internalSetAppliedImpulse (the last row's, as Bullet) */
    int numRows;          /* rows built this substep (getInfo1), 0 when disabled or broken */
    int broken;           /* 1: a row reached the breaking threshold (setEnabled(false) due) */
    int touched;          /* 1: in a solved island this substep (a body moved by the solver):
                             Bullet resets and writes back only the constraints it solves */
} BtgJointState;

/* btJointFeedback of a joint with BTG_JOINT_FEEDBACK (read back only while some joint has one). */
typedef struct {
    BtgFloat4 forceA;   /* m_appliedForceBodyA, N; w: 0 */
    BtgFloat4 torqueA;  /* m_appliedTorqueBodyA, N m */
    BtgFloat4 forceB;
    BtgFloat4 torqueB;
} BtgJointFeedback;

/* Per-step solver settings the joints read (btContactSolverInfo), passed by value. */
typedef struct {
    float dt;        /* s */
    float erp;       /* m_erp: getInfo2's info->erp */
    float globalCfm; /* m_globalCfm: every row's cfm before getInfo2 */
    float damping;   /* m_damping: getInfo2's info->m_damping (joints that do not set their own) */
    int numJoints;
    int firstContactSlot; /* unused by the joints: keeps the struct 16-byte sized */
    int numIterations;    /* m_numIterations: getInfo2's info->m_numIterations (6-DoF springs) */
    int pad1;
} BtgJointStepParams;

#ifndef __OPENCL_C_VERSION__
static_assert(sizeof(BtgSliderParams) == 96, "BtgSliderParams layout");
static_assert(sizeof(BtgSixDofAxis) == 64, "BtgSixDofAxis layout");
static_assert(sizeof(BtgSixDofParams) == 400, "BtgSixDofParams layout");
static_assert(sizeof(BtgJoint) == 784, "BtgJoint layout");
static_assert(sizeof(BtgJointRow) == 112, "BtgJointRow layout");
static_assert(sizeof(BtgJointState) == 16, "BtgJointState layout");
static_assert(sizeof(BtgJointFeedback) == 64, "BtgJointFeedback layout");
static_assert(sizeof(BtgJointStepParams) == 32, "BtgJointStepParams layout");
#endif

static inline int btgJointMaxRows(int type)
{
    if (type == BTG_JOINT_POINT2POINT) return BTG_JOINT_P2P_ROWS;
    if (type == BTG_JOINT_HINGE) return BTG_JOINT_HINGE_ROWS;
    if (type == BTG_JOINT_CONE_TWIST) return BTG_JOINT_CONE_TWIST_ROWS;
    if (type == BTG_JOINT_SLIDER) return BTG_JOINT_SLIDER_ROWS;
    if (type == BTG_JOINT_SIXDOF2) return BTG_JOINT_SIXDOF2_ROWS;
    if (type == BTG_JOINT_SIXDOF) return BTG_JOINT_SIXDOF_ROWS;
    if (type == BTG_JOINT_GEAR) return BTG_JOINT_GEAR_ROWS;
    return 0;
}

/* A joint's pose input: a body's centre-of-mass transform, its solver body and its velocity
 * (after this substep's forces: convertJoint reads v + external force impulse). */
typedef struct {
    BtgFloat4 pos;
    BtgMat3 basis;
    BtgSolverBody body;
    BtgBodyVel vel;
    BtgFloat4 linVel0;   /* m/s before this substep's forces (btRigidBody::getLinearVelocity in getInfo2) */
    BtgFloat4 angVel0;   /* rad/s before this substep's forces (btRigidBody::getAngularVelocity in getInfo2) */
    float rbInvMass;     /* btRigidBody::getInvMass: 1/kg, 0 unless dynamic (asleep or not) */
    float pad0, pad1, pad2;
} BtgJointBody;

static inline BtgJointBody btgFixedJointBody(void)
{
    BtgJointBody b;
    b.pos = btgZero4();
    b.basis.r0 = btgMake4(1.0f, 0.0f, 0.0f, 0.0f);
    b.basis.r1 = btgMake4(0.0f, 1.0f, 0.0f, 0.0f);
    b.basis.r2 = btgMake4(0.0f, 0.0f, 1.0f, 0.0f);
    b.body.invI.r0 = btgZero4();
    b.body.invI.r1 = btgZero4();
    b.body.invI.r2 = btgZero4();
    b.body.invMassLin = btgZero4();
    b.body.linFactor = btgMake4(1.0f, 1.0f, 1.0f, 0.0f);
    b.body.angFactor = btgMake4(1.0f, 1.0f, 1.0f, 0.0f);
    b.body.invMass = 0.0f;
    b.body.dynamic = 0;
    b.body.moving = 0;
    b.body.pad0 = 0;
    b.vel.lin = btgZero4();
    b.vel.ang = btgZero4();
    b.linVel0 = btgZero4();
    b.angVel0 = btgZero4();
    b.rbInvMass = 0.0f;
    b.pad0 = b.pad1 = b.pad2 = 0.0f;
    return b;
}

/* A body row as a joint reads it: rot is its quaternion, i0..i2 its world inverse inertia rows. */
static inline BtgJointBody btgMakeJointBody(BtgBodyProps p, BtgFloat4 i0, BtgFloat4 i1, BtgFloat4 i2, BtgFloat4 pos,
                                            BtgFloat4 rot, BtgFloat4 lin, BtgFloat4 ang, BtgFloat4 lin0, BtgFloat4 ang0)
{
    BtgJointBody b;
    b.pos = btgXyz(pos);
    b.basis = btgQuatToMat3(rot);
    b.body = btgMakeSolverBody(p, i0, i1, i2);
    b.vel = btgMakeBodyVel(b.body.moving, lin, ang);
    b.linVel0 = b.body.moving ? btgXyz(lin0) : btgZero4();
    b.angVel0 = b.body.moving ? btgXyz(ang0) : btgZero4();
    b.rbInvMass = (p.flags & BTG_BODY_DYNAMIC) ? p.invMass : 0.0f;
    b.pad0 = b.pad1 = b.pad2 = 0.0f;
    return b;
}

/* The graph edge of joint j: its two body rows; a side on the fixed body takes the other's row
 * (a static side claims nothing and joins no island), and a joint that builds no rows links
 * nothing (an edge from a body to itself), as a disabled constraint merges no islands. */
static inline BtgEdge btgJointEdge(BtgJoint j, int active)
{
    BtgEdge e;
    int a = j.bodyA >= 0 ? j.bodyA : j.bodyB;
    int b = j.bodyB >= 0 ? j.bodyB : j.bodyA;
    e.bodyA = a;
    e.bodyB = active ? b : a;
    return e;
}

/* getInfo2's output for one row, before convertJoint finishes it. */
typedef struct {
    BtgFloat4 linA;  /* m_J1linearAxis */
    BtgFloat4 angA;  /* m_J1angularAxis */
    BtgFloat4 linB;  /* m_J2linearAxis */
    BtgFloat4 angB;  /* m_J2angularAxis */
    float error;     /* m_constraintError (velocity units, fps * erp * error) */
    float cfm;
    float lower;
    float upper;
} BtgJointInfoRow;

/* btPoint2PointConstraint::getInfo2NonVirtual, row k (0..2): the pivot's world positions meet
 * along world axis k. */
static inline BtgJointInfoRow btgP2PInfoRow(BtgJoint j, BtgJointBody a, BtgJointBody b, int k, float fps,
                                            float erp, float globalCfm)
{
    BtgJointInfoRow r;
    BtgFloat4 axis = btgMake4(k == 0 ? 1.0f : 0.0f, k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f, 0.0f);
    BtgFloat4 a1 = btgMat3MulVec(a.basis, j.pivotA);
    BtgFloat4 a2 = btgMat3MulVec(b.basis, j.pivotB);
    r.linA = axis;
    r.linB = -axis;
    /* Rows of skew(-a1) and skew(a2): a1 x axis and -(a2 x axis). */
    r.angA = btgCross3(a1, axis);
    r.angB = -btgCross3(a2, axis);
    float currErp = (j.flags & BTG_JOINT_OWN_ERP) ? j.erp : erp;
    float kk = fps * currErp;
    /* Bullet's order of operations: a2 + originB - a1 - originA, per component. */
    BtgFloat4 d = btgMake4(a2.x + b.pos.x - a1.x - a.pos.x, a2.y + b.pos.y - a1.y - a.pos.y, a2.z + b.pos.z - a1.z - a.pos.z,
                 0.0f);
    r.error = kk * btgLane(d, k);
    /* convertJoint sets m_globalCfm on the joint's first row only (the rest start at 0). */
    r.cfm = (j.flags & BTG_JOINT_OWN_CFM) ? j.cfm : (k == 0 ? globalCfm : 0.0f);
    r.lower = -INFINITY;
    r.upper = INFINITY;
    if (j.impulseClamp > 0.0f) {
        r.lower = -j.impulseClamp;
        r.upper = j.impulseClamp;
    }
    return r;
}

/* btGearConstraint::getInfo2, its one row: the two bodies' angular velocities about their axes
 * (in each body's frame) coupled by the ratio, axisA . wA + ratio axisB . wB = 0; no linear part,
 * no error, unbounded; convertJoint's first-row cfm. */
static inline BtgJointInfoRow btgGearInfoRow(BtgJoint j, BtgJointBody a, BtgJointBody b, float globalCfm)
{
    BtgJointInfoRow r;
    BtgFloat4 axisA = btgMat3MulVec(a.basis, j.axesA[0]);
    BtgFloat4 axisB = btgMat3MulVec(b.basis, j.axesB[0]);
    r.linA = btgZero4();
    r.linB = btgZero4();
    r.angA = axisA;
    r.angB = btgMake4(j.gearRatio * axisB.x, j.gearRatio * axisB.y, j.gearRatio * axisB.z, 0.0f);
    r.error = 0.0f;
    r.cfm = globalCfm;
    r.lower = -INFINITY;
    r.upper = INFINITY;
    return r;
}

/* convertJoint's finishing of a row: bounds within the breaking threshold, the angular
 * components, the effective mass from the unscaled inverse masses (Bullet leaves the linear and
 * angular factors out of m_jacDiagABInv), and the right-hand side as a target velocity: Bullet's
 * rhs (error - damping J v0) / m is reached by deltas from v0, so the target for J v is
 * error + (1 - damping) J v0. */
static inline BtgJointRow btgFinishJointRow(BtgJointInfoRow in, BtgJointBody a, BtgJointBody b, float damping,
                                            float breakingThreshold)
{
    BtgJointRow r;
    r.lower = in.lower;
    r.upper = in.upper;
    if (r.upper >= breakingThreshold) r.upper = breakingThreshold;
    if (r.lower <= -breakingThreshold) r.lower = -breakingThreshold;
    r.jacobian.linear = btgXyz(in.linA);
    r.jacobian.angularA = btgXyz(in.angA);
    r.jacobian.angularB = btgXyz(in.angB);
    BtgFloat4 iMJaA = btgMat3MulVec(a.body.invI, r.jacobian.angularA);
    BtgFloat4 iMJaB = btgMat3MulVec(b.body.invI, r.jacobian.angularB);
    r.jacobian.responseA = iMJaA * a.body.angFactor;
    r.jacobian.responseB = iMJaB * b.body.angFactor;
    BtgFloat4 linB = btgXyz(in.linB);
    float sum = btgDot3(r.jacobian.linear * a.body.invMass, r.jacobian.linear);
    sum += btgDot3(iMJaA, r.jacobian.angularA);
    sum += btgDot3(linB * b.body.invMass, linB);
    sum += btgDot3(iMJaB, r.jacobian.angularB);
    r.mass = btgAbs(sum) > 1.192092896e-07f ? 1.0f / sum : 0.0f;
    float v0 = btgRowVelocity(r.jacobian, a.vel, b.vel);
    /* Bullet: rhs = error*m + (0 - v0*damping)*m; solving from v0 by deltas equals driving J v
     * to rhs/m + v0. */
    r.target = in.error - v0 * damping + v0;
    r.impulse = 0.0f;
    r.cfm = in.cfm * r.mass;
    r.flags = 0;
    r.bias = 0.0f;
    return r;
}

/* resolveSingleConstraintRowGeneric on velocities (not deltas): the impulse change that drives
 * J v to the target less the cfm share of the accumulated impulse, clamped to the bounds. */
static inline void btgJointRowSolve(BtgJointRow* r, BtgSolverBody a, BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb)
{
    float delta = (r->target - btgRowVelocity(r->jacobian, *va, *vb)) * r->mass - r->impulse * r->cfm;
    float sum = r->impulse + delta;
    if (sum < r->lower) {
        delta = r->lower - r->impulse;
        r->impulse = r->lower;
    } else if (sum > r->upper) {
        delta = r->upper - r->impulse;
        r->impulse = r->upper;
    } else {
        r->impulse = sum;
    }
    btgRowApply(r->jacobian, a, b, va, vb, delta);
}

/* Whether a joint builds rows this substep: enabled by the app, not broken, and one of its
 * bodies moved by the solver (a joint of a sleeping island is not solved, as Bullet skips
 * sleeping islands). */
static inline int btgJointActive(BtgJoint j, BtgJointState s, BtgJointBody a, BtgJointBody b)
{
    return (j.flags & BTG_JOINT_ENABLED) != 0u && !s.broken && (a.body.dynamic || b.body.dynamic);
}

/* writeBackJoints for one joint: feedback summed over its rows (each row's Jacobian times its
 * impulse, with the bodies' factors, per second), the applied impulse of its last row, and a
 * break when any row's impulse reached the threshold. */
static inline void btgFinishJoint(BtgJointState* s, BtgJointFeedback* f, BtgJoint j, BTG_CONST_GLOBAL BtgJointRow* rows,
                                  BtgJointBody a, BtgJointBody b, float dt)
{
    if (!s->touched) return;
    if (j.flags & BTG_JOINT_FEEDBACK) {
        f->forceA = btgZero4();
        f->torqueA = btgZero4();
        f->forceB = btgZero4();
        f->torqueB = btgZero4();
    }
    for (int k = 0; k < s->numRows; ++k) {
        BtgJointRow r = rows[j.firstRow + k];
        if (j.flags & BTG_JOINT_FEEDBACK) {
            f->forceA = f->forceA + r.jacobian.linear * r.impulse * a.body.linFactor / dt;
            f->forceB = f->forceB + (-r.jacobian.linear) * r.impulse * b.body.linFactor / dt;
            f->torqueA = f->torqueA + r.jacobian.angularA * a.body.angFactor * r.impulse / dt;
            f->torqueB = f->torqueB + r.jacobian.angularB * b.body.angFactor * r.impulse / dt;
        }
        s->appliedImpulse = r.impulse;
        if (btgAbs(r.impulse) >= j.breakingThreshold) s->broken = 1;
    }
}

#endif
