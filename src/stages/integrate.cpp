// integrate.cpp — host launchers of the integrate stage.
#include "stages/integrate.h"

namespace btgpu {

void predictMotion(DeviceWorld& w, float dt)
{
    cl::Launch(w.ctx, w.ctx.program("integrate").kernel("predict_motion"), &w.profiler)
        .arg(w.numBodies).arg(w.props).arg(w.linVel).arg(w.angVel).arg(dt)
        .run(w.numBodies);
}

void applyForces(DeviceWorld& w, float dt, float maxGyroscopicForce)
{
    cl::Launch(w.ctx, w.ctx.program("integrate").kernel("apply_forces"), &w.profiler)
        .arg(w.numBodies).arg(w.rot).arg(w.props).arg(w.extForce).arg(w.extTorque).arg(w.invInertiaWorld)
        .arg(w.linVel0).arg(w.angVel0).arg(w.linVel).arg(w.angVel).arg(w.pushLin).arg(w.pushAng).arg(dt)
        .arg(maxGyroscopicForce)
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
