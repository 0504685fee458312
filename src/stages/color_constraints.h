// color_constraints.h — Stage: GPU batching (graph coloring). Gives every contact a color so
// that no dynamic body appears twice in one color (static and kinematic bodies may); the
// coloring is a pure function of the contact list (deterministic). Runs `maxColors - 1`
// rounds on the device; contacts still uncolored after them get color maxColors - 1, which
// the solver runs serially (one work-item), so no host round trip is needed.
// Reads contacts (bodyA, bodyB), props (flags), counters[kContactCount].
// Writes contacts.color, solverScratch.bodyClaim, w.numColors (= maxColors).
#pragma once
#include "world/device_world.h"

namespace btgpu {
void colorConstraints(DeviceWorld& w, int maxColors);
}
