// solve_jacobi.h — Stage: Jacobi with mass splitting (Tonge et al. 2012), the alternative to
// color_constraints + solve_constraints (Config::solver). Builds each dynamic body's list of
// solvable contacts, then warm start, `iterations` velocity passes and, when
// params.splitImpulse, `iterations` push passes; each pass solves every contact at once against
// copies of its bodies holding 1/n of their mass (n: the body's contact count), then sets each
// body to the average of its copies. Two launches per pass, no coloring.
// pushLin/pushAng are zeroed here (first numBodies rows) when params.splitImpulse.
// Reads contacts, props, invInertiaWorld, counters. Writes linVel, angVel, pushLin, pushAng
// (xyz of dynamic rows with contacts), contacts (accumulated impulses), solverScratch.jacobi*.
#pragma once
#include "world/device_world.h"

namespace btgpu {
void solveJacobi(DeviceWorld& w, const BtgStepParams& params, int iterations);
}
