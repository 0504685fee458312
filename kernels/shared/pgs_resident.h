/* pgs_resident.h (inlined at every include) — the one-launch solve kernel, BTG_RESIDENT_KERNEL,
 * for solve_constraints.cl, which includes it twice: solve_resident (BTG_RESIDENT_WIDE 0: every
 * sweep an edge a work-item, the flow's ordering where asked) and, on CPU devices only,
 * solve_resident_wide (BTG_RESIDENT_WIDE 1: the warm-start, normal and friction sweeps in the wide
 * chunks of pgs_wide_passes.h, no flow). Two kernels, not one with both: PoCL's build of the
 * kernel with the wide sweeps in it broke the flow's waits (PrepareJoints.SolveWithContactsFlow
 * timed out). No include guard, on purpose. Needs the helpers solve_constraints.cl defines
 * before it. OpenCL only. */

/* solve_resident: every pass and color in ONE launch over resident work-groups (GPUs), with a
 * grid barrier (shared/grid_barrier.h) where the per-color path has a kernel boundary: a step
 * has (colors + 1) x (1 + 2 x iterations) of those. Body velocities go through BTG_SHARED
 * pointers (see solve_contact); an edge's impulses are touched by the same work-item in every
 * pass (the assignment is fixed for the launch), so plain accesses suffice there. The
 * arithmetic and color order are the per-color launches' ones: the results are the same bit
 * for bit. A batching that timed out at its own barrier leaves nothing to solve: the step is redone. */

