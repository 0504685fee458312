// solve_constraints.h — Stage: batched projected Gauss–Seidel over the colored constraint
// graph (its edges: the contacts now), color by color (one launch per color per iteration;
// the last color serially). Each constraint's rows are solved as solver_rows.h rows. First
// applies the
// warm-start impulses, then `iterations` passes over normal and friction rows (friction
// clamped by friction * normal impulse), then, when params.splitImpulse, the same number of
// passes on the push velocities for the split rows.
// pushLin/pushAng are zeroed here (first numBodies rows) when params.splitImpulse. The last
// color's launch also takes any higher color, so numColors may be below what was assigned.
// With rolling friction each velocity pass ends with a sweep of the rolling rows; with
// anisotropic friction the friction rows take w.frictionDirs' directions.
// Reads edgeColor, contacts, rollingContacts, frictionDirs, props, invInertiaWorld, counters.
// Writes linVel, angVel, pushLin, pushAng (xyz of dynamic rows only), contacts (accumulated
// impulses, kept for next step's warm start), rollingContacts (their impulses).
#pragma once
#include "world/device_world.h"

namespace btgpu {
void solveConstraints(DeviceWorld& w, const BtgStepParams& params, int iterations, int numColors);
}
