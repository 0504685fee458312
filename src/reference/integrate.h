// integrate.h (reference) — CPU versions of the integrate stage's kernels, calling the same
// shared functions (kernels/shared/integrate.h), for the unit tests.
#pragma once
#include "shared/math.h"
#include "shared/types.h"

#include <vector>

namespace btgpu::reference {

struct Bodies {
    std::vector<BtgFloat4> pos, rot, linVel, angVel, extForce, extTorque, pushLin, pushAng;
    std::vector<BtgBodyProps> props;
};

void predictMotion(Bodies& b, float dt);
// Also returns the world inverse inertia rows (3 per body).
void applyForces(Bodies& b, float dt, std::vector<BtgFloat4>& invInertiaWorld, float maxGyroscopicForce = 100.0f);
void integrateTransforms(Bodies& b, float dt, float turnErp);

}  // namespace btgpu::reference
