/* slider_rows.h — btSliderConstraint's rows as its getInfo1/getInfo2 build them (Bullet 3.24):
 * calculateTransforms and the linear and angular limit tests, then two angular rows, two
 * linear rows (the frame-offset variant, Bullet's default, or the old one), and the linear and
 * angular limit/motor rows along the slider axis (motor factor, softness, damping bounce, the
 * flags' own ERP/CFM). Shared by prepare_joints and its reference, through joint_prepare.h. */
#ifndef BTG_SLIDER_ROWS_H
#define BTG_SLIDER_ROWS_H
#include "hinge_rows.h"

/* btAdjustAngleToLimits */
static inline float btgAdjustAngleToLimits(float a, float lo, float hi)
{
    if (lo >= hi) return a;
    if (a < lo) {
        float diffLo = btgAbs(btgNormalizeAngle(lo - a));
        float diffHi = btgAbs(btgNormalizeAngle(hi - a));
        return diffLo < diffHi ? a : a + BTG_2PI;
    }
    if (a > hi) {
        float diffHi = btgAbs(btgNormalizeAngle(a - hi));
        float diffLo = btgAbs(btgNormalizeAngle(a - lo));
        return diffLo < diffHi ? a - BTG_2PI : a;
    }
    return a;
}

/* getInfo1 and getInfo2NonVirtual of a slider: rows[0, returned count). */
static inline int btgSliderInfoRows(BtgJoint j, BtgJointBody a, BtgJointBody b, float fps, float erp, float globalCfm,
                                    BtgJointInfoRow* rows)
{
    const BtgSliderParams sp = j.slider;
    const int linRefA = (sp.options & BTG_SLIDER_LINEAR_REFERENCE_A) != 0u;
    const int offset = (sp.options & BTG_SLIDER_FRAME_OFFSET) != 0u;
    for (int k = 0; k < BTG_JOINT_SLIDER_ROWS; ++k) rows[k] = btgEmptyInfoRow(k == 0 ? globalCfm : 0.0f);
    /* calculateTransforms */
    BtgFloat4 pivotA = btgMat3MulVec(a.basis, j.pivotA) + a.pos, pivotB = btgMat3MulVec(b.basis, j.pivotB) + b.pos;
    BtgFloat4 colA0 = btgFrameAxis(a, j.axesA[0]), colA1 = btgFrameAxis(a, j.axesA[1]), colA2 = btgFrameAxis(a, j.axesA[2]);
    BtgFloat4 colB0 = btgFrameAxis(b, j.axesB[0]), colB1 = btgFrameAxis(b, j.axesB[1]);
    BtgFloat4 delta = linRefA ? pivotB - pivotA : pivotA - pivotB;
    float depth0 = btgDot3(delta, colA0);
    /* testAngLimits */
    float angDepth = 0.0f, angPos = 0.0f;
    int solveAng = 0;
    if (sp.lowerAng <= sp.upperAng) {
        float rot = btgAtan2(btgDot3(colB1, colA2), btgDot3(colB1, colA1));
        rot = btgAdjustAngleToLimits(rot, sp.lowerAng, sp.upperAng);
        angPos = rot;
        if (rot < sp.lowerAng) {
            angDepth = rot - sp.lowerAng;
            solveAng = 1;
        } else if (rot > sp.upperAng) {
            angDepth = rot - sp.upperAng;
            solveAng = 1;
        }
    }
    /* testLinLimits */
    int solveLin = 0;
    const float linPos = depth0;
    if (sp.lowerLin <= sp.upperLin) {
        if (depth0 > sp.upperLin) {
            depth0 -= sp.upperLin;
            solveLin = 1;
        } else if (depth0 < sp.lowerLin) {
            depth0 -= sp.lowerLin;
            solveLin = 1;
        } else {
            depth0 = 0.0f;
        }
    } else {
        depth0 = 0.0f;
    }
    /* getInfo2NonVirtual */
    const float signFact = linRefA ? 1.0f : -1.0f;
    BtgFloat4 ofs = pivotB - pivotA;
    const float miA = a.rbInvMass, miB = b.rbInvMass;
    const int hasStaticBody = (miA < BTG_FLT_EPSILON) || (miB < BTG_FLT_EPSILON);
    const float miS = miA + miB;
    const float factA = miS > 0.0f ? miB / miS : 0.5f;
    const float factB = 1.0f - factA;
    BtgFloat4 ax1, p, q;
    const BtgFloat4 ax1A = colA0, ax1B = colB0;
    if (offset) {
        ax1 = ax1A * factA + ax1B * factB;
        ax1 = ax1 * (1.0f / btgSqrt(btgDot3(ax1, ax1)));
        btgPlaneSpace(ax1, &p, &q);
    } else {
        ax1 = colA0;
        p = colA1;
        q = colA2;
    }
    rows[0].angA = btgXyz(p);
    rows[0].angB = -btgXyz(p);
    rows[1].angA = btgXyz(q);
    rows[1].angB = -btgXyz(q);
    float currErp = (sp.flags & 128u) ? sp.softnessOrthoAng : sp.softnessOrthoAng * erp; /* ERP_ORTANG */
    float k = fps * currErp;
    BtgFloat4 u = btgCross3(ax1A, ax1B);
    rows[0].error = k * btgDot3(u, p);
    rows[1].error = k * btgDot3(u, q);
    if (sp.flags & 64u) { /* CFM_ORTANG */
        rows[0].cfm = sp.cfmOrthoAng;
        rows[1].cfm = sp.cfmOrthoAng;
    }
    BtgFloat4 relA = btgZero4(), relB = btgZero4(), c = btgZero4();
    if (offset) {
        relB = pivotB - b.pos;
        BtgFloat4 projB = ax1 * btgDot3(relB, ax1);
        BtgFloat4 orthoB = relB - projB;
        relA = pivotA - a.pos;
        BtgFloat4 projA = ax1 * btgDot3(relA, ax1);
        BtgFloat4 orthoA = relA - projA;
        const float sliderOffs = linPos - depth0;
        BtgFloat4 totalDist = projA + ax1 * sliderOffs - projB;
        relA = orthoA + totalDist * factA;
        relB = orthoB - totalDist * factB;
        p = orthoB * factA + orthoA * factB;
        float len2 = btgDot3(p, p);
        if (len2 > BTG_FLT_EPSILON) p = p / btgSqrt(len2);
        else p = colA1;
        q = btgCross3(ax1, p);
        BtgFloat4 tmpA = btgCross3(relA, p), tmpB = btgCross3(relB, p);
        rows[2].angA = tmpA;
        rows[2].angB = -tmpB;
        tmpA = btgCross3(relA, q);
        tmpB = btgCross3(relB, q);
        if (hasStaticBody && solveAng) {
            tmpB = tmpB * factB;
            tmpA = tmpA * factA;
        }
        rows[3].angA = tmpA;
        rows[3].angB = -tmpB;
    } else {
        c = b.pos - a.pos;
        BtgFloat4 tmp = btgCross3(c, p);
        rows[2].angA = tmp * factA;
        rows[2].angB = tmp * factB;
        tmp = btgCross3(c, q);
        rows[3].angA = tmp * factA;
        rows[3].angB = tmp * factB;
    }
    rows[2].linA = btgXyz(p);
    rows[3].linA = btgXyz(q);
    currErp = (sp.flags & 32u) ? sp.softnessOrthoLin : sp.softnessOrthoLin * erp; /* ERP_ORTLIN */
    k = fps * currErp;
    rows[2].error = k * btgDot3(p, ofs);
    rows[3].error = k * btgDot3(q, ofs);
    if (sp.flags & 16u) { /* CFM_ORTLIN */
        rows[2].cfm = sp.cfmOrthoLin;
        rows[3].cfm = sp.cfmOrthoLin;
    }
    int n = 4;
    /* The linear limit / motor row. */
    float limitErr = 0.0f;
    int limit = 0;
    if (solveLin) {
        limitErr = depth0 * signFact;
        limit = limitErr > 0.0f ? 2 : 1;
    }
    int powered = (sp.options & BTG_SLIDER_LIN_MOTOR) != 0u;
    if (limit || powered) {
        BtgJointInfoRow* r = &rows[n++];
        r->linA = btgXyz(ax1);
        if (offset) {
            if (!hasStaticBody) {
                r->angA = btgCross3(relA, ax1);
                r->angB = -btgCross3(relB, ax1);
            }
        } else {
            BtgFloat4 ltd = btgCross3(c, ax1);
            r->angA = ltd * factA;
            r->angB = ltd * factB;
        }
        const float lostop = sp.lowerLin, histop = sp.upperLin;
        if (limit && lostop == histop) powered = 0;
        r->error = 0.0f;
        r->lower = 0.0f;
        r->upper = 0.0f;
        currErp = (sp.flags & 512u) ? sp.softnessLimLin : erp; /* ERP_LIMLIN */
        if (powered) {
            if (sp.flags & 1u) r->cfm = sp.cfmDirLin; /* CFM_DIRLIN */
            float motFact = btgMotorFactor(linPos, sp.lowerLin, sp.upperLin, sp.linMotorVelocity, fps * currErp);
            r->error -= signFact * motFact * sp.linMotorVelocity;
            r->lower += -sp.linMotorMaxForce / fps;
            r->upper += sp.linMotorMaxForce / fps;
        }
        if (limit) {
            k = fps * currErp;
            r->error += k * limitErr;
            if (sp.flags & 256u) r->cfm = sp.cfmLimLin; /* CFM_LIMLIN */
            if (lostop == histop) {
                r->lower = -INFINITY;
                r->upper = INFINITY;
            } else if (limit == 1) {
                r->lower = -INFINITY;
                r->upper = 0.0f;
            } else {
                r->lower = 0.0f;
                r->upper = INFINITY;
            }
            const float bounce = btgAbs(1.0f - sp.dampingLimLin);
            if (bounce > 0.0f) {
                float vel = btgDot3(a.linVel0, ax1);
                vel -= btgDot3(b.linVel0, ax1);
                vel *= signFact;
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
            r->error *= sp.softnessLimLin;
        }
    }
    /* The angular limit / motor row. */
    limitErr = 0.0f;
    limit = 0;
    if (solveAng) {
        limitErr = angDepth;
        limit = limitErr > 0.0f ? 1 : 2;
    }
    powered = (sp.options & BTG_SLIDER_ANG_MOTOR) != 0u;
    if (limit || powered) {
        BtgJointInfoRow* r = &rows[n++];
        r->angA = btgXyz(ax1);
        r->angB = -btgXyz(ax1);
        const float lostop = sp.lowerAng, histop = sp.upperAng;
        if (limit && lostop == histop) powered = 0;
        currErp = (sp.flags & 2048u) ? sp.softnessLimAng : erp; /* ERP_LIMANG */
        if (powered) {
            if (sp.flags & 4u) r->cfm = sp.cfmDirAng; /* CFM_DIRANG */
            float motFact = btgMotorFactor(angPos, sp.lowerAng, sp.upperAng, sp.angMotorVelocity, fps * currErp);
            r->error = motFact * sp.angMotorVelocity;
            r->lower = -sp.angMotorMaxForce / fps;
            r->upper = sp.angMotorMaxForce / fps;
        }
        if (limit) {
            k = fps * currErp;
            r->error += k * limitErr;
            if (sp.flags & 1024u) r->cfm = sp.cfmLimAng; /* CFM_LIMANG */
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
            const float bounce = btgAbs(1.0f - sp.dampingLimAng);
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
            r->error *= sp.softnessLimAng;
        }
    }
    /* J2 linear is -J1 linear in every slider row. */
    for (int r = 0; r < n; ++r) rows[r].linB = -rows[r].linA;
    return n;
}

#endif
