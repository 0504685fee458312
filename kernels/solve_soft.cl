/* solve_soft.cl — Stage: soft step (SolverKind::SoftStep, Box2D v3's solver on the colored
 * constraint graph; shared/soft_rows.h). Per step: bodies begin (velocities before forces),
 * contacts prepare; per substep: integrate velocities and warm start (one body pass: each body
 * gathers its edges' impulses), solve (soft, biased), integrate positions (deltas only), relax
 * (unbiased); then restitution and store, and the velocities back into the world's columns
 * (the passes keep them in the bodies' soft rows, beside the deltas). Edge e below
 * the contact count is contact e, edge contacts + j is joint j.
 * Launch: soft_color_count / soft_color_fill: one work-item per edge slot, edge indices into
 * per-color ranges (and each contact's soft data at its place there, edgeSlot) (soft_color_offsets:
 * one work-item); soft_list_count / soft_list_fill: one per edge slot, soft_list_sort one per
 * body row (the bodies' edge lists the warm start gathers over); soft_solver_bodies (each
 * body's solver record for the step, before the passes) and soft_bodies: one per body row;
 * soft_color_range: a color's range strided over the launch; soft_color_serial: one work-item,
 * every edge of the last color or higher in index order (the coloring's leftovers);
 * soft_resident: all of the stage in one launch (resident groups on GPUs, one group for small
 * scenes on CPUs); soft_transforms (Stage soft_transforms, after the cache is stored): one per
 * body row. CPU devices (BTG_CPU_DEVICE) solve and relax eight contacts a work-item
 * (shared/soft_wide_passes.h: soft_color_wide over chunks, soft_wide_pack / soft_wide_unpack one
 * per slot, soft_wide_offsets one work-item); the flow's kernels are in shared/soft_flow_passes.h.
 * Reads counters[kEdgeCount, kContactCount, kColorsUsed, kLeftovers], edges, edgeColor, props,
 * invInertiaWorld, linVel0, angVel0, contacts, joints, jointState, jointRows, frictionDirs
 * (BtgSoftParams.anisotropic only).
 * Writes counters[kSoftMassRatio] (soft_color_count: the largest mass ratio of an edge between two
 * dynamic bodies, which sets the step's substeps), softContacts (a held pair's pass also its support's impulses), softSolver (the bodies'
 * solver records), softBodies (scratch: the velocities, deltas, force shares and, prepared color by
 * color with heldMassRatio, supports), linVel, angVel (dynamic rows, at the end), contacts (impulses,
 * tangents), jointRows (impulses: a step's, substep's times substeps), and in soft_transforms
 * pos, rot and NaN status. */
#include "shared/soft_kernel_args.h" /* first: it may set BTG_SHARED */
#include "shared/types.h"
#include "shared/math.h"
#include "shared/soft_held_rows.h"
#include "shared/soft_quad_rows.h" /* NVIDIA only: a contact's rows on four work-items */
#include "shared/integrate.h"
#include "shared/counters.h"
#include "shared/grid_barrier.h"
#include "shared/soft_flow.h"
#include "shared/contact_material.h"
#ifdef BTG_CPU_DEVICE
#include "shared/soft_wide.h" /* the wide sweeps: CPU devices only (a GPU's build never sees them) */
#endif

#include "shared/soft_loads.h" /* the passes' loads and stores of the soft rows and contacts */

/* Contact i's soft data lives at `slot`: its place in the color order (soft_color_fill), so
 * that a color's pass reads them one after another. */
/* key: the sweep's order key (SOLVER_RANDMIZE_ORDER; 0: in order), which permutes the points. */
/* mode: the pass, BTG_SOFT_WARM_TOTALS or'ed in where the substep's warm start was carried. */
/* lane: -1, or (NVIDIA, solve and relax sweeps) this work-item's place 0..3 in the quad of
 * work-items that takes the contact (soft_quad_rows.h): all four load and run it, work-item 0
 * stores it. */
