/* update_activation.cl — Stage: update_activation (deactivation, as Bullet's).
 * own_timers      one work-item per body. Reads linVel, angVel, props. Writes sleepTime (own
 *                 timer), islandTime (min(own, island + dt)), wake (cleared).
 * island_min      one work-item per constraint-graph edge (contacts and any other kind).
 *                 Reads edges, counters[kEdgeCount, kContactCount], props, sleepTime, islandSrc.
 *                 Writes islandDst (atomic_min over both bodies: deterministic, min is order-
 *                 free), wake (a sleeping body touched by a moving, non-slow body, or jointed
 *                 to an awake one: the edges past the contacts are joints).
 * apply_sleep     one work-item per body. Reads islandTime, wake, sleepTime. Writes props.flags
 *                 (BTG_BODY_SLEEPING), linVel/angVel (zero when falling asleep, and while asleep
 *                 as stock's), sleepState.
 * The three above do nothing in a substep whose status asks for a redo (BTG_STATUS_REDO): the
 *                 call is redone from a snapshot that holds no timers or flags.
 * wake_touched    one work-item per contact, before the contacts' rows are made (wakeTouched).
 *                 Reads contacts, counters[kContactCount], props, sleepTime. Writes wake (a
 *                 sleeping body a moving one touches, btgWakes, as island_min judges it).
 * wake_jointed    one work-group, after wake_touched, only with joints. Reads joints, props.
 *                 Writes wake (the bodies joined by enabled joints to an awake or woken one,
 *                 followed joint by joint until none is added: stock wakes the whole island).
 * wake_apply      one work-item per body, after wake_touched (and wake_jointed). Reads wake. Writes props.flags
 *                 (SLEEPING cleared), sleepTime (0), sleepState (0), wake (cleared).
 * wake_paired     one work-item per pair, last in the step (after apply_sleep). Reads pairs,
 *                 counters[kPairCount], props, sleepTime, islandLabel. Writes islandWake (the
 *                 island of a sleeping body whose pair a moving one is in, btgWakes).
 * wake_paired_apply  one work-item per body, after wake_paired. Reads islandLabel, islandWake.
 *                 Writes props.flags (SLEEPING cleared), sleepTime (0), sleepState (0).
 * These two do nothing under a redo status either. */
#include "shared/activation.h"
#include "shared/counters.h"
#include "shared/joint_rows.h"
#include "shared/types.h"

