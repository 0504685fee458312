// plan_test.cpp — the plan from Bullet-free facts about the rows (derivePlan): which pair kinds
// and stages a scene gets, in launch order, which bodies leave the grid, the cell size, and the
// Report's stage names — without a Bullet world or a device.
#include "shared/types.h"
#include "world/plan.h"

#include <algorithm>
#include <gtest/gtest.h>

using namespace btgpu;

namespace {

PlanBody body(int shape, float size, bool dynamic)
{
    PlanBody b;
    b.shapeType = shape;
    b.size = size;
    b.movable = dynamic;
    b.dynamic = dynamic;
    return b;
}

bool has(const std::vector<Stage>& stages, Stage s) { return std::find(stages.begin(), stages.end(), s) != stages.end(); }

}  // namespace

TEST(Plan, SpheresOnAPlaneLeaveOutSat)
{
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_PLANE, 0, false), body(BTG_SHAPE_SPHERE, 1, true), body(BTG_SHAPE_SPHERE, 1, true)};
    DerivedPlan d = derivePlan(in);
    EXPECT_TRUE(d.plan.kinds.has(BTG_PAIR_SPHERE_SPHERE));
    EXPECT_TRUE(d.plan.kinds.has(BTG_PAIR_SPHERE_PLANE));
    EXPECT_FALSE(d.plan.kinds.has(BTG_PAIR_HULL_HULL));
    EXPECT_FALSE(d.plan.kinds.has(BTG_PAIR_SPHERE_HULL));
    EXPECT_EQ(d.plan.kinds.count(), 2);
    EXPECT_EQ(d.planeRows, std::vector<int>{0});
    EXPECT_TRUE(d.largeRows.empty());
    const std::vector<Stage> stages = d.plan.substep();
    EXPECT_TRUE(has(stages, Stage::Narrowphase));
    EXPECT_FALSE(has(stages, Stage::NarrowphaseSat));
    const std::vector<std::string> names = d.plan.stages();
    EXPECT_EQ(names.front(), "sync_in");
    EXPECT_EQ(names.back(), "sync_out");
    EXPECT_EQ(names.size(), stages.size() + 2);
}

TEST(Plan, StagesInTheTalksOrder)
{
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_BOX, 100, false), body(BTG_SHAPE_BOX, 1, true), body(BTG_SHAPE_BOX, 1, true)};
    const std::vector<Stage> expected = {
        Stage::Integrate,   Stage::UpdateAabbs,      Stage::UniformGrid,       Stage::FindPairs,
        Stage::NarrowphaseSat, Stage::ApplyForces,   Stage::ContactCache,      Stage::PrepareContacts,
        Stage::ColorConstraints, Stage::SolveConstraints, Stage::StoreContactCache, Stage::StorePersistentManifolds,
        Stage::IntegrateTransforms, Stage::UpdateActivation};
    EXPECT_EQ(derivePlan(in).plan.substep(), expected);
    in.solver = SolverKind::JacobiMassSplitting;
    const std::vector<Stage> jacobi = derivePlan(in).plan.substep();
    EXPECT_TRUE(has(jacobi, Stage::SolveJacobi));
    EXPECT_FALSE(has(jacobi, Stage::ColorConstraints));
    EXPECT_FALSE(has(jacobi, Stage::SolveConstraints));
}

