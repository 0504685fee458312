/* cone_twist_rows.h — btConeTwistConstraint's rows as its getInfo1/getInfo2 build them (Bullet
 * 3.24): calcAngleInfo2's split of the relative rotation into cone and twist
 * (computeConeLimitInfo, the ellipse normal, computeTwistLimitInfo, or the locked swing of
 * spans below the fix threshold), or with the motor on the rotation from the motor target as
 * the one swing row (bounded by m_maxMotorImpulse), then three point rows and the swing and
 * twist limit rows. m_angularOnly and m_damping are read only by the obsolete solve.
 * Quaternions follow btQuaternion's formulas, and a body's rotation is taken from its basis as
 * btMatrix3x3::getRotation does (Bullet reads transA.getRotation()). */
#ifndef BTG_CONE_TWIST_ROWS_H
#define BTG_CONE_TWIST_ROWS_H
#include "hinge_rows.h"

/* btMatrix3x3::getRotation */
static inline BtgFloat4 btgMat3ToQuat(BtgMat3 m)
{
    float e[3][3] = {{m.r0.x, m.r0.y, m.r0.z}, {m.r1.x, m.r1.y, m.r1.z}, {m.r2.x, m.r2.y, m.r2.z}};
    float t[4];
    float trace = e[0][0] + e[1][1] + e[2][2];
    if (trace > 0.0f) {
        float s = btgSqrt(trace + 1.0f);
        t[3] = s * 0.5f;
        s = 0.5f / s;
        t[0] = (e[2][1] - e[1][2]) * s;
        t[1] = (e[0][2] - e[2][0]) * s;
        t[2] = (e[1][0] - e[0][1]) * s;
    } else {
        int i = e[0][0] < e[1][1] ? (e[1][1] < e[2][2] ? 2 : 1) : (e[0][0] < e[2][2] ? 2 : 0);
        int j = (i + 1) % 3;
        int k = (i + 2) % 3;
        float s = btgSqrt(e[i][i] - e[j][j] - e[k][k] + 1.0f);
        t[i] = s * 0.5f;
        s = 0.5f / s;
        t[3] = (e[k][j] - e[j][k]) * s;
        t[j] = (e[j][i] + e[i][j]) * s;
        t[k] = (e[k][i] + e[i][k]) * s;
    }
    return btgMake4(t[0], t[1], t[2], t[3]);
}

/* quatRotate(q, v): q v q^-1 through btQuaternion's quaternion-vector product. */
static inline BtgFloat4 btgQuatRotateBt(BtgFloat4 q, BtgFloat4 w)
{
    BtgFloat4 p = btgMake4(q.w * w.x + q.y * w.z - q.z * w.y, q.w * w.y + q.z * w.x - q.x * w.z,
                           q.w * w.z + q.x * w.y - q.y * w.x, -q.x * w.x - q.y * w.y - q.z * w.z);
    p = btgQuatMul(p, btgQuatConj(q));
    return btgMake4(p.x, p.y, p.z, 0.0f);
}

static inline BtgFloat4 btgQuatNormalizeBt(BtgFloat4 q)
{
    float len = btgSqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    return q / len;
}

/* btQuaternion::getAngle */
static inline float btgQuatAngle(BtgFloat4 q)
{
    float w = q.w < -1.0f ? -1.0f : (q.w > 1.0f ? 1.0f : q.w);
    return 2.0f * btgAcos(w);
}

/* btVector3::normalize: times 1 / length (no guard, as Bullet). */
static inline BtgFloat4 btgNormalizeBt3(BtgFloat4 v)
{
    return v * (1.0f / btgSqrt(btgDot3(v, v)));
}

/* shortestArcQuat(v0, v1) for unit v0 = the twist axis x. */
static inline BtgFloat4 btgShortestArcFromX(BtgFloat4 v1)
{
    BtgFloat4 v0 = btgMake4(1.0f, 0.0f, 0.0f, 0.0f);
    BtgFloat4 c = btgCross3(v0, v1);
    float d = btgDot3(v0, v1);
    if (d < -1.0f + BTG_FLT_EPSILON) return btgMake4(0.0f, 1.0f, 0.0f, 0.0f); /* btPlaneSpace1 of x */
    float s = btgSqrt((1.0f + d) * 2.0f);
    float rs = 1.0f / s;
    return btgMake4(c.x * rs, c.y * rs, c.z * rs, s * 0.5f);
}