static void soft_contact(int i, int slot, int mode, uint key, int lane, SOFT_FN_ARGS)
{
    SOFT_FN_PARAMS
    const int warmTotals = (mode & BTG_SOFT_WARM_TOTALS) != 0;
    mode = btgSoftBaseMode(mode);
    if (mode == BTG_SOFT_STORE) {
        /* the totals the gather wrote, the impulses a held pair may have: from other work-items */
        BtgSoftContact s = softContacts[slot];
        BTG_SHARED __global BtgSoftContact* sc = shared_soft(softContacts);
        s.normalImpulse = btgLoadShared4(&sc[slot].normalImpulse);
        s.tangent1Impulse = btgLoadShared4(&sc[slot].tangent1Impulse);
        s.tangent2Impulse = btgLoadShared4(&sc[slot].tangent2Impulse);
        s.totalNormal = btgLoadShared4(&sc[slot].totalNormal);
        s.total1 = btgLoadShared4(&sc[slot].total1);
        s.total2 = btgLoadShared4(&sc[slot].total2);
        btgSoftStore(contacts, i, &s);
        return;
    }
    /* a contact that never bounces (s.restitution 0: btgSoftRestitution's first test) leaves its
     * bodies and impulses as they are: not read and written back */
    if (mode == BTG_SOFT_RESTITUTION && softContacts[slot].restitution == 0.0f) return;
    /* the passes after prepare take the bodies from the soft contact: one struct a pass, not two */
    const int prepare = mode == BTG_SOFT_PREPARE;
    const int bodyA = prepare ? contacts[i].bodyA : softContacts[slot].bodyA;
    const int bodyB = prepare ? contacts[i].bodyB : softContacts[slot].bodyB;
    BtgBodyVel va, vb;
    BtgSolverBody a = load_body(softSolver, softBodies, bodyA, &va);
    BtgSolverBody b = load_body(softSolver, softBodies, bodyB, &vb);
    if (mode == BTG_SOFT_PREPARE) {
        BtgBodyProps pa = props[bodyA], pb = props[bodyB];
        BtgBodyVel a0 = btgMakeBodyVel(a.moving, linVel0[bodyA], angVel0[bodyA]);
        BtgBodyVel b0 = btgMakeBodyVel(b.moving, linVel0[bodyB], angVel0[bodyB]);
        /* the restitution a contact callback gave the points (contact_material.h), else the pair's */
        const float r = pa.restitution * pb.restitution;
        BtgFloat4 restitution = btgMake4(r, r, r, r);
        const int m = numMaterials > 0 ? btgFindMaterial(materials, numMaterials, contactManifolds[i]) : -1;
        if (m >= 0) restitution = materials[m].restitution;
        const int bullet = btgSoftTakesBulletDirections(pa.flags, pb.flags, params);
        BtgFrictionDirs dirs;
        if (bullet) dirs = frictionDirs[i];
        const BtgSoftContact prepared = btgSoftPrepare(contacts[i], a, b, a0, b0, restitution,
                                                       btgContactSolvable(pa.flags, pb.flags), params,
                                                       btgPairMaterial(pa, pb), bullet ? &dirs : 0);
        /* a contact that may bounce: soft_resident's restitution pass runs */
        if (prepared.restitution != 0.0f) atomic_or(&counters[BTG_COUNTER_SOFT_BOUNCE], 1u);
        softContacts[slot] = btgSoftPack(prepared);
        if (params.heldMassRatio > 0.0f) {
            const int fixed = a.dynamic != b.dynamic && btgContactSolvable(pa.flags, pb.flags);
            const int light = btgSoftLightSide(a, b, params);
            const int rowA = BTG_SOFT_BODY_ROWS * bodyA + BTG_SOFT_SUPPORT, rowB = BTG_SOFT_BODY_ROWS * bodyB + BTG_SOFT_SUPPORT;
            if (a.dynamic) softBodies[rowA] = btgSoftNoteSupport(btgLoadShared4(&softBodies[rowA]), fixed, light == 1, slot);
            if (b.dynamic) softBodies[rowB] = btgSoftNoteSupport(btgLoadShared4(&softBodies[rowB]), fixed, light == 2, slot);
        }
        return;
    }
    BtgSoftContact s = load_soft(softContacts, slot, mode, params.frictionInSolve);
    if (mode == BTG_SOFT_RESTITUTION) {
        btgSoftRestitution(&s, a, b, &va, &vb, params);
    } else {
        const int rA = BTG_SOFT_BODY_ROWS * bodyA, rB = BTG_SOFT_BODY_ROWS * bodyB;
        const BtgSoftDelta dA = load_delta(softBodies, rA), dB = load_delta(softBodies, rB);
        int normals = 1;
        if (params.heldMassRatio > 0.0f) {
            const int light = btgSoftLightSide(a, b, params);
            if (light) {
                const BtgFloat4 support = btgLoadShared4(&softBodies[(light == 1 ? rA : rB) + BTG_SOFT_SUPPORT]);
                if (support.x == 1.0f && btgSoftHeldNormals(&s, light == 1, shared_soft(softContacts) + (int)support.y, a, b, &va,
                                                            &vb, dA, dB, mode == BTG_SOFT_SOLVE, params))
                    normals = 0;
            } else if (a.dynamic != b.dynamic && btgLoadShared4(&softBodies[(a.dynamic ? rA : rB) + BTG_SOFT_SUPPORT]).z == 1.0f) {
                normals = 3;
            }
        }
        /* Bullet's directions where the contact takes them, read where friction rows run */
        const int bullet = (s.flags & BTG_SOFT_BULLET_DIRECTIONS) && (mode == BTG_SOFT_RELAX || params.frictionInSolve);
        if (warmTotals)
            btgSoftCarriedTotals(&s, mode == BTG_SOFT_SOLVE,
                                 params.frictionInSolve ? mode == BTG_SOFT_SOLVE : mode == BTG_SOFT_RELAX);
        BtgFrictionDirs dirs;
        if (bullet) dirs = frictionDirs[i];
#if defined(BTG_NVIDIA)
        if (lane >= 0 && key == 0u && !params.interleave && normals == 1 && !bullet) {
            const uint mask = 0xfu << (get_local_id(0) & 28u);
            btgSoftSolveQuad(&s, a, b, &va, &vb, dA, dB, mode == BTG_SOFT_SOLVE, params, lane, mask);
        } else
#endif
        btgSoftSolve(&s, a, b, &va, &vb, dA, dB, mode == BTG_SOFT_SOLVE, normals, params, btgItemKey(key, (uint)i + 1u),
                     bullet ? &dirs : 0);
        if (params.rolling && mode == BTG_SOFT_RELAX) {
            BtgRollingContact r = btgSoftRolling(rolling[i], &s, a, b, &va, &vb);
            /* a contact with rolling rows relaxes its rows and them BTG_SOFT_ROLLING_ROUNDS times:
             * one round a substep left the friction and rolling rows fighting (a sphere of rolling
             * friction 1 crept 1.3 cm/s down a 20 degree ramp of friction 1) */
            const int rounds = r.rollingFriction > 0.0f ? BTG_SOFT_ROLLING_ROUNDS : 1;
            for (int round = 1; round < rounds; ++round) {
                btgSoftSolve(&s, a, b, &va, &vb, dA, dB, 0, normals, params, btgItemKey(key, (uint)i + 1u), bullet ? &dirs : 0);
                r = btgSoftRolling(r, &s, a, b, &va, &vb);
            }
            if (lane <= 0) {
                rolling[i].spinImpulse = r.spinImpulse;
                rolling[i].roll1Impulse = r.roll1Impulse;
                rolling[i].roll2Impulse = r.roll2Impulse;
            }
        }
    }
    if (lane > 0) return; /* the quad's other work-items hold the same results */
    if (a.dynamic) store_vel(va, a, softBodies, bodyA);
    if (b.dynamic) store_vel(vb, b, softBodies, bodyB);
    softContacts[slot].normalImpulse = s.normalImpulse;
    softContacts[slot].totalNormal = s.totalNormal;
    if (mode == BTG_SOFT_RELAX || (mode == BTG_SOFT_SOLVE && params.frictionInSolve)) {
        softContacts[slot].tangent1Impulse = s.tangent1Impulse;
        softContacts[slot].tangent2Impulse = s.tangent2Impulse;
        softContacts[slot].total1 = s.total1;
        softContacts[slot].total2 = s.total2;
    }
}

