/* sixdof_rows.h — btGeneric6DofSpring2Constraint's rows as its getInfo1/getInfo2 build them
 * (Bullet 3.24; also btFixedConstraint and btHinge2Constraint, which add no rows of their own):
 * calculateTransforms (the six rotation orders' Euler angles and axes), the angular rows first
 * in the order's sequence, then the linear rows; per axis the limit rows (locked: one, ranged:
 * two one-sided rows with bounce), the velocity motor or servo row and the spring row (its
 * stiffness and damping limited as setStiffness/setDamping's limitIfNeeded ask). */
#ifndef BTG_SIXDOF_ROWS_H
#define BTG_SIXDOF_ROWS_H
#include "slider_rows.h"

/* Bullet's SIMD_INFINITY in the float build: FLT_MAX, not an IEEE infinity. */
#define BTG_SIMD_INFINITY 3.402823466e+38f

/* Rows one 6-DoF joint builds at most with its settings (its slots in the row table). */
static inline int btgSixDofMaxRows(BtgSixDofParams p)
{
    int n = 0;
    for (int i = 0; i < 6; ++i) {
        BtgSixDofAxis x = p.axis[i];
        n += x.lo < x.hi ? 2 : (x.lo == x.hi ? 1 : 0);
        n += (x.mode & BTG_SIXDOF_MOTOR) ? 1 : 0;
        n += (x.mode & BTG_SIXDOF_SPRING) ? 1 : 0;
    }
    return n;
}

/* btRotationalLimitMotor2 / btTranslationalLimitMotor2::testLimitValue */
typedef struct {
    int limit;       /* 0 free, 3 locked, 4 ranged */
    float error;     /* m_currentLimitError */
    float errorHi;   /* m_currentLimitErrorHi (ranged only) */
    float position;  /* m_currentPosition / m_currentLinearDiff */
} BtgSixDofLimit;

static inline BtgSixDofLimit btgSixDofTestLimit(BtgSixDofAxis x, float value)
{
    BtgSixDofLimit l;
    l.position = value;
    l.errorHi = 0.0f;
    if (x.lo > x.hi) {
        l.limit = 0;
        l.error = 0.0f;
    } else if (x.lo == x.hi) {
        l.limit = 3;
        l.error = value - x.lo;
    } else {
        l.limit = 4;
        l.error = value - x.lo;
        l.errorHi = value - x.hi;
    }
    return l;
}

/* matrixToEuler* of the relative frame; e(k) is btGetMatrixElem(rel, k) = rel[k % 3][k / 3]. */
static inline BtgFloat4 btgSixDofEuler(int order, const float* e)
{
    const float h = 1.57079632679489661923f;
    float x = 0.0f, y = 0.0f, z = 0.0f;
    if (order == 0) { /* XYZ */
        float fi = e[2];
        if (fi < 1.0f) {
            if (fi > -1.0f) { x = btgAtan2(-e[5], e[8]); y = btgAsin(e[2]); z = btgAtan2(-e[1], e[0]); }
            else { x = -btgAtan2(e[3], e[4]); y = -h; }
        } else { x = btgAtan2(e[3], e[4]); y = h; }
    } else if (order == 1) { /* XZY */
        float fi = e[1];
        if (fi < 1.0f) {
            if (fi > -1.0f) { x = btgAtan2(e[7], e[4]); y = btgAtan2(e[2], e[0]); z = btgAsin(-e[1]); }
            else { x = -btgAtan2(-e[6], e[8]); z = h; }
        } else { x = btgAtan2(-e[6], e[8]); z = -h; }
    } else if (order == 2) { /* YXZ */
        float fi = e[5];
        if (fi < 1.0f) {
            if (fi > -1.0f) { x = btgAsin(-e[5]); y = btgAtan2(e[2], e[8]); z = btgAtan2(e[3], e[4]); }
            else { x = h; y = -btgAtan2(-e[1], e[0]); }
        } else { x = -h; y = btgAtan2(-e[1], e[0]); }
    } else if (order == 3) { /* YZX */
        float fi = e[3];
        if (fi < 1.0f) {
            if (fi > -1.0f) { x = btgAtan2(-e[5], e[4]); y = btgAtan2(-e[6], e[0]); z = btgAsin(e[3]); }
            else { y = -btgAtan2(e[7], e[8]); z = -h; }
        } else { y = btgAtan2(e[7], e[8]); z = h; }
    } else if (order == 4) { /* ZXY */
        float fi = e[7];
        if (fi < 1.0f) {
            if (fi > -1.0f) { x = btgAsin(e[7]); y = btgAtan2(-e[6], e[8]); z = btgAtan2(-e[1], e[4]); }
            else { x = -h; z = -btgAtan2(e[2], e[0]); }
        } else { x = h; z = btgAtan2(e[2], e[0]); }
    } else { /* ZYX */
        float fi = e[6];
        if (fi < 1.0f) {
            if (fi > -1.0f) { x = btgAtan2(e[7], e[8]); y = btgAsin(-e[6]); z = btgAtan2(e[3], e[0]); }
            else { y = h; z = -btgAtan2(e[1], e[2]); }
        } else { y = -h; z = btgAtan2(-e[1], -e[2]); }
    }
    return btgMake4(x, y, z, 0.0f);
}

