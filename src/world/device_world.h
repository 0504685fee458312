// device_world.h — DeviceWorld: every device buffer of one simulated world, as struct-of-arrays
// columns indexed by dense body row, plus the shape tables and the per-step work lists.
// Rows are assigned by compat/ (the map from Bullet objects to rows lives there). Columns grow
// with the scene; nothing has a maximum the user must set.
#pragma once
#include "cl/buffer.h"
#include "cl/launch.h"
#include "shared/counters.h"
#include "shared/concave.h"
#include "shared/contact_material.h"
#include "shared/contact_report.h"
#include "shared/joint_rows.h"
#include "shared/soft_rows.h"
#include "shared/types.h"
#include "world/broadphase_scratch.h"
#include "world/leaf_buffers.h"
#include "world/solver_scratch.h"
#include "stages/prims/scan.h"

namespace btgpu {

// Slots of the `counters` buffer (values from kernels/shared/counters.h): device-side counts
// and the status word, read back together.
enum Counter : int {
    kPairCount = BTG_COUNTER_PAIRS,               // pairs written by find_pairs (may exceed capacity: overflow)
    kContactCount = BTG_COUNTER_CONTACTS,         // manifolds with points, compacted into `contacts`
    kPrevContactCount = BTG_COUNTER_PREV_CONTACTS,  // entries of contactCache (the previous substep's contacts)
    kStatus = BTG_COUNTER_STATUS,                 // BTG_STATUS_* bits
    kNanBody = BTG_COUNTER_NAN_BODY,              // lowest body row found non-finite (0xffffffff: none)
    kColorsUsed = BTG_COUNTER_COLORS_USED,        // colors the batching assigned in the last substep
    kLeftovers = BTG_COUNTER_LEFTOVERS,           // edges it left to the solver's serial pass
    kEdgeCount = BTG_COUNTER_EDGES,               // constraint-graph edges (contacts first, then other kinds)
    kSubPairCount = BTG_COUNTER_SUB_PAIRS,        // midphase sub-pairs (may exceed subPairCapacity: overflow)
    kSoftMassRatio = BTG_COUNTER_SOFT_MASS_RATIO, // the soft step's largest edge mass ratio (float bits)
    kSoftBounce = BTG_COUNTER_SOFT_BOUNCE,        // the soft step's prepare found a contact that may bounce
    kNumCounters = BTG_NUM_COUNTERS
};

struct DeviceWorld {
    explicit DeviceWorld(cl::Context& c) : ctx(c) {}
    DeviceWorld(const DeviceWorld&) = delete;
    DeviceWorld& operator=(const DeviceWorld&) = delete;
    ~DeviceWorld();
    cl::Context& ctx;
    cl::Profiler profiler;
    int numBodies = 0;  // rows in use (some may be BTG_BODY_EXCLUDED)

    // --- bodies (N rows) ---
    cl::DeviceArray<BtgFloat4> pos;        // m, centre of mass
    cl::DeviceArray<BtgFloat4> rot;        // unit quaternion (x, y, z, w)
    cl::DeviceArray<BtgFloat4> linVel;     // m/s
    cl::DeviceArray<BtgFloat4> angVel;     // rad/s
    cl::DeviceArray<BtgBodyProps> props;
    cl::DeviceArray<BtgFloat4> extForce;   // N, app forces for this stepSimulation call
    cl::DeviceArray<BtgFloat4> extTorque;  // N m
    cl::DeviceArray<BtgFloat4> invInertiaWorld;  // 3 rows per body (3N): R diag(I^-1) R^T
    // split-impulse velocities, m/s (solver scratch; held by applyForces, a placeholder row in
    // the soft step)
    cl::DeviceArray<BtgFloat4> pushLin;
    cl::DeviceArray<BtgFloat4> pushAng;    // rad/s
    cl::DeviceArray<BtgFloat4> aabbMin;    // m, world AABB grown by the contact threshold
    cl::DeviceArray<BtgFloat4> aabbMax;
    cl::DeviceArray<float> sleepTime;      // s spent under the sleeping thresholds
    cl::DeviceArray<uint> islandTime;      // float bits: least timer over the body's island
    cl::DeviceArray<uint> islandScratch;   // ping-pong partner of islandTime
    cl::DeviceArray<uint> wake;            // 1: a moving body touched this sleeping one
    // The body's island as island_min last found it (the least row over up to its rounds' hops),
    // frozen while the body sleeps (0xffffffff: none), so that a sleeping island wakes whole
    // before the solve as stock's does; islandWake[l]: island l has a body woken this step.
    cl::DeviceArray<uint> islandLabel;
    cl::DeviceArray<uint> islandLabelScratch;
    cl::DeviceArray<uint> islandWake;
    cl::DeviceArray<uint> sleepState;      // 1: asleep after this step (read back)
    cl::DeviceArray<BtgFloat4> linVel0;    // m/s before this substep's forces (restitution uses it, as Bullet)
    cl::DeviceArray<BtgFloat4> angVel0;    // rad/s before this substep's forces

