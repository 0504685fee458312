// prepare_joints.cpp — host launcher of the joint stages: one work-item per joint for
// prepare_joints (rows and edges) and finish_joints (write-back values and breaks).
#include "stages/prepare_joints.h"

#include "cl/program.h"

#include <algorithm>

namespace btgpu {

void prepareJoints(DeviceWorld& w, const BtgJointStepParams& params)
{
    if (w.numJoints <= 0) return;
    // Contact slots as prepare_contacts counts them (none are filled without a contact stage:
    // the contact count is zeroed every substep).
    const int contactCapacity = int(std::min(w.contactCapacity, w.contacts.capacity()));
    const size_t edgeCapacity = size_t(contactCapacity) + size_t(w.numJoints);
    if (w.edgeCapacity != edgeCapacity || w.edges.capacity() < edgeCapacity) {
        // Only when no prepare_contacts ran before (it sizes the edges for the joints too).
        w.edgeCapacity = edgeCapacity;
        w.edges.reserveExact(w.ctx, edgeCapacity);
        w.edgeColor.reserveExact(w.ctx, edgeCapacity);
    }
    cl::Launch(w.ctx, w.ctx.program("prepare_joints").kernel("prepare_joints"), &w.profiler)
        .arg(w.joints).arg(w.jointState).arg(w.jointRows).arg(w.counters).arg(contactCapacity).arg(w.props)
        .arg(w.invInertiaWorld).arg(w.pos).arg(w.rot).arg(w.linVel).arg(w.angVel).arg(w.linVel0).arg(w.angVel0).arg(w.edges).arg(params)
        .run(size_t(w.numJoints));
}

void finishJoints(DeviceWorld& w, const BtgJointStepParams& params)
{
    if (w.numJoints <= 0) return;
    cl::Launch(w.ctx, w.ctx.program("prepare_joints").kernel("finish_joints"), &w.profiler)
        .arg(w.joints).arg(w.jointState).arg(w.jointFeedback).arg(w.jointRows).arg(w.props).arg(params)
        .run(size_t(w.numJoints));
}

}  // namespace btgpu
