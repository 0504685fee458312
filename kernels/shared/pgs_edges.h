/* pgs_edges.h (inlined at every include) — one edge of the batched PGS (a contact's rows in
 * one pass, or a joint's rows) against the bodies' velocities, for solve_constraints.cl, which
 * includes it once for each place
 * the velocities live: BTG_PGS_VEL is the velocity pointer type (BTG_SHARED __global, or
 * __local in solve_local), BTG_PGS_LOAD(p) a velocity read through it, BTG_PGS_FN(name) the
 * functions' names. Needs load_body, JOINT_ARGS and JOINT_PASS from the includer. No include
 * guard, and the first line's words tell the kernel inliner (src/cl/kernel_inline.cpp) to inline
 * it at every include: included twice on purpose. OpenCL only. */

/* A dynamic body's solved velocities back; w of the velocity columns is not the solver's: kept. */
static void BTG_PGS_FN(store_velocity)(BTG_PGS_VEL lin, BTG_PGS_VEL ang, int body, BtgBodyVel v, BtgFloat4 linOld,
                                       BtgFloat4 angOld)
{
    lin[body] = btgMake4(v.lin.x, v.lin.y, v.lin.z, linOld.w);
    ang[body] = btgMake4(v.ang.x, v.ang.y, v.ang.z, angOld.w);
}

static void BTG_PGS_FN(solve_contact)(int i, int slot, int mode, int rows, __global BtgContact* contacts,
                      __global BtgRollingContact* rolling, __global const BtgFrictionDirs* restrict frictionDirs, __global const BtgFrictionAnchor* restrict anchors,
                      __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld,
                      BTG_PGS_VEL lin, BTG_PGS_VEL ang, uint key)
{
    /* SOLVER_RANDMIZE_ORDER: this contact's points in its own order within the sweep (0: in order) */
    const uint order = btgItemKey(key, (uint)i + 1u);
    BtgContact c = btgLoadContactRows(contacts, slot, mode == BTG_PASS_ROLLING ? BTG_PASS_NORMALS : mode, rows);
    BtgSolverBody a = load_body(props, invInertiaWorld, c.bodyA);
    BtgSolverBody b = load_body(props, invInertiaWorld, c.bodyB);
    /* Push velocities of infinite-mass bodies are zero, as Bullet's solver bodies start them. */
    int movingA = mode == BTG_PASS_PUSH ? a.dynamic : a.moving, movingB = mode == BTG_PASS_PUSH ? b.dynamic : b.moving;
    BtgFloat4 linA = BTG_PGS_LOAD(&lin[c.bodyA]), angA = BTG_PGS_LOAD(&ang[c.bodyA]);
    BtgFloat4 linB = BTG_PGS_LOAD(&lin[c.bodyB]), angB = BTG_PGS_LOAD(&ang[c.bodyB]);
    BtgBodyVel va = btgMakeBodyVel(movingA, linA, angA);
    BtgBodyVel vb = btgMakeBodyVel(movingB, linB, angB);
    /* anisotropic friction: the explicit directions, for the passes with friction rows */
    BtgFrictionDirs dirs;
    const int explicitDirs = (rows & BTG_ROWS_ANISOTROPIC) != 0 &&
                             (mode == BTG_PASS_WARM_START || mode == BTG_PASS_FRICTION || mode == BTG_PASS_VELOCITY);
    if (explicitDirs) dirs = frictionDirs[i];
    const BtgFrictionDirs* d = explicitDirs ? &dirs : 0;
    /* friction anchors: the friction rows' positional targets, for the friction passes */
    BtgFrictionAnchor anchor;
    const int anchored = (rows & BTG_ROWS_ANCHORS) != 0 && (mode == BTG_PASS_FRICTION || mode == BTG_PASS_VELOCITY);
    if (anchored) anchor = anchors[i];
    const BtgFrictionAnchor* f = anchored ? &anchor : 0;
    /* key is the same for every work-item of the launch: without SOLVER_RANDMIZE_ORDER the
     * unpermuted loops, with no permutation code in them */
    if (mode == BTG_PASS_WARM_START) btgContactWarmStartDirs(&c, d, a, b, &va, &vb, rows);
    else if (mode == BTG_PASS_NORMALS && key == 0u) btgContactSolveNormals(&c, a, b, &va, &vb);
    else if (mode == BTG_PASS_NORMALS) btgContactSolveNormalsOrdered(&c, order, a, b, &va, &vb);
    else if (mode == BTG_PASS_FRICTION && key == 0u && !anchored) btgContactSolveFrictionDirs(&c, d, a, b, &va, &vb, rows);
    else if (mode == BTG_PASS_FRICTION && key == 0u) btgContactSolveFrictionAnchored(&c, d, f, a, b, &va, &vb, rows);
    else if (mode == BTG_PASS_FRICTION) btgContactSolveFrictionOrdered(&c, d, f, order, a, b, &va, &vb, rows);
    else if (mode == BTG_PASS_VELOCITY) btgContactSolveInterleavedOrdered(&c, d, f, order, a, b, &va, &vb, rows);
    else if (mode == BTG_PASS_ROLLING) {
        BtgRollingContact r = rolling[i];
        btgRollingSolve(&r, c.normal, btgSolvedNormalImpulse(&c), c.numPoints, a, b, &va, &vb);
        rolling[i].spinImpulse = r.spinImpulse;
        rolling[i].roll1Impulse = r.roll1Impulse;
        rolling[i].roll2Impulse = r.roll2Impulse;
    } else if (key == 0u) btgContactSolvePush(&c, a, b, &va, &vb);
    else btgContactSolvePushOrdered(&c, order, a, b, &va, &vb);
    if (a.dynamic) BTG_PGS_FN(store_velocity)(lin, ang, c.bodyA, va, linA, angA);
    if (b.dynamic) BTG_PGS_FN(store_velocity)(lin, ang, c.bodyB, vb, linB, angB);
    if (mode != BTG_PASS_ROLLING) btgStoreContactImpulses(contacts, slot, &c, mode, rows);
}