/* A body's carry mark (BTG_SOFT_MARK_ANG) less an angular velocity change: the next substep's
 * carried warm start gains it (btgSoftBodyCarry). Its body pass wrote the mark in this launch. */
static void soft_move_mark(BTG_SHARED __global BtgFloat4* softBodies, int i, BtgFloat4 dAng)
{
    const int r = BTG_SOFT_BODY_ROWS * i + BTG_SOFT_MARK_ANG;
    softBodies[r] = btgLoadShared4(&softBodies[r]) - btgXyz(dAng);
}

static void soft_joint(int j, int mode, SOFT_FN_ARGS)
{
    SOFT_FN_PARAMS
    const int rows = jointState[j].numRows;
    mode = btgSoftBaseMode(mode); /* a joint has no totals: its impulse is a substep's, times substeps at the store */
    if (rows == 0 || mode == BTG_SOFT_PREPARE || mode == BTG_SOFT_RESTITUTION) return;
    const BtgJoint joint = joints[j];
    if (mode == BTG_SOFT_STORE) {
        for (int k = 0; k < rows; ++k)
            if (!(jointRows[joint.firstRow + k].flags & BTG_JOINT_ROW_SPRING)) /* a spring's is the step's already */
                jointRows[joint.firstRow + k].impulse *= (float)params.substeps;
        return;
    }
    BtgBodyVel va = btgMakeBodyVel(0, btgZero4(), btgZero4()), vb = va;
    BtgSolverBody a = joint.bodyA >= 0 ? load_body(softSolver, softBodies, joint.bodyA, &va) : btgFixedJointBody().body;
    BtgSolverBody b = joint.bodyB >= 0 ? load_body(softSolver, softBodies, joint.bodyB, &vb) : btgFixedJointBody().body;
    if (mode == BTG_SOFT_RELAX) {
        /* the relax turns the rows to the poses the substep moved the bodies to; the next
         * substep's warm start and solve find them so (the first solve: the step's own poses) */
        const BtgMat3 still = btgQuatToMat3(btgMake4(0.0f, 0.0f, 0.0f, 1.0f));
        const BtgMat3 dA = joint.bodyA >= 0 ? load_delta(softBodies, BTG_SOFT_BODY_ROWS * joint.bodyA).rot : still;
        const BtgMat3 dB = joint.bodyB >= 0 ? load_delta(softBodies, BTG_SOFT_BODY_ROWS * joint.bodyB).rot : still;
        BtgFloat4 turnA, turnB;
        btgSoftTurnLinearRows(jointRows, joint.firstRow, rows, a, b, dA, dB, &turnA, &turnB);
        if (!params.gather) {
            /* the next substep carries its warm start (the velocity change since the mark): the
             * gather would apply the impulses along the turned rows, so the carry takes the
             * difference too, by the mark moved back (the velocities themselves stay) */
            if (a.dynamic) soft_move_mark(softBodies, joint.bodyA, turnA);
            if (b.dynamic) soft_move_mark(softBodies, joint.bodyB, turnB);
        }
    }
    btgSoftJointSolve(jointRows, joint.firstRow, rows, a, b, &va, &vb, params.jointBoundScale, mode == BTG_SOFT_RELAX);
    if (a.dynamic) store_vel(va, a, softBodies, joint.bodyA);
    if (b.dynamic) store_vel(vb, b, softBodies, joint.bodyB);
}

static void soft_edge_lane(int e, int slot, int nc, int mode, uint key, int lane, SOFT_FN_ARGS)
{
    if (e < nc) soft_contact(e, slot, mode, key, lane, SOFT_FN_PASS);
    else if (lane <= 0) soft_joint(e - nc, mode, SOFT_FN_PASS); /* a joint: the quad's work-item 0 alone */
}
static void soft_edge(int e, int slot, int nc, int mode, uint key, SOFT_FN_ARGS)
{
    soft_edge_lane(e, slot, nc, mode, key, -1, SOFT_FN_PASS);
}

/* Flags that say what a body's kind (w of its VEL_LIN row, soft_kind) says: dynamic, moving
 * (kinematic) or fixed, for the rows' helpers. */
static uint soft_kind_flags(float kind)
{
    return kind >= 2.0f ? BTG_BODY_DYNAMIC : (kind == 1.0f ? BTG_BODY_KINEMATIC : BTG_BODY_STATIC);
}