__kernel void own_timers(int n, __global const BtgFloat4* restrict linVel, __global const BtgFloat4* restrict angVel,
                         __global const BtgBodyProps* restrict props, __global float* sleepTime,
                         __global uint* islandTime, __global uint* wake, float dt, __global const uint* restrict counters,
                         __global uint* islandLabel, __global uint* islandWake)
{
    int i = get_global_id(0);
    if (i >= n || (counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) return; /* redone: nothing counted */
    BtgBodyProps p = props[i];
    wake[i] = 0u;
    islandWake[i] = 0u; /* this step's marks are spent (wake_island_spread) */
    /* an awake body's island is found afresh each step (island_min); a sleeper keeps the one it
       fell asleep in */
    if (!(p.flags & BTG_BODY_SLEEPING)) islandLabel[i] = (uint)i;
    if (!btgCanSleep(p.flags)) {
        islandTime[i] = BTG_NEVER_UINT;
        return;
    }
    float own = btgOwnTimer(sleepTime[i], linVel[i], angVel[i], p, dt);
    sleepTime[i] = own;
    float island = as_float(islandTime[i]);
    island = (as_uint(island) == BTG_NEVER_UINT) ? own : fmin(own, island + dt);
    islandTime[i] = as_uint(island);
}

__kernel void island_min(__global const BtgEdge* restrict edges, __global const uint* restrict counters,
                         int capacity, __global const BtgBodyProps* restrict props, __global const float* restrict sleepTime,
                         __global const uint* restrict islandSrc, __global uint* islandDst, __global uint* wake,
                         int numJoints, __global const uint* restrict labelSrc, __global uint* labelDst)
{
    int k = get_global_id(0);
    int count = (int)min(counters[BTG_COUNTER_EDGES], (uint)capacity);
    if (k >= count || (counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) return;
    BtgEdge c = edges[k];
    uint fa = props[c.bodyA].flags, fb = props[c.bodyB].flags;
    /* Joints unite any two dynamic bodies (stock's calculateSimulationIslands), contacts only
     * bodies that respond. */
    const int joint = numJoints > 0 && k >= (int)min(counters[BTG_COUNTER_CONTACTS], (uint)(capacity - numJoints));
    if (joint ? btgCanSleep(fa) && btgCanSleep(fb) : btgMergesIslands(fa) && btgMergesIslands(fb)) {
        atomic_min(&islandDst[c.bodyA], islandSrc[c.bodyB]);
        atomic_min(&islandDst[c.bodyB], islandSrc[c.bodyA]);
        /* the least row of the island, a hop a round, among awake bodies (a sleeper keeps the
           label it fell asleep with) */
        if (!((fa | fb) & BTG_BODY_SLEEPING)) {
            atomic_min(&labelDst[c.bodyA], labelSrc[c.bodyB]);
            atomic_min(&labelDst[c.bodyB], labelSrc[c.bodyA]);
        }
    }
    if (joint) {
        if (btgJointWakes(fa, fb)) wake[c.bodyB] = 1u;
        if (btgJointWakes(fb, fa)) wake[c.bodyA] = 1u;
    }
    if (btgWakes(fa, fb, sleepTime[c.bodyA])) wake[c.bodyB] = 1u;
    if (btgWakes(fb, fa, sleepTime[c.bodyB])) wake[c.bodyA] = 1u;
}

__kernel void apply_sleep(int n, __global const uint* restrict islandTime, __global const uint* restrict wake,
                          __global float* sleepTime, __global BtgBodyProps* props, __global BtgFloat4* linVel,
                          __global BtgFloat4* angVel, __global uint* sleepState, float deactivationTime,
                          __global const uint* restrict counters)
{
    int i = get_global_id(0);
    if (i >= n || (counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) return;
    uint f = props[i].flags;
    if ((f & BTG_BODY_SLEEPING) && wake[i]) {
        props[i].flags = f & ~BTG_BODY_SLEEPING;
        sleepTime[i] = 0.0f;
        sleepState[i] = 0u;
        return;
    }
    /* Stock's updateActivationState zeroes a sleeping body's velocities every step (wantsSleeping
     * holds while deactivation is on): one the app set without activate() is gone by the step's
     * end, and does not move the body when it wakes later. */
    if ((f & BTG_BODY_SLEEPING) && deactivationTime > 0.0f) {
        if (any(linVel[i] != (float4)(0.0f)) || any(angVel[i] != (float4)(0.0f))) {
            linVel[i] = (float4)(0.0f);
            angVel[i] = (float4)(0.0f);
        }
        sleepState[i] = 1u;
        return;
    }
    if (btgCanSleep(f) && deactivationTime > 0.0f && as_float(islandTime[i]) > deactivationTime) {
        props[i].flags = f | BTG_BODY_SLEEPING;
        linVel[i] = (float4)(0.0f);
        angVel[i] = (float4)(0.0f);
        sleepState[i] = 1u;
        return;
    }
    sleepState[i] = (f & BTG_BODY_SLEEPING) ? 1u : 0u;
}

/* Stock wakes a sleeping body that a moving one touches before its solve (buildIslands: the
 * island of an active body, or one a moving kinematic body touches, is activated whole), so the
 * blow moves it in the same step. Woken only at the step's end (apply_sleep), it was solved as a
 * fixed body for the step it was hit in: a ball shot into a sleeping stack bounced off it as off
 * a wall. The toucher's own timer is the last step's (the same rule as island_min's); a body
 * woken here wakes what it touches in the next step (one contact a step, as island_min). Marks
 * first, then clears the flags: the marks read the flags as the step found them, whatever the
 * order of the work-items. */
__kernel void wake_touched(__global const BtgContact* restrict contacts, __global const uint* restrict counters,
                           int capacity, __global const BtgBodyProps* restrict props,
                           __global const float* restrict sleepTime, __global uint* wake)
{
    const int k = get_global_id(0);
    if (k >= (int)min(counters[BTG_COUNTER_CONTACTS], (uint)capacity)) return;
    const int a = contacts[k].bodyA, b = contacts[k].bodyB;
    if (contacts[k].numPoints <= 0 || a < 0 || b < 0) return;
    const uint fa = props[a].flags, fb = props[b].flags;
    if (btgWakes(fa, fb, sleepTime[a])) wake[b] = 1u;
    if (btgWakes(fb, fa, sleepTime[b])) wake[a] = 1u;
}

/* A sleeping body joined to one that is awake, or woken above, wakes too, and so on along the
 * joints: stock's island is every body its joints join, activated whole before the solve. Only
 * joints (an app's ragdolls and robots: few edges) are followed to the end, in one work-group;
 * contacts wake one hop a step, as island_min. A mark only ever goes from 0 to 1, so the marks
 * this ends with are the joints' closure whatever the order of the work-items. */
__kernel void wake_jointed(__global const BtgJoint* restrict joints, int numJoints,
                           __global const BtgBodyProps* restrict props, __global uint* wake)
{
    __local int changed;
    const int lid = (int)get_local_id(0), size = (int)get_local_size(0);
    /* every round but the last wakes a body, so numJoints + 1 rounds reach the closure */
    for (int round = 0; round <= numJoints; ++round) {
        barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE); /* the last round's look at `changed` */
        if (lid == 0) changed = 0;
        barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
        for (int j = lid; j < numJoints; j += size) {
            const int a = joints[j].bodyA, b = joints[j].bodyB;
            if (!(joints[j].flags & BTG_JOINT_ENABLED) || a < 0 || b < 0) continue;
            /* a body marked is awake for this rule (its flag is cleared by wake_apply) */
            const uint fa = wake[a] ? props[a].flags & ~BTG_BODY_SLEEPING : props[a].flags;
            const uint fb = wake[b] ? props[b].flags & ~BTG_BODY_SLEEPING : props[b].flags;
            if (btgJointWakes(fa, fb) && !wake[b]) {
                wake[b] = 1u;
                changed = 1;
            }
            if (btgJointWakes(fb, fa) && !wake[a]) {
                wake[a] = 1u;
                changed = 1;
            }
        }
        barrier(CLK_LOCAL_MEM_FENCE | CLK_GLOBAL_MEM_FENCE);
        if (!changed) break;
    }
}

/* Stock activates a sleeping island whole before its solve once any of its bodies is active
 * (buildIslands): the islands of the bodies marked so far (wake_touched, wake_jointed, and the
 * app's activate(): reset_rows) are marked, then every sleeping dynamic body of a marked island
 * is. An island is the label island_min gave its bodies when they fell asleep: the least row
 * within its rounds' hops of each, so a large island may hold several labels and wakes label by
 * label as before, a contact a step. */
__kernel void wake_island_mark(int n, __global const uint* restrict wake, __global const BtgBodyProps* restrict props,
                               __global const uint* restrict islandLabel, __global uint* islandWake)
{
    const int i = get_global_id(0);
    if (i >= n || !wake[i] || !(props[i].flags & BTG_BODY_SLEEPING)) return;
    const uint l = islandLabel[i];
    if (l < (uint)n) islandWake[l] = 1u;
}

__kernel void wake_island_spread(int n, __global uint* wake, __global const BtgBodyProps* restrict props,
                                 __global const uint* restrict islandLabel, __global const uint* restrict islandWake)
{
    const int i = get_global_id(0);
    if (i >= n || wake[i]) return;
    const uint f = props[i].flags;
    if (!(f & BTG_BODY_SLEEPING) || !(f & BTG_BODY_DYNAMIC) || (f & BTG_BODY_EXCLUDED)) return;
    const uint l = islandLabel[i];
    if (l < (uint)n && islandWake[l]) wake[i] = 1u;
}

__kernel void wake_apply(int n, __global uint* wake, __global BtgBodyProps* props, __global float* sleepTime,
                         __global uint* sleepState)
{
    const int i = get_global_id(0);
    if (i >= n || !wake[i]) return;
    wake[i] = 0u;
    const uint f = props[i].flags;
    if (!(f & BTG_BODY_SLEEPING)) return;
    props[i].flags = f & ~BTG_BODY_SLEEPING;
    sleepTime[i] = 0.0f;
    sleepState[i] = 0u;
}

/* Stock's islands are its broadphase pairs (findUnions over the overlapping pairs: bodies whose
 * AABBs, grown by the contact threshold and swept to their predicted poses, overlap), so a
 * moving body wakes a sleeping island as soon as their AABBs meet, a step or more before they
 * touch, and by the time the blow lands the island's own pairs are collided again. Woken only by
 * a contact (wake_touched, before the solve), the island's own pairs had not been collided in
 * that step (both asleep when the pairs were found), so its bodies fell free for the step: a box
 * dropped onto a sleeping stack of three pushed the top box 6 cm down in one step where stock's
 * moved 3 cm. At the step's end, then, the island (its label) of a sleeper that this step's
 * pairs put beside a moving body (btgWakes, as wake_touched judges a touch) is marked, and
 * wake_paired_apply wakes it whole: the next step finds its pairs. */
__kernel void wake_paired(__global const BtgPair* restrict pairs, __global const uint* restrict counters, int capacity,
                          int n, __global const BtgBodyProps* restrict props, __global const float* restrict sleepTime,
                          __global const uint* restrict islandLabel, __global uint* islandWake)
{
    const int k = get_global_id(0);
    if (k >= (int)min(counters[BTG_COUNTER_PAIRS], (uint)capacity) || (counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u)
        return;
    const int a = pairs[k].a, b = pairs[k].b;
    if (a < 0 || b < 0 || a >= n || b >= n || a == b) return;
    const uint fa = props[a].flags, fb = props[b].flags;
    if (btgWakes(fa, fb, sleepTime[a]) && islandLabel[b] < (uint)n) islandWake[islandLabel[b]] = 1u;
    if (btgWakes(fb, fa, sleepTime[b]) && islandLabel[a] < (uint)n) islandWake[islandLabel[a]] = 1u;
}

__kernel void wake_paired_apply(int n, __global BtgBodyProps* props, __global float* sleepTime, __global uint* sleepState,
                                __global const uint* restrict islandLabel, __global const uint* restrict islandWake,
                                __global const uint* restrict counters)
{
    const int i = get_global_id(0);
    if (i >= n || (counters[BTG_COUNTER_STATUS] & BTG_STATUS_REDO) != 0u) return;
    const uint f = props[i].flags;
    if (!(f & BTG_BODY_SLEEPING) || !(f & BTG_BODY_DYNAMIC) || (f & BTG_BODY_EXCLUDED)) return;
    const uint l = islandLabel[i];
    if (l >= (uint)n || !islandWake[l]) return;
    props[i].flags = f & ~BTG_BODY_SLEEPING;
    sleepTime[i] = 0.0f;
    sleepState[i] = 0u;
}
