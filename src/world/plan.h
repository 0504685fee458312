// plan.h — what this scene needs: which pair kinds exist (rows of the pair-kind table,
// world/pair_kinds.h), which stages run. Derived from the scene by compat/ (recomputed when
// bodies or shapes come and go); the pipeline builds, allocates and launches only what the
// plan names.
#pragma once
#include "world/pair_kinds.h"

#include <btgpu/Config.h>

#include <string>
#include <vector>

namespace btgpu {

// How the small bodies (neither large nor planes) are paired. The grid's cell must hold the
// largest of them, so when sizes differ a lot most cells hold much more than a body and the
// grid scans many far-apart neighbours; the sweep's cost does not depend on the largest size.
enum class Broadphase { UniformGrid, SortAndSweep };

// One stage of a substep, as the pipeline launches it (Box2D's b2SolverStage list): the plan
// lists them in order, runSubstep runs them, Report::stages and the per-stage profile are
// named by stageName.
enum class Stage {
    Integrate,            // damping and the predicted motion (predictMotion)
    BroadphaseLeaves,     // stock's Dbvt leaves and their pairs (the fill's empty manifolds only)
    UpdateAabbs,
    UniformGrid,          // small bodies' pairs, by grid ...
    SortSweep,            // ... or by sort-and-sweep
    FindPairs,            // large and plane passes, pair sort
    ExpandCompounds,      // pairs with a compound side become their leaves' pairs (scenes with compounds only)
    Midphase,             // convex–mesh pairs split into (convex, triangle) sub-pairs by BVH walk
    Narrowphase,          // the pair kinds of program "narrowphase" (no SAT)
    NarrowphaseSat,       // those of "narrowphase_sat" (box-box)
    NarrowphaseGjk,       // those of "narrowphase_gjk" (support-function convex shapes)
    NarrowphaseMesh,      // those of "narrowphase_mesh" (convex against triangles)
    FilterPairs,          // pairs that ignore each other's collision check lose their contacts
    ApplyForces,          // gravity, app forces, gyroscopic term
    ContactCache,         // contact list and warm start
    PrepareContacts,
    ContactCallbacks,     // contacts prepared again with what the app's contact callbacks set (contact_callbacks)
    PrepareJoints,        // joint rows and edges (scenes with joints only)
    ColorConstraints,
    SolveConstraints,
    SolveJacobi,
    SolveSoft,            // the soft step's substeps (SolverKind::SoftStep), poses kept as deltas
    FinishJoints,         // applied impulses, feedback, breaks
    StoreContactCache,
    StorePersistentManifolds,  // the box and GJK kinds' manifolds beside the cache
    ReportContacts,       // the contacts packed for the app's dispatcher (last substep of a call only)
    IntegrateTransforms,
    SoftTransforms,       // the soft step's poses from its deltas (in place of integrate_transforms)
    UpdateActivation,
};
const char* stageName(Stage stage);

// The narrowphase programs of the pair-kind table, in launch order, and the stage of each.
struct NarrowphaseProgram {
    const char* program;
    Stage stage;
};
extern const NarrowphaseProgram kNarrowphasePrograms[];
extern const int kNumNarrowphasePrograms;
// The program a narrowphase stage launches (nullptr for any other stage).
const char* narrowphaseProgramOf(Stage stage);

struct Plan {
    PairKinds kinds;
    bool hasDynamic = false;   // anything to integrate
    bool hasLarge = false;     // bodies outside the uniform grid
    bool hasPlanes = false;
    bool gyroscopic = false;   // some body asks for a gyroscopic term
    bool hasJoints = false;    // the app added joints (served ones: the rules send the rest away)
    bool hasIgnoredPairs = false;  // objects ignore each other's collision check (filter_pairs)
    bool hasCompounds = false;     // compound bodies (expand_compounds)
    bool reportContacts = false;   // Config::fillDispatcherManifolds (report_contacts)
    bool broadphaseLeaves = false; // the fill holds stock's empty manifolds from the device (broadphase_leaves)
    // The app's gContactAddedCallback runs on the host between a substep's contacts and its
    // contact list (a CF_CUSTOM_MATERIAL_CALLBACK body is in the scene): contact_callbacks runs.
    bool contactCallbacks = false;
    SolverKind solver = SolverKind::BatchedPgs;  // Config::solver: which solve stages run
    Broadphase broadphase = Broadphase::UniformGrid;
    float cellSize = 1.0f;     // m: uniform grid cell, >= the largest small body's AABB extent
    // The stages of one substep, in launch order.
    std::vector<Stage> substep() const;
    // Names of what a stepSimulation call runs, in order (visible through Report): sync_in, the
    // substep's stages, sync_out.
    std::vector<std::string> stages() const;
};

// What the plan needs to know of one body row (compat/ reads it off Bullet's objects).
struct PlanBody {
    int shapeType = 0;       // BTG_SHAPE_*
    unsigned leafKinds = 0;  // a compound: bit per BTG_SHAPE_* of its leaves (they are its pairs' sides)
    float size = 0.0f;       // m: bounding diameter about the body origin (planes: 0)
    bool movable = false;    // not static (dynamic or kinematic)
    bool dynamic = false;    // moved by the solver
    bool gyroscopic = false;  // asks for a gyroscopic term (explicit, implicit world or body frame)
    bool live = true;        // false: a retired row (no body), ignored
};
struct PlanInput {
    std::vector<PlanBody> bodies;  // by row
    int numJoints = 0;             // joints on the device
    SolverKind solver = SolverKind::BatchedPgs;
    float largeBodyFactor = 4.0f;     // Config::largeBodyFactor
    float contactThreshold = 0.02f;   // m, Config::contactThreshold (AABB growth)
};
struct DerivedPlan {
    Plan plan;
    std::vector<int> largeRows;  // rows paired by the large pass (BTG_BODY_LARGE)
    std::vector<int> planeRows;  // rows whose shape is a plane
};
// The plan of a scene: the pair kinds present (a row of the table whose two shape kinds occur,
// on two bodies, one of which can move), the large
// bodies (bounding size above largeBodyFactor x the median: a ground box, paired against
// everything so it does not inflate the grid cell), the cell, the small bodies' broadphase.
DerivedPlan derivePlan(const PlanInput& in);

// The broadphase for bodies of these bounding sizes (m; planes left out): those above
// `largeSize` are paired by the large pass and do not count. Sort-and-sweep when the small
// ones leave most of a grid cell empty: the mean of (size / largest size)^3, the share of a
// cell a body's bounding cube fills, below kSweepFill — debris among a few crates, where the
// crates set the cell and each cell holds dozens of pieces. Measured, the sweep loses to the
// grid on the bench's mixed scene (fill 0.24, half extents 0.1-2.5 m): H200 broadphase 1.49
// against 0.78 ms/frame, PoCL 80 against 35 (frames 1-130), same pairs and contacts. The large
// pass keeps the cell within largeBodyFactor x the median size, and a 1D sweep through a dense
// 3D pile meets about N^(2/3) rows per body, so the sweep is kept for far emptier cells.
Broadphase chooseBroadphase(const std::vector<float>& sizes, float largeSize);
constexpr float kSweepFill = 0.05f;

}  // namespace btgpu
