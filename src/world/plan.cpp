// plan.cpp — the plan's stage list, as the pipeline will launch it, the pair kinds a scene has
// (from the pair-kind table), and the choice of the small bodies' broadphase.
#include "world/plan.h"

#include "shared/types.h"

#include <algorithm>

namespace btgpu {

const char* stageName(Stage stage)
{
    switch (stage) {
        case Stage::Integrate: return "integrate";
        case Stage::BroadphaseLeaves: return "broadphase_leaves";
        case Stage::UpdateAabbs: return "update_aabbs";
        case Stage::UniformGrid: return "uniform_grid";
        case Stage::SortSweep: return "sort_sweep";
        case Stage::FindPairs: return "find_pairs";
        case Stage::ExpandCompounds: return "expand_compounds";
        case Stage::Midphase: return "midphase";
        case Stage::Narrowphase: return "narrowphase";
        case Stage::NarrowphaseSat: return "narrowphase_sat";
        case Stage::NarrowphaseGjk: return "narrowphase_gjk";
        case Stage::NarrowphaseMesh: return "narrowphase_mesh";
        case Stage::FilterPairs: return "filter_pairs";
        case Stage::ApplyForces: return "apply_forces";
        case Stage::ContactCache: return "contact_cache";
        case Stage::PrepareContacts: return "prepare_contacts";
        case Stage::ContactCallbacks: return "contact_callbacks";
        case Stage::PrepareJoints: return "prepare_joints";
        case Stage::FinishJoints: return "finish_joints";
        case Stage::ColorConstraints: return "color_constraints";
        case Stage::SolveConstraints: return "solve_constraints";
        case Stage::SolveJacobi: return "solve_jacobi";
        case Stage::SolveSoft: return "solve_soft";
        case Stage::StoreContactCache: return "store_contact_cache";
        case Stage::StorePersistentManifolds: return "store_persistent_manifolds";
        case Stage::ReportContacts: return "report_contacts";
        case Stage::IntegrateTransforms: return "integrate_transforms";
        case Stage::SoftTransforms: return "soft_transforms";
        case Stage::UpdateActivation: return "update_activation";
    }
    return "?";
}

const NarrowphaseProgram kNarrowphasePrograms[] = {{"narrowphase", Stage::Narrowphase},
                                                   {"narrowphase_sat", Stage::NarrowphaseSat},
                                                   {"narrowphase_gjk", Stage::NarrowphaseGjk},
                                                   {"narrowphase_mesh", Stage::NarrowphaseMesh}};
const int kNumNarrowphasePrograms = int(sizeof(kNarrowphasePrograms) / sizeof(kNarrowphasePrograms[0]));

const char* narrowphaseProgramOf(Stage stage)
{
    for (int p = 0; p < kNumNarrowphasePrograms; ++p)
        if (kNarrowphasePrograms[p].stage == stage) return kNarrowphasePrograms[p].program;
    return nullptr;
}

std::vector<Stage> Plan::substep() const
{
    std::vector<Stage> s = {Stage::Integrate};
    // Right after the damping, as stock's predictUnconstraintMotion precedes its AABB update.
    if (broadphaseLeaves) s.push_back(Stage::BroadphaseLeaves);
    const bool collide = kinds.any();
    if (collide) {
        s.push_back(Stage::UpdateAabbs);
        s.push_back(broadphase == Broadphase::SortAndSweep ? Stage::SortSweep : Stage::UniformGrid);
        s.push_back(Stage::FindPairs);
        if (hasCompounds) s.push_back(Stage::ExpandCompounds);
        if (kinds.anyIn("narrowphase_mesh")) s.push_back(Stage::Midphase);
        for (int p = 0; p < kNumNarrowphasePrograms; ++p)
            if (kinds.anyIn(kNarrowphasePrograms[p].program)) s.push_back(kNarrowphasePrograms[p].stage);
        if (hasIgnoredPairs) s.push_back(Stage::FilterPairs);
    }
    s.push_back(Stage::ApplyForces);
    if (collide || hasJoints) {
        if (collide) s.insert(s.end(), {Stage::ContactCache, Stage::PrepareContacts});
        if (collide && contactCallbacks) s.push_back(Stage::ContactCallbacks);
        // Joints are PGS rows: the Jacobi solver takes contacts only (the CPU-path rules send a
        // Jacobi world with joints away).
        if (hasJoints) s.push_back(Stage::PrepareJoints);
        if (solver == SolverKind::JacobiMassSplitting && !hasJoints) s.push_back(Stage::SolveJacobi);
        else if (solver == SolverKind::SoftStep) s.insert(s.end(), {Stage::ColorConstraints, Stage::SolveSoft});
        else s.insert(s.end(), {Stage::ColorConstraints, Stage::SolveConstraints});
        if (hasJoints) s.push_back(Stage::FinishJoints);
        // Before the bodies move: the cache keys use A's rotation as the contacts were built.
        if (collide) {
            s.push_back(Stage::StoreContactCache);
            if (keepsPersistentManifolds(kinds, solver == SolverKind::SoftStep)) s.push_back(Stage::StorePersistentManifolds);
            if (reportContacts) s.push_back(Stage::ReportContacts);
        }
    }
    // The soft step moves the bodies through its substeps: its deltas give the poses.
    const bool soft = solver == SolverKind::SoftStep && (collide || hasJoints);
    s.insert(s.end(), {soft ? Stage::SoftTransforms : Stage::IntegrateTransforms, Stage::UpdateActivation});
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
    plan.hasJoints = in.numJoints > 0;
    // Per shape kind: bodies, and bodies that can move.
    int count[BTG_NUM_SHAPE_KINDS] = {}, moving[BTG_NUM_SHAPE_KINDS] = {};
    std::vector<float> sizes;
    for (size_t r = 0; r < in.bodies.size(); ++r) {
        const PlanBody& b = in.bodies[r];
        if (!b.live) continue;
        if (b.dynamic) plan.hasDynamic = true;
        if (b.gyroscopic) plan.gyroscopic = true;
        if (b.shapeType == BTG_SHAPE_COMPOUND) {
            // Its pairs are its leaves' pairs: each leaf kind counts as a body of that kind.
            plan.hasCompounds = true;
            for (int k = 0; k < BTG_NUM_SHAPE_KINDS; ++k)
                if (b.leafKinds >> k & 1u) {
                    ++count[k];
                    moving[k] += b.movable;
                }
        } else if (b.shapeType >= 0 && b.shapeType < BTG_NUM_SHAPE_KINDS) {
            ++count[b.shapeType];
            moving[b.shapeType] += b.movable;
        }
        if (b.shapeType == BTG_SHAPE_PLANE) d.planeRows.push_back(int(r));
        else sizes.push_back(b.size);
    }
    for (int k = 0; k < kNumPairKindRows; ++k) {
        const PairKindRow& row = kPairKindRows[k];
        const bool same = row.shapeA == row.shapeB;
        const bool bodies = same ? count[row.shapeA] >= 2 : count[row.shapeA] >= 1 && count[row.shapeB] >= 1;
        const int movers = moving[row.shapeA] + (same ? 0 : moving[row.shapeB]);
        if (bodies && movers >= 1) plan.kinds.add(row.kind);
    }
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
