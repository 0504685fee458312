// subclass_rules.h — an app's own subclass of btGpuDynamicsWorld that overrides a step hook the
// GPU path does not call (integrateTransforms, solveConstraints, ...) would be bypassed in
// silence: such a world runs on the CPU path, where every hook runs as in Bullet.
#pragma once
#include <string>

class btDiscreteDynamicsWorld;

namespace btgpu {

// "" for btGpuDynamicsWorld itself or a subclass overriding none of the hooks, else the reason
// naming the first overridden hook.
std::string subclassReason(btDiscreteDynamicsWorld& world);

}  // namespace btgpu
