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

// Substeps of a fixed step: SoftStepConfig::substeps, or m_numIterations when that is 0.
int softSubsteps(const SoftStepConfig& c, int iterations);
// The kernels' scalars for a fixed step of params.dt.
BtgSoftParams makeSoftParams(const SoftStepConfig& c, const BtgStepParams& params, int iterations);

void solveSoft(DeviceWorld& w, const BtgSoftParams& params, int numColors);
void softTransforms(DeviceWorld& w);

}  // namespace btgpu