static void soft_body(int i, int mode, SOFT_FN_ARGS)
{
    SOFT_FN_PARAMS
    const int row = BTG_SOFT_BODY_ROWS * i;
    /* the step's first pass reads the body's flags (props: a line a body, 160 bytes apart); the
     * others its kind, which that pass left in the velocity row they read anyway (a fifth of a
     * CPU's body passes waited for props) */
    const BtgFloat4 velLin = mode == BTG_SOFT_BODY_BEGIN ? btgZero4() : btgLoadShared4(&softBodies[row + BTG_SOFT_VEL_LIN]);
    const uint flags = mode == BTG_SOFT_BODY_BEGIN ? props[i].flags : soft_kind_flags(velLin.w);
    if (mode == BTG_SOFT_BODY_END) {
        /* the step's velocities back into the world's columns (their w kept) */
        if (btgIsSolverDynamic(flags)) {
            const BtgFloat4 v = velLin, w = btgLoadShared4(&softBodies[row + BTG_SOFT_VEL_ANG]);
            lin[i] = btgMake4(v.x, v.y, v.z, lin[i].w);
            ang[i] = btgMake4(w.x, w.y, w.z, ang[i].w);
        }
        return;
    }
    /* Each pass reads and writes only its rows: begin writes them all (the velocities from the
     * world's columns); the velocity pass reads the forces' share (and notes the mark where the
     * later substeps carry their warm start), the carry reads both and moves the mark; the
     * position pass moves the deltas. The support row (prepare's, between them) a held step's
     * substeps leave alone. */
    const int velocity = mode == BTG_SOFT_BODY_VELOCITY || mode == BTG_SOFT_BODY_CARRY;
    const int mark = mode == BTG_SOFT_BODY_CARRY || (mode == BTG_SOFT_BODY_VELOCITY && !params.gather);
    BtgFloat4 rows[BTG_SOFT_BODY_ROWS];
    for (int r = 0; r < BTG_SOFT_BODY_ROWS; ++r) {
        const int read = (velocity && r == BTG_SOFT_FORCE_LIN) ||
                         (mode == BTG_SOFT_BODY_CARRY && (r == BTG_SOFT_MARK_LIN || r == BTG_SOFT_MARK_ANG)) ||
                         (mode == BTG_SOFT_BODY_POSITION && (r == BTG_SOFT_DELTA_POS || r == BTG_SOFT_DELTA_ROT));
        rows[r] = read ? btgLoadShared4(&softBodies[row + r]) : btgZero4();
    }
    BtgFloat4 v, w;
    if (mode == BTG_SOFT_BODY_BEGIN) {
        v = lin[i];
        w = ang[i];
    } else {
        v = velLin;
        w = btgLoadShared4(&softBodies[row + BTG_SOFT_VEL_ANG]);
    }
    if (mode == BTG_SOFT_BODY_BEGIN) btgSoftBodyBegin(flags, &v, linVel0[i], rows, params.substeps);
    else if (mode == BTG_SOFT_BODY_VELOCITY) btgSoftBodyVelocity(flags, &v, &w, rows, mark);
    else if (mode == BTG_SOFT_BODY_CARRY) btgSoftBodyCarry(flags, &v, &w, rows);
    else btgSoftBodyPosition(flags, v, w, rows, params.h);
    if (mode == BTG_SOFT_BODY_VELOCITY && btgIsSolverDynamic(flags)) {
        /* the substep's warm start, gathered from the body's edges in list order */
        const BtgSolverBody body = soft_solver_body(softSolver, soft_kind(flags), i);
        BtgBodyVel vel = btgMakeBodyVel(1, v, w);
#ifdef BTG_CPU_DEVICE
        /* the body's contacts lie anywhere among the soft contacts: all of them asked for before
         * the first is read, so their cache misses overlap (the pass waited for each in turn) */
        for (uint q = listStart[i]; q < listStart[i + 1]; ++q) {
            const uint entry = listEntries[q];
            if (entry & BTG_SOFT_ENTRY_JOINT) continue;
            __global const char* c = (__global const char*)(softContacts + slotOf[entry >> 2]);
            for (int b = 0; b < (int)sizeof(BtgSoftContact); b += 64) btgPrefetch(c + b);
            btgPrefetch(c + sizeof(BtgSoftContact) - 1);
        }
#endif
        for (uint q = listStart[i]; q < listStart[i + 1]; ++q) {
            const uint entry = listEntries[q];
            const int side = (int)(entry & 1u);
            if (entry & BTG_SOFT_ENTRY_JOINT) {
                const int j = (int)((entry & ~BTG_SOFT_ENTRY_JOINT) >> 2);
                /* the joint rows' impulses of the last substep (zero at the step's start) on this
                 * side, each read as shared data: the joint's work-item (another group) wrote them */
                BTG_SHARED __global const BtgJointRow* rowsShared = (BTG_SHARED __global const BtgJointRow*)jointRows;
                for (int r = joints[j].firstRow; r < joints[j].firstRow + jointState[j].numRows; ++r) {
                    if (jointRows[r].flags & BTG_JOINT_ROW_SPRING) continue; /* applied once, where it was solved */
                    /* the Jacobian as the joint's last relax turned it (btgSoftTurnLinearRows), shared too */
                    const BtgFloat4 linear = btgLoadShared4(&rowsShared[r].jacobian.linear);
                    const BtgFloat4 response = side ? btgLoadShared4(&rowsShared[r].jacobian.responseB)
                                                    : btgLoadShared4(&rowsShared[r].jacobian.responseA);
                    btgSoftApplySide(linear, response, side, body, &vel, btgLoadSharedFloat(&rowsShared[r].impulse));
                }
                continue;
            }
            const int slot = slotOf[entry >> 2], owner = (entry & 2u) != 0u;
            BtgSoftContact s = load_soft_gather(softContacts, slot, side, owner);
            const int bullet = (s.flags & BTG_SOFT_BULLET_DIRECTIONS) != 0;
            BtgFrictionDirs dirs;
            if (bullet) dirs = frictionDirs[entry >> 2];
            btgSoftWarmStartSide(&s, side, body, &vel, bullet ? &dirs : 0);
            if (owner) {
                btgSoftWarmTotals(&s);
                shared_soft(softContacts)[slot].totalNormal = s.totalNormal;
                shared_soft(softContacts)[slot].total1 = s.total1;
                shared_soft(softContacts)[slot].total2 = s.total2;
            }
        }
        v = vel.lin;
        w = vel.ang;
    }
    for (int r = 0; r < BTG_SOFT_BODY_ROWS; ++r) {
        const int written = mode == BTG_SOFT_BODY_BEGIN ||
                            (mode == BTG_SOFT_BODY_POSITION && btgIsSolverMoving(flags) &&
                             (r == BTG_SOFT_DELTA_POS || r == BTG_SOFT_DELTA_ROT)) ||
                            (mark && btgIsSolverDynamic(flags) && (r == BTG_SOFT_MARK_LIN || r == BTG_SOFT_MARK_ANG));
        if (written && r != BTG_SOFT_VEL_LIN && r != BTG_SOFT_VEL_ANG) softBodies[row + r] = rows[r];
    }
    /* the velocity the rows see (w of VEL_LIN the kind): every body's at the start, a dynamic
     * one's after its substep's forces and warm start */
    if (mode == BTG_SOFT_BODY_BEGIN || (velocity && btgIsSolverDynamic(flags))) {
        softBodies[row + BTG_SOFT_VEL_LIN] = btgMake4(v.x, v.y, v.z, soft_kind(flags));
        softBodies[row + BTG_SOFT_VEL_ANG] = btgMake4(w.x, w.y, w.z, 0.0f);
    }
}

/* Each body's solver record for the step (soft_solver_body reads it): btgMakeSolverBody's
 * fields, packed. */