__kernel void BTG_RESIDENT_KERNEL(__global const int* restrict edgeColor, __global BtgContact* contacts,
                             __global BtgRollingContact* rolling, __global const BtgFrictionDirs* restrict frictionDirs, __global const BtgFrictionAnchor* restrict anchors,
                             __global uint* counters, int edgeCapacity,
                             __global const uint* restrict colorStart, __global const int* restrict colorOrder,
                             __global const BtgBodyProps* restrict props, __global const BtgFloat4* restrict invInertiaWorld,
                             BTG_SHARED __global BtgFloat4* linVel, BTG_SHARED __global BtgFloat4* angVel,
                             BTG_SHARED __global BtgFloat4* pushLin, BTG_SHARED __global BtgFloat4* pushAng,
                             volatile __global BtgGridBarrier* bar, int numColors, int orderStride, int iterations,
                             int splitImpulse, int rows, int spinLimit, JOINT_ARGS, int jointIterations, uint seed,
                             __global const uint* restrict flowMasks, volatile __global uint* flowDone, int flow,
                             int passFirst, int wide, __global const uint* restrict wideStart, __global float* wideBlock,
                             __global int* wideLanes, __global const BtgFloat4* restrict wideBodies,
                             __global const int* restrict wideKinds)
{
    __local int quit;
    /* the flow orders every sweep by the bodies' counts: only where every sweep is in colour
     * order, and each colour is a bit of the masks */
    const int flowing = !BTG_RESIDENT_WIDE && flow && seed == 0u && numColors - 1 <= 32;
    int4 flowSweeps = (int4)(0, 0, 0, 0); /* flow sweeps done per list */
    int flowStopped = 0;
    if (counters[BTG_COUNTER_STATUS] & BTG_STATUS_GRID_BARRIER_TIMEOUT) return;
    const int gid = (int)get_global_id(0), gsize = (int)get_global_size(0);
    const int n = edge_count(counters, edgeCapacity);
    const int nc = contact_edges(counters, edgeCapacity, numJoints);
    const int last = numColors - 1;
    const int walkLast = walk_leftovers(counters, last);
    const int velocity = velocity_passes(iterations, numJoints, jointIterations);
    const int passes = 1 + velocity + (splitImpulse ? iterations : 0);
    /* passFirst: where the host's per-colour launches took the passes before it (a CPU device's
     * push passes, one group, in one launch: they were a hundred launches of mostly empty colours) */
    for (int pass = passFirst; pass < passes; ++pass) {
        const int mode = pass_mode(pass, velocity);
        const int iteration = pass - 1;
        BTG_SHARED __global BtgFloat4* lin = mode == 2 ? pushLin : linVel;
        BTG_SHARED __global BtgFloat4* ang = mode == 2 ? pushAng : angVel;
        /* Phase 1: the joints (velocity passes only), then phase 0: the contacts, whose
         * velocity pass is two sweeps (normals, then friction). */
        for (int phase = first_phase(mode, numJoints); phase >= last_phase(mode, iteration, iterations); --phase) {
            /* push passes: only contacts with a push target */
            const int list = phase_list(mode, phase);
            const int sweeps = phase_sweeps(mode, phase, rows);
            for (int sweep = 0; sweep < sweeps; ++sweep) {
                const int m = sweep_mode(mode, phase, rows, sweep, sweeps);
                const uint key = btgPassKey(seed, m, phase, iteration);
                for (int ci = 0; ci < last; ++ci) {
                    const int color = btgPermute(key, last, ci); /* SOLVER_RANDMIZE_ORDER, else ci */
                    const int2 range = color_range(colorStart, list, numColors, color);
                    const int begin = range.x, end = range.y;
                    /* an empty colour (the coloring's slack, a list's unused colours) needs no
                     * barrier: every work-item reads the same range */
                    if (begin == end) continue;
#if BTG_RESIDENT_WIDE
                    /* a CPU device's wide sweeps (pgs_wide_passes.h): each work-item a run of the
                     * colour's chunks of eight contacts (the host packed them; never with the flow) */
                    const int wideSweep = wide && phase == 0 && list == 0 &&
                                          (m == BTG_PASS_WARM_START || m == BTG_PASS_NORMALS || m == BTG_PASS_FRICTION);
                    if (wideSweep) {
                        const int2 run = btgWideRun((int)(wideStart[color + 1] - wideStart[color]), gid, gsize);
                        for (int q = run.x; q < run.y; ++q)
                            pgs_wide_chunk((int)wideStart[color] + q, q + 1 < run.y ? (int)wideStart[color] + q + 1 : -1, m,
                                           (rows & BTG_ROWS_TWO_FRICTION) != 0, wideStart, wideBlock, wideLanes, wideBodies,
                                           wideKinds, lin, ang);
                    }
#else
                    const int wideSweep = 0;
#endif
                    for (int k = begin + gid; k < end && !wideSweep; k += gsize) {
                        const int e = colorOrder[list * orderStride + k];
                        /* one call of the rows for both orders: one compiled copy of their arithmetic */
                        int2 ab = (int2)(0, 0);
                        long wantA = -1, wantB = -1;
                        const int slot = mode == BTG_PASS_PUSH ? 1 : 0;
                        if (flowing) {
                            /* a wait that gave up stops this work-item's edges (its group's
                             * barriers still need it); the others give up at their next look at
                             * the flag */
                            if (flowStopped) continue;
                            ab = flow_edge_bodies(e, list, nc, contacts, joints);
                            wantA = flow_want(flowMasks, ab.x, list, color, last, flowSweeps);
                            wantB = ab.y != ab.x ? flow_want(flowMasks, ab.y, list, color, last, flowSweeps) : -1;
                            if (flow_wait(&flowDone[2 * max(ab.x, 0) + slot], wantA, bar, spinLimit) ||
                                flow_wait(&flowDone[2 * max(ab.y, 0) + slot], wantB, bar, spinLimit)) {
                                atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
                                flowStopped = 1;
                                continue;
                            }
                            mem_fence(CLK_GLOBAL_MEM_FENCE); /* the bodies' velocities read after their counts */
                        }
                        solve_phase_edge(e, e, phase, nc, iteration, m, rows, contacts, rolling, frictionDirs, anchors,
                                         JOINT_PASS, props, invInertiaWorld, lin, ang, key);
                        if (flowing) {
                            mem_fence(CLK_GLOBAL_MEM_FENCE); /* written before the counts move on */
                            if (wantA >= 0) flowDone[2 * ab.x + slot] = (uint)wantA + 1u;
                            if (wantB >= 0) flowDone[2 * ab.y + slot] = (uint)wantB + 1u;
                        }
                    }
                    if (flowing) continue;
                    if (btgGridBarrier(bar, spinLimit, &quit)) {
                        if (gid == 0) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
                        return;
                    }
                }
                if (flowing) {
                    if (list == 0) ++flowSweeps.x;
                    else if (list == 1) ++flowSweeps.y;
                    else ++flowSweeps.z;
                    /* the leftovers after every regular edge of the sweep */
                    if (walkLast && btgGridBarrier(bar, spinLimit, &quit)) {
                        if (gid == 0) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
                        return;
                    }
                }
                if (walkLast) {
                    if (gid == 0)
                        for (int i = phase ? nc : 0; i < (phase ? n : min(n, nc)); ++i)
                            if (edgeColor[i] >= last)
                                solve_phase_edge(i, i, phase, nc, iteration, m, rows, contacts, rolling, frictionDirs, anchors, JOINT_PASS,
                                                 props, invInertiaWorld, lin, ang, key);
                    if (btgGridBarrier(bar, spinLimit, &quit)) {
                        if (gid == 0) atomic_or(&counters[BTG_COUNTER_STATUS], BTG_STATUS_GRID_BARRIER_TIMEOUT);
                        return;
                    }
                }
            }
        }
    }
}