static inline BtgFloat4 btgNormalized3(BtgFloat4 v) { return v * (1.0f / btgSqrt(btgDot3(v, v))); }

/* get_limit_motor_info2's servo row error: the motor drives the axis toward its servo target at
 * its target speed, slowed near the target (getMotorFactor with the target as a limit). */
static inline float btgSixDofServoError(BtgSixDofAxis x, BtgSixDofLimit l, int rotational, float fps, float motorErp)
{
    const float pi = 3.1415926535897932384626433832795029f, twoPi = 2.0f * pi;
    float error = l.position - x.servoTarget;
    float cur = x.servoTarget;
    if (rotational) {
        if (error > pi) {
            error -= twoPi;
            cur += twoPi;
        }
        if (error < -pi) {
            error += twoPi;
            cur -= twoPi;
        }
    }
    const float tv = error < 0.0f ? -x.targetVelocity : x.targetVelocity;
    float f = 0.0f;
    if (error != 0.0f) {
        float lo, hi;
        if (x.lo > x.hi) {
            lo = error > 0.0f ? cur : -BTG_SIMD_INFINITY;
            hi = error < 0.0f ? cur : BTG_SIMD_INFINITY;
        } else {
            lo = error > 0.0f && cur > x.lo ? cur : x.lo;
            hi = error < 0.0f && cur < x.hi ? cur : x.hi;
        }
        f = btgMotorFactor(l.position, lo, hi, -tv, fps * motorErp);
    }
    return f * tv * (rotational ? -1.0f : 1.0f);
}

/* What the spring row reads of the two bodies (m_rbA/m_rbB and the frames' lever arms). */
typedef struct {
    BtgJointBody a, b;
    BtgFloat4 relA, relB; /* frame origins from the centres of mass, unscaled */
    uint infiniteError;   /* BT_6DOF_FLAGS_USE_INFINITE_ERROR */
} BtgSixDofBodies;

/* get_limit_motor_info2's spring row: an impulse of one step of the spring force (stiffness
 * and damping limited to what the step can sample when asked), bounded by it. */