TEST(Plan, ConvexShapesBringTheGjkStagesAndNothingElseDoes)
{
    // A sphere and boxes: no GJK program (sphere-box pairs are closed form); two boxes keep a
    // persistent manifold (stock's box detector), so the store comes with the box program.
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_SPHERE, 0, false), body(BTG_SHAPE_BOX, 1, true)};
    std::vector<Stage> stages = derivePlan(in).plan.substep();
    EXPECT_FALSE(has(stages, Stage::NarrowphaseGjk));
    EXPECT_FALSE(has(stages, Stage::StorePersistentManifolds));
    // Two spheres take stock's sphere-sphere algorithm in the GJK program, with its state buffers (the
    // bullet mode); the soft step collides them afresh and keeps nothing.
    in.bodies.push_back(body(BTG_SHAPE_SPHERE, 1, true));
    stages = derivePlan(in).plan.substep();
    EXPECT_TRUE(has(stages, Stage::NarrowphaseGjk));
    EXPECT_TRUE(has(stages, Stage::StorePersistentManifolds));
    in.solver = SolverKind::SoftStep;
    stages = derivePlan(in).plan.substep();
    EXPECT_TRUE(has(stages, Stage::NarrowphaseGjk));
    EXPECT_FALSE(has(stages, Stage::StorePersistentManifolds));
    in.solver = PlanInput{}.solver;
    in.bodies = {body(BTG_SHAPE_BOX, 0, false), body(BTG_SHAPE_SPHERE, 1, true), body(BTG_SHAPE_BOX, 1, true)};
    stages = derivePlan(in).plan.substep();
    EXPECT_FALSE(has(stages, Stage::NarrowphaseGjk));
    EXPECT_TRUE(has(stages, Stage::NarrowphaseSat));
    EXPECT_TRUE(has(stages, Stage::StorePersistentManifolds));
    // A capsule (a convex row) arrives: its pairs with the box, the sphere and the ground box
    // are GJK kinds; the store follows the cache's.
    in.bodies.push_back(body(BTG_SHAPE_CONVEX, 1, true));
    DerivedPlan d = derivePlan(in);
    EXPECT_TRUE(d.plan.kinds.has(BTG_PAIR_CONVEX_BOX));
    EXPECT_TRUE(d.plan.kinds.has(BTG_PAIR_SPHERE_CONVEX));
    EXPECT_FALSE(d.plan.kinds.has(BTG_PAIR_CONVEX_CONVEX));
    stages = d.plan.substep();
    ASSERT_TRUE(has(stages, Stage::NarrowphaseGjk));
    auto at = [&](Stage st) { return std::find(stages.begin(), stages.end(), st) - stages.begin(); };
    EXPECT_EQ(at(Stage::StorePersistentManifolds), at(Stage::StoreContactCache) + 1);
    EXPECT_LT(at(Stage::NarrowphaseGjk), at(Stage::ContactCache));
}

TEST(Plan, TheSoftStepKeepsPersistentManifoldsForGjkPairsOnly)
{
    // The soft step collides two boxes (and convex–mesh pairs) afresh every substep: nothing to
    // store for them. GJK pairs keep stock's persistent manifold in both solvers.
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_BOX, 0, false), body(BTG_SHAPE_BOX, 1, true), body(BTG_SHAPE_BOX, 1, true)};
    in.solver = SolverKind::SoftStep;
    EXPECT_FALSE(has(derivePlan(in).plan.substep(), Stage::StorePersistentManifolds));
    EXPECT_FALSE(keepsPersistentManifolds(derivePlan(in).plan.kinds, true));
    in.solver = SolverKind::BatchedPgs;
    EXPECT_TRUE(has(derivePlan(in).plan.substep(), Stage::StorePersistentManifolds));
    in.solver = SolverKind::SoftStep;
    in.bodies.push_back(body(BTG_SHAPE_CONVEX, 1, true));
    EXPECT_TRUE(has(derivePlan(in).plan.substep(), Stage::StorePersistentManifolds));
    EXPECT_TRUE(keepsPersistentManifolds(derivePlan(in).plan.kinds, true));
}

TEST(Plan, PairsFollowStocksAlgorithmChoice)
{
    // Stock clips two boxes (btBoxBoxDetector) and two hulls with polyhedral features; a box
    // meets such a hull, and anything meets a plane, through GJK or the plane's support point.
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_BOX, 1, true), body(BTG_SHAPE_BOX, 1, true)};
    DerivedPlan d = derivePlan(in);
    EXPECT_TRUE(d.plan.kinds.has(BTG_PAIR_BOX_BOX));
    EXPECT_TRUE(has(d.plan.substep(), Stage::NarrowphaseSat));
    EXPECT_FALSE(has(d.plan.substep(), Stage::NarrowphaseGjk));
    in.bodies.push_back(body(BTG_SHAPE_PLANE, 0, false));
    d = derivePlan(in);
    EXPECT_TRUE(d.plan.kinds.has(BTG_PAIR_PLANE_BOX));
    EXPECT_TRUE(has(d.plan.substep(), Stage::NarrowphaseGjk));
    in.bodies = {body(BTG_SHAPE_HULL, 1, true), body(BTG_SHAPE_HULL, 1, true), body(BTG_SHAPE_BOX, 10, false)};
    d = derivePlan(in);
    EXPECT_TRUE(d.plan.kinds.has(BTG_PAIR_HULL_HULL));
    EXPECT_TRUE(d.plan.kinds.has(BTG_PAIR_HULL_BOX));
    EXPECT_FALSE(has(d.plan.substep(), Stage::NarrowphaseSat));  // featured hull pairs: GJK, then clipping
    EXPECT_TRUE(has(d.plan.substep(), Stage::NarrowphaseGjk));
}

