/* generic6dof_rows.h — btGeneric6DofConstraint's rows as 3.24's getInfo1/getInfo2 build them
 * (also btUniversalConstraint, and btGeneric6DofSpringConstraint, whose getInfo2 first turns
 * each spring into its axis's motor target and force as internalUpdateSprings does): XYZ Euler
 * angles, one row per axis that is powered or past a limit (rotational limit motors wrap the
 * error into +-pi), angular rows first with the frame offset (Bullet's default), linear first
 * without it; the linear rows' lever arms by useOffsetForConstraintFrame. */
#ifndef BTG_GENERIC6DOF_ROWS_H
#define BTG_GENERIC6DOF_ROWS_H
#include "sixdof_rows.h"

/* BtgSixDofParams.options of BTG_JOINT_SIXDOF */
#define BTG_SIXDOF_FRAME_OFFSET 2u /* m_useOffsetForConstraintFrame */

/* BtgSixDofAxis.flags of BTG_JOINT_SIXDOF: the axis's 3 bits of m_flags (BT_6DOF_FLAGS_*) */
#define BTG_G6DOF_CFM_NORM 1u
#define BTG_G6DOF_CFM_STOP 2u
#define BTG_G6DOF_ERP_STOP 4u

/* testLimitValue of btRotationalLimitMotor (rotational: 1 low, 2 high, error wrapped into
 * +-pi) or btTranslationalLimitMotor (linear: 2 low, 1 high). */
static inline BtgSixDofLimit btgG6DofTestLimit(BtgSixDofAxis x, float value, int rotational)
{
    const float pi = 3.1415926535897932384626433832795029f, twoPi = 2.0f * pi;
    BtgSixDofLimit l;
    l.position = value;
    l.errorHi = 0.0f;
    l.limit = 0;
    l.error = 0.0f;
    if (x.lo > x.hi) return l;
    if (value < x.lo) {
        l.limit = rotational ? 1 : 2;
        l.error = value - x.lo;
    } else if (value > x.hi) {
        l.limit = rotational ? 2 : 1;
        l.error = value - x.hi;
    } else {
        return l;
    }
    if (rotational) {
        if (l.error > pi)
            l.error -= twoPi;
        else if (l.error < -pi)
            l.error += twoPi;
    }
    return l;
}

/* What the linear rows' lever arms read. */
typedef struct {
    BtgFloat4 relA, relB;  /* frame origins from the centres of mass */
    BtgFloat4 cB;          /* frame B's origin from body A's centre (without the frame offset) */
    float factA, factB;
    int hasStaticBody;
    int offset;            /* m_useOffsetForConstraintFrame */
} BtgG6DofArms;

/* get_limit_motor_info2 of btGeneric6DofConstraint for one axis: a row at rows[*n] when it is
 * powered or past a limit. */
static inline void btgG6DofAxisRow(BtgSixDofAxis x, BtgSixDofLimit l, BtgFloat4 ax, int rotational, int rotAllowed,
                                   BtgG6DofArms arms, BtgFloat4 velA, BtgFloat4 velB, float fps, float erp,
                                   BtgJointInfoRow* rows, int* n)
{
    int powered = (x.mode & BTG_SIXDOF_MOTOR) != 0u;
    const int limit = l.limit;
    if (!powered && !limit) return;
    /* Unset values take info->cfm[0] as it stands now (an earlier row may have written it). */
    const float cfm0 = rows[0].cfm;
    const float normalCfm = (x.flags & BTG_G6DOF_CFM_NORM) ? x.motorCfm : cfm0;
    const float stopCfm = (x.flags & BTG_G6DOF_CFM_STOP) ? x.stopCfm : cfm0;
    const float stopErp = (x.flags & BTG_G6DOF_ERP_STOP) ? x.stopErp : erp;
    BtgJointInfoRow r;
    r.linA = btgZero4();
    r.linB = btgZero4();
    if (rotational) {
        r.angA = btgXyz(ax);
        r.angB = -btgXyz(ax);
    } else {
        r.linA = btgXyz(ax);
        r.linB = -btgXyz(ax);
        if (arms.offset) {
            const BtgFloat4 projB = ax * btgDot3(arms.relB, ax), orthoB = arms.relB - projB;
            const BtgFloat4 projA = ax * btgDot3(arms.relA, ax), orthoA = arms.relA - projA;
            const float desiredOffs = l.position - l.error;
            const BtgFloat4 totalDist = projA + ax * desiredOffs - projB;
            const BtgFloat4 relA = orthoA + totalDist * arms.factA;
            const BtgFloat4 relB = orthoB - totalDist * arms.factB;
            BtgFloat4 tmpA = btgCross3(relA, ax), tmpB = btgCross3(relB, ax);
            if (arms.hasStaticBody && !rotAllowed) {
                tmpA = tmpA * arms.factA;
                tmpB = tmpB * arms.factB;
            }
            r.angA = tmpA;
            r.angB = -tmpB;
        } else {
            r.angA = btgCross3(arms.cB, ax);
            r.angB = -btgCross3(arms.relB, ax);
        }
    }
    r.lower = -BTG_SIMD_INFINITY;
    r.upper = BTG_SIMD_INFINITY;
    r.cfm = (*n == 0) ? cfm0 : 0.0f;
    if (limit && x.lo == x.hi) powered = 0;
    r.error = 0.0f;
    if (powered) {
        r.cfm = normalCfm;
        if (!limit) {
            const float tagVel = rotational ? x.targetVelocity : -x.targetVelocity;
            const float f = btgMotorFactor(l.position, x.lo, x.hi, tagVel, fps * stopErp);
            r.error += f * x.targetVelocity;
            r.lower = -x.maxMotorForce / fps;
            r.upper = x.maxMotorForce / fps;
        }
    }
    if (limit) {
        const float k = fps * stopErp;
        if (!rotational)
            r.error += k * l.error;
        else
            r.error += -k * l.error;
        r.cfm = stopCfm;
        if (x.lo == x.hi) {
            r.lower = -BTG_SIMD_INFINITY;
            r.upper = BTG_SIMD_INFINITY;
        } else {
            if (limit == 1) {
                r.lower = 0.0f;
                r.upper = BTG_SIMD_INFINITY;
            } else {
                r.lower = -BTG_SIMD_INFINITY;
                r.upper = 0.0f;
            }
            const float bounce = rotational ? x.bounce : 0.0f;
            if (bounce > 0.0f) {
                const float vel = btgDot3(velA, ax) - btgDot3(velB, ax);
                if (limit == 1) {
                    if (vel < 0.0f) {
                        const float newc = -bounce * vel;
                        if (newc > r.error) r.error = newc;
                    }
                } else if (vel > 0.0f) {
                    const float newc = -bounce * vel;
                    if (newc < r.error) r.error = newc;
                }
            }
        }
    }
    rows[(*n)++] = r;
}

