/* soft_joint_rows.h — the soft step's joint rows: a joint's Bullet rows (built once a step by
 * prepare_joints) solved in each substep (soft_rows.h includes it). */
#ifndef BTG_SOFT_JOINT_ROWS_H
#define BTG_SOFT_JOINT_ROWS_H

/* One Gauss-Seidel step on each row, its bounds (N s a step) scaled to a substep: the row's
 * impulse is a substep's, warm-started in each substep as a force held over the step. A spring
 * row (BTG_JOINT_ROW_SPRING) is not: Bullet's is one step's impulse of the spring force from the
 * step's start, which drives the velocity to its target at the step's end, and held over the
 * substeps (the velocity reaching it only at the end, the positions following the ramp) it fed
 * the spring energy: a 2 kg box on a 6-DoF spring2 of 100 N/m, undamped, swung 0.2 m on stock
 * and 0.85 m after 10 s on the soft step's 10 substeps (0.51 on 2, 0.20 on 1). Its impulse is the
 * step's so far, within the step's bounds, never warm-started again (the velocity pass skips it),
 * so the velocity meets the target in the first substep, as symplectic Euler has it on stock.
 * The relax (relax set) drives a point-to-point row (BTG_JOINT_ROW_POSITION) without its bias, as
 * Box2D's relax does, so that its position correction leaves no velocity behind: a chain of three
 * boxes hanging on point-to-point joints gained 11 % of its energy in 60 s with it (150 to 167 J;
 * stock, damped by its own correction, lost 15 %), 0.5 % without. The other rows keep their
 * Bullet bias in the relax: it carries motors and limits as well as position error, which their
 * rows do not tell apart. */
static inline void btgSoftJointSolve(BTG_GLOBAL BtgJointRow* rows, int first, int count, BtgSolverBody a,
                                     BtgSolverBody b, BtgBodyVel* va, BtgBodyVel* vb, float boundScale, int relax)
{
    for (int k = 0; k < count; ++k) {
        BtgJointRow r = rows[first + k];
        if (relax && (r.flags & BTG_JOINT_ROW_POSITION)) r.target -= r.bias; /* no position correction in the relax */
        const float scale = (r.flags & BTG_JOINT_ROW_SPRING) ? 1.0f : boundScale;
        r.lower *= scale;
        r.upper *= scale;
        btgJointRowSolve(&r, a, b, va, vb);
        rows[first + k].impulse = r.impulse;
    }
}

#endif