/* One edge of the graph: the contacts are the edges [0, contacts); a constraint kind with
 * edges after them is solved here by its own rows. A contact's rows are contacts[slot]: the
 * contact list's own (slot e), or the colour-ordered copy's (see contacts_gather). */
static void BTG_PGS_FN(solve_edge)(int e, int slot, int mode, int rows, __global BtgContact* contacts,
                       __global BtgRollingContact* rolling, __global const BtgFrictionDirs* restrict frictionDirs, __global const BtgFrictionAnchor* restrict anchors,
                       __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld,
                       BTG_PGS_VEL lin, BTG_PGS_VEL ang, uint key)
{
    BTG_PGS_FN(solve_contact)(e, slot, mode, rows, contacts, rolling, frictionDirs, anchors, props, invInertiaWorld, lin, ang, key);
}

/* Joint j's rows, one Gauss-Seidel step each in row order (the rows of one joint share its two
 * bodies, so one work-item takes them all). */
static void BTG_PGS_FN(solve_joint)(int j, int iteration, JOINT_ARGS, __global const BtgBodyProps* restrict props,
                        __global const BtgFloat4* restrict invInertiaWorld, BTG_PGS_VEL lin,
                        BTG_PGS_VEL ang)
{
    BtgJoint joint = joints[j];
    const int rows = jointState[j].numRows;
    if (rows == 0 || iteration >= joint.iterations) return;
    BtgSolverBody a = joint.bodyA >= 0 ? load_body(props, invInertiaWorld, joint.bodyA) : btgFixedJointBody().body;
    BtgSolverBody b = joint.bodyB >= 0 ? load_body(props, invInertiaWorld, joint.bodyB) : btgFixedJointBody().body;
    BtgFloat4 linA = btgZero4(), angA = btgZero4(), linB = btgZero4(), angB = btgZero4();
    if (joint.bodyA >= 0) {
        linA = BTG_PGS_LOAD(&lin[joint.bodyA]);
        angA = BTG_PGS_LOAD(&ang[joint.bodyA]);
    }
    if (joint.bodyB >= 0) {
        linB = BTG_PGS_LOAD(&lin[joint.bodyB]);
        angB = BTG_PGS_LOAD(&ang[joint.bodyB]);
    }
    BtgBodyVel va = btgMakeBodyVel(a.moving, linA, angA);
    BtgBodyVel vb = btgMakeBodyVel(b.moving, linB, angB);
    for (int k = 0; k < rows; ++k) {
        BtgJointRow r = jointRows[joint.firstRow + k];
        btgJointRowSolve(&r, a, b, &va, &vb);
        jointRows[joint.firstRow + k].impulse = r.impulse;
    }
    if (a.dynamic) BTG_PGS_FN(store_velocity)(lin, ang, joint.bodyA, va, linA, angA);
    if (b.dynamic) BTG_PGS_FN(store_velocity)(lin, ang, joint.bodyB, vb, linB, angB);
}

/* One edge of the phase: a joint edge (phase 1) or a contact (phase 0). */
static void BTG_PGS_FN(solve_phase_edge)(int e, int slot, int phase, int contacts, int iteration, int mode, int rows,
                             __global BtgContact* contactRows, __global BtgRollingContact* rolling,
                             __global const BtgFrictionDirs* restrict frictionDirs, __global const BtgFrictionAnchor* restrict anchors, JOINT_ARGS,
                             __global const BtgBodyProps* restrict props,
                             __global const BtgFloat4* restrict invInertiaWorld, BTG_PGS_VEL lin,
                             BTG_PGS_VEL ang, uint key)
{
    if (phase) BTG_PGS_FN(solve_joint)(e - contacts, iteration, JOINT_PASS, props, invInertiaWorld, lin, ang);
    else BTG_PGS_FN(solve_edge)(e, slot, mode, rows, contactRows, rolling, frictionDirs, anchors, props, invInertiaWorld, lin, ang, key);
}

