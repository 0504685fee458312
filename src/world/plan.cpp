// plan.cpp — the plan's stage list, as the pipeline will launch it, and the choice of the
// small bodies' broadphase.
#include "world/plan.h"

#include "shared/types.h"

#include <algorithm>

namespace btgpu {

const char* stageName(Stage stage)
{
    switch (stage) {
        case Stage::Integrate: return "integrate";
        case Stage::UpdateAabbs: return "update_aabbs";
        case Stage::UniformGrid: return "uniform_grid";
        case Stage::SortSweep: return "sort_sweep";
        case Stage::FindPairs: return "find_pairs";
        case Stage::Narrowphase: return "narrowphase";
        case Stage::NarrowphaseSat: return "narrowphase_sat";
        case Stage::ApplyForces: return "apply_forces";
        case Stage::ContactCache: return "contact_cache";
        case Stage::PrepareContacts: return "prepare_contacts";
        case Stage::ColorConstraints: return "color_constraints";
        case Stage::SolveConstraints: return "solve_constraints";
        case Stage::SolveJacobi: return "solve_jacobi";
        case Stage::StoreContactCache: return "store_contact_cache";
        case Stage::IntegrateTransforms: return "integrate_transforms";
        case Stage::UpdateActivation: return "update_activation";
    }
    return "?";
}

std::vector<Stage> Plan::substep() const
{
    std::vector<Stage> s = {Stage::Integrate};
    const bool collide = kinds.any();
    if (collide) {
        s.push_back(Stage::UpdateAabbs);
        s.push_back(broadphase == Broadphase::SortAndSweep ? Stage::SortSweep : Stage::UniformGrid);
        s.push_back(Stage::FindPairs);
        if (kinds.simple()) s.push_back(Stage::Narrowphase);
        if (kinds.hullHull) s.push_back(Stage::NarrowphaseSat);
    }
    s.push_back(Stage::ApplyForces);
    if (collide) {
        s.insert(s.end(), {Stage::ContactCache, Stage::PrepareContacts});
        if (solver == SolverKind::JacobiMassSplitting) s.push_back(Stage::SolveJacobi);
        else s.insert(s.end(), {Stage::ColorConstraints, Stage::SolveConstraints});
        // Before the bodies move: the cache keys use A's rotation as the contacts were built.
        s.push_back(Stage::StoreContactCache);
    }
    s.insert(s.end(), {Stage::IntegrateTransforms, Stage::UpdateActivation});
    return s;
}

std::vector<std::string> Plan::stages() const
{
    std::vector<std::string> names = {"sync_in"};
    for (Stage stage : substep()) names.push_back(stageName(stage));
    names.push_back("sync_out");
    return names;
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

DerivedPlan derivePlan(const PlanInput& in)
{
    DerivedPlan d;
    Plan& plan = d.plan;
    plan.solver = in.solver;
    int spheres = 0, hulls = 0, planes = 0, movSpheres = 0, movHulls = 0;
    std::vector<float> sizes;
    for (size_t r = 0; r < in.bodies.size(); ++r) {
        const PlanBody& b = in.bodies[r];
        if (!b.live) continue;
        if (b.dynamic) plan.hasDynamic = true;
        if (b.gyroscopic) plan.gyroscopic = true;
        if (b.shapeType == BTG_SHAPE_SPHERE) { ++spheres; movSpheres += b.movable; }
        if (b.shapeType == BTG_SHAPE_HULL) { ++hulls; movHulls += b.movable; }
        if (b.shapeType == BTG_SHAPE_PLANE) { ++planes; d.planeRows.push_back(int(r)); }
        else sizes.push_back(b.size);
    }
    const int movable = movSpheres + movHulls;
    plan.kinds.sphereSphere = spheres >= 2 && movSpheres >= 1;
    plan.kinds.sphereHull = spheres >= 1 && hulls >= 1 && movable >= 1;
    plan.kinds.hullHull = hulls >= 2 && movHulls >= 1;
    plan.kinds.spherePlane = planes >= 1 && movSpheres >= 1;
    plan.kinds.hullPlane = planes >= 1 && movHulls >= 1;
    float median = 0.0f;
    if (!sizes.empty()) {
        std::vector<float> sorted = sizes;
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        median = sorted[sorted.size() / 2];
    }
    const float largeSize = in.largeBodyFactor * median;
    float cell = 0.0f;
    for (size_t r = 0; r < in.bodies.size(); ++r) {
        const PlanBody& b = in.bodies[r];
        if (!b.live || b.shapeType == BTG_SHAPE_PLANE) continue;
        if (b.size > largeSize) d.largeRows.push_back(int(r));
        else cell = std::max(cell, b.size);
    }
    // 1% slack: an AABB exactly one cell wide must not be missed by rounding of centre / cell.
    plan.cellSize = std::max(1.01f * (cell + 2.0f * in.contactThreshold), 1e-3f);
    plan.broadphase = chooseBroadphase(sizes, largeSize);
    plan.hasLarge = !d.largeRows.empty();
    plan.hasPlanes = !d.planeRows.empty();
    return d;
}

}  // namespace btgpu