static inline int btgFuzzyZero(float x) { return btgAbs(x) < BTG_FLT_EPSILON; }

/* What calcAngleInfo2 leaves for getInfo2. */
typedef struct {
    BtgFloat4 swingAxis; /* world */
    BtgFloat4 twistAxis; /* world */
    float swingCorrection;
    float twistCorrection;
    int solveSwing;
    int solveTwist;
} BtgConeAngles;

/* calcAngleInfo2 with the motor on: the rotation still to go to the target, trB * target *
 * trA^-1, as the swing row's axis and correction (no twist row). */
static inline BtgConeAngles btgConeTwistMotorAngles(BtgJoint j, BtgJointBody a, BtgJointBody b, BtgConeAngles r)
{
    BtgFloat4 colA[3], colB[3], pcol[3];
    for (int c = 0; c < 3; ++c) {
        colA[c] = btgFrameAxis(a, j.axesA[c]);
        colB[c] = btgFrameAxis(b, j.axesB[c]);
    }
    /* btMatrix3x3::setRotation of the target */
    const BtgFloat4 q = j.motorTarget;
    const float d = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, s = 2.0f / d;
    const float xs = q.x * s, ys = q.y * s, zs = q.z * s;
    const float wx = q.w * xs, wy = q.w * ys, wz = q.w * zs;
    const float xx = q.x * xs, xy = q.x * ys, xz = q.x * zs;
    const float yy = q.y * ys, yz = q.y * zs, zz = q.z * zs;
    const float t[3][3] = {{1.0f - (yy + zz), xy - wz, xz + wy},
                           {xy + wz, 1.0f - (xx + zz), yz - wx},
                           {xz - wy, yz + wx, 1.0f - (xx + yy)}};
    /* (trB basis * target) columns, then times trA's basis transposed */
    for (int c = 0; c < 3; ++c) pcol[c] = colB[0] * t[0][c] + colB[1] * t[1][c] + colB[2] * t[2][c];
    BtgMat3 m;
    m.r0 = colA[0] * pcol[0].x + colA[1] * pcol[1].x + colA[2] * pcol[2].x;
    m.r1 = colA[0] * pcol[0].y + colA[1] * pcol[1].y + colA[2] * pcol[2].y;
    m.r2 = colA[0] * pcol[0].z + colA[1] * pcol[1].z + colA[2] * pcol[2].z;
    const BtgFloat4 qd = btgMat3ToQuat(m);
    const BtgFloat4 axis = btgMake4(qd.x, qd.y, qd.z, 0.0f);
    if (btgFuzzyZero(btgDot3(axis, axis))) return r;
    r.swingAxis = btgNormalizeBt3(axis);
    r.swingCorrection = btgQuatAngle(qd);
    if (!btgFuzzyZero(r.swingCorrection)) r.solveSwing = 1;
    return r;
}

