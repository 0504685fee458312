// step_arguments.h — the check of stepSimulation's arguments that both paths make first: an
// argument that would make Bullet's time bookkeeping overflow or run time backwards simulates
// nothing and is named in the report, instead of writing garbage into every body.
#pragma once
#include <string>

namespace btgpu {

// Longest simulated step taken (s): a fixed step, or a variable step with maxSubSteps 0.
constexpr double kMaxStepSeconds = 1e6;

// "" when stepSimulation(timeStep, maxSubSteps, fixedTimeStep) with the world's local time
// `localTime` is well-formed, else which argument is wrong and why.
std::string badStepArguments(float timeStep, int maxSubSteps, float fixedTimeStep, float localTime);

}  // namespace btgpu