__kernel void soft_solver_bodies(int n, __global const BtgBodyProps* restrict props,
                                 __global const BtgFloat4* restrict invInertiaWorld, __global BtgFloat4* softSolver)
{
    const int i = (int)get_global_id(0);
    if (i >= n) return;
    const BtgSolverBody b = btgMakeSolverBody(props[i], invInertiaWorld[3 * i], invInertiaWorld[3 * i + 1],
                                              invInertiaWorld[3 * i + 2]);
    softSolver[BTG_SOFT_SOLVER_ROWS * i] = btgMake4(b.invI.r0.x, b.invI.r0.y, b.invI.r0.z, b.invMass);
    softSolver[BTG_SOFT_SOLVER_ROWS * i + 1] = btgMake4(b.invI.r1.x, b.invI.r1.y, b.invI.r1.z, b.linFactor.x);
    softSolver[BTG_SOFT_SOLVER_ROWS * i + 2] = btgMake4(b.invI.r2.x, b.invI.r2.y, b.invI.r2.z, b.linFactor.y);
    softSolver[BTG_SOFT_SOLVER_ROWS * i + 3] = btgMake4(b.angFactor.x, b.angFactor.y, b.angFactor.z, b.linFactor.z);
}

/* One list of color ranges over every edge (contacts and joints alike): count per color,
 * offsets, fill. Within a range the order is the atomics', which does not matter: edges of one
 * color share no dynamic body. */
__kernel void soft_color_count(__global const int* restrict edgeColor, __global uint* counters, int edgeCapacity,
                               __global uint* colorCount, int numColors, __global const BtgEdge* restrict edges,
                               __global const BtgBodyProps* restrict props)
{
    int i = (int)get_global_id(0);
    if (i >= edge_count(counters, edgeCapacity)) return;
    int c = edgeColor[i];
    if (c >= 0) atomic_inc(&colorCount[min(c, numColors - 1)]);
    /* The step's substeps follow its largest edge mass ratio (btgSoftSubstepsFor): positive
     * floats order as their bits. */
    const BtgEdge e = edges[i];
    if (e.bodyA >= 0 && e.bodyB >= 0) {
        const float ratio = btgSoftMassRatio(props[e.bodyA].flags, props[e.bodyA].invMass, props[e.bodyB].flags,
                                             props[e.bodyB].invMass);
        if (ratio > 1.0f) atomic_max(&counters[BTG_COUNTER_SOFT_MASS_RATIO], as_uint(ratio));
    }
}

__kernel void soft_color_offsets(__global uint* colorCount, __global uint* colorStart, int numColors)
{
    if (get_global_id(0) != 0) return;
    uint sum = 0u;
    for (int c = 0; c < numColors; ++c) {
        colorStart[c] = sum;
        sum += colorCount[c];
        colorCount[c] = 0u; /* the fill cursor */
    }
    colorStart[numColors] = sum;
}

/* Each colored edge's slot: its place in its color's range (the last range: the leftovers,
 * walked in index order, their slots only storage). */
__kernel void soft_color_fill(__global const int* restrict edgeColor, __global const uint* restrict counters,
                              int edgeCapacity, __global const uint* restrict colorStart, __global uint* colorCursor,
                              __global int* colorOrder, int numColors, __global int* edgeSlot)
{
    int i = (int)get_global_id(0);
    if (i >= edge_count(counters, edgeCapacity)) return;
    int c = edgeColor[i];
    if (c < 0) return;
    c = min(c, numColors - 1);
    const int k = (int)(colorStart[c] + atomic_inc(&colorCursor[c]));
    colorOrder[k] = i;
    edgeSlot[i] = k;
}

/* The bodies' edge lists for the warm start (btgSoftContactEntry, btgSoftJointEntry): count
 * per body, then (after an exclusive scan of the counts into listStart) fill, then each list
 * sorted. Only dynamic sides are listed. */
static int list_side(__global const BtgBodyProps* restrict props, int body)
{
    return body >= 0 && btgIsSolverDynamic(props[body].flags);
}
static void list_edge(int e, int nc, __global const int* restrict edgeColor, __global const BtgEdge* restrict edges,
                      __global const BtgJoint* restrict joints,
                      __global const BtgJointState* restrict jointState, __global const BtgBodyProps* restrict props,
                      __global uint* cursor, __global const uint* restrict start, __global uint* entries)
{
    if (edgeColor[e] < 0) return; /* never solved: no soft rows (soft_color_fill gave it no slot) */
    int a, b;
    if (e < nc) {
        a = edges[e].bodyA;
        b = edges[e].bodyB;
    } else {
        const int j = e - nc;
        if (jointState[j].numRows == 0) return;
        a = joints[j].bodyA;
        b = joints[j].bodyB;
    }
    const int listA = list_side(props, a), listB = list_side(props, b) && b != a;
    for (int side = 0; side < 2; ++side) {
        if (!(side ? listB : listA)) continue;
        const int body = side ? b : a;
        const uint k = atomic_inc(&cursor[body]);
        if (start) entries[start[body] + k] = e < nc ? btgSoftContactEntry(e, side == 0 || !listA, side)
                                                     : btgSoftJointEntry(e - nc, side);
    }
}
__kernel void soft_list_count(__global const uint* restrict counters, int edgeCapacity, int numJoints,
                              __global const int* restrict edgeColor, __global const BtgEdge* restrict edges, __global const BtgJoint* restrict joints,
                              __global const BtgJointState* restrict jointState,
                              __global const BtgBodyProps* restrict props, __global uint* cursor)
{
    const int e = (int)get_global_id(0);
    if (e >= edge_count(counters, edgeCapacity)) return;
    list_edge(e, contact_edges(counters, edgeCapacity, numJoints), edgeColor, edges, joints, jointState, props, cursor,
              0, 0);
}
__kernel void soft_list_fill(__global const uint* restrict counters, int edgeCapacity, int numJoints,
                             __global const int* restrict edgeColor, __global const BtgEdge* restrict edges, __global const BtgJoint* restrict joints,
                             __global const BtgJointState* restrict jointState,
                             __global const BtgBodyProps* restrict props, __global uint* cursor,
                             __global const uint* restrict start, __global uint* entries)
{
    const int e = (int)get_global_id(0);
    if (e >= edge_count(counters, edgeCapacity)) return;
    list_edge(e, contact_edges(counters, edgeCapacity, numJoints), edgeColor, edges, joints, jointState, props, cursor,
              start, entries);
}
/* Insertion sort of one body's list: short (the edges touching one body). */
__kernel void soft_list_sort(int numBodies, __global const uint* restrict start, __global uint* entries)
{
    const int b = (int)get_global_id(0);
    if (b >= numBodies) return;
    const uint lo = start[b], hi = start[b + 1];
    for (uint i = lo + 1u; i < hi; ++i) {
        const uint e = entries[i];
        uint j = i;
        while (j > lo && entries[j - 1u] > e) {
            entries[j] = entries[j - 1u];
            --j;
        }
        entries[j] = e;
    }
}

