// plan.h — what this scene needs: which pair kinds exist, which stages run. Derived from the
// scene by compat/ (recomputed when bodies or shapes come and go); the pipeline builds,
// allocates and launches only what the plan names.
#pragma once
#include <btgpu/Config.h>

#include <string>
#include <vector>

namespace btgpu {

struct PairKinds {
    bool sphereSphere = false;
    bool sphereHull = false;
    bool spherePlane = false;
    bool hullPlane = false;
    bool hullHull = false;  // needs the SAT + clipping program
    bool any() const { return sphereSphere || sphereHull || spherePlane || hullPlane || hullHull; }
    bool simple() const { return sphereSphere || sphereHull || spherePlane || hullPlane; }
};

struct Plan {
    PairKinds kinds;
    bool hasDynamic = false;   // anything to integrate
    bool hasLarge = false;     // bodies outside the uniform grid
    bool hasPlanes = false;
    bool gyroscopic = false;   // some body asks for the implicit gyroscopic term
    SolverKind solver = SolverKind::BatchedPgs;  // Config::solver: which solve stages run
    float cellSize = 1.0f;     // m: uniform grid cell, >= the largest small body's AABB extent
    // Names of the stages the step launches, in order (visible through Report).
    std::vector<std::string> stages() const;
};

}  // namespace btgpu
