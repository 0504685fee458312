/* soft_joint_rows.h — the soft step's joint rows: a joint's Bullet rows (built once a step by
 * prepare_joints) solved in each substep (soft_rows.h includes it). */
#ifndef BTG_SOFT_JOINT_ROWS_H
#define BTG_SOFT_JOINT_ROWS_H

/* A row with a linear part (a unit direction n on A, -n on B): its angular parts are the lever
 * arms' moments, rA x n and -(rB x n). */
static inline int btgSoftLinearRow(BtgJacobian j)
{
    return btgDot3(j.linear, j.linear) > 0.5f;
}

/* The soft step's linear rows on lever arms turned with the bodies (dA, dB: their rotations since
 * the step's start), written back once a substep (its relax: solve_soft.cl's soft_joint), as
 * Box2D's joints take their anchors turned by the bodies' delta rotations each substep. Bullet's rows, built once a step, keep the step's start
 * arms: over the substeps the pivot drifts outward about w^2 r h^2 / 2 a substep, the fall
 * outward gains energy, and the next step's correction, relaxed away, returns it free (a rod
 * pendulum swung 10 degrees had 7 to 8 times its swing energy after 20 s on every joint type with
 * a pivot).
 * The arms come back from the joint's first two orthogonal linear rows: Bullet builds a joint's
 * linear rows from one arm a body (a point-to-point's pivot, a hinge's or slider's relA / relB,
 * a cone twist's, a 6-DoF's frame origin), and for orthonormal n0, n1 and n2 = n0 x n1,
 * n0 x (r x n0) + n1 x (r x n1) = r + n2 (n2 . r). A linear row turns only where its built
 * angular parts are those arms' (at the step's first turn: BTG_JOINT_ROW_TURNED): a hinge's or
 * 6-DoF's row that Bullet scales by its masses' factors against a static body stays as built.
 * The start arms are kept in the w of the two rows' Jacobian parts, where no pass reads
 * (BTG_JOINT_ROW_ARMS on the joint's first row). Each turned row's responses, mass and cfm anew,
 * as btgFinishJointRow makes them; its target, bounds and impulse as they are. A joint with
 * fewer than two orthogonal linear rows (a gear, a 6-DoF with one locked axis) keeps its rows.
 * turnA, turnB: the change of the bodies' angular velocity that the rows' impulses so far make
 * along the turned rows less along the rows as they were (the linear parts do not turn): a
 * carried warm start (btgSoftBodyCarry) adds it to what it carries, so that it carries what the
 * gather would (solve_soft.cl's soft_joint moves the bodies' marks by it). */
static inline void btgSoftTurnLinearRows(BTG_GLOBAL BtgJointRow* rows, int first, int count, BtgSolverBody a,
                                         BtgSolverBody b, BtgMat3 dA, BtgMat3 dB, BtgFloat4* turnA, BtgFloat4* turnB)
{
    *turnA = btgZero4();
    *turnB = btgZero4();
    int i0 = -1, i1 = -1;
    for (int k = 0; k < count && i1 < 0; ++k) {
        if (!btgSoftLinearRow(rows[first + k].jacobian)) continue;
        if (i0 < 0) i0 = k;
        else if (btgAbs(btgDot3(rows[first + i0].jacobian.linear, rows[first + k].jacobian.linear)) < 1e-4f) i1 = k;
    }
    if (i1 < 0) return;
    const int stashed = (rows[first].flags & BTG_JOINT_ROW_ARMS) != 0;
    const BtgJacobian j0 = rows[first + i0].jacobian, j1 = rows[first + i1].jacobian;
    BtgFloat4 armA, armB;
    if (stashed) {
        armA = btgMake4(j0.linear.w, j0.angularA.w, j0.angularB.w, 0.0f);
        armB = btgMake4(j1.linear.w, j1.angularA.w, j1.angularB.w, 0.0f);
    } else {
        const BtgFloat4 n0 = btgXyz(j0.linear), n1 = btgXyz(j1.linear), n2 = btgCross3(n0, n1);
        armA = btgCross3(n0, btgXyz(j0.angularA)) + btgCross3(n1, btgXyz(j1.angularA));
        armB = -(btgCross3(n0, btgXyz(j0.angularB)) + btgCross3(n1, btgXyz(j1.angularB)));
        armA = armA - n2 * (0.5f * btgDot3(n2, armA));
        armB = armB - n2 * (0.5f * btgDot3(n2, armB));
    }
    const BtgFloat4 nowA = btgMat3MulVec(dA, armA), nowB = btgMat3MulVec(dB, armB);
    /* a built row is the arms' when its moments match theirs to float rounding */
    const float tol2 = 1e-8f * (btgDot3(armA, armA) + btgDot3(armB, armB)) + 1e-14f;
    for (int k = 0; k < count; ++k) {
        BtgJointRow r = rows[first + k];
        if (!btgSoftLinearRow(r.jacobian)) continue;
        const BtgFloat4 n = btgXyz(r.jacobian.linear);
        if (!stashed) {
            const BtgFloat4 eA = btgCross3(armA, n) - btgXyz(r.jacobian.angularA);
            const BtgFloat4 eB = btgXyz(r.jacobian.angularB) + btgCross3(armB, n);
            if (btgDot3(eA, eA) + btgDot3(eB, eB) > tol2) continue;
            r.flags |= BTG_JOINT_ROW_TURNED;
        } else if (!(r.flags & BTG_JOINT_ROW_TURNED)) {
            continue;
        }
        const BtgFloat4 oldA = btgXyz(r.jacobian.responseA), oldB = btgXyz(r.jacobian.responseB);
        r.jacobian.linear = n;
        r.jacobian.angularA = btgCross3(nowA, n);
        r.jacobian.angularB = -btgCross3(nowB, n);
        const BtgFloat4 iA = btgMat3MulVec(a.invI, r.jacobian.angularA), iB = btgMat3MulVec(b.invI, r.jacobian.angularB);
        r.jacobian.responseA = iA * a.angFactor;
        r.jacobian.responseB = iB * b.angFactor;
        const float sum = btgDot3(n, n) * (a.invMass + b.invMass) + btgDot3(iA, r.jacobian.angularA) +
                          btgDot3(iB, r.jacobian.angularB);
        const float mass = btgAbs(sum) > 1.192092896e-07f ? 1.0f / sum : 0.0f;
        r.cfm = r.mass > 0.0f ? r.cfm / r.mass * mass : 0.0f;
        r.mass = mass;
        /* what the row's impulse so far does to the bodies' spin, turned less as built (as btgRowApply applies it) */
        *turnA = *turnA + (r.jacobian.responseA - oldA) * (a.angFactor * r.impulse);
        *turnB = *turnB + (r.jacobian.responseB - oldB) * (b.angFactor * r.impulse);
        rows[first + k].jacobian = r.jacobian;
        rows[first + k].mass = r.mass;
        rows[first + k].cfm = r.cfm;
        rows[first + k].flags = r.flags;
    }
    /* the start arms, kept where no row reads (w of a Jacobian's parts) */
    rows[first + i0].jacobian.linear.w = armA.x;
    rows[first + i0].jacobian.angularA.w = armA.y;
    rows[first + i0].jacobian.angularB.w = armA.z;
    rows[first + i1].jacobian.linear.w = armB.x;
    rows[first + i1].jacobian.angularA.w = armB.y;
    rows[first + i1].jacobian.angularB.w = armB.z;
    rows[first].flags |= BTG_JOINT_ROW_ARMS;
}

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
