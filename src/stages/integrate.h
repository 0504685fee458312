// integrate.h — Stage: integrate (kernels/integrate.cl). Three launches per substep, in
// Bullet's order: predictMotion (damping) before collision detection, applyForces (gravity,
// app forces and torques, gyroscopic term; caches world inverse inertia) before the contact
// setup, integrateTransforms (split-impulse push, then velocity) after the solver.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void predictMotion(DeviceWorld& w, float dt);
// push: the solver has split-impulse passes and integrateTransforms reads pushLin/pushAng (not
// the soft step): they are held a row a body and zeroed here; else one placeholder row each.
void applyForces(DeviceWorld& w, float dt, float maxGyroscopicForce = 100.0f, bool push = true);  // m_maxGyroscopicForce
void integrateTransforms(DeviceWorld& w, float dt, float splitTurnErp);
}  // namespace btgpu
