// gpu_world.h — GpuWorld: everything btGpuDynamicsWorld adds to its base class. It owns the
// OpenCL context and the DeviceWorld, maps Bullet objects to body rows, decides between the
// GPU path and the base class's CPU path, and runs stepSimulation's substeps on the device
// with Bullet's time, kinematic, motion-state and force semantics around them.
#pragma once
#include "btgpu/btGpuDynamicsWorld.h"
#include "contact_callbacks.h"
#include "cpu_path_guard.h"
#include "cpu_path_rules.h"
#include "ignored_pairs.h"
#include "joint_rows.h"
#include "leaf_pairs.h"
#include "manifold_sync.h"
#include "row_map.h"
#include "pipeline.h"
#include "shape_tables.h"
#include "side_task.h"
#include "stages/sync_bodies.h"
#include "world/device_world.h"
#include "world/plan.h"

#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

namespace btgpu {

class GpuWorld {
public:
    GpuWorld(btGpuDynamicsWorld& world, const Config& config);
    ~GpuWorld();

    // False (reported as a BadArgument issue) when the call's arguments are refused: nothing
    // is simulated. Also names a non-finite world gravity.
    bool acceptStep(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep);
    // The whole stepSimulation on the GPU path. Returns false (having changed nothing) when
    // the CPU path must run this call instead.
    bool step(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep, int* substepsDone);
    // The base class's stepSimulation, with bad bodies named and held out of it.
    int stepOnCpuPath(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep);

    void structureChanged() { m_structureDirty = true; }
    // An object left the world (called before Bullet forgets it; it may be deleted after).
    void removed(const btCollisionObject* object)
    {
        m_removed.insert(object);
        m_manifolds.removed(m_world.getDispatcher(), object);
    }
    // An OpenCL failure during a step: reported once, and the world stays on the CPU path.
    void failDevice(const std::string& what);
    void report(Issue issue);
    std::uint64_t stateHash() const;
    // True once after a write-back that also synchronized Bullet's own motion states and
    // cleared forces: the world's synchronizeMotionStates and clearForces then skip that work.
    bool takeFusedWriteBack();
    bool fusedWriteBackPending() const { return m_fusedWriteBack; }

    Report m_report;
    Config m_config;
    float m_appThreshold;  // Config::contactThreshold as the app gave it (m_config's follows gContactBreakingThreshold)

private:
    // What the device holds for a row, as last written or read back. Plain data without
    // initialisers, so that m_mirror can be sized without writing it (the rebuild writes every
    // row's in parallel): a row starts as fresh().
    struct Mirror {
        btTransform xf;
        btVector3 linVel, angVel, force, torque;
        BtgBodyProps props;
        bool excluded;
        // The app changed this sleeping dynamic body before the call (a teleport, a velocity
        // without activate()): its write-back does what stock's step does to a sleeper.
        bool touchedAsleep;
        // The body's m_deactivationTime as the last write-back left it (the device's timer): the
        // app's activate() zeroes it, which keeps a slow body awake on stock.
        float deactivation;
        static Mirror fresh()
        {
            Mirror m;
            m.xf.setIdentity();
            m.linVel = m.angVel = m.force = m.torque = btVector3(0, 0, 0);
            m.props = BtgBodyProps{};
            m.excluded = false;
            m.touchedAsleep = false;
            m.deactivation = 0.0f;
            return m;
        }
    };

