/* prepare_joints.cl — Stage: prepare_joints (each joint's solver rows from the current body
 * poses, as its getInfo2 and convertJoint build them, and its edge of the constraint graph)
 * and finish_joints (writeBackJoints: applied impulse, joint feedback, breaking).
 * Launch: one work-item per joint, both kernels.
 * prepare_joints  Reads joints, jointState, counters[kContactCount], props, invInertiaWorld,
 *                 pos, rot, linVel, angVel (after this substep's forces), linVel0, angVel0 (before
 *                 them: the limits' bounce reads the rigid body's own). Writes jointRows,
 *                 jointState (rows built, applied impulse reset), edges[contacts + j],
 *                 counters[kEdgeCount] (= contacts + joints).
 * finish_joints   Reads joints, jointRows, props. Writes jointState (applied impulse, broken),
 *                 jointFeedback (joints with a btJointFeedback). */
#include "shared/counters.h"
#include "shared/types.h"
#include "shared/math.h"
#include "shared/joint_prepare.h"

static BtgJointBody load_joint_body(int i, __global const BtgBodyProps* restrict props,
                                    __global const BtgFloat4* restrict invInertiaWorld,
                                    __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                                    __global const BtgFloat4* restrict linVel, __global const BtgFloat4* restrict angVel,
                                    __global const BtgFloat4* restrict linVel0, __global const BtgFloat4* restrict angVel0)
{
    if (i < 0) return btgFixedJointBody();
    return btgMakeJointBody(props[i], invInertiaWorld[3 * i], invInertiaWorld[3 * i + 1], invInertiaWorld[3 * i + 2],
                            pos[i], rot[i], linVel[i], angVel[i], linVel0[i], angVel0[i]);
}

__kernel void prepare_joints(__global const BtgJoint* restrict joints, __global BtgJointState* jointState,
                             __global BtgJointRow* jointRows, __global uint* counters, int contactCapacity,
                             __global const BtgBodyProps* restrict props,
                             __global const BtgFloat4* restrict invInertiaWorld, __global const BtgFloat4* restrict pos,
                             __global const BtgFloat4* restrict rot, __global const BtgFloat4* restrict linVel,
                             __global const BtgFloat4* restrict angVel, __global const BtgFloat4* restrict linVel0,
                             __global const BtgFloat4* restrict angVel0,
                             __global BtgEdge* edges, BtgJointStepParams p)
{
    int j = (int)get_global_id(0);
    const uint n = min(counters[BTG_COUNTER_CONTACTS], (uint)contactCapacity);
    if (j == 0) counters[BTG_COUNTER_EDGES] = n + (uint)p.numJoints;
    if (j >= p.numJoints) return;
    BtgJoint joint = joints[j];
    BtgJointBody a = load_joint_body(joint.bodyA, props, invInertiaWorld, pos, rot, linVel, angVel, linVel0, angVel0);
    BtgJointBody b = load_joint_body(joint.bodyB, props, invInertiaWorld, pos, rot, linVel, angVel, linVel0, angVel0);
    BtgJointState s = jointState[j];
    btgPrepareJoint(joint, &s, jointRows, a, b, p);
    jointState[j] = s;
    edges[n + (uint)j] = btgJointEdge(joint, s.numRows > 0);
}

__kernel void finish_joints(__global const BtgJoint* restrict joints, __global BtgJointState* jointState,
                            __global BtgJointFeedback* jointFeedback, __global const BtgJointRow* restrict jointRows,
                            __global const BtgBodyProps* restrict props, BtgJointStepParams p)
{
    int j = (int)get_global_id(0);
    if (j >= p.numJoints) return;
    BtgJoint joint = joints[j];
    BtgJointBody a = btgFixedJointBody(), b = btgFixedJointBody();
    /* Feedback scales by the bodies' factors only. */
    if (joint.bodyA >= 0) {
        a.body.linFactor = btgXyz(props[joint.bodyA].linearFactor);
        a.body.angFactor = btgXyz(props[joint.bodyA].angularFactor);
    }
    if (joint.bodyB >= 0) {
        b.body.linFactor = btgXyz(props[joint.bodyB].linearFactor);
        b.body.angFactor = btgXyz(props[joint.bodyB].angularFactor);
    }
    BtgJointState s = jointState[j];
    BtgJointFeedback f = jointFeedback[j];
    btgFinishJoint(&s, &f, joint, jointRows, a, b, p.dt);
    jointState[j] = s;
    if (joint.flags & BTG_JOINT_FEEDBACK) jointFeedback[j] = f;
}