    // --- shapes ---
    cl::DeviceArray<BtgShape> shapes;
    cl::DeviceArray<BtgFloat4> hullVertices;  // m, shape-local
    cl::DeviceArray<BtgFace> hullFaces;
    cl::DeviceArray<int> hullIndices;
    cl::DeviceArray<BtgFloat4> hullEdges;     // unit directions, shape-local
    int numShapes = 0;
    // Triangle meshes (shared/mesh.h): one row per mesh however many bodies and scaled wrappers
    // use it; Bullet's quantized BVH nodes, triangles as vertex rows, mesh-local vertices, and
    // each part's first triangle. Sized by the meshes, no maximum.
    cl::DeviceArray<BtgMesh> meshes;
    cl::DeviceArray<BtgBvhNode> meshNodes;
    cl::DeviceArray<BtgTriangle> meshTriangles;
    cl::DeviceArray<BtgFloat4> meshVertices;
    cl::DeviceArray<int> meshParts;
    // Heightfields (shared/heightfield.h): the grid's parameters and the app's heights as
    // floats; triangles are formed from them where the midphase finds them, never stored.
    cl::DeviceArray<BtgHeightfield> heightfields;
    cl::DeviceArray<float> heightfieldHeights;

    // Compound leaves (shared/compound.h): shape row and transform in the compound body's frame;
    // a compound shape row names its range.
    cl::DeviceArray<BtgChild> children;

    // --- broadphase ---
    cl::DeviceArray<int> largeBodies;  // rows flagged BTG_BODY_LARGE (planes excluded)
    int numLarge = 0;
    cl::DeviceArray<int> planeBodies;  // rows whose shape is a plane
    int numPlanes = 0;
    cl::DeviceArray<BtgPair> pairs;    // sorted by (a, b) after find_pairs
    size_t pairCapacity = 0;
    // The pair sort's values (pairCapacity): while find_pairs sorts, slots of its raw pairs; after
    // it, the slots of `pairs` ordered by (kind, a, b). Each narrowphase kernel walks its kind's
    // range, pairKindRanges[BTG_KIND_RANGE_*(kind)]; when the plan has a single kind nothing is
    // sorted and the ranges index `pairs` directly (pairKindsIndirect false).
    cl::DeviceArray<uint> pairOrder;
    cl::DeviceArray<uint> pairKindRanges;  // BTG_KIND_RANGES_SIZE
    bool pairKindsIndirect = false;
    BroadphaseScratch broadphase;      // find_pairs' own temporaries
    // Stock's Dbvt leaves and the pairs they overlap in (broadphase_leaves: only while the fill
    // wants stock's empty manifolds).
    LeafBuffers leaves;

    // --- expand_compounds: each pair with a compound side becomes its leaf pairs ---
    // compoundOffsets (pairCapacity + 1): per pair its first leaf pair, the last the total;
    // compoundPairs the expanded list, copied back over `pairs`.
    cl::DeviceArray<uint> compoundOffsets;
    cl::DeviceArray<BtgPair> compoundPairs;
    ScanScratch compoundScan;

    // --- midphase: (convex, triangle) sub-pairs of the convex–mesh pairs ---
    // subPairOffsets (pairCapacity + 1): per mesh pair (its place in the mesh kinds' range) the
    // first of its sub-pairs, the last entry the total. The triangles' manifolds lie in
    // `manifolds` past the pair slots, at pairCapacity + sub-pair index (manifolds holds
    // pairCapacity + subPairCapacity while the plan has meshes).
    cl::DeviceArray<uint> subPairOffsets;
    cl::DeviceArray<BtgSubPair> subPairs;
    size_t subPairCapacity = 0;
    ScanScratch subPairScan;