TEST(Plan, NothingToCollideRunsOnlyTheIntegrator)
{
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_HULL, 1, false), body(BTG_SHAPE_SPHERE, 1, false)};
    const std::vector<Stage> expected = {Stage::Integrate, Stage::ApplyForces, Stage::IntegrateTransforms,
                                         Stage::UpdateActivation};
    DerivedPlan d = derivePlan(in);
    EXPECT_FALSE(d.plan.kinds.any());
    EXPECT_FALSE(d.plan.hasDynamic);
    EXPECT_EQ(d.plan.substep(), expected);
}

TEST(Plan, JointsAddTheirStagesAroundTheSolve)
{
    // A lone pendulum: nothing to collide, but joints to solve.
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_SPHERE, 1, true)};
    in.numJoints = 1;
    const std::vector<Stage> alone = {Stage::Integrate,        Stage::ApplyForces,   Stage::PrepareJoints,
                                      Stage::ColorConstraints, Stage::SolveConstraints, Stage::FinishJoints,
                                      Stage::IntegrateTransforms, Stage::UpdateActivation};
    EXPECT_EQ(derivePlan(in).plan.substep(), alone);
    // With contacts: the joints' rows after the contacts', one batching and solve for both.
    in.bodies = {body(BTG_SHAPE_BOX, 100, false), body(BTG_SHAPE_BOX, 1, true), body(BTG_SHAPE_BOX, 1, true)};
    const std::vector<Stage> both = {
        Stage::Integrate,     Stage::UpdateAabbs,      Stage::UniformGrid,      Stage::FindPairs,
        Stage::NarrowphaseSat, Stage::ApplyForces,     Stage::ContactCache,     Stage::PrepareContacts,
        Stage::PrepareJoints, Stage::ColorConstraints, Stage::SolveConstraints, Stage::FinishJoints,
        Stage::StoreContactCache, Stage::StorePersistentManifolds, Stage::IntegrateTransforms, Stage::UpdateActivation};
    EXPECT_EQ(derivePlan(in).plan.substep(), both);
    const std::vector<std::string> names = derivePlan(in).plan.stages();
    EXPECT_NE(std::find(names.begin(), names.end(), "prepare_joints"), names.end());
    // Joints are PGS rows: no Jacobi stage with joints (the CPU-path rules refuse the pair).
    in.solver = SolverKind::JacobiMassSplitting;
    EXPECT_FALSE(has(derivePlan(in).plan.substep(), Stage::SolveJacobi));
    in.numJoints = 0;
    EXPECT_FALSE(has(derivePlan(in).plan.substep(), Stage::PrepareJoints));
}

TEST(Plan, LargeBodiesLeaveTheGridAndTheCellFitsTheRest)
{
    PlanInput in;
    in.contactThreshold = 0.02f;
    in.bodies = {body(BTG_SHAPE_HULL, 200, false)};
    for (int i = 0; i < 10; ++i) in.bodies.push_back(body(BTG_SHAPE_HULL, i == 3 ? 1.5f : 1.0f, true));
    DerivedPlan d = derivePlan(in);
    EXPECT_EQ(d.largeRows, std::vector<int>{0});
    EXPECT_TRUE(d.plan.hasLarge);
    EXPECT_FLOAT_EQ(d.plan.cellSize, 1.01f * (1.5f + 2.0f * 0.02f));
    EXPECT_EQ(d.plan.broadphase, Broadphase::UniformGrid);
}

TEST(Plan, DebrisAmongCratesSweeps)
{
    PlanInput in;
    // Three crates of 2 m (within 4x the median, so still gridded) among 97 pieces of 0.5 m.
    for (int i = 0; i < 100; ++i) in.bodies.push_back(body(BTG_SHAPE_HULL, i < 3 ? 2.0f : 0.5f, true));
    EXPECT_EQ(derivePlan(in).plan.broadphase, Broadphase::SortAndSweep);
    std::vector<Stage> stages = derivePlan(in).plan.substep();
    EXPECT_TRUE(has(stages, Stage::SortSweep));
    EXPECT_FALSE(has(stages, Stage::UniformGrid));
}

