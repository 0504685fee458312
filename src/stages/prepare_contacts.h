// prepare_contacts.h — Stage: solver rows for each contact, by btSequentialImpulseConstraint-
// Solver's rules: friction directions (btPlaneSpace of the normal), effective masses, the
// normal target velocity (restitution from linVel0/angVel0 with the restitution threshold,
// erp bias or speculative approach for separated points) and the split-impulse target.
// Targets are velocities the solver reaches against the live velocity ((target - J v) * mass),
// so this stage does not read linVel/angVel. Contacts with no dynamic body, or a no-response
// body, get zero masses and impulses (never solved).
// Each contact is also an edge of the constraint graph (edge i = contact i's bodies), which the
// batching colors and the islands walk.
// With the solver features of params.solverFlags also each contact's rolling rows
// (w.rollingContacts) and anisotropic friction directions (w.frictionDirs), else those stay one
// placeholder element; m_sor, m_globalCfm and soft contacts enter the normal and friction rows.
// softStep (the plan's solver is the soft step, which makes its own rows): where the soft step
// reads no more of this stage (no rolling rows, anisotropic directions or anchors), only the
// normal, the pair's friction and the zeroed impulses of points without rows are made
// (btgPrepareSoftContact; the soft step's answer bitwise the same: SolveSoft.ItsPrepareIsBitwiseTheFullOne).
// Reads contacts, counters, props, invInertiaWorld, rot, linVel0, angVel0, linVel, angVel.
// Writes contacts (combined friction, per-point friction directions, row masses, cfm, normal and
// push targets), rollingContacts, frictionDirs, edges[0, contacts), counters[kEdgeCount],
// w.edgeCapacity (= contact slots + joints).
#pragma once
#include "world/device_world.h"

namespace btgpu {
void prepareContacts(DeviceWorld& w, const BtgStepParams& params, bool softStep = false);
}