    // --- narrowphase and contacts ---
    // Manifold slots (today one per pair slot, at the pair's own index) and each pair's range of
    // those with points: pairManifolds[i] = (start, count) of pair i (reset by find_pairs,
    // written by the narrowphase); the contact list is the ranges' manifolds in pair order.
    cl::DeviceArray<BtgManifold> manifolds;
    cl::DeviceArray<BtgManifoldRange> pairManifolds;  // pairCapacity
    cl::DeviceArray<BtgContact> contacts;    // this step's, in pair order
    cl::DeviceArray<uint> contactManifolds;  // contactCapacity: the manifold slot of each contact
    // Rolling and spinning friction rows, same index as contacts; only while some body has
    // rolling friction (BTG_SOLVER_ROLLING_FRICTION), else one placeholder element.
    cl::DeviceArray<BtgRollingContact> rollingContacts;
    // Per-point friction directions of anisotropic friction, likewise only while a body has it
    // (BTG_SOLVER_ANISOTROPIC_FRICTION).
    cl::DeviceArray<BtgFrictionDirs> frictionDirs;
    // Friction anchors' positional targets, likewise only while a body has CF_HAS_FRICTION_ANCHOR
    // (BTG_SOLVER_FRICTION_ANCHORS).
    cl::DeviceArray<BtgFrictionAnchor> frictionAnchors;
    // The last substep's contacts packed for the app's dispatcher (stage report_contacts, only
    // while Config::fillDispatcherManifolds): read back by syncOut when written since its last read.
    // `reports` is where they lie: contactReports, or (the soft step) its rows' storage, dead
    // after its solve (SolverScratch::rowsAs), with no buffer of their own.
    cl::DeviceArray<BtgContactReport> contactReports;
    cl::ArrayView<BtgContactReport> reports;
    bool contactReportsWritten = false;
    // On a CPU device syncOut maps the reports for the fill instead of copying them out (the
    // device's memory is the host's): the mapping, undone before the next call's stages run
    // (unmapReports: the soft step's solve writes their storage) and when the world goes.
    void* reportsMapped = nullptr;
    // The app's contact callbacks before the solve (stage contact_callbacks, only while a
    // CF_CUSTOM_MATERIAL_CALLBACK body meets gContactAddedCallback): the flagged pairs' manifolds
    // gathered for the host (slot, copy; count in callbackCount[0]), the ones it changed sent
    // back, and the materials it set, applied right after prepare_contacts (numMaterials of them,
    // reset once applied).
    cl::DeviceArray<uint> callbackCount;
    cl::DeviceArray<uint> callbackSlots;
    cl::DeviceArray<BtgManifold> callbackManifolds;
    cl::DeviceArray<int> callbackAdded;  // per gathered manifold: BtgPersistentManifold::added, -2 for none
    cl::DeviceArray<BtgContactMaterial> contactMaterials;
    int numMaterials = 0;
    int appliedMaterials = 0;  // the materials apply_contact_materials took this substep (solve_soft reads them, then 0)
    // The warm-start cache: the last substep's solved contacts, reduced to what matching and
    // warm start read (112 bytes against a contact's 352), in the same pair order.
    cl::DeviceArray<BtgCachedContact> contactCache;
    size_t contactCapacity = 0;              // contacts and contactCache hold this many
    // The new cache is written here beside the old one (which it merges entries of), then the two
    // swap; carryRank: per old entry, carried entries before it (exclusive scan of carry_flags;
    // the total at cacheCapacity); cachePos / carryPos: where each contact's and each carried
    // entry's went (the GJK cache takes the same places); carrying: this substep ranked them.
    // (The soft step has no contactCacheNext: its store writes into its rows' dead storage and
    // copies back, SolverScratch::rowsAs.)
    cl::DeviceArray<BtgCachedContact> contactCacheNext;
    cl::DeviceArray<uint> carryRank;
    cl::DeviceArray<uint> cachePos;
    cl::DeviceArray<uint> carryPos;
    ScanScratch carryScan;
    bool carrying = false;
    size_t carryCapacity = 0;  // the cache capacity carryRank was ranked over
    // The cache as this call found it, for a redo; only while a call runs several substeps.
    cl::DeviceArray<BtgCachedContact> contactCacheAtCall;
    bool contactCacheKept = false;
    // The GJK pair kinds' persistent manifolds (narrowphase_gjk): this substep's per pair slot,
    // and the previous substep's beside the warm-start cache (same index), with the copy a
    // redo starts from. Allocated only when the plan has those kinds.
    cl::DeviceArray<BtgPersistentManifold> gjkPairState;
    cl::DeviceArray<BtgPersistentManifold> gjkCache;
    cl::DeviceArray<BtgPersistentManifold> gjkCacheNext;  // written beside gjkCache, then swapped
    cl::DeviceArray<BtgPersistentManifold> gjkCacheAtCall;
    bool gjkCacheCurrent = false;  // gjkCache was stored by the last substep that stored the cache
    // The soft step's contacts: box pairs take each step's SAT clip with speculative points, and
    // convex–mesh pairs each triangle's clip with the pair's threshold (its substeps need this
    // step's points), instead of stock's algorithms into persistent manifolds (narrowphase_sat.cl,
    // narrowphase_mesh.cl). Set by the pipeline each substep from the plan's solver.
    bool speculativeContacts = false;