#include "shared/soft_flow_passes.h"

__kernel void soft_bodies(int n, int mode, SOFT_ARGS)
{
    int i = (int)get_global_id(0);
    /* the step's first pass clears the bounce flag prepare sets (soft_resident's does the same) */
    if (i == 0 && mode == BTG_SOFT_BODY_BEGIN) counters[BTG_COUNTER_SOFT_BOUNCE] = 0u;
    if (i < n) soft_body(i, mode, SOFT_PASS);
}
/* The substeps' body passes with their mode known when compiled: soft_body's branches and row
 * loops for the other modes fall away (a CPU device runs each pass's bodies as straight code). The
 * same arithmetic, so the same bits. */
#define SOFT_BODIES_OF_MODE(name, m)                                                                        \
    __kernel void name(int n, SOFT_ARGS)                                                                    \
    {                                                                                                      \
        const int i = (int)get_global_id(0);                                                               \
        if (i < n) soft_body(i, m, SOFT_PASS);                                                             \
    }
SOFT_BODIES_OF_MODE(soft_bodies_velocity, BTG_SOFT_BODY_VELOCITY)
SOFT_BODIES_OF_MODE(soft_bodies_carry, BTG_SOFT_BODY_CARRY)
SOFT_BODIES_OF_MODE(soft_bodies_position, BTG_SOFT_BODY_POSITION)

/* colours color .. lastColor - 1 (one colour in a sweep; a pass that touches each edge alone takes
 * every regular colour in one launch, as soft_resident does) */
__kernel void soft_color_range(__global const uint* restrict colorStart, __global const int* restrict colorOrder,
                               int edgeCapacity, int numJoints, int color, int lastColor, int mode, uint key, SOFT_ARGS)
{
    /* no contact of the step bounces (prepare noted none): nothing to read */
    if (btgSoftBaseMode(mode) == BTG_SOFT_RESTITUTION && counters[BTG_COUNTER_SOFT_BOUNCE] == 0u) return;
    const int begin = (int)colorStart[color], end = (int)colorStart[lastColor];
    const int nc = contact_edges(counters, edgeCapacity, numJoints);
    for (int k = begin + (int)get_global_id(0); k < end; k += (int)get_global_size(0))
        soft_edge(colorOrder[k], k, nc, mode, key, SOFT_PASS);
}

#define WIDE_INFO 3 /* ints a lane of a chunk: its mode (1: wide), body A, body B (each 8 a chunk) */
#define WIDE_ARGS __global const uint* restrict wideStart, __global float* wideBlock, __global int* wideLanes
#define WIDE_PASS wideStart, wideBlock, wideLanes
#ifdef BTG_CPU_DEVICE
#include "shared/soft_wide_passes.h"
#endif

/* Prepare (where it notes no supports) by contact rather than by slot: work-item i reads the
 * narrowphase's contact i (400 bytes) in order and writes its soft contact at its slot (the
 * leftovers' too: their slots are storage only). By slot, a colour's contacts came scattered over
 * the narrowphase's records (PoCL cubes 8,000: most of the pass waited for them). Each edge
 * alone, so the same bits in any order. */
__kernel void soft_prepare_by_contact(__global const int* restrict edgeColor, int edgeCapacity, int numJoints, SOFT_ARGS)
{
    const int i = (int)get_global_id(0), nc = contact_edges(counters, edgeCapacity, numJoints);
    if (i < nc && edgeColor[i] >= 0) soft_edge(i, slotOf[i], nc, BTG_SOFT_PREPARE, 0u, SOFT_PASS);
}

__kernel void soft_color_serial(__global const int* restrict edgeColor, int edgeCapacity, int numJoints, int color,
                                int mode, uint key, SOFT_ARGS)
{
    if (get_global_id(0) != 0) return;
    if (counters[BTG_COUNTER_LEFTOVERS] == 0u && counters[BTG_COUNTER_COLORS_USED] <= (uint)color) return;
    const int n = edge_count(counters, edgeCapacity), nc = contact_edges(counters, edgeCapacity, numJoints);
    for (int i = 0; i < n; ++i)
        if (edgeColor[i] >= color) soft_edge(i, slotOf[i], nc, mode, key, SOFT_PASS);
}

/* Every pass of the stage in one launch, a grid barrier where the per-color path has a kernel
 * boundary; the same arithmetic in the same color order, so the same results bit for bit.
 * Each edge stays with one work-item for the launch; body velocities and deltas, and what the
 * bodies' warm-start gather shares of the soft contacts (shared_soft), go through BTG_SHARED
 * pointers. */
#define SOFT_BARRIER()                                                                                    \
    if (btgGridBarrierCounting(bar, &barPhase, spinLimit, &quit)) {                                       \
        if (gid == 0) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);          \
        return;                                                                                           \
    }

