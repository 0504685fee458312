// prepare_joints.h — Stage: each joint's solver rows for this substep, from the current body
// poses and the velocities after this substep's forces (getInfo1/getInfo2 and convertJoint,
// kernels/shared/joint_rows.h), and the joints' edges of the constraint graph after the
// contacts'; after the solve, finish_joints (writeBackJoints: applied impulse, feedback,
// breaking). Reads joints, jointState, props, invInertiaWorld, pos, rot, linVel, angVel, linVel0, angVel0,
// counters[kContactCount]. Writes jointRows, jointState, edges[contacts, contacts + joints),
// counters[kEdgeCount], w.edgeCapacity (= contact slots + joints).
#pragma once
#include "world/device_world.h"

namespace btgpu {
void prepareJoints(DeviceWorld& w, const BtgJointStepParams& params);
void finishJoints(DeviceWorld& w, const BtgJointStepParams& params);
}  // namespace btgpu
