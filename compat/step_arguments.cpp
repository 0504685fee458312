// step_arguments.cpp — which stepSimulation arguments are refused, and why each.
#include "step_arguments.h"

#include <cmath>
#include <sstream>

namespace btgpu {

namespace {
std::string show(float v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}
}  // namespace

std::string badStepArguments(float timeStep, int maxSubSteps, float fixedTimeStep, float localTime)
{
    const std::string call = "stepSimulation(" + show(timeStep) + ", " + std::to_string(maxSubSteps) + ", " +
                             show(fixedTimeStep) + ")";
    if (!std::isfinite(timeStep)) return call + ": timeStep is not finite";
    if (timeStep < 0.0f) return call + ": timeStep is negative (time would run backwards)";
    if (maxSubSteps < 0) return call + ": maxSubSteps is negative";
    if (maxSubSteps == 0) {
        if (timeStep > kMaxStepSeconds) return call + ": a variable step of more than 1e6 s";
        return "";
    }
    if (!std::isfinite(fixedTimeStep) || fixedTimeStep <= 0.0f) return call + ": fixedTimeStep is not a positive number";
    if (fixedTimeStep > kMaxStepSeconds) return call + ": fixedTimeStep is more than 1e6 s";
    // Bullet counts the substeps as int(localTime / fixedTimeStep) in float: past INT_MAX that
    // overflows; 2^30 leaves room for the float quotient's rounding.
    if ((double(localTime) + double(timeStep)) / double(fixedTimeStep) >= 1073741824.0)
        return call + ": timeStep / fixedTimeStep overflows the substep count";
    return "";
}

}  // namespace btgpu