__kernel void soft_resident(__global const int* restrict edgeColor, int edgeCapacity,
                            __global const uint* restrict colorStart, __global const int* restrict colorOrder,
                            volatile __global BtgGridBarrier* bar, int numColors, int numJoints, int numBodies,
                            int spinLimit, __global const uint* restrict flowRank, volatile __global uint* flowDone,
                            __global const uint* restrict flowDeg, int flow, WIDE_ARGS, int wide, int quad, SOFT_ARGS)
{
    __local int quit;
    uint barPhase = 0u; /* the grid barriers passed (btgGridBarrierCounting: bar's words zeroed by the host) */
    if (counters[BTG_COUNTER_STATUS] & BTG_STATUS_GRID_BARRIER_TIMEOUT) return;
    const int gid = (int)get_global_id(0), gsize = (int)get_global_size(0);
    const int n = edge_count(counters, edgeCapacity), nc = contact_edges(counters, edgeCapacity, numJoints);
    const int last = numColors - 1;
    const int walkLast = counters[BTG_COUNTER_LEFTOVERS] != 0u || counters[BTG_COUNTER_COLORS_USED] > (uint)last;
    /* the substeps this step's mass ratio needs (soft_color_count noted it) */
    const int substeps = btgSoftSubstepsFor(params, as_float(counters[BTG_COUNTER_SOFT_MASS_RATIO]));
    if (substeps != params.substeps) params = btgSoftParamsWith(params, substeps);
    /* pass list: prepare; per substep velocity and warm start (bodies: gathered, or carried after
     * the first), solve, position, relax; restitution; store; the velocities back (bodies) */
    const int passes = 2 + 4 * params.substeps + 3;
    uint flowSweep = 0u, flowPasses = 0u; /* the flow sweeps and body passes run so far */
    int flowStopped = 0;
    /* flow 2: the substeps' body passes in the flow too (every sweep in colour order; a
     * kinematic body's position pass keeps its barriers) */
    const int flowBodies = flow == 2 && params.orderSeed == 0u;
    const int flowPosition = flowBodies && flowRank[2 * edgeCapacity] == 0u;
    int nonEmpty = 0; /* the regular colours with edges (the same for every work-item) */
    for (int c = 0; c < last; ++c) nonEmpty += colorStart[c] != colorStart[c + 1];
    for (int pass = 0; pass < passes; ++pass) {
        int bodyMode = -1, mode = -1;
        if (pass == 0) bodyMode = BTG_SOFT_BODY_BEGIN;
        else if (pass == 1) mode = BTG_SOFT_PREPARE;
        else if (pass == passes - 1) bodyMode = BTG_SOFT_BODY_END;
        else if (pass == passes - 2) mode = BTG_SOFT_STORE;
        else if (pass == passes - 3) mode = BTG_SOFT_RESTITUTION;
        else {
            const int q = (pass - 2) % 4, substep = (pass - 2) / 4;
            if (q == 0) bodyMode = btgSoftVelocityMode(params, substep);
            else if (q == 1) mode = btgSoftSweepMode(params, substep, 0);
            else if (q == 2) bodyMode = BTG_SOFT_BODY_POSITION;
            else mode = btgSoftSweepMode(params, substep, 1);
        }
        if (bodyMode >= 0) {
            /* flow 2: each body after its own edges of the sweeps before, its edges of the next
             * after it, with no barrier */
            const int flowPass = flowBodies && (bodyMode == BTG_SOFT_BODY_VELOCITY || bodyMode == BTG_SOFT_BODY_CARRY ||
                                                (bodyMode == BTG_SOFT_BODY_POSITION && flowPosition));
            for (int i = gid; i < numBodies; i += gsize) {
                uint want = 0u;
                if (flowPass) {
                    if (flowStopped) break;
                    want = flowSweep * flowDeg[i] + flowPasses;
                    if (btgWaitForCount(&flowDone[i], want, bar, spinLimit)) {
                        atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
                        flowStopped = 1;
                        break;
                    }
                    mem_fence(CLK_GLOBAL_MEM_FENCE);
                }
                soft_body(i, bodyMode, SOFT_PASS);
                if (flowPass) {
                    mem_fence(CLK_GLOBAL_MEM_FENCE);
                    flowDone[i] = want + 1u;
                }
                if (flow && bodyMode == BTG_SOFT_BODY_BEGIN) flowDone[i] = 0u;
            }
            if (flowPass) {
                ++flowPasses;
                continue;
            }
            if (bodyMode == BTG_SOFT_BODY_END) break; /* the last pass: each body's own rows */
            if (bodyMode == BTG_SOFT_BODY_BEGIN && gid == 0) counters[BTG_COUNTER_SOFT_BOUNCE] = 0u; /* prepare notes a bounce */
            SOFT_BARRIER();
#ifdef BTG_CPU_DEVICE
            if (wide && pass == 2) {
                /* a CPU device's wide sweeps: the lanes from the soft contacts after the first
                 * substep's gather (soft_wide_pack's) */
                for (int k = gid; k < (int)colorStart[last]; k += gsize)
                    wide_pack_slot(k, colorStart, colorOrder, nc, WIDE_PASS, softContacts);
                SOFT_BARRIER();
            }
#endif
            continue;
        }
#ifdef BTG_CPU_DEVICE
        if (wide && mode == BTG_SOFT_RESTITUTION) {
            for (int k = gid; k < (int)colorStart[last]; k += gsize) wide_unpack_slot(k, colorStart, WIDE_PASS, softContacts);
            SOFT_BARRIER();
        }
#endif
        /* no contact of the step bounces (prepare noted none, every work-item reads the same word
         * after the barriers since): the restitution pass has nothing to do, nor its barriers */
        if (mode == BTG_SOFT_RESTITUTION && !flow && ((volatile __global uint*)counters)[BTG_COUNTER_SOFT_BOUNCE] == 0u)
            continue;
        /* store (and prepare, unless it notes the bodies' supports) touch each edge alone: no barrier between colors */
        const int independent = (mode == BTG_SOFT_PREPARE && !(params.heldMassRatio > 0.0f)) || mode == BTG_SOFT_STORE;
        /* SOLVER_RANDMIZE_ORDER: a substep's solve and relax sweeps take their colours (the
         * leftovers last) and points in an order of their own */
        const int base = btgSoftBaseMode(mode);
        const uint key = base == BTG_SOFT_SOLVE || base == BTG_SOFT_RELAX
                             ? btgSoftSweepKey(params, (pass - 2) / 4, base == BTG_SOFT_RELAX)
                             : 0u;
        /* the sweeps in colour order, where flow is on: no barrier between their colours */
        const int flowing = flow && key == 0u && (base == BTG_SOFT_SOLVE || base == BTG_SOFT_RELAX ||
                                                  base == BTG_SOFT_RESTITUTION);
        /* quad (NVIDIA, from the host): the solve and relax sweeps in order take a contact on four
         * work-items (soft_quad_rows.h) */
        const int quadSweep = quad && !flowing && key == 0u && (base == BTG_SOFT_SOLVE || base == BTG_SOFT_RELAX);
        /* a pass that touches each edge alone takes the regular colours' slots as one range: a
         * work-item's share is then its part of all of them, not one contact of every colour
         * one after another (cubes 32,768: 14 dependent rounds -> 4) */
        if (independent)
            for (int k = (int)colorStart[0] + gid; k < (int)colorStart[last]; k += gsize)
                soft_edge(colorOrder[k], k, nc, mode, key, SOFT_PASS);
        int left = nonEmpty; /* regular colours of the sweep still to run */
        for (int ci = 0; ci < last && !independent; ++ci) {
            const int color = btgPermute(key, last, ci);
            const int begin = (int)colorStart[color], end = (int)colorStart[color + 1];
            if (begin == end) continue; /* the coloring's slack: every work-item reads the same range */
            --left;
#ifdef BTG_CPU_DEVICE
            const int wideSweep = wide && (base == BTG_SOFT_SOLVE || base == BTG_SOFT_RELAX);
            if (wideSweep) {
                const int chunks = (end - begin + BTG_SOFT_WIDE - 1) / BTG_SOFT_WIDE;
                for (int m = gid; m < chunks; m += gsize)
                    soft_wide_chunk(color, m, m + gsize < chunks ? m + gsize : -1, begin, end, colorOrder, WIDE_PASS, nc,
                                    mode, key, SOFT_PASS);
            }
#else
            const int wideSweep = 0; /* a GPU's build has no wide sweeps (the host never asks) */
#endif
            /* in quads where the colour's contacts fit the launch's quads at once; a larger colour
             * one contact a work-item (two rounds of quads cost more than one round of single
             * work-items; both give the same bits) */
            const int quadColor = quadSweep && end - begin <= (gsize >> 2);
            const int first = quadColor ? gid >> 2 : gid, stride = quadColor ? gsize >> 2 : gsize;
            const int lane = quadColor ? (gid & 3) : -1;
            for (int k = begin + first; k < end && !wideSweep; k += stride) {
                const int e = colorOrder[k];
                /* one call of the rows for both orders: one compiled copy of their arithmetic */
                int2 ab = (int2)(0, 0);
                uint packA = BTG_SOFT_FLOW_FREE, packB = BTG_SOFT_FLOW_FREE;
                if (flowing) {
                    ab = flow_bodies(e, k, nc, softContacts, joints);
                    packA = flowRank[2 * k];
                    packB = flowRank[2 * k + 1];
                    /* a wait that gave up stops this work-item's flow edges (not the work-item:
                     * its group's barriers still need it); every other wait then gives up at
                     * its next look at the flag, and the host redoes the step */
                    if (flowStopped) continue;
                    if (flow_wait(flowDone, ab.x, packA, flowSweep, flowPasses, bar, spinLimit) ||
                        flow_wait(flowDone, ab.y, packB, flowSweep, flowPasses, bar, spinLimit)) {
                        atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
                        flowStopped = 1;
                        continue;
                    }
                    mem_fence(CLK_GLOBAL_MEM_FENCE); /* the bodies' rows read after their counts */
                }
                soft_edge_lane(e, k, nc, mode, key, lane, SOFT_PASS);
                if (flowing) {
                    mem_fence(CLK_GLOBAL_MEM_FENCE); /* the rows written before the counts move on */
                    flow_signal(flowDone, ab.x, packA, flowSweep, flowPasses);
                    flow_signal(flowDone, ab.y, packB, flowSweep, flowPasses);
                }
            }
            /* the sweep's own barrier below follows the last colour where no leftovers come
             * between: one barrier there, not two */
            if (!independent && !flowing && (left > 0 || walkLast)) SOFT_BARRIER();
        }
        if (flowing) {
            ++flowSweep;
            if (walkLast) SOFT_BARRIER(); /* the leftovers after every regular edge */
        }
        if (walkLast && gid == 0)
            for (int i = 0; i < n; ++i)
                if (edgeColor[i] >= last) soft_edge(i, slotOf[i], nc, mode, key, SOFT_PASS);
        /* flow 2: a sweep that a flow pass follows ends without a barrier */
        const int nextFlows = flowBodies && !walkLast && ((base == BTG_SOFT_SOLVE && flowPosition) || base == BTG_SOFT_RELAX);
        if (!(flowing && nextFlows)) SOFT_BARRIER();
    }
}