    bool ensureDevice();
    // Why this step must run on the CPU path (cpu_path_rules.h), "" for the GPU path; a
    // per-body reason sets *bodyIndex. *shapes (when given) gets shapesSwapped's answer from
    // the rules' walk over the objects, where that walk saw them all (ShapeWalk::complete).
    std::string cpuPathReason(int* bodyIndex, ShapeWalk* shapes = nullptr);
    // Bullet features the soft step (Config::solver = SoftStep) does not serve, "" when none.
    std::string softStepReason() const;
    // The solver the next step runs: Config::solver, Auto resolved by the last cpuPathReason
    // (the soft step unless m_autoReason names what only the batched PGS serves).
    SolverKind solverToRun() const;
    // Every row from scratch: the rows, the shape tables, the plan, the device state (the
    // warm-start cache dropped). After the CPU path ran, or when retired rows pile up.
    void rebuild();
    // The rows follow the objects added and removed since the last step, the rest untouched.
    void followRows();
    // The shape tables to the device: whole, or (appended) only the rows added since.
    void uploadShapeTables(bool appended);
    void makePlan();
    // True when a collision object's shape is no longer the one the tables were built for.
    bool shapesSwapped() const;
    // The rows whose Bullet state differs from their mirror, in row order.
    BodyRowUploads changedRows();
    // Every row, each mirror started fresh (the rebuild's).
    BodyColumns everyRow();
    // Row r holds no body: excluded from everything, its mirror saying so.
    BodyRowUpdate retireRow(size_t r);
    void reportNewlyBad(const std::vector<std::vector<std::pair<size_t, std::string>>>& newlyBad);
    // One row against its mirror: true (and the update, and a reason when the row has just
    // turned bad) when the device must be told. Touches only row r: safe in parallel.
    bool compareRow(size_t r, bool all, BodyRowUpdate* u, std::string* newlyBad);
    // False when `betweenContacts` (the app's contact callbacks) abandoned the call.
    bool runOnDevice(int substeps, btScalar dt, SubstepPart part = SubstepPart::Whole,
                     const std::function<bool()>& betweenContacts = {});
    // The app's actions (btActionInterface) between the two parts of an internal step, and
    // what they changed up to the device.
    void runActions(btScalar dt);
    // Internal step `batch` of a call, after an action or callback added or removed
    // something: false when the rest of the call ran on the CPU path.
    bool followWithinCall(int batch, int batches, btScalar fixedTimeStep);
    // The host's part between an internal step's contacts and its solve while the app's contact
    // callbacks or an overlap filter need it (empty otherwise); keeps the plan's stage in step.
    std::function<bool()> contactHostPart();
    // Internal steps [batch, batches) of this call on the CPU path, for `why`.
    // preTickCalled: the step's pre-tick callback ran already (the step began on the GPU path).
    void cpuPathFrom(int batch, int batches, btScalar fixedTimeStep, const std::string& why, bool preTickCalled = false);
    // Bullet's broadphase AABBs where the bodies are, without its pair tests (see the .cpp), and
    // the pairs those left out, found before a CPU-path step.
    btDbvtBroadphase* dbvtBroadphase() const;
    void syncBroadphaseAabbs();
    void completeBroadphasePairs();
    bool m_broadphasePairsStale = false;
    // Bullet's broadphase runs as stock's at each internal step's start: for ghosts, an overlap
    // filter, and stock's empty manifolds (Config::stockEmptyManifolds); its AABBs are then
    // stock's own and the after-step sync leaves them.
    // Continuous collision detection: the bodies stock's sweeps look at (cpuPathReason), and why
    // they cannot be served beside what else the world has ("" when they can).
    std::vector<btRigidBody*> m_ccdBodies;
    std::string ccdReason() const;
    bool broadphaseAsStock() const
    {
        return (!m_ghosts.empty() && !ghostsFromDevice()) || m_overlapFilter ||
               (m_config.fillDispatcherManifolds && m_config.stockEmptyManifolds);
    }
    // Triggers in a big world (Config::ghostPairsFromDevice, past ghostPairsExactUpTo): their pairs
    // from the device's Dbvt leaves and the host's follow of stock's pair cache (leaf_pairs.cpp),
    // added to and removed from Bullet's pair cache, whose ghost callback fills the ghosts' lists;
    // no broadphase work on the host.
    bool ghostsFromDevice() const;
    // After a device call with the leaf stage, for ghostsFromDevice: the ghost pairs that joined
    // and left stock's pair cache, through Bullet's pair cache; the bodies held awake by them.
    void followGhostPairs();
    // Stock's empty manifolds from the device's leaf pairs (Config::deviceEmptyManifolds): while
    // the fill wants them and nothing else decides the pairs (Bullet's broadphase on the host for
    // ghosts, an overlap filter or stockEmptyManifolds; an app that turned off
    // m_forceUpdateAllAabbs, whose resting leaves stock moves to its fixed tree).
    bool deviceLeafPairs() const;
    // Before a device call with the stage: the leaves' settings as stock's world has them.
    void startLeafPairs();
    // After it, before the write-back: the leaf pairs' change read back, stock's pair cache
    // followed, the fill's pairs noted (the bodies as the step found them, as stock's near
    // callback sees them).
    void noteLeafPairs(int steps);
    LeafPairCache m_leafPairs;
    // The app's dispatcher manifolds from the readback just taken (Config::fillDispatcherManifolds).
    void fillManifolds(const std::function<void()>& beforeEvents = {});
    // Whether this call's last broadphase AABB sync may run beside the manifold fill (SideTask):
    // a big world, Bullet's own Dbvt, dispatcher and world classes, the write-back's fused pass
    // (no tick callback, nothing of the app's between the fill and the sync but its own motion
    // states, called after both).
    bool aabbsBesideFill() const;
    // The fill, with the call's broadphase AABB sync on the side thread beside it.
    void fillBesideAabbSync();
    SideTask m_side;
    bool m_aabbsSynced = false;   // this call's sync ran beside the fill
    double m_aabbWaitMs = 0.0;    // what it added to the call: the fill's wait for it
    // The CPU path runs next: our manifolds go back to the dispatcher's pool (its algorithms
    // make their own); coming back, the algorithms' go (ours replace them).
    void leaveGpuPath();
    void dropCpuPathManifolds();
    // synchronizeMotionStates, clearForces, the AABB sync and the report's totals.
    bool finishCall(bool profiled, bool gpuPath);
    // The pair and contact buffers for `rows` bodies, never smaller than they are; keepCache:
    // the warm-start cache's contents stay (rows followed, not rebuilt).
    void reservePairsAndContacts(size_t rows, bool keepCache);
    // Results into the btRigidBody objects; `last`: the call's final write-back, which may also
    // do synchronizeMotionStates' and clearForces' work in the same pass (see takeFusedWriteBack).
    // sleepRead: rb's sleep states are this step's (false after a part stopped before the
    // deactivation).
    void writeBack(const BodyReadback& rb, bool last, bool sleepRead = true);
    // One row; true when the body fell asleep in this step. Touches only row r.
    bool writeRow(size_t r, btRigidBody* body, const BodyReadback& rb, bool sleepRead, std::vector<size_t>* bad);
    // A sleeping body the app changed before the call, after a call it slept through.
    void settleSleeper(btRigidBody* body, Mirror& m);
    StepSettings settings(int substeps, btScalar dt) const;