static inline void btgSixDofSpringRow(BtgSixDofAxis x, BtgSixDofLimit l, BtgFloat4 ax, int rotational,
                                      BtgSixDofBodies s, float fps, BtgJointInfoRow* r)
{
    const float sgn = rotational ? -1.0f : 1.0f;
    const float error = l.position - x.equilibrium;
    const float dt = 1.0f / fps;
    float kd = x.damping, ks = x.stiffness, vel;
    if (rotational) {
        vel = btgDot3(s.a.angVel0, ax) - btgDot3(s.b.angVel0, ax);
    } else {
        const BtgFloat4 tA = btgCross3(s.a.angVel0, s.relA), tB = btgCross3(s.b.angVel0, s.relB);
        vel = btgDot3(s.a.linVel0 + tA, ax) - btgDot3(s.b.linVel0 + tB, ax);
    }
    /* m_rbA.getInvMass(), as the solver sees the body: a body asleep while its partner moves
     * (woken a step late here, where Bullet wakes the island first) counts as static, rather
     * than meeting a zero world inertia of the sleeping body (inf / inf). */
    const float miA = s.a.body.invMass, miB = s.b.body.invMass;
    float mA = 1.0f / miA, mB = 1.0f / miB;
    if (rotational) {
        const float rrA = btgDot3(s.relA, s.relA), rrB = btgDot3(s.relB, s.relB);
        if (miA != 0.0f) mA = mA * rrA + 1.0f / btgSqrt(btgDot3(btgMat3MulVec(s.a.body.invI, ax), btgMat3MulVec(s.a.body.invI, ax)));
        if (miB != 0.0f) mB = mB * rrB + 1.0f / btgSqrt(btgDot3(btgMat3MulVec(s.b.body.invI, ax), btgMat3MulVec(s.b.body.invI, ax)));
    }
    const float m = miA == 0.0f ? mB : (miB == 0.0f ? mA : mA * mB / (mA + mB));
    const float angularFreq = btgSqrt(ks / m);
    if ((x.mode & BTG_SIXDOF_STIFF_LIMITED) && 0.25f < angularFreq * dt) ks = 1.0f / dt / dt / 16.0f * m;
    if ((x.mode & BTG_SIXDOF_DAMP_LIMITED) && kd * dt > m) kd = m / dt;
    const float fs = ks * error * dt;
    const float fd = -kd * vel * sgn * dt;
    const float f = fs + fd;
    if (s.infiniteError)
        r->error = sgn * (f < 0.0f ? -BTG_SIMD_INFINITY : BTG_SIMD_INFINITY);
    else
        r->error = vel + f / m * sgn;
    const float minf = f < fd ? f : fd, maxf = f < fd ? fd : f;
    if (!rotational) {
        r->lower = minf > 0.0f ? 0.0f : minf;
        r->upper = maxf < 0.0f ? 0.0f : maxf;
    } else {
        r->lower = -maxf > 0.0f ? 0.0f : -maxf;
        r->upper = -minf < 0.0f ? 0.0f : -minf;
    }
    r->cfm = 0.0f;
}

