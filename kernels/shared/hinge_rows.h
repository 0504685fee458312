/* hinge_rows.h — btHingeConstraint's rows as its getInfo1/getInfo2 build them (Bullet 3.24,
 * _BT_USE_CENTER_LIMIT_): the hinge angle and btAngularLimit's test, the three point rows and
 * two angular rows (the frame-offset variant, Bullet's default, or the plain one), and the
 * limit/motor row along the axis (getMotorFactor, stop ERP/CFM, bias and relaxation bounce).
 * Shared by prepare_joints and its reference, through joint_prepare.h. */
#ifndef BTG_HINGE_ROWS_H
#define BTG_HINGE_ROWS_H
#include "joint_rows.h"

#define BTG_PI 3.1415926535897932384626433832795029f
#define BTG_2PI (2.0f * BTG_PI)
#define BTG_FLT_EPSILON 1.192092896e-07f

/* btNormalizeAngle */
static inline float btgNormalizeAngle(float a)
{
    a = btgFmod(a, BTG_2PI);
    if (a < -BTG_PI) return a + BTG_2PI;
    if (a > BTG_PI) return a - BTG_2PI;
    return a;
}

/* btTypedConstraint::getMotorFactor */
static inline float btgMotorFactor(float pos, float lowLim, float uppLim, float vel, float timeFact)
{
    if (lowLim > uppLim) return 1.0f;
    if (lowLim == uppLim) return 0.0f;
    float f = 1.0f;
    float deltaMax = vel / timeFact;
    if (deltaMax < 0.0f) {
        if (pos >= lowLim && pos < lowLim - deltaMax) f = (lowLim - pos) / deltaMax;
        else if (pos < lowLim) f = 0.0f;
        else f = 1.0f;
    } else if (deltaMax > 0.0f) {
        if (pos <= uppLim && pos > uppLim - deltaMax) f = (uppLim - pos) / deltaMax;
        else if (pos > uppLim) f = 0.0f;
        else f = 1.0f;
    } else {
        f = 0.0f;
    }
    return f;
}

/* A frame's basis column c in world space: the body's basis times the column (trA.getBasis()
 * .getColumn(c) of transA * m_rbAFrame). */
static inline BtgFloat4 btgFrameAxis(BtgJointBody b, BtgFloat4 col)
{
    return btgMat3MulVec(b.basis, col);
}

/* testLimit: the hinge angle (getHingeAngle) and btAngularLimit::test's verdict. */
typedef struct {
    float angle;      /* rad, m_hingeAngle */
    float correction; /* rad, m_limit.getCorrection() */
    int solveLimit;
} BtgHingeLimit;

static inline BtgHingeLimit btgHingeTestLimit(BtgJoint j, BtgJointBody a, BtgJointBody b)
{
    BtgHingeLimit l;
    BtgFloat4 ref0 = btgFrameAxis(a, j.axesA[0]);
    BtgFloat4 ref1 = btgFrameAxis(a, j.axesA[1]);
    BtgFloat4 swing = btgFrameAxis(b, j.axesB[1]);
    l.angle = j.referenceSign * btgAtan2(btgDot3(swing, ref0), btgDot3(swing, ref1));
    l.correction = 0.0f;
    l.solveLimit = 0;
    if (j.limitHalfRange >= 0.0f) {
        float deviation = btgNormalizeAngle(l.angle - j.limitCenter);
        if (deviation < -j.limitHalfRange) {
            l.solveLimit = 1;
            l.correction = -(deviation + j.limitHalfRange);
        } else if (deviation > j.limitHalfRange) {
            l.solveLimit = 1;
            l.correction = j.limitHalfRange - deviation;
        }
    }
    return l;
}

static inline BtgJointInfoRow btgEmptyInfoRow(float globalCfm)
{
    BtgJointInfoRow r;
    r.linA = btgZero4();
    r.angA = btgZero4();
    r.linB = btgZero4();
    r.angB = btgZero4();
    r.error = 0.0f;
    r.cfm = globalCfm;
    r.lower = -INFINITY;
    r.upper = INFINITY;
    return r;
}

