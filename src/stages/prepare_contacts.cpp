// prepare_contacts.cpp — host launcher of the prepare stage: one work-item per contact slot;
// the kernel stops at the device-side contact count. The constraint graph holds an edge slot
// per contact slot and one per joint.
#include "stages/prepare_contacts.h"

#include "cl/program.h"

#include <algorithm>

namespace btgpu {

void prepareContacts(DeviceWorld& w, const BtgStepParams& params, bool softStep)
{
    int contactCapacity = int(std::min(w.contactCapacity, w.contacts.capacity()));
    // The joints' edges follow the contacts' (prepare_joints writes them).
    w.edgeCapacity = size_t(contactCapacity) + size_t(w.numJoints);
    w.edges.reserveExact(w.ctx, w.edgeCapacity);
    w.edgeColor.reserveExact(w.ctx, w.edgeCapacity);
    // Rolling rows only for a scene with rolling friction (a placeholder element otherwise).
    const size_t rows = size_t(std::max(contactCapacity, 1));
    w.rollingContacts.reserve(w.ctx, (params.solverFlags & BTG_SOLVER_ROLLING_FRICTION) ? rows : 1);
    w.frictionDirs.reserve(w.ctx, (params.solverFlags & BTG_SOLVER_ANISOTROPIC_FRICTION) ? rows : 1);
    w.frictionAnchors.reserve(w.ctx, (params.solverFlags & BTG_SOLVER_FRICTION_ANCHORS) ? rows : 1);
    cl::Launch(w.ctx, w.ctx.program("prepare_contacts").kernel("prepare_contacts"), &w.profiler)
        .arg(w.contacts).arg(w.counters).arg(contactCapacity).arg(w.props).arg(w.invInertiaWorld).arg(w.rot)
        .arg(w.linVel0).arg(w.angVel0).arg(w.linVel).arg(w.angVel).arg(w.edges).arg(w.rollingContacts)
        .arg(w.frictionDirs).arg(w.pos).arg(w.frictionAnchors).arg(params).arg(softStep ? 1 : 0)
        .run(size_t(contactCapacity));
}

}  // namespace btgpu
