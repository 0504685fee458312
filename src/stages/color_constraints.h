// color_constraints.h — Stage: GPU batching (coloring of the constraint graph). Gives every
// edge (a contact, or a constraint of another kind) a color so that no dynamic body appears
// twice in one color (static and kinematic bodies may); the coloring is a pure function of the
// edge list (deterministic). Runs `maxColors - 1` rounds on the device; edges still uncolored
// after them get color maxColors - 1, which the solver runs serially (one work-item), so no
// host round trip is needed.
// orderJoints (the bullet mode): joint j takes colour w.jointLevels[j] (stock's order of the
// joints that share a body: compat's levels, w.maxJointLevel the largest; 0 or less: none
// shares), the contacts colour around them.
// Reads edges, props (flags), counters[kEdgeCount, kContactCount], jointLevels.
// Writes edgeColor, solverScratch.bodyClaim/bodyColor, counters[kColorsUsed, kLeftovers],
// w.numColors (= maxColors).
#pragma once
#include "world/device_world.h"

namespace btgpu {
void colorConstraints(DeviceWorld& w, int maxColors, bool orderJoints = false);
}