    // --- the constraint graph: one edge (body A, body B) per constraint of any kind ---
    // Rebuilt every substep; the batching colors it and the islands walk it. Edge e below the
    // contact count is contact e (prepare_contacts writes those); other kinds append after them.
    cl::DeviceArray<BtgEdge> edges;
    cl::DeviceArray<int> edgeColor;          // batch of each edge: no dynamic body twice in one
    size_t edgeCapacity = 0;                 // edges and edgeColor hold this many (contactCapacity now)
    int numColors = 0;                       // batches the solver launches (host estimate)
    int colorRounds = 8;                     // coloring rounds to run: set from the last readback
    int lastContactCount = 1 << 30;          // contacts at the last readback (chooses launch shapes)
    size_t softResidentGroups = 0;           // the soft step's resident groups where set (tests), else one a unit
    BtgSoftParams softParams{};              // the soft step's scalars as the host chose them, last step
    int lastColorsUsed = 0;                  // colors the last readback's coloring used
    int lastSoftSubsteps = 0;                // substeps the soft step took at the last readback (its mass ratio's)
    float lastSoftMassRatio = 0.0f;          // the largest edge mass ratio it saw then
    SolverScratch solverScratch;             // contact stages' scratch (block sums, claims)
    // Batching and solve in one launch each over resident work-groups (stages/resident.h):
    // Auto takes it on GPUs; set Off for good when a grid barrier timed out on this device (the
    // step is then redone with per-round launches). On forces it (tests).
    enum class Resident { Auto, Off, On };
    Resident resident = Resident::Auto;
    // The resident soft step's sweeps ordered by per-body counts instead of a grid barrier per
    // colour (solve_soft.cl's flow; the same results bit for bit). Auto: the BTGPU_SOFT_FLOW knob
    // (1 on, else off); On forces it (tests; on a CPU device its groups are of one work-item).
    Resident softFlow = Resident::Auto;
    // The same for the bullet mode's resident solve (solve_constraints.cl's flow; BTGPU_PGS_FLOW=1).
    Resident pgsFlow = Resident::Auto;
    // The bullet mode's solve on one work-group with the velocities in local memory
    // (solve_constraints.cl's solve_local; the same results bit for bit): Auto takes it on GPUs
    // for small scenes (solve_constraints.cpp), On wherever the velocities fit (tests), Off never.
    Resident pgsLocal = Resident::Auto;

    // --- joints (issue 11): the app's joints, their rows and what the solve leaves of them ---
    // Edge contacts + j of the constraint graph is joint j; joint j's rows are
    // jointRows[joints[j].firstRow, + max rows of its type). Without joints each holds one
    // placeholder element (kernels take a bound buffer).
    cl::DeviceArray<BtgJoint> joints;
    cl::DeviceArray<BtgJointState> jointState;
    cl::DeviceArray<BtgJointFeedback> jointFeedback;  // per joint; written for joints with feedback
    cl::DeviceArray<BtgJointRow> jointRows;
    int numJoints = 0;
    int jointIterations = 0;  // the largest of the joints' iteration counts
    int jointSprings = 0;     // 6-DoF spring2 axes with their spring on (the soft step then gathers)
    // Stock's solve order of the joints that share a body (compat/joint_order.h): joint j's
    // colour in the bullet mode's batching, one above every joint before it in stock's order
    // that shares a body with it; maxJointLevel the largest (0 or less: no two joints share a
    // body, and the batching colours them as contacts).
    cl::DeviceArray<int> jointLevels;
    int maxJointLevel = 0;
    // Pairs of rows (a < b, sorted) that ignore each other's collision check (filter_pairs).
    cl::DeviceArray<BtgPair> ignoredPairs;
    int numIgnoredPairs = 0;

    // --- sync_in staging (kept across calls: a quiet step allocates nothing) ---
    cl::DeviceArray<int> stagingRows;
    cl::DeviceArray<BtgFloat4> stagingStates;  // 6 per row: pos, rot, linVel, angVel, force, torque
    cl::DeviceArray<float> stagingTimes;       // setSleepTimes: a deactivation timer per row
    cl::DeviceArray<BtgBodyProps> stagingProps;

    // --- counts and status ---
    cl::DeviceArray<uint> counters;  // Counter slots
};

}  // namespace btgpu