__kernel void soft_transforms(int n, __global const BtgBodyProps* restrict props,
                              __global const BtgFloat4* restrict softBodies, __global const BtgFloat4* restrict linVel,
                              __global const BtgFloat4* restrict angVel, __global BtgFloat4* pos, __global BtgFloat4* rot,
                              __global uint* counters)
{
    int i = (int)get_global_id(0);
    if (i >= n) return;
    if (!btgIsMoving(props[i].flags)) return;
    BtgFloat4 rows[BTG_SOFT_BODY_ROWS];
    for (int r = 0; r < BTG_SOFT_BODY_ROWS; ++r)
        rows[r] = r == BTG_SOFT_DELTA_POS || r == BTG_SOFT_DELTA_ROT ? softBodies[BTG_SOFT_BODY_ROWS * i + r] : btgZero4();
    BtgFloat4 x = pos[i], q = rot[i];
    btgSoftBodyFinish(&x, &q, rows);
    if (!btgIsFinite4(x) || !btgIsFinite4(q) || !btgIsFinite4(linVel[i]) || !btgIsFinite4(angVel[i])) {
        atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_NAN);
        atomic_min(&counters[BTG_COUNTER_NAN_BODY], (uint)i);
    }
    pos[i] = x;
    rot[i] = q;
}