    btGpuDynamicsWorld& m_world;
    std::unique_ptr<cl::Context> m_ctx;
    std::unique_ptr<DeviceWorld> m_dev;
    bool m_deviceFailed = false;
    bool m_structureDirty = true;  // added or removed since the structure was last checked
    std::vector<const btCollisionShape*> m_shapeOfObject;  // per collision object, at that check
    std::string m_structureReason;  // that check's verdict, kept until the next add or remove
    std::vector<const btCollisionObject*> m_ghosts;  // ghost objects, at that check (ghost_objects.h)
    std::vector<char> m_ghostResponds;               // each one's hasContactResponse() then
    std::vector<char> m_heldAwake;  // per row: in a broadphase pair with a ghost that merges islands
    SolverKind m_solver = SolverKind::BatchedPgs;  // the solver the plan runs (never Auto)
    std::string m_autoReason;       // Config::solver = Auto: why not the soft step ("" for it)
    bool m_needsRebuild = true;     // rows must be rebuilt (structure changed, or the CPU path ran)
    bool m_onCpuPath = false;
    float m_stepDt = 0.0f;  // the fixed step of the call being synced (the AABB overflow rule)
    long m_calls = 0;  // stepSimulation calls on the GPU path (profiling cadence)
    unsigned m_orderStream = 1u;  // SOLVER_RANDMIZE_ORDER: the next substep's solve-order seed
    Plan m_plan;
    ShapeTables m_shapes;
    RowMap m_rows;
    size_t m_uploadedShapeRows[13] = {};  // rows of each shape and mesh table on the device
    std::unordered_set<const btCollisionObject*> m_removed;  // since the rows last followed the world
    bool m_rowsStale = true;  // objects added or removed since the rows last followed them
    UntouchedVector<Mirror> m_mirror;
    unsigned m_solverFlags = 0;  // BTG_SOLVER_* the bodies call for (bodiesReason, each step)
    std::vector<bool> m_large;  // rows paired by brute force instead of the grid
    // Per row, set by compareRow: the app woke this sleeping body (activate()), which restarts
    // its deactivation timer in Bullet; the device's timers are reset to match.
    std::vector<char> m_woken;
    std::vector<char> m_reshaped;  // per row: its mesh or heightfield was edited (compareRow)
    // per row: the app set its deactivation timer (activate(), setDeactivationTime), and to what
    std::vector<char> m_timerSet;
    std::vector<float> m_timerValue;
    // The rows' timers the app set, to the device (after the rows' own upload).
    void uploadTimers();
    bool m_softCapReported = false;   // the Difference issue of SoftStepConfig::maxSubsteps was made
    bool m_emptyCapReported = false;  // the Difference issue of Config::deviceEmptyManifoldsUpTo was made
    // After a syncIn: the woken rows' timers reset, the edited concave rows' kept points dropped.
    void afterSyncIn();
    ManifoldSync m_manifolds;   // the app's dispatcher manifolds on the GPU path
    ContactCallbacks m_callbacks;  // the app's callbacks between the contacts and the solve
    // A change the callbacks made that the device cannot carry: the world stays on the CPU path
    // until something is added or removed or the callbacks are others.
    std::string m_callbackReason;
    ContactCallbacks::Set m_callbackReasonFor{};
    // An overlap filter callback is set: Bullet's broadphase runs on the host at each internal
    // step and decides the pairs (the rows' group and mask then accept everything on the device).
    bool m_overlapFilter = false;
    JointSync m_joints;         // the joint table on the device and its write-back
    IgnoredPairs m_ignored;     // collision-check exceptions (disableCollisionsBetweenLinkedBodies)
    Snapshot m_snapshot;
    BodyReadback m_readback;
    bool m_fusedWriteBack = false;
    CpuPathGuard m_cpuGuard;
    std::string m_lastBadArgument;  // reported once while it repeats
    bool m_badGravityNamed = false;
};

}  // namespace btgpu