// The pair-kind table: every pair of shape kinds reaches exactly one row or none, in either
// order; every row's program is a narrowphase program; ids are unique and within range.
TEST(Plan, PairKindTableCoversEachShapePairOnce)
{
    std::vector<int> seen(BTG_NUM_PAIR_KINDS, 0);
    for (int r = 0; r < kNumPairKindRows; ++r) {
        const PairKindRow& row = kPairKindRows[r];
        ASSERT_GT(row.kind, BTG_PAIR_NONE);
        ASSERT_LT(row.kind, BTG_NUM_PAIR_KINDS);
        EXPECT_EQ(++seen[size_t(row.kind)], 1) << "kind " << row.kind << " listed twice";
        EXPECT_LE(row.shapeA, row.shapeB);
        EXPECT_EQ(btgPairKind(row.shapeA, row.shapeB), row.kind);
        EXPECT_EQ(btgPairKind(row.shapeB, row.shapeA), row.kind);
        EXPECT_EQ(pairKindRow(row.kind), &row);
        bool known = false;
        for (int p = 0; p < kNumNarrowphasePrograms; ++p) known |= std::string(kNarrowphasePrograms[p].program) == row.program;
        EXPECT_TRUE(known) << row.kernel << " in unknown program " << row.program;
    }
    int rows = 0;
    for (int a = 0; a < BTG_NUM_SHAPE_KINDS; ++a)
        for (int b = a; b < BTG_NUM_SHAPE_KINDS; ++b) rows += btgPairKind(a, b) != BTG_PAIR_NONE;
    EXPECT_EQ(rows, kNumPairKindRows);
    EXPECT_EQ(btgPairKind(BTG_SHAPE_PLANE, BTG_SHAPE_PLANE), BTG_PAIR_NONE);
}

// Each row becomes a kind of the plan as soon as its two shapes occur and one can move; the
// stages are the programs holding those kinds.
TEST(Plan, KindsComeFromTheTable)
{
    for (int r = 0; r < kNumPairKindRows; ++r) {
        const PairKindRow& row = kPairKindRows[r];
        PlanInput in;
        in.bodies = {body(row.shapeA, 1, false), body(row.shapeB, 1, true)};
        DerivedPlan d = derivePlan(in);
        EXPECT_EQ(d.plan.kinds.mask, 1u << row.kind) << row.kernel;
        for (int p = 0; p < kNumNarrowphasePrograms; ++p)
            EXPECT_EQ(has(d.plan.substep(), kNarrowphasePrograms[p].stage),
                      std::string(kNarrowphasePrograms[p].program) == row.program)
                << row.kernel;
        in.bodies[1].movable = in.bodies[1].dynamic = false;
        EXPECT_FALSE(derivePlan(in).plan.kinds.any()) << row.kernel << ": nothing can move";
    }
}

TEST(Plan, MeshesBringTheMidphaseAndNothingElseDoes)
{
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_BOX, 100, false), body(BTG_SHAPE_BOX, 1, true), body(BTG_SHAPE_SPHERE, 1, true)};
    Plan plain = derivePlan(in).plan;
    EXPECT_FALSE(has(plain.substep(), Stage::Midphase));
    EXPECT_FALSE(has(plain.substep(), Stage::NarrowphaseMesh));
    EXPECT_FALSE(plain.kinds.anyIn("narrowphase_mesh"));
    // A static mesh ground under a box and a sphere: both mesh kinds, the midphase right after
    // the pairs and the triangles' narrowphase after the convex programs.
    in.bodies.push_back(body(BTG_SHAPE_MESH, 200, false));
    Plan mesh = derivePlan(in).plan;
    EXPECT_TRUE(mesh.kinds.has(BTG_PAIR_SPHERE_MESH));
    EXPECT_TRUE(mesh.kinds.has(BTG_PAIR_BOX_MESH));
    const std::vector<Stage> s = mesh.substep();
    auto at = [&](Stage st) { return std::find(s.begin(), s.end(), st) - s.begin(); };
    ASSERT_TRUE(has(s, Stage::Midphase));
    ASSERT_TRUE(has(s, Stage::NarrowphaseMesh));
    EXPECT_EQ(at(Stage::Midphase), at(Stage::FindPairs) + 1);
    EXPECT_GT(at(Stage::NarrowphaseMesh), at(Stage::Narrowphase));
    EXPECT_GT(at(Stage::NarrowphaseMesh), at(Stage::NarrowphaseSat));
    EXPECT_LT(at(Stage::NarrowphaseMesh), at(Stage::ContactCache));
    // Only spheres on the mesh: no hull–mesh kind, and two static meshes meet nothing.
    in.bodies = {body(BTG_SHAPE_MESH, 200, false), body(BTG_SHAPE_MESH, 200, false), body(BTG_SHAPE_SPHERE, 1, true)};
    Plan spheres = derivePlan(in).plan;
    EXPECT_TRUE(spheres.kinds.has(BTG_PAIR_SPHERE_MESH));
    EXPECT_FALSE(spheres.kinds.has(BTG_PAIR_HULL_MESH));
    EXPECT_TRUE(has(spheres.substep(), Stage::Midphase));
}

