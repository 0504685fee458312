/* soft_body_rows.h — the soft step's passes over the bodies (btgSoftBodyBegin, Velocity, Carry,
 * Position, Finish) and a body's deltas as the rows read them, on the soft rows of a body
 * (BTG_SOFT_*). Part of soft_rows.h, which includes it after the types it uses; shared with the
 * CPU reference through it. */
#ifndef BTG_SOFT_BODY_ROWS_H
#define BTG_SOFT_BODY_ROWS_H

/* A body's deltas from its rows: the rotation as its matrix (as btgQuatRotate forms it), made
 * once for all the points of a contact's side. */
static inline BtgSoftDelta btgSoftDeltaOf(const BtgFloat4* rows)
{
    BtgSoftDelta d;
    d.pos = rows[BTG_SOFT_DELTA_POS];
    d.rot = btgQuatToMat3(rows[BTG_SOFT_DELTA_ROT]);
    return d;
}

/* The step's start: the linear velocity back to before the forces (the substeps add them a
 * share at a time), nothing moved yet. v0: apply_forces' linVel0; lin/ang: after the forces.
 * The angular velocity keeps the forces' whole change from the start: that change carries
 * Bullet's implicit gyroscopic term, made for one rotation at the velocity it leaves; shared out
 * over the substeps while they turn the body, a box tumbling near its intermediate axis drifted
 * in energy twice as much as stock's in 2 s at 10 substeps, the more the more substeps; now as
 * the bullet mode's (SoftStepMotion.TumblingBoxTurnsAsTheBulletMode, btgpu_accuracy's
 * tumbling_box). */
static inline void btgSoftBodyBegin(uint flags, BtgFloat4* lin, BtgFloat4 v0, BtgFloat4* rows, int substeps)
{
    rows[BTG_SOFT_DELTA_POS] = btgZero4();
    rows[BTG_SOFT_DELTA_ROT] = btgMake4(0.0f, 0.0f, 0.0f, 1.0f);
    rows[BTG_SOFT_FORCE_LIN] = btgZero4();
    rows[BTG_SOFT_SUPPORT] = btgZero4();
    if (!btgIsSolverDynamic(flags)) return;
    float share = 1.0f / (float)substeps;
    rows[BTG_SOFT_FORCE_LIN] = (btgXyz(*lin) - btgXyz(v0)) * share;
    *lin = btgMake4(v0.x, v0.y, v0.z, (*lin).w);
}
/* IntegrateVelocities: a substep's share of the forces. mark: note the velocity it leaves (the
 * carried warm start's origin, before the gathered one is added). */
static inline void btgSoftBodyVelocity(uint flags, BtgFloat4* lin, BtgFloat4* ang, BtgFloat4* rows, int mark)
{
    if (!btgIsSolverDynamic(flags)) return;
    *lin = *lin + rows[BTG_SOFT_FORCE_LIN];
    if (!mark) return;
    rows[BTG_SOFT_MARK_LIN] = btgXyz(*lin);
    rows[BTG_SOFT_MARK_ANG] = btgXyz(*ang);
}
/* IntegrateVelocities and WarmStart of a substep after the first, without the gather. The
 * rows' Jacobians (fixed anchors, normal and tangents, the step's inverse inertia) and the
 * bodies' masses stay the same over a step, and every row applies exactly its impulse's change,
 * so what the last substep's warm start and rows did to a body's velocity is M^-1 J^T of the
 * impulses it ended with: the warm start this substep would gather. Carried as that velocity
 * change (now minus the mark), it costs a body pass instead of one walk over the body's edges
 * (up to a dozen contacts of four points). Rolling rows (never warm-started) and held pairs
 * (btgSoftHeldNormals sets another contact's impulses) break the identity: those steps gather
 * (BtgSoftParams.gather). Rounding aside (a velocity difference), the same warm start. */
static inline void btgSoftBodyCarry(uint flags, BtgFloat4* lin, BtgFloat4* ang, BtgFloat4* rows)
{
    if (!btgIsSolverDynamic(flags)) return;
    const BtgFloat4 dLin = btgXyz(*lin) - btgXyz(rows[BTG_SOFT_MARK_LIN]);
    const BtgFloat4 dAng = btgXyz(*ang) - btgXyz(rows[BTG_SOFT_MARK_ANG]);
    btgSoftBodyVelocity(flags, lin, ang, rows, 1);
    *lin = *lin + dLin;
    *ang = *ang + dAng;
}
/* IntegratePositions: the deltas of every body whose velocity enters the rows (kinematic ones
 * too: the host moves them by their velocity over the step). */
static inline void btgSoftBodyPosition(uint flags, BtgFloat4 lin, BtgFloat4 ang, BtgFloat4* rows, float h)
{
    if (!btgIsSolverMoving(flags)) return;
    rows[BTG_SOFT_DELTA_POS] = btgXyz(rows[BTG_SOFT_DELTA_POS]) + btgXyz(lin) * h;
    rows[BTG_SOFT_DELTA_ROT] = btgIntegrateRotation(rows[BTG_SOFT_DELTA_ROT], btgXyz(ang), h);
}
/* The step's end for a body the integrator moves: its pose moved by the deltas. */
static inline void btgSoftBodyFinish(BtgFloat4* pos, BtgFloat4* rot, const BtgFloat4* rows)
{
    *pos = btgXyz(*pos) + btgXyz(rows[BTG_SOFT_DELTA_POS]);
    *rot = btgQuatNormalize(btgQuatMul(rows[BTG_SOFT_DELTA_ROT], *rot));
}

#endif
