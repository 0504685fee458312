// prepare_contacts.h — Stage: solver rows for each contact, by btSequentialImpulseConstraint-
// Solver's rules: friction directions (btPlaneSpace of the normal), effective masses, the
// normal target velocity (restitution from linVel0/angVel0 with the restitution threshold,
// erp bias or speculative approach for separated points) and the split-impulse target.
// Reads contacts, pos, props, invInertiaWorld, linVel, angVel, linVel0, angVel0.
// Writes contacts (t1, t2, masses, targets in rA.w / rB.w, combined friction/restitution).
#pragma once
#include "world/device_world.h"

namespace btgpu {
void prepareContacts(DeviceWorld& w, const BtgStepParams& params);
}