/* getInfo1 and getInfo2 of a hinge: rows[0, returned count). */
static inline int btgHingeInfoRows(BtgJoint j, BtgJointBody a, BtgJointBody b, float fps, float erp, float globalCfm,
                                   BtgJointInfoRow* rows)
{
    BtgHingeLimit lim = btgHingeTestLimit(j, a, b);
    /* convertJoint sets m_globalCfm on the first row only. */
    for (int k = 0; k < BTG_JOINT_HINGE_ROWS; ++k) rows[k] = btgEmptyInfoRow(k == 0 ? globalCfm : 0.0f);
    const int angularOnly = (j.flags & BTG_JOINT_ANGULAR_ONLY) != 0u;
    /* World frames: trA = transA * m_rbAFrame. */
    BtgFloat4 pivotAInW = btgMat3MulVec(a.basis, j.pivotA) + a.pos;
    BtgFloat4 pivotBInW = btgMat3MulVec(b.basis, j.pivotB) + b.pos;
    BtgFloat4 ax1A = btgFrameAxis(a, j.axesA[2]);
    BtgFloat4 ax1B = btgFrameAxis(b, j.axesB[2]);
    const float normalErp = (j.flags & BTG_JOINT_OWN_ERP) ? j.erp : erp;
    float k = fps * normalErp;
    BtgFloat4 ax1, p, q;
    if (j.flags & BTG_JOINT_FRAME_OFFSET) {
        /* getInfo2InternalUsingFrameOffset */
        BtgFloat4 ofs = pivotBInW - pivotAInW;
        const float miA = a.rbInvMass, miB = b.rbInvMass;
        const int hasStaticBody = (miA < BTG_FLT_EPSILON) || (miB < BTG_FLT_EPSILON);
        const float miS = miA + miB;
        float factA = miS > 0.0f ? miB / miS : 0.5f;
        float factB = 1.0f - factA;
        ax1 = ax1A * factA + ax1B * factB;
        if (btgDot3(ax1, ax1) < BTG_FLT_EPSILON) {
            factA = 0.0f;
            factB = 1.0f;
            ax1 = ax1A * factA + ax1B * factB;
        }
        ax1 = ax1 * (1.0f / btgSqrt(btgDot3(ax1, ax1)));
        BtgFloat4 relB = pivotBInW - b.pos;
        BtgFloat4 projB = ax1 * btgDot3(relB, ax1);
        BtgFloat4 orthoB = relB - projB;
        BtgFloat4 relA = pivotAInW - a.pos;
        BtgFloat4 projA = ax1 * btgDot3(relA, ax1);
        BtgFloat4 orthoA = relA - projA;
        BtgFloat4 totalDist = projA - projB;
        relA = orthoA + totalDist * factA;
        relB = orthoB - totalDist * factB;
        p = orthoB * factA + orthoA * factB;
        float len2 = btgDot3(p, p);
        if (len2 > BTG_FLT_EPSILON) p = p / btgSqrt(len2);
        else p = btgFrameAxis(a, j.axesA[1]);
        q = btgCross3(ax1, p);
        BtgFloat4 tmpA = btgCross3(relA, p), tmpB = btgCross3(relB, p);
        rows[0].angA = tmpA;
        rows[0].angB = -tmpB;
        tmpA = btgCross3(relA, q);
        tmpB = btgCross3(relB, q);
        if (hasStaticBody && lim.solveLimit) {
            tmpB = tmpB * factB;
            tmpA = tmpA * factA;
        }
        rows[1].angA = tmpA;
        rows[1].angB = -tmpB;
        tmpA = btgCross3(relA, ax1);
        tmpB = btgCross3(relB, ax1);
        if (hasStaticBody) {
            tmpB = tmpB * factB;
            tmpA = tmpA * factA;
        }
        rows[2].angA = tmpA;
        rows[2].angB = -tmpB;
        if (!angularOnly) {
            rows[0].linA = btgXyz(p);
            rows[1].linA = btgXyz(q);
            rows[2].linA = btgXyz(ax1);
            rows[0].error = k * btgDot3(p, ofs);
            rows[1].error = k * btgDot3(q, ofs);
            rows[2].error = k * btgDot3(ax1, ofs);
        }
        BtgFloat4 u = btgCross3(ax1A, ax1B);
        rows[3].angA = btgXyz(p);
        rows[4].angA = btgXyz(q);
        rows[3].error = k * btgDot3(u, p);
        rows[4].error = k * btgDot3(u, q);
    } else {
        /* getInfo2Internal */
        BtgFloat4 a1 = pivotAInW - a.pos, a2 = pivotBInW - b.pos;
        for (int r = 0; r < 3; ++r) {
            BtgFloat4 axis = btgMake4(r == 0 ? 1.0f : 0.0f, r == 1 ? 1.0f : 0.0f, r == 2 ? 1.0f : 0.0f, 0.0f);
            if (!angularOnly) rows[r].linA = axis;
            rows[r].angA = btgCross3(a1, axis);
            rows[r].angB = -btgCross3(a2, axis);
            if (!angularOnly) rows[r].error = k * (btgLane(pivotBInW, r) - btgLane(pivotAInW, r));
        }
        ax1 = ax1A;
        p = btgFrameAxis(a, j.axesA[0]);
        q = btgFrameAxis(a, j.axesA[1]);
        BtgFloat4 u = btgCross3(ax1, ax1B);
        rows[3].angA = btgXyz(p);
        rows[4].angA = btgXyz(q);
        rows[3].error = k * btgDot3(u, p);
        rows[4].error = k * btgDot3(u, q);
    }
    rows[3].angB = -rows[3].angA;
    rows[4].angB = -rows[4].angA;
    for (int r = 0; r < 5; ++r) rows[r].linB = -rows[r].linA;
    /* The limit / motor row along the axis. */
    float limitErr = 0.0f;
    int limit = 0;
    if (lim.solveLimit) {
        limitErr = lim.correction * j.referenceSign;
        limit = limitErr > 0.0f ? 1 : 2;
    }
    int powered = (j.flags & BTG_JOINT_MOTOR) != 0u;
    if (!limit && !powered) return 5;
    BtgJointInfoRow* r = &rows[5];
    r->angA = btgXyz(ax1);
    r->angB = -btgXyz(ax1);
    const float lostop = btgNormalizeAngle(j.limitCenter - j.limitHalfRange);
    const float histop = btgNormalizeAngle(j.limitCenter + j.limitHalfRange);
    if (limit && lostop == histop) powered = 0;
    r->error = 0.0f;
    const float currErp = (j.flags & BTG_JOINT_OWN_STOP_ERP) ? j.stopErp : normalErp;
    if (powered) {
        if (j.flags & BTG_JOINT_OWN_CFM) r->cfm = j.cfm;
        float motFact = btgMotorFactor(lim.angle, lostop, histop, j.motorVelocity, fps * currErp);
        r->error += motFact * j.motorVelocity * j.referenceSign;
        r->lower = -j.motorMaxImpulse;
        r->upper = j.motorMaxImpulse;
    }
    if (limit) {
        k = fps * currErp;
        r->error += k * limitErr;
        if (j.flags & BTG_JOINT_OWN_STOP_CFM) r->cfm = j.stopCfm;
        if (lostop == histop) {
            r->lower = -INFINITY;
            r->upper = INFINITY;
        } else if (limit == 1) {
            r->lower = 0.0f;
            r->upper = INFINITY;
        } else {
            r->lower = -INFINITY;
            r->upper = 0.0f;
        }
        const float bounce = j.limitRelaxation;
        if (bounce > 0.0f) {
            float vel = btgDot3(a.angVel0, ax1);
            vel -= btgDot3(b.angVel0, ax1);
            if (limit == 1) {
                if (vel < 0.0f) {
                    float newc = -bounce * vel;
                    if (newc > r->error) r->error = newc;
                }
            } else if (vel > 0.0f) {
                float newc = -bounce * vel;
                if (newc < r->error) r->error = newc;
            }
        }
        r->error *= j.limitBias;
    }
    return 6;
}

#endif
