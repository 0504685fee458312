// solve_soft.h — Stage: the soft step (SolverKind::SoftStep, kernels/solve_soft.cl): the
// solve of a fixed step as Box2D v3's substeps over the colored graph of contacts and joints,
// and, after the contact cache is stored, the bodies' poses from the substeps' deltas (in place
// of integrate_transforms). Reads edgeColor, contacts, jointRows, props, invInertiaWorld,
// linVel0, angVel0, linVel, angVel, counters. Writes linVel, angVel, contacts (impulses,
// tangents), jointRows (impulses), the soft scratch, and (softTransforms) pos, rot.
#pragma once
#include "world/device_world.h"

#include <btgpu/Config.h>

namespace btgpu {

// Substeps of a fixed step: SoftStepConfig::substeps; when that is 0, m_numIterations, raised
// to what the largest mass ratio of the step's edges (massRatio) needs.
int softSubsteps(const SoftStepConfig& c, int iterations, float massRatio = 0.0f);
// The fastest the soft contacts push a penetration apart: c.pushSpeed, or where it is 0 what
// stock's solver info gives (m_erp x |m_splitImpulsePenetrationThreshold| / dt with split
// impulse on, else Box2D's 3 m/s).
float pushSpeedFor(const SoftStepConfig& c, const BtgStepParams& params);
// The kernels' scalars for a fixed step of params.dt at softSubsteps(c, iterations); the stage
// raises them to what this step's mass ratio needs (btgSoftSubstepsFor).
BtgSoftParams makeSoftParams(const SoftStepConfig& c, const BtgStepParams& params, int iterations);

// Takes more substeps than params' where the step's edges need them (btgSoftSubstepsFor).
void solveSoft(DeviceWorld& w, BtgSoftParams params, int numColors);
void softTransforms(DeviceWorld& w);

}  // namespace btgpu
