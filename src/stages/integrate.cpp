// integrate.cpp — host launchers of the integrate stage.
#include "stages/integrate.h"

#include <algorithm>

namespace btgpu {

void predictMotion(DeviceWorld& w, float dt)
{
    cl::Launch(w.ctx, w.ctx.program("integrate").kernel("predict_motion"), &w.profiler)
        .arg(w.numBodies).arg(w.props).arg(w.linVel).arg(w.angVel).arg(dt)
        .run(w.numBodies);
}

void applyForces(DeviceWorld& w, float dt, float maxGyroscopicForce, bool push)
{
    const size_t pushRows = push ? size_t(std::max(w.numBodies, 1)) : 1;
    if (!push && w.pushLin.capacity() > 1) {  // the soft step's world (Auto switched): 32 bytes a body back
        w.pushLin.release();
        w.pushAng.release();
    }
    w.pushLin.reserve(w.ctx, pushRows);
    w.pushAng.reserve(w.ctx, pushRows);
    cl::Launch(w.ctx, w.ctx.program("integrate").kernel("apply_forces"), &w.profiler)
        .arg(w.numBodies).arg(w.rot).arg(w.props).arg(w.extForce).arg(w.extTorque).arg(w.invInertiaWorld)
        .arg(w.linVel0).arg(w.angVel0).arg(w.linVel).arg(w.angVel).arg(w.pushLin).arg(w.pushAng).arg(push ? 1 : 0)
        .arg(dt).arg(maxGyroscopicForce)
        .run(w.numBodies);
}

void integrateTransforms(DeviceWorld& w, float dt, float splitTurnErp)
{
    cl::Launch(w.ctx, w.ctx.program("integrate").kernel("integrate_transforms"), &w.profiler)
        .arg(w.numBodies).arg(w.props).arg(w.linVel).arg(w.angVel).arg(w.pushLin).arg(w.pushAng)
        .arg(w.pos).arg(w.rot).arg(w.counters).arg(dt).arg(splitTurnErp)
        .run(w.numBodies);
}

}  // namespace btgpu