/* internalUpdateSprings for one axis of a btGeneric6DofSpringConstraint: the motor's target
 * velocity and force from the spring's stretch (Hooke's law, damping per solver iteration). */
static inline BtgSixDofAxis btgG6DofSpringMotor(BtgSixDofAxis x, float position, int rotational, float fps,
                                                int numIterations)
{
    if (!(x.mode & BTG_SIXDOF_SPRING)) return x;
    const float delta = position - x.equilibrium;
    const float force = rotational ? -delta * x.stiffness : delta * x.stiffness;
    const float velFactor = fps * x.damping / (float)numIterations;
    x.targetVelocity = velFactor * force;
    x.maxMotorForce = btgAbs(force);
    return x;
}

/* getInfo1 and getInfo2 of a btGeneric6DofConstraint: rows[0, returned count); bit k of
 * springRows set where rows[k] is the row of an axis whose spring drives its motor. */
static inline int btgG6DofInfoRows(BtgJoint j, BtgJointBody a, BtgJointBody b, float fps, float erp, float globalCfm,
                                   int numIterations, BtgJointInfoRow* rows, uint* springRows)
{
    const BtgSixDofParams p = j.sixdof;
    *springRows = 0u;
    rows[0] = btgEmptyInfoRow(globalCfm);
    BtgFloat4 colA[3], colB[3];
    for (int c = 0; c < 3; ++c) {
        colA[c] = btgFrameAxis(a, j.axesA[c]);
        colB[c] = btgFrameAxis(b, j.axesB[c]);
    }
    BtgG6DofArms arms;
    arms.relA = btgMat3MulVec(a.basis, j.pivotA);
    arms.relB = btgMat3MulVec(b.basis, j.pivotB);
    const BtgFloat4 originB = arms.relB + b.pos;
    arms.cB = originB - a.pos;
    const BtgFloat4 d = originB - (arms.relA + a.pos);
    arms.offset = (p.options & BTG_SIXDOF_FRAME_OFFSET) != 0u;
    const float miA = a.rbInvMass, miB = b.rbInvMass, miS = miA + miB;
    arms.hasStaticBody = (miA < BTG_FLT_EPSILON) || (miB < BTG_FLT_EPSILON);
    arms.factA = miS > 0.0f ? miB / miS : 0.5f;
    arms.factB = 1.0f - arms.factA;
    /* calculateLinearInfo, calculateAngleInfo (XYZ), testAngularLimitMotor */
    float e[9];
    for (int k = 0; k < 9; ++k) e[k] = btgDot3(colA[k % 3], colB[k / 3]);
    const BtgFloat4 euler = btgSixDofEuler(0, e);
    BtgFloat4 axis[3];
    axis[1] = btgCross3(colA[2], colB[0]);
    axis[0] = btgCross3(axis[1], colA[2]);
    axis[2] = btgCross3(colB[0], axis[1]);
    BtgSixDofAxis x[6];
    BtgSixDofLimit lim[6];
    for (int i = 0; i < 3; ++i) {
        const float pos = btgDot3(colA[i], d);
        x[i] = btgG6DofSpringMotor(p.axis[i], pos, 0, fps, numIterations);
        lim[i] = btgG6DofTestLimit(x[i], pos, 0);
        axis[i] = btgNormalized3(axis[i]);
        const float raw = btgLane(euler, i);
        x[3 + i] = btgG6DofSpringMotor(p.axis[3 + i], raw, 1, fps, numIterations);
        lim[3 + i] = btgG6DofTestLimit(x[3 + i], btgAdjustAngleToLimits(raw, x[3 + i].lo, x[3 + i].hi), 1);
    }
    int n = 0;
    for (int pass = 0; pass < 2; ++pass) {
        const int angular = arms.offset ? pass == 0 : pass == 1;
        for (int i = 0; i < 3; ++i) {
            const int before = n;
            if (angular) {
                btgG6DofAxisRow(x[3 + i], lim[3 + i], axis[i], 1, 1, arms, a.angVel0, b.angVel0, fps, erp, rows, &n);
            } else {
                const int rotAllowed = !(lim[3 + (i + 1) % 3].limit && lim[3 + (i + 2) % 3].limit);
                btgG6DofAxisRow(x[i], lim[i], colA[i], 0, rotAllowed, arms, a.linVel0, b.linVel0, fps, erp, rows, &n);
            }
            if (n > before && (p.axis[angular ? 3 + i : i].mode & BTG_SIXDOF_SPRING)) *springRows |= 1u << before;
        }
    }
    return n;
}

#endif
