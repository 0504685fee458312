// plan.cpp — the plan's stage list, as the pipeline will launch it, and the choice of the
// small bodies' broadphase.
#include "world/plan.h"

#include <algorithm>

namespace btgpu {

std::vector<std::string> Plan::stages() const
{
    std::vector<std::string> s = {"sync_in", "integrate"};
    if (kinds.any()) {
        s.push_back("update_aabbs");
        // The small bodies' pass, then the rest of find_pairs (large, planes, pair sort).
        s.push_back(broadphase == Broadphase::SortAndSweep ? "sort_sweep" : "uniform_grid");
        s.push_back("find_pairs");
        if (kinds.simple()) s.push_back("narrowphase");
        if (kinds.hullHull) s.push_back("narrowphase_sat");
        s.insert(s.end(), {"contact_cache", "prepare_contacts"});
        if (solver == SolverKind::JacobiMassSplitting) s.push_back("solve_jacobi");
        else s.insert(s.end(), {"color_constraints", "solve_constraints"});
    }
    s.insert(s.end(), {"integrate_transforms", "update_activation", "sync_out"});
    return s;
}

Broadphase chooseBroadphase(const std::vector<float>& sizes, float largeSize)
{
    float largest = 0.0f;
    for (float s : sizes)
        if (s <= largeSize) largest = std::max(largest, s);
    if (largest <= 0.0f) return Broadphase::UniformGrid;
    // A fill statistic rather than largest / smallest: one pebble among a thousand crates does
    // not make the grid worse, while a wide spread of sizes leaves most of each cell empty.
    double fill = 0.0;
    size_t count = 0;
    for (float s : sizes) {
        if (s > largeSize) continue;
        double f = double(s) / double(largest);
        fill += f * f * f;
        ++count;
    }
    return fill < kSweepFill * double(count) ? Broadphase::SortAndSweep : Broadphase::UniformGrid;
}

}  // namespace btgpu