/* calculateJacobi plus get_limit_motor_info2 for one axis: rows appended at rows[*n]. */
static inline void btgSixDofAxisRows(BtgSixDofAxis x, BtgSixDofLimit l, BtgFloat4 ax, int rotational, BtgSixDofBodies s,
                                     float jScaleA, float jScaleB, float vel, float fps, float erp,
                                     BtgJointInfoRow* rows, int* n, uint* springRows)
{
    const BtgFloat4 relA = s.relA, relB = s.relB;
    /* Unset values take info->cfm[0] as it stands now: row 0's cfm, which an earlier row may
     * already have overwritten (Bullet reads it through the same pointer). */
    const float cfm0 = rows[0].cfm;
    const float stopCfm = (x.flags & 1u) ? x.stopCfm : cfm0;
    const float stopErp = (x.flags & 2u) ? x.stopErp : erp;
    const float motorCfm = (x.flags & 4u) ? x.motorCfm : cfm0;
    const float motorErp = (x.flags & 8u) ? x.motorErp : erp;
    const float sign = rotational ? -1.0f : 1.0f;
    BtgJointInfoRow j;
    j.linA = btgZero4();
    j.linB = btgZero4();
    if (rotational) {
        j.angA = btgXyz(ax);
        j.angB = -btgXyz(ax);
    } else {
        j.linA = btgXyz(ax);
        j.linB = -btgXyz(ax);
        j.angA = btgCross3(relA, ax) * jScaleA;
        j.angB = -(btgCross3(relB, ax) * jScaleB);
    }
    if (l.limit == 4) {
        BtgJointInfoRow r = j;
        r.error = fps * stopErp * l.error * sign;
        if (rotational) {
            if (r.error - vel * stopErp > 0.0f) {
                float b = -x.bounce * vel;
                if (b > r.error) r.error = b;
            }
        } else if (r.error - vel * stopErp < 0.0f) {
            float b = -x.bounce * vel;
            if (b < r.error) r.error = b;
        }
        r.lower = rotational ? 0.0f : -INFINITY;
        r.upper = rotational ? INFINITY : 0.0f;
        r.cfm = stopCfm;
        rows[(*n)++] = r;
        r = j;
        r.error = fps * stopErp * l.errorHi * sign;
        if (rotational) {
            if (r.error - vel * stopErp < 0.0f) {
                float b = -x.bounce * vel;
                if (b < r.error) r.error = b;
            }
        } else if (r.error - vel * stopErp > 0.0f) {
            float b = -x.bounce * vel;
            if (b > r.error) r.error = b;
        }
        r.lower = rotational ? -INFINITY : 0.0f;
        r.upper = rotational ? 0.0f : INFINITY;
        r.cfm = stopCfm;
        rows[(*n)++] = r;
    } else if (l.limit == 3) {
        BtgJointInfoRow r = j;
        r.error = fps * stopErp * l.error * sign;
        r.lower = -INFINITY;
        r.upper = INFINITY;
        r.cfm = stopCfm;
        rows[(*n)++] = r;
    }
    if (x.mode & BTG_SIXDOF_MOTOR) {
        BtgJointInfoRow r = j;
        if (x.mode & BTG_SIXDOF_SERVO) {
            r.error = btgSixDofServoError(x, l, rotational, fps, motorErp);
        } else {
            const float tagVel = rotational ? x.targetVelocity : -x.targetVelocity;
            r.error = btgMotorFactor(l.position, x.lo, x.hi, tagVel, fps * motorErp) * x.targetVelocity;
        }
        r.lower = -x.maxMotorForce / fps;
        r.upper = x.maxMotorForce / fps;
        r.cfm = motorCfm;
        rows[(*n)++] = r;
    }
    if (x.mode & BTG_SIXDOF_SPRING) {
        BtgJointInfoRow r = j;
        btgSixDofSpringRow(x, l, ax, rotational, s, fps, &r);
        *springRows |= 1u << *n;
        rows[(*n)++] = r;
    }
}

/* Whether an angular limit counts as violated for the linear rows' rotAllowed. */
static inline int btgSixDofViolated(BtgSixDofLimit l)
{
    const float t = 1.0e-3f;
    return l.limit == 1 || l.limit == 2 || (l.limit == 3 && (l.error < -t || l.error > t)) ||
           (l.limit == 4 && (l.error < -t || l.errorHi > t));
}

/* getInfo1 and getInfo2 of a 6-DoF spring2 joint: rows[0, returned count), the spring rows'
 * places in springRows. */