TEST(Plan, CompoundsBringExpandCompoundsAndTheirLeavesKinds)
{
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_BOX, 100, false), body(BTG_SHAPE_SPHERE, 1, true)};
    EXPECT_FALSE(has(derivePlan(in).plan.substep(), Stage::ExpandCompounds));
    // A dynamic compound of boxes and spheres on the ground box: its pairs are its leaves', so
    // box-box and sphere-box are in the plan although no body's own shape gives box-box.
    in.bodies = {body(BTG_SHAPE_BOX, 100, false), body(BTG_SHAPE_COMPOUND, 2, true)};
    in.bodies[1].leafKinds = 1u << BTG_SHAPE_BOX | 1u << BTG_SHAPE_SPHERE;
    const Plan p = derivePlan(in).plan;
    EXPECT_TRUE(p.hasCompounds);
    EXPECT_TRUE(p.kinds.has(BTG_PAIR_BOX_BOX));
    EXPECT_TRUE(p.kinds.has(BTG_PAIR_SPHERE_BOX));
    EXPECT_FALSE(p.kinds.has(BTG_PAIR_SPHERE_SPHERE));  // one compound's leaves never meet each other
    const std::vector<Stage> s = p.substep();
    auto at = [&](Stage st) { return std::find(s.begin(), s.end(), st) - s.begin(); };
    ASSERT_TRUE(has(s, Stage::ExpandCompounds));
    EXPECT_EQ(at(Stage::ExpandCompounds), at(Stage::FindPairs) + 1);
    EXPECT_LT(at(Stage::ExpandCompounds), at(Stage::Narrowphase));
}

// The contact report (Config::fillDispatcherManifolds): only when asked for and when anything
// collides, after the cache store, before the bodies move.
TEST(Plan, ContactReportOnlyWhenAskedBeforeTheBodiesMove)
{
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_BOX, 100, false), body(BTG_SHAPE_BOX, 1, true)};
    Plan p = derivePlan(in).plan;
    EXPECT_FALSE(has(p.substep(), Stage::ReportContacts));
    p.reportContacts = true;
    const std::vector<Stage> s = p.substep();
    auto at = [&](Stage x) { return std::find(s.begin(), s.end(), x) - s.begin(); };
    ASSERT_TRUE(has(s, Stage::ReportContacts));
    EXPECT_EQ(at(Stage::ReportContacts), at(Stage::StorePersistentManifolds) + 1);
    EXPECT_EQ(at(Stage::StorePersistentManifolds), at(Stage::StoreContactCache) + 1);
    EXPECT_LT(at(Stage::ReportContacts), at(Stage::IntegrateTransforms));
    const std::vector<std::string> names = p.stages();
    EXPECT_NE(std::find(names.begin(), names.end(), "report_contacts"), names.end());
    in.bodies = {body(BTG_SHAPE_BOX, 1, true)};  // nothing to collide
    Plan alone = derivePlan(in).plan;
    alone.reportContacts = true;
    EXPECT_FALSE(has(alone.substep(), Stage::ReportContacts));
}

TEST(Plan, ContactCallbacksRightAfterTheContactsArePrepared)
{
    PlanInput in;
    in.bodies = {body(BTG_SHAPE_BOX, 100, false), body(BTG_SHAPE_BOX, 1, true)};
    Plan p = derivePlan(in).plan;
    EXPECT_FALSE(has(p.substep(), Stage::ContactCallbacks));
    p.contactCallbacks = true;
    const std::vector<Stage> s = p.substep();
    auto at = [&](Stage x) { return std::find(s.begin(), s.end(), x) - s.begin(); };
    ASSERT_TRUE(has(s, Stage::ContactCallbacks));
    // The host's callbacks run between the contacts found and the contact list (runSubstep splits
    // at ContactCache); their materials are applied to the prepared rows, before any solve.
    EXPECT_EQ(at(Stage::ContactCallbacks), at(Stage::PrepareContacts) + 1);
    EXPECT_LT(at(Stage::ApplyForces), at(Stage::ContactCache));
    const std::vector<std::string> names = p.stages();
    EXPECT_NE(std::find(names.begin(), names.end(), "contact_callbacks"), names.end());
}
