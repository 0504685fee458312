/* joint_prepare.h — convertJoints for one joint of any served type: which rows it builds this
 * substep and each row finished for the solver (joint_rows.h, hinge_rows.h,
 * cone_twist_rows.h, slider_rows.h, sixdof_rows.h, generic6dof_rows.h; the gear's row in joint_rows.h). */
#ifndef BTG_JOINT_PREPARE_H
#define BTG_JOINT_PREPARE_H
#include "joint_rows.h"
#include "hinge_rows.h"
#include "cone_twist_rows.h"
#include "slider_rows.h"
#include "sixdof_rows.h"
#include "generic6dof_rows.h"

/* Its applied impulse reset when its island is solved, and its rows (getInfo1's count,
 * getInfo2's rows finished by convertJoint) when it is active. */
static inline void btgPrepareJoint(BtgJoint j, BtgJointState* s, BTG_GLOBAL BtgJointRow* rows, BtgJointBody a,
                                   BtgJointBody b, BtgJointStepParams p)
{
    s->touched = (a.body.dynamic || b.body.dynamic) ? 1 : 0;
    if (s->touched) s->appliedImpulse = 0.0f;
    s->numRows = 0;
    if (!btgJointActive(j, *s, a, b)) return;
    const float fps = 1.0f / p.dt;
    if (j.type == BTG_JOINT_POINT2POINT) {
        /* btPoint2PointConstraint sets info->m_damping to its own setting. */
        for (int k = 0; k < BTG_JOINT_P2P_ROWS; ++k) {
            const BtgJointInfoRow info = btgP2PInfoRow(j, a, b, k, fps, p.erp, p.globalCfm);
            BtgJointRow r = btgFinishJointRow(info, a, b, j.damping, j.breakingThreshold);
            r.flags = BTG_JOINT_ROW_POSITION;
            r.bias = info.error;
            rows[j.firstRow + k] = r;
        }
        s->numRows = BTG_JOINT_P2P_ROWS;
    } else if (j.type == BTG_JOINT_GEAR) {
        rows[j.firstRow] = btgFinishJointRow(btgGearInfoRow(j, a, b, p.globalCfm), a, b, p.damping, j.breakingThreshold);
        s->numRows = BTG_JOINT_GEAR_ROWS;
    } else if (j.type == BTG_JOINT_HINGE) {
        BtgJointInfoRow info[BTG_JOINT_HINGE_ROWS];
        const int n = btgHingeInfoRows(j, a, b, fps, p.erp, p.globalCfm, info);
        for (int k = 0; k < n; ++k)
            rows[j.firstRow + k] = btgFinishJointRow(info[k], a, b, p.damping, j.breakingThreshold);
        s->numRows = n;
    } else if (j.type == BTG_JOINT_CONE_TWIST || j.type == BTG_JOINT_SLIDER) {
        BtgJointInfoRow info[BTG_JOINT_MAX_ROWS];
        const int n = j.type == BTG_JOINT_SLIDER ? btgSliderInfoRows(j, a, b, fps, p.erp, p.globalCfm, info)
                                                 : btgConeTwistInfoRows(j, a, b, fps, p.erp, p.globalCfm, info);
        for (int k = 0; k < n; ++k)
            rows[j.firstRow + k] = btgFinishJointRow(info[k], a, b, p.damping, j.breakingThreshold);
        s->numRows = n;
    } else if (j.type == BTG_JOINT_SIXDOF) {
        BtgJointInfoRow info[BTG_JOINT_SIXDOF_ROWS];
        uint springRows = 0u;
        const int n = btgG6DofInfoRows(j, a, b, fps, p.erp, p.globalCfm, p.numIterations, info, &springRows);
        for (int k = 0; k < n; ++k) {
            BtgJointRow r = btgFinishJointRow(info[k], a, b, p.damping, j.breakingThreshold);
            if ((springRows >> k) & 1u) r.flags = BTG_JOINT_ROW_SPRING;
            rows[j.firstRow + k] = r;
        }
        s->numRows = n;
    } else if (j.type == BTG_JOINT_SIXDOF2) {
        BtgJointInfoRow info[BTG_JOINT_SIXDOF2_ROWS];
        uint springRows = 0u;
        const int n = btgSixDofInfoRows(j, a, b, fps, p.erp, p.globalCfm, info, &springRows);
        for (int k = 0; k < n; ++k) {
            BtgJointRow r = btgFinishJointRow(info[k], a, b, p.damping, j.breakingThreshold);
            if ((springRows >> k) & 1u) r.flags = BTG_JOINT_ROW_SPRING;
            rows[j.firstRow + k] = r;
        }
        s->numRows = n;
    }
}

#endif