static inline int btgSixDofInfoRows(BtgJoint j, BtgJointBody a, BtgJointBody b, float fps, float erp, float globalCfm,
                                    BtgJointInfoRow* rows, uint* springRows)
{
    const BtgSixDofParams p = j.sixdof;
    *springRows = 0u; /* bit k: rows[k] is a spring row */
    rows[0] = btgEmptyInfoRow(globalCfm);
    /* calculateTransforms */
    BtgFloat4 colA[3], colB[3];
    for (int c = 0; c < 3; ++c) {
        colA[c] = btgFrameAxis(a, j.axesA[c]);
        colB[c] = btgFrameAxis(b, j.axesB[c]);
    }
    const BtgFloat4 relA = btgMat3MulVec(a.basis, j.pivotA), relB = btgMat3MulVec(b.basis, j.pivotB);
    const BtgFloat4 d = (relB + b.pos) - (relA + a.pos);
    BtgSixDofLimit lin[3], ang[3];
    for (int i = 0; i < 3; ++i) lin[i] = btgSixDofTestLimit(p.axis[i], btgDot3(colA[i], d));
    float e[9];
    for (int k = 0; k < 9; ++k) e[k] = btgDot3(colA[k % 3], colB[k / 3]);
    const BtgFloat4 euler = btgSixDofEuler(p.rotateOrder, e);
    BtgFloat4 axis[3];
    const int o = p.rotateOrder;
    if (o == 0) {
        axis[1] = btgCross3(colA[2], colB[0]);
        axis[0] = btgCross3(axis[1], colA[2]);
        axis[2] = btgCross3(colB[0], axis[1]);
    } else if (o == 1) {
        axis[2] = btgCross3(colB[0], colA[1]);
        axis[0] = btgCross3(colA[1], axis[2]);
        axis[1] = btgCross3(axis[2], colB[0]);
    } else if (o == 2) {
        axis[0] = btgCross3(colB[1], colA[2]);
        axis[1] = btgCross3(colA[2], axis[0]);
        axis[2] = btgCross3(axis[0], colB[1]);
    } else if (o == 3) {
        axis[2] = btgCross3(colA[0], colB[1]);
        axis[0] = btgCross3(colB[1], axis[2]);
        axis[1] = btgCross3(axis[2], colA[0]);
    } else if (o == 4) {
        axis[0] = btgCross3(colA[1], colB[2]);
        axis[1] = btgCross3(colB[2], axis[0]);
        axis[2] = btgCross3(axis[0], colA[1]);
    } else {
        axis[1] = btgCross3(colB[2], colA[0]);
        axis[0] = btgCross3(axis[1], colB[2]);
        axis[2] = btgCross3(colA[0], axis[1]);
    }
    for (int i = 0; i < 3; ++i) {
        axis[i] = btgNormalized3(axis[i]);
        BtgSixDofAxis x = p.axis[3 + i];
        ang[i] = btgSixDofTestLimit(x, btgAdjustAngleToLimits(btgLane(euler, i), x.lo, x.hi));
    }
    const float miA = a.rbInvMass, miB = b.rbInvMass;
    const int hasStaticBody = (miA < BTG_FLT_EPSILON) || (miB < BTG_FLT_EPSILON);
    const float miS = miA + miB;
    const float factA = miS > 0.0f ? miB / miS : 0.5f;
    const float factB = 1.0f - factA;
    BtgSixDofBodies s;
    s.a = a;
    s.b = b;
    s.relA = relA;
    s.relB = relB;
    s.infiniteError = p.options & BTG_SIXDOF_INFINITE_ERROR;
    /* setAngularLimits, in the rotation order's sequence */
    const int seq0[6] = {0, 0, 1, 1, 2, 2}, seq1[6] = {1, 2, 0, 2, 0, 1}, seq2[6] = {2, 1, 2, 0, 1, 0};
    int n = 0;
    for (int ii = 0; ii < 3; ++ii) {
        const int i = ii == 0 ? seq0[o] : (ii == 1 ? seq1[o] : seq2[o]);
        BtgSixDofAxis x = p.axis[3 + i];
        if (!ang[i].limit && !(x.mode & (BTG_SIXDOF_MOTOR | BTG_SIXDOF_SPRING))) continue;
        const float vel = btgDot3(a.angVel0, axis[i]) - btgDot3(b.angVel0, axis[i]);
        btgSixDofAxisRows(x, ang[i], axis[i], 1, s, 1.0f, 1.0f, vel, fps, erp, rows, &n, springRows);
    }
    /* setLinearLimits */
    for (int i = 0; i < 3; ++i) {
        BtgSixDofAxis x = p.axis[i];
        if (!lin[i].limit && !(x.mode & (BTG_SIXDOF_MOTOR | BTG_SIXDOF_SPRING))) continue;
        const int rotAllowed = !(btgSixDofViolated(ang[(i + 1) % 3]) && btgSixDofViolated(ang[(i + 2) % 3]));
        const int scale = hasStaticBody && !rotAllowed;
        const float vel = btgDot3(a.linVel0, colA[i]) - btgDot3(b.linVel0, colA[i]);
        btgSixDofAxisRows(x, lin[i], colA[i], 0, s, scale ? factA : 1.0f, scale ? factB : 1.0f, vel, fps, erp, rows, &n, springRows);
    }
    return n;
}

#endif