static inline BtgConeAngles btgConeTwistAngles(BtgJoint j, BtgJointBody a, BtgJointBody b)
{
    BtgConeAngles r;
    r.swingAxis = btgZero4();
    r.twistAxis = btgZero4();
    r.swingCorrection = 0.0f;
    r.twistCorrection = 0.0f;
    r.solveSwing = 0;
    r.solveTwist = 0;
    if (j.flags & BTG_JOINT_MOTOR) return btgConeTwistMotorAngles(j, a, b, r);
    BtgFloat4 qA = btgQuatMul(btgMat3ToQuat(a.basis), j.frameRotA);
    BtgFloat4 qB = btgQuatMul(btgMat3ToQuat(b.basis), j.frameRotB);
    BtgFloat4 qAB = btgQuatMul(btgQuatConj(qB), qA);
    BtgFloat4 vConeNoTwist = btgNormalizeBt3(btgQuatRotateBt(qAB, btgMake4(1.0f, 0.0f, 0.0f, 0.0f)));
    BtgFloat4 qABCone = btgQuatNormalizeBt(btgShortestArcFromX(vConeNoTwist));
    BtgFloat4 qABTwist = btgQuatNormalizeBt(btgQuatMul(btgQuatConj(qABCone), qAB));
    const float span1 = j.swingSpan1, span2 = j.swingSpan2, soft = j.limitSoftness;
    if (span1 >= j.fixThresh && span2 >= j.fixThresh) {
        /* computeConeLimitInfo */
        float swingAngle = btgQuatAngle(qABCone), swingLimit = 0.0f;
        BtgFloat4 swingAxis = btgZero4();
        if (swingAngle > BTG_FLT_EPSILON) {
            swingAxis = btgNormalizeBt3(btgMake4(qABCone.x, qABCone.y, qABCone.z, 0.0f));
            float xE = swingAxis.y, yE = -swingAxis.z;
            swingLimit = span1;
            if (btgAbs(xE) > BTG_FLT_EPSILON) {
                float slope2 = (yE * yE) / (xE * xE);
                float norm = 1.0f / (span2 * span2);
                norm += slope2 / (span1 * span1);
                swingLimit = btgSqrt((1.0f + slope2) / norm);
            }
        }
        if (swingAngle > swingLimit * soft) {
            r.solveSwing = 1;
            r.swingCorrection = swingAngle - swingLimit * soft;
            /* adjustSwingAxisToUseEllipseNormal */
            float y = -swingAxis.z, z = swingAxis.y;
            if (btgAbs(z) > BTG_FLT_EPSILON) {
                float grad = y / z;
                grad *= span2 / span1;
                y = y > 0.0f ? btgAbs(grad * z) : -btgAbs(grad * z);
                swingAxis.z = -y;
                swingAxis.y = z;
                swingAxis = btgNormalizeBt3(swingAxis);
            }
            r.swingAxis = btgQuatRotateBt(qB, -swingAxis);
        }
    } else {
        BtgFloat4 ivA = btgFrameAxis(a, j.axesA[0]), jvA = btgFrameAxis(a, j.axesA[1]), kvA = btgFrameAxis(a, j.axesA[2]);
        BtgFloat4 ivB = btgFrameAxis(b, j.axesB[0]);
        float x = btgDot3(ivB, ivA), y = btgDot3(ivB, jvA), z = btgDot3(ivB, kvA);
        if (span1 < j.fixThresh && span2 < j.fixThresh) {
            if (!btgFuzzyZero(y) || !btgFuzzyZero(z)) {
                r.solveSwing = 1;
                r.swingAxis = -btgCross3(ivB, ivA);
            }
        } else {
            if (span1 < j.fixThresh) {
                if (!btgFuzzyZero(x) || !btgFuzzyZero(z)) {
                    r.solveSwing = 1;
                    if (span2 >= j.fixThresh) {
                        y = 0.0f;
                        float s2 = btgAtan2(z, x);
                        if (s2 > span2) {
                            x = btgCos(span2);
                            z = btgSin(span2);
                        } else if (s2 < -span2) {
                            x = btgCos(span2);
                            z = -btgSin(span2);
                        }
                    }
                }
            } else if (!btgFuzzyZero(x) || !btgFuzzyZero(y)) {
                r.solveSwing = 1;
                if (span1 >= j.fixThresh) {
                    z = 0.0f;
                    float s1 = btgAtan2(y, x);
                    if (s1 > span1) {
                        x = btgCos(span1);
                        y = btgSin(span1);
                    } else if (s1 < -span1) {
                        x = btgCos(span1);
                        y = -btgSin(span1);
                    }
                }
            }
            BtgFloat4 target = btgMake4(x * ivA.x + y * jvA.x + z * kvA.x, x * ivA.y + y * jvA.y + z * kvA.y,
                                        x * ivA.z + y * jvA.z + z * kvA.z, 0.0f);
            target = btgNormalizeBt3(target);
            r.swingAxis = -btgCross3(ivB, target);
            r.swingCorrection = btgSqrt(btgDot3(r.swingAxis, r.swingAxis));
            if (!btgFuzzyZero(r.swingCorrection)) r.swingAxis = btgNormalizeBt3(r.swingAxis);
        }
    }
    if (j.twistSpan >= 0.0f) {
        /* computeTwistLimitInfo */
        BtgFloat4 qMin = qABTwist;
        float twistAngle = btgQuatAngle(qABTwist);
        if (twistAngle > BTG_PI) {
            qMin = -qABTwist;
            twistAngle = btgQuatAngle(qMin);
        }
        BtgFloat4 twistAxis = btgMake4(qMin.x, qMin.y, qMin.z, 0.0f);
        if (twistAngle > BTG_FLT_EPSILON) twistAxis = btgNormalizeBt3(twistAxis);
        if (twistAngle > j.twistSpan * soft) {
            r.solveTwist = 1;
            r.twistCorrection = twistAngle - j.twistSpan * soft;
            r.twistAxis = btgQuatRotateBt(qB, -twistAxis);
        }
    }
    return r;
}

/* getInfo1 and getInfo2NonVirtual of a cone-twist joint: rows[0, returned count). */
static inline int btgConeTwistInfoRows(BtgJoint j, BtgJointBody a, BtgJointBody b, float fps, float erp,
                                       float globalCfm, BtgJointInfoRow* rows)
{
    BtgConeAngles ang = btgConeTwistAngles(j, a, b);
    for (int k = 0; k < BTG_JOINT_CONE_TWIST_ROWS; ++k) rows[k] = btgEmptyInfoRow(k == 0 ? globalCfm : 0.0f);
    BtgFloat4 a1 = btgMat3MulVec(a.basis, j.pivotA), a2 = btgMat3MulVec(b.basis, j.pivotB);
    const float linErp = (j.flags & BTG_JOINT_OWN_ERP) ? j.erp : erp;
    const float k = fps * linErp;
    for (int r = 0; r < 3; ++r) {
        BtgFloat4 axis = btgMake4(r == 0 ? 1.0f : 0.0f, r == 1 ? 1.0f : 0.0f, r == 2 ? 1.0f : 0.0f, 0.0f);
        rows[r].linA = axis;
        rows[r].linB = -axis;
        rows[r].angA = btgCross3(a1, axis);
        rows[r].angB = -btgCross3(a2, axis);
        rows[r].error = k * (btgLane(a2, r) + btgLane(b.pos, r) - btgLane(a1, r) - btgLane(a.pos, r));
        if (j.flags & BTG_JOINT_OWN_CFM) rows[r].cfm = j.cfm;
    }
    int n = 3;
    const float relax2 = j.limitRelaxation * j.limitRelaxation;
    if (ang.solveSwing) {
        if (j.swingSpan1 < j.fixThresh && j.swingSpan2 < j.fixThresh) {
            BtgFloat4 p = btgFrameAxis(a, j.axesA[1]), q = btgFrameAxis(a, j.axesA[2]);
            const float fact = fps * j.limitRelaxation;
            rows[n].angA = btgXyz(p);
            rows[n].angB = -btgXyz(p);
            rows[n].error = fact * btgDot3(ang.swingAxis, p);
            rows[n + 1].angA = btgXyz(q);
            rows[n + 1].angB = -btgXyz(q);
            rows[n + 1].error = fact * btgDot3(ang.swingAxis, q);
            n += 2;
        } else {
            BtgFloat4 ax1 = ang.swingAxis * relax2;
            rows[n].angA = btgXyz(ax1);
            rows[n].angB = -btgXyz(ax1);
            rows[n].error = fps * j.limitBias * ang.swingCorrection;
            if (j.flags & BTG_JOINT_OWN_STOP_CFM) rows[n].cfm = j.stopCfm;
            rows[n].lower = 0.0f;
            rows[n].upper = ((j.flags & BTG_JOINT_MOTOR) && j.motorMaxImpulse >= 0.0f) ? j.motorMaxImpulse : INFINITY;
            n += 1;
        }
    }
    if (ang.solveTwist) {
        BtgFloat4 ax1 = ang.twistAxis * relax2;
        rows[n].angA = btgXyz(ax1);
        rows[n].angB = -btgXyz(ax1);
        rows[n].error = fps * j.limitBias * ang.twistCorrection;
        if (j.flags & BTG_JOINT_OWN_STOP_CFM) rows[n].cfm = j.stopCfm;
        if (j.twistSpan > 0.0f) {
            if (ang.twistCorrection > 0.0f) {
                rows[n].lower = 0.0f;
                rows[n].upper = INFINITY;
            } else {
                rows[n].lower = -INFINITY;
                rows[n].upper = 0.0f;
            }
        }
        n += 1;
    }
    return n;
}

#endif
