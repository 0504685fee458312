// gpu_world.cpp — the GPU path of btGpuDynamicsWorld::stepSimulation: device choice, the
// scene → rows rebuild and plan, per-call sync of what the app changed (found by row_changes.cpp), the device substeps
// with redo on overflow (the write-back that leaves every body as stock Bullet would: write_back.cpp).
#include "gpu_world.h"
#include "seed_contacts.h"

#include "ccd_steps.h"

#include "body_rows.h"
#include "cpu_path_rules.h"
#include "ghost_objects.h"
#include "parallel_rows.h"
#include "step_arguments.h"
#include "shared/integrate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <type_traits>
#include <typeinfo>

namespace btgpu {

namespace {

using Clock = std::chrono::steady_clock;
double msBetween(Clock::time_point a, Clock::time_point b)
{
    return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

GpuWorld::GpuWorld(btGpuDynamicsWorld& world, const Config& config)
    : m_config(config), m_appThreshold(config.contactThreshold), m_world(world)
{
}

GpuWorld::~GpuWorld()
{
    m_manifolds.releaseAll(m_world.getDispatcher());
    m_readback.release();
    m_dev.reset();
    m_snapshot = Snapshot();
    m_ctx.reset();
}

void GpuWorld::report(Issue issue)
{
    if (m_config.onIssue) m_config.onIssue(issue);
    m_report.issues.push_back(std::move(issue));
}

void GpuWorld::failDevice(const std::string& what)
{
    m_deviceFailed = true;
    m_report.gpuPath = false;
    m_report.cpuPathReason = "OpenCL failure: " + what;
    std::cerr << "btgpu: " << m_report.cpuPathReason << "\n         continuing on the CPU path\n";
    report({Issue::Kind::OpenCL, what});
    m_report.deviceBytes = 0;  // everything below is released
    try {
        m_readback.release();
    } catch (...) {
    }
    m_dev.reset();
    m_snapshot = Snapshot();
    m_ctx.reset();
}

bool GpuWorld::ensureDevice()
{
    if (m_ctx) return true;
    if (m_deviceFailed) return false;
    try {
        cl::DeviceInfo d = cl::selectDevice(m_config.device);
        m_ctx = std::make_unique<cl::Context>(d);
        m_ctx->setMemoryLimit(m_config.deviceMemoryLimit);
        m_dev = std::make_unique<DeviceWorld>(*m_ctx);
        m_report.device = d.describe();
        std::cerr << "btgpu: OpenCL device " << m_report.device << "\n";
        return true;
    } catch (const std::exception& e) {
        m_deviceFailed = true;
        m_report.cpuPathReason = std::string("no usable OpenCL device: ") + e.what();
        std::cerr << "btgpu: running on the CPU path (" << m_report.cpuPathReason << ")\n";
        report({Issue::Kind::Device, m_report.cpuPathReason});
        return false;
    }
}

std::string GpuWorld::cpuPathReason(int* bodyIndex, ShapeWalk* shapes)
{
    *bodyIndex = -1;
    // The scene's make-up changes only when something is added or removed: checked then, and
    // the verdict kept. World and body settings can change between any two steps.
    // An app that changes Bullet's gContactBreakingThreshold (and leaves Config::contactThreshold
    // at its default) gets it as the GPU path's threshold, from the next step on, as stock's
    // next manifolds and AABBs take it.
    m_config.contactThreshold = (m_appThreshold == 0.02f && gContactBreakingThreshold != btScalar(0.02))
                                    ? float(gContactBreakingThreshold)
                                    : m_appThreshold;
    // Contact breaking thresholds, per shape as Bullet's dispatcher sets them up (its flags can
    // change between steps: the tables follow).
    const auto* dispatcher = dynamic_cast<const btCollisionDispatcher*>(m_world.getDispatcher());
    const bool relative = dispatcher && (dispatcher->getDispatcherFlags() &
                                         btCollisionDispatcher::CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD);
    if (relative != m_shapes.relativeThreshold || m_config.contactThreshold != m_shapes.absoluteThreshold) {
        m_shapes.relativeThreshold = relative;
        m_shapes.absoluteThreshold = m_config.contactThreshold;
        m_structureDirty = true;
    }
    // A ghost given or relieved of contact response changes what its shape meets on the device.
    for (size_t g = 0; g < m_ghosts.size() && !m_structureDirty; ++g)
        if (m_ghosts[g]->hasContactResponse() != bool(m_ghostResponds[g])) m_structureDirty = true;
    if (m_structureDirty) {
        m_callbackReason.clear();
        m_structureReason = structureReason(m_world, &m_shapes);
        const btCollisionObjectArray& objs = m_world.getCollisionObjectArray();
        m_shapeOfObject.resize(size_t(objs.size()));
        for (int i = 0; i < objs.size(); ++i) m_shapeOfObject[size_t(i)] = objs[i]->getCollisionShape();
        m_ghosts = findGhosts(m_world);
        m_ghostResponds.clear();
        m_heldAwake.clear();
        for (const btCollisionObject* g : m_ghosts) m_ghostResponds.push_back(g->hasContactResponse());
        m_structureDirty = false;
        m_rowsStale = true;
    }
    if (!m_structureReason.empty()) return m_structureReason;
    std::string why = worldReason(m_world, m_config);
    if (why.empty()) {
        if (shapes) shapes->expected = &m_shapeOfObject;
        why = bodiesReason(m_world, bodyIndex, m_config.solver, &m_solverFlags,
                           &m_ccdBodies, shapes);
    }
    if (why.empty() && !m_ccdBodies.empty()) why = ccdReason();
    if (why.empty() && (ContactCallbacks::wanted(m_world) || ContactCallbacks::events() ||
                        ContactCallbacks::overlapFilter(m_world))) {
        if (!m_callbackReason.empty() && m_callbackReasonFor == ContactCallbacks::current()) return m_callbackReason;
        why = ContactCallbacks::unservedReason(m_world, m_config);
        // The callbacks' second preparation of a contact (contact_material.h) rebuilds its rows
        // from the changed friction and restitution, but not the rows prepare_contacts adds for
        // rolling friction or anisotropic friction directions.
        if (why.empty() && ContactCallbacks::wanted(m_world) &&
            (m_solverFlags & (BTG_SOLVER_ROLLING_FRICTION | BTG_SOLVER_ANISOTROPIC_FRICTION | BTG_SOLVER_FRICTION_ANCHORS)))
            why = "contact callbacks that run before the solve (gContactAddedCallback on a CF_CUSTOM_MATERIAL_CALLBACK "
                  "body, gContactProcessedCallback, a custom combiner) beside rolling, spinning or anisotropic "
                  "friction or friction anchors (their rows are not prepared again with the callbacks' changes)";
    }
    if (why.empty() && m_config.solver == SolverKind::SoftStep) why = softStepReason();
    // Auto: what the soft step would be sent away for, the batched PGS serves.
    m_autoReason = why.empty() && m_config.solver == SolverKind::Auto ? softStepReason() : std::string();
    return why;
}

SolverKind GpuWorld::solverToRun() const
{
    if (m_config.solver != SolverKind::Auto) return m_config.solver;
    return m_autoReason.empty() ? SolverKind::SoftStep : SolverKind::BatchedPgs;
}

std::string GpuWorld::softStepReason() const
{
    // The soft step's contacts are its own springs (soft_rows.h) on a fresh clip each step
    // (box-box pairs keep no persistent manifold in it, so no point stays as a friction anchor),
    // with no relaxation factor (m_sor: tried as each row's change times m_sor, under-relaxed
    // the relax no longer takes out the spring's push and a box landing from 3 m at m_sor 0.3
    // bounced 31 cm where stock's rises 3 cm) nor a spring for a negative cfm. Anisotropic
    // friction it serves: a contact of an anisotropic body runs its friction rows along Bullet's
    // scaled directions (BtgSoftParams::anisotropic).
    if (m_solverFlags & BTG_SOLVER_FRICTION_ANCHORS)
        return "friction anchors (CF_HAS_FRICTION_ANCHOR) with Config::solver = SoftStep";
    const btContactSolverInfo& info = m_world.getSolverInfo();
    if (info.m_sor != btScalar(1))
        return "btContactSolverInfo::m_sor changed with Config::solver = SoftStep";
    // m_globalCfm is the contacts' spring (btgSoftCfmSpring); a negative one is none
    if (info.m_globalCfm < btScalar(0))
        return "a negative btContactSolverInfo::m_globalCfm with Config::solver = SoftStep";
    return "";
}

void GpuWorld::makePlan()
{
    // The plan is derived from Bullet-free facts about each row (src/world/plan.h).
    PlanInput in;
    in.solver = m_solver;
    in.largeBodyFactor = m_config.largeBodyFactor;
    in.contactThreshold = m_config.contactThreshold;
    in.numJoints = m_world.getNumConstraints();  // all served while on the GPU path
    // Each row's facts read in parallel chunks (a shape lookup and a walk into each scattered
    // object: 90 ms a rebuild at 1,000,000 bodies on one core), each at its own index.
    in.bodies.resize(m_rows.size());
    forEachChunk(m_rows.size(), kBodyRowsPerThread, [&](size_t begin, size_t end, int) {
        for (size_t r = begin; r < end; ++r) {
            const btCollisionObject* o = m_rows.at(r);
            PlanBody& b = in.bodies[r];
            if (!o) {
                b.live = false;
                continue;
            }
            const bool ghost = o->getInternalType() == btCollisionObject::CO_GHOST_OBJECT;
            const BtgShape& s = m_shapes.shapes[size_t(m_shapes.rowOf.at(o->getCollisionShape()))];
            b.shapeType = s.type;
            for (int k = 0; k < s.numChildren && s.type == BTG_SHAPE_COMPOUND; ++k)
                b.leafKinds |= 1u << m_shapes.shapes[size_t(m_shapes.children[size_t(s.firstChild + k)].shape)].type;
            b.size = s.type == BTG_SHAPE_PLANE ? 0.0f : 2.0f * boundingRadius(s);
            // A kinematic body made with mass 0 keeps CF_STATIC_OBJECT beside CF_KINEMATIC_OBJECT.
            b.movable = !o->isStaticObject() || o->isKinematicObject() || ghost;
            b.dynamic = !o->isStaticOrKinematicObject() && !ghost;
            const btRigidBody* rb = btRigidBody::upcast(o);
            b.gyroscopic = rb && (rb->getFlags() & (BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY | BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT |
                                                   BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD));
        }
    });
    DerivedPlan d = derivePlan(in);
    m_plan = d.plan;
    m_plan.hasIgnoredPairs = m_ignored.any();
    m_plan.reportContacts = m_config.fillDispatcherManifolds;
    m_plan.broadphaseLeaves = deviceLeafPairs();
    m_dev->leaves.reset = true;  // rows may have moved: every leaf and the pair list start afresh
    m_leafPairs.clear();
    m_plan.contactCallbacks = ContactCallbacks::wanted(m_world);
    m_large.assign(m_rows.size(), false);
    for (int r : d.largeRows) m_large[size_t(r)] = true;
    DeviceWorld& w = *m_dev;
    w.numLarge = int(d.largeRows.size());
    w.numPlanes = int(d.planeRows.size());
    d.largeRows.push_back(-1);  // never an empty buffer
    d.planeRows.push_back(-1);
    w.largeBodies.upload(w.ctx, d.largeRows);
    w.planeBodies.upload(w.ctx, d.planeRows);
    m_report.stages = m_plan.stages();
}

void GpuWorld::uploadShapeTables(bool appended)
{
    // The tables only grow between rebuilds (rows are never changed in place), so after an add
    // only their new tails travel.
    DeviceWorld& w = *m_dev;
    size_t table = 0;
    auto uploadTable = [&](auto& arr, const auto& v) {
        size_t& done = m_uploadedShapeRows[table++];
        if (!appended) done = 0;
        if (v.empty()) {
            std::decay_t<decltype(v)> one(1);  // a bound buffer even when the table is empty
            arr.upload(w.ctx, one);
            done = 0;
        } else if (v.size() > done) {
            arr.upload(w.ctx, v.data() + done, v.size() - done, done);
            done = v.size();
        }
    };
    uploadTable(w.shapes, m_shapes.shapes);
    uploadTable(w.hullVertices, m_shapes.vertices);
    uploadTable(w.hullFaces, m_shapes.faces);
    uploadTable(w.hullIndices, m_shapes.indices);
    uploadTable(w.hullEdges, m_shapes.edges);
    uploadTable(w.children, m_shapes.children);
    const MeshTables& mesh = m_shapes.meshTables;
    uploadTable(w.meshes, mesh.meshes);
    uploadTable(w.meshNodes, mesh.nodes);
    uploadTable(w.meshTriangles, mesh.triangles);
    uploadTable(w.meshVertices, mesh.vertices);
    uploadTable(w.meshParts, mesh.parts);
    uploadTable(w.heightfields, mesh.heightfields);
    uploadTable(w.heightfieldHeights, mesh.heights);
    w.numShapes = int(m_shapes.shapes.size());
}

void GpuWorld::rebuild()
{
    DeviceWorld& w = *m_dev;
    const btCollisionObjectArray& objs = m_world.getCollisionObjectArray();
    // Shape rows nobody uses any more are dropped here, where every row is rebuilt anyway.
    if (m_shapes.unreferenced() > 0) {
        m_shapes.clear();
        structureReason(m_world, &m_shapes);  // verdict known: empty
    }
    m_shapes.takeGrown();
    m_rows.reset(objs);
    m_removed.clear();
    m_rowsStale = false;
    resizeBodies(w, int(m_rows.size()));
    uploadShapeTables(false);
    // No callback materials carry over (a solver switch rebuilds: the soft step reads them).
    w.appliedMaterials = 0;
    makePlan();
    // Rows changed meaning: the warm-start cache is dropped (one step without warm start).
    size_t n = m_rows.size();
    reservePairsAndContacts(n, false);
    std::vector<uint> counters(kNumCounters, 0u);
    counters[kNanBody] = 0xffffffffu;
    w.counters.upload(w.ctx, counters);
    w.sleepTime.zero(w.ctx, std::max<size_t>(n, 1));
    std::vector<uint> never(std::max<size_t>(n, 1), 0x7f800000u);  // +inf: no island yet
    w.islandTime.upload(w.ctx, never);
    w.islandLabel.fill(w.ctx, 0xffffffffu, 0, std::max<size_t>(n, 1));  // rows renumbered: no island kept
    w.islandWake.fill(w.ctx, 0u, 0, std::max<size_t>(n, 1));
    m_mirror.clear();
    m_mirror.resize(n);  // unwritten: everyRow starts each row's mirror
    writeColumns(w, everyRow());
    uploadTimers();
    // The sleep state read back before a step's deactivation (the actions' part) is the app's
    // until the device's deactivation writes it; left unwritten it was whatever the buffer held.
    std::vector<uint> asleep(std::max<size_t>(n, 1), 0u);
    for (size_t r = 0; r < n; ++r) asleep[r] = (m_mirror[r].props.flags & BTG_BODY_SLEEPING) ? 1u : 0u;
    w.sleepState.upload(w.ctx, asleep);
    m_joints.reset();
    m_ignored.reset();
}


StepSettings GpuWorld::settings(int substeps, btScalar dt) const
{
    const btContactSolverInfo& info = m_world.getSolverInfo();
    StepSettings s;
    BtgStepParams& p = s.params;
    p = BtgStepParams{};
    p.dt = dt;
    p.erp = info.m_erp;
    p.erp2 = info.m_erp2;
    p.splitPenetrationThreshold = info.m_splitImpulsePenetrationThreshold;
    p.splitTurnErp = info.m_splitImpulseTurnErp;
    p.warmstartFactor = (info.m_solverMode & SOLVER_USE_WARMSTARTING) ? info.m_warmstartingFactor : 0.0f;
    p.restitutionThreshold = info.m_restitutionVelocityThreshold;
    p.contactThreshold = m_config.contactThreshold;
    p.deactivationTime = gDisableDeactivation ? 0.0f : gDeactivationTime;
    p.splitImpulse = info.m_splitImpulse ? 1 : 0;
    p.numBodies = m_dev->numBodies;
    p.twoFrictionDirections = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) ? 1 : 0;
    p.solverFlags = m_solverFlags;
    if (info.m_solverMode & SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION)
        p.solverFlags |= BTG_SOLVER_VELOCITY_INDEPENDENT_FRICTION;
    if (info.m_solverMode & SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS) p.solverFlags |= BTG_SOLVER_INTERLEAVE;
    // The soft step warm-starts its friction against fixed bodies across steps, as Box2D does
    // (its tangents follow the normal): started at zero each step, a resting box on a slope slid
    // during each step's first substep, about 0.65 mm/s at 0.1 rad (btgSoftPrepare,
    // SolverFeatures.SoftStepHoldsABoxOnASlope).
    if (m_solver == SolverKind::SoftStep) p.solverFlags |= BTG_SOLVER_WARM_FRICTION;
    p.sor = info.m_sor;
    p.globalCfm = info.m_globalCfm;
    p.maxGyroscopicForce = info.m_maxGyroscopicForce;
    p.frictionErp = info.m_frictionERP;
    s.substeps = substeps;
    s.iterations = std::max(info.m_numIterations, 1);
    s.maxColors = std::max(m_config.maxColors, 2);
    s.solver = m_solver;
    s.soft = m_config.softStep;
    BtgJointStepParams& j = s.joints;
    j = BtgJointStepParams{};
    j.dt = dt;
    j.erp = info.m_erp;
    j.globalCfm = info.m_globalCfm;
    j.damping = info.m_damping;
    j.numIterations = info.m_numIterations;
    j.numJoints = m_dev->numJoints;
    return s;
}

bool GpuWorld::runOnDevice(int substeps, btScalar dt, SubstepPart part, const std::function<bool()>& betweenContacts)
{
    DeviceWorld& w = *m_dev;
    // substeps * k stays an int: k is capped where the product would overflow.
    const int k = std::max(std::min(m_config.internalSubsteps, std::numeric_limits<int>::max() / std::max(substeps, 1)), 1);
    StepSettings s = settings(part == SubstepPart::ActivationOnly ? 1 : substeps * k, dt / btScalar(k));
    s.lastPart = part;
    // SOLVER_RANDMIZE_ORDER: the solver's own stream (solver_rows.h), one seed per substep this
    // world has run; never 0, which means off.
    if (m_world.getSolverInfo().m_solverMode & SOLVER_RANDMIZE_ORDER)
        s.params.randomSeed = m_orderStream == 0u ? 1u : m_orderStream;
    const CallOutcome outcome = runCall(w, m_plan, s, m_snapshot, m_readback, betweenContacts);
    for (const CallEvent& e : outcome.events)
        report({e.kind == CallEvent::Kind::Grew ? Issue::Kind::Overflow : Issue::Kind::Device, e.message});
    m_report.redoneSteps += outcome.redone;
    m_report.colors = w.lastColorsUsed;
    m_report.softSubsteps = w.lastSoftSubsteps;
    // A mass ratio that needs more substeps than SoftStepConfig::maxSubsteps gives: said once
    // each time the world comes to one.
    BtgSoftParams uncapped = w.softParams;
    uncapped.maxSubsteps = 1 << 16;
    const bool softCapped = w.lastSoftSubsteps > 0 && btgSoftSubstepsFor(uncapped, w.lastSoftMassRatio) > w.lastSoftSubsteps;
    if (softCapped && !m_softCapReported)
        report({Issue::Kind::Difference,
                "the soft step's substeps are capped at SoftStepConfig::maxSubsteps (" +
                    std::to_string(w.lastSoftSubsteps) + "): a contact or joint of mass ratio " +
                    std::to_string(w.lastSoftMassRatio) + " needs " +
                    std::to_string(btgSoftSubstepsFor(uncapped, w.lastSoftMassRatio)) +
                    " to hold a heavy body on a light one"});
    m_softCapReported = softCapped;
    if (outcome.abandoned) return false;
    if (s.params.randomSeed != 0u) m_orderStream = s.params.randomSeed + unsigned(s.substeps);
    m_rows.stepped();
    m_report.pairs = int(std::min<size_t>(m_readback.counters[kPairCount], w.pairCapacity));
    m_report.contacts = int(m_readback.counters[kContactCount]);
    return true;
}

bool GpuWorld::acceptStep(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
    const btVector3 g = m_world.getGravity();
    const bool badGravity = !std::isfinite(g.x()) || !std::isfinite(g.y()) || !std::isfinite(g.z());
    if (badGravity && !m_badGravityNamed)
        report({Issue::Kind::BadArgument, "world gravity is not finite (setGravity): the bodies it was given to are "
                                          "kept out of the simulation"});
    m_badGravityNamed = badGravity;
    std::string bad = badStepArguments(timeStep, maxSubSteps, fixedTimeStep, m_world.m_localTime);
    if (bad.empty()) {
        m_lastBadArgument.clear();
        return true;
    }
    if (bad != m_lastBadArgument) report({Issue::Kind::BadArgument, bad + "; nothing simulated"});
    m_lastBadArgument = bad;
    return false;
}

int GpuWorld::stepOnCpuPath(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
    m_cpuGuard.hold(m_world, [this](Issue issue) { report(std::move(issue)); });
    struct Release {
        CpuPathGuard& guard;
        ~Release() { guard.release(); }
    } release{m_cpuGuard};
    // The GPU rows no longer hold what the bodies hold: resynced from scratch when it returns.
    m_needsRebuild = true;
    leaveGpuPath();
    completeBroadphasePairs();
    return m_world.baseStepSimulation(timeStep, maxSubSteps, fixedTimeStep);
}

bool GpuWorld::step(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep, int* substepsDone)
{
    if (m_config.forceCpu) {
        m_report.gpuPath = false;
        m_report.cpuPathReason = "Config::forceCpu";
        return false;
    }
    if (!ensureDevice()) {
        m_report.gpuPath = false;
        return false;
    }
    const Clock::time_point checkStart = Clock::now();
    m_stepDt = maxSubSteps ? fixedTimeStep : timeStep;
    m_overlapFilter = ContactCallbacks::overlapFilter(m_world);
    // A body given another shape (setCollisionShape), or a shape the app changed in place
    // (setLocalScaling, setMargin, its points) since the tables were built: they are built
    // again, as for an added body, and the rules asked again. Swaps first: the app may have
    // deleted a shape it swapped out, and only shapes still in use are read. The swaps are
    // seen on the rules' own walk over the objects (one walk a step, not two: H100 host, cubes
    // 112,500, the checks were 0.73-0.79 ms); shapesSwapped() walks them itself only where a
    // rule stopped that walk short.
    int bodyIndex = -1;
    std::string why;
    if (m_structureDirty) {
        why = cpuPathReason(&bodyIndex);
    } else {
        ShapeWalk walk;
        why = cpuPathReason(&bodyIndex, &walk);
        const bool swapped = !m_structureDirty && (walk.complete ? walk.swapped : shapesSwapped());
        if (!m_structureDirty && (swapped || m_shapes.changedSinceBuilt())) {
            m_structureDirty = true;
            why = cpuPathReason(&bodyIndex);
        }
    }
    if (!why.empty()) {
        if (!m_onCpuPath || why != m_report.cpuPathReason) {
            std::cerr << "btgpu: running on the CPU path: " << why << "\n";
            Issue issue{Issue::Kind::Fallback, why};
            if (bodyIndex >= 0) {
                const btCollisionObject* o = m_world.getCollisionObjectArray()[bodyIndex];
                issue.bodyIndex = bodyIndex;
                issue.userIndex = o->getUserIndex();
                issue.shapeType = o->getCollisionShape()->getShapeType();
            }
            report(issue);
        }
        m_onCpuPath = true;
        m_report.cpuPathReason = why;
        m_report.gpuPath = false;
        // The CPU path moves the bodies (and may add, remove or change anything): the step
        // that comes back uploads every row again.
        m_needsRebuild = true;
        return false;
    }
    // Auto between its two solvers: the contacts start afresh (each keeps its own manifolds).
    const SolverKind run = solverToRun();
    const bool switched = run != m_solver;
    m_solver = run;
    m_report.solver = run;
    m_report.solverReason = m_autoReason;
    if (m_needsRebuild) {
        // Stock's contacts as its algorithms leave them, continued by the device's first step.
        const std::vector<StockContact> stock = takeStockContacts(m_world.getDispatcher());
        m_manifolds.takeFromStock(m_world.getDispatcher());
        dropCpuPathManifolds();
        rebuild();
        seedContacts(*m_dev, stock, m_rows, [this](int row) {
            const int shape = m_mirror.at(size_t(row)).props.shape;
            return shape >= 0 && size_t(shape) < m_shapes.shapes.size() ? m_shapes.shapes[size_t(shape)].type : -1;
        });
        m_needsRebuild = false;
    } else if (switched) {
        rebuild();
    } else if (m_rowsStale) {
        followRows();
    }
    // Past Config::deviceEmptyManifoldsUpTo the dispatcher holds no empty manifolds, where stock
    // holds one per broadphase pair: said once each time the world grows past it.
    const bool emptyCapped = m_config.fillDispatcherManifolds && m_config.deviceEmptyManifolds &&
                             !m_config.stockEmptyManifolds &&
                             m_world.getNumCollisionObjects() > m_config.deviceEmptyManifoldsUpTo;
    if (emptyCapped && !m_emptyCapReported)
        report({Issue::Kind::Difference,
                "the dispatcher holds the contact manifolds with points only (stock also holds an empty one per "
                "broadphase pair): " + std::to_string(m_world.getNumCollisionObjects()) +
                    " collision objects, more than Config::deviceEmptyManifoldsUpTo (" +
                    std::to_string(m_config.deviceEmptyManifoldsUpTo) + ")"});
    m_emptyCapReported = emptyCapped;
    // Ghosts, an overlap filter or the host's exact mode may come and go between plans.
    if ((deviceLeafPairs() || ghostsFromDevice()) != m_plan.broadphaseLeaves) {
        m_plan.broadphaseLeaves = !m_plan.broadphaseLeaves;
        m_report.stages = m_plan.stages();
        m_dev->leaves.reset = true;
        m_leafPairs.clear();
    }
    m_onCpuPath = false;
    m_report.cpuPathReason.clear();
    m_report.checkMs = msBetween(checkStart, Clock::now());

    // Time bookkeeping exactly as btDiscreteDynamicsWorld::stepSimulation.
    btScalar localTime = m_world.m_localTime;
    int numSubSteps = 0;
    if (maxSubSteps) {
        localTime += timeStep;
        if (localTime >= fixedTimeStep) {
            numSubSteps = int(localTime / fixedTimeStep);
            localTime -= numSubSteps * fixedTimeStep;
        }
    } else {
        fixedTimeStep = timeStep;
        localTime = m_world.m_latencyMotionStateInterpolation ? 0 : timeStep;
        if (btFuzzyZero(timeStep)) {
            numSubSteps = 0;
            maxSubSteps = 0;
        } else {
            numSubSteps = 1;
            maxSubSteps = 1;
        }
    }

    // As stepSimulation: a debug drawer's DBG_NoDeactivation decides gDisableDeactivation.
    if (btIDebugDraw* drawer = m_world.getDebugDrawer())
        gDisableDeactivation = (drawer->getDebugMode() & btIDebugDraw::DBG_NoDeactivation) != 0;

    m_dev->profiler.resetLaunchCount();
    m_report.syncInMs = m_report.deviceMs = m_report.writeBackMs = m_report.manifoldFillMs = 0.0;
    m_report.ghostBroadphaseMs = 0.0;
    m_report.callbackMs = 0.0;
    m_report.contactCallbacks = 0;
    const bool profiled = m_config.profile && (m_calls++ % std::max(m_config.profileEvery, 1)) == 0;
    m_dev->profiler.enabled = profiled;
    // Set before the substeps, as stock Bullet does: motion-state interpolation reads them.
    m_world.m_localTime = localTime;
    m_world.m_fixedTimeStep = maxSubSteps ? fixedTimeStep : 0;
    m_fusedWriteBack = false;
    if (numSubSteps) {
        int clamped = numSubSteps > maxSubSteps ? maxSubSteps : numSubSteps;
        m_world.saveKinematicState(fixedTimeStep * clamped);
        const bool actions = m_world.m_actions.size() > 0;
        // Ghosts: the host runs stock's broadphase update at each internal step's start.
        const bool ghosts = !m_ghosts.empty();
        // The app's contact callbacks: each internal step stops between its contacts and its solve.
        const std::function<bool()> betweenContacts = contactHostPart();
        const bool callbacks = bool(betweenContacts);
        // The manifold events are the fill's, at every internal step as stock's.
        // Bullet's broadphase on the host at each internal step's start: for ghosts, for an
        // app's overlap filter (which stock's pair cache asks for each new pair), and for stock's
        // empty manifolds (its pairs).
        const bool hostBroadphase = broadphaseAsStock();
        const bool stockPairs = m_config.fillDispatcherManifolds && m_config.stockEmptyManifolds;
        // CCD: each internal step its own device call, asked before and after whether stock's
        // sweeps would hit (ccd_steps.h).
        const bool ccd = !m_ccdBodies.empty();
        bool perSubstep = m_world.m_internalTickCallback || m_world.m_internalPreTickCallback || actions || ghosts ||
                          callbacks || ContactCallbacks::events() || stockPairs || ccd || tracksAnglesEachStep(m_world);
        int batches = perSubstep ? clamped : 1;
        int perBatch = perSubstep ? 1 : clamped;
        for (int b = 0; b < batches; ++b) {
            // An action or tick callback of the step before may have added or removed something
            // or changed a setting the rules look at: the rows follow, or the rest of the call
            // runs on the CPU path.
            if (b > 0 && !followWithinCall(b, batches, fixedTimeStep)) {
                *substepsDone = numSubSteps;
                return finishCall(profiled, false);
            }
            if (m_world.m_internalPreTickCallback) m_world.m_internalPreTickCallback(&m_world, fixedTimeStep);
            // Stock's predictive sweep, with the velocity the step starts with: a hit makes a
            // contact the device has not, so this step is Bullet's own.
            std::string ccdHit;
            if (ccd && ccdSweepHits(m_world, m_ccdBodies, fixedTimeStep,
                                    [&](btRigidBody* body) { return dampedVelocity(body, fixedTimeStep); }, &ccdHit)) {
                cpuPathFrom(b, batches, fixedTimeStep, ccdHit, true);
                *substepsDone = numSubSteps;
                return finishCall(profiled, false);
            }
            // What internalSingleStepSimulation sets for the app's callbacks and queries.
            btDispatcherInfo& dispatchInfo = m_world.getDispatchInfo();
            dispatchInfo.m_timeStep = fixedTimeStep;
            dispatchInfo.m_stepCount = 0;
            dispatchInfo.m_debugDraw = m_world.getDebugDrawer();
            m_world.getSolverInfo().m_timeStep = fixedTimeStep;
            Clock::time_point t0 = Clock::now();
            if (hostBroadphase) {
                const Clock::time_point g0 = Clock::now();
                btDbvtBroadphase* dbvt = dbvtBroadphase();
                const bool ghostsOnly = dbvt && !m_ghosts.empty() && !m_overlapFilter && !stockPairs &&
                                        m_world.getNumCollisionObjects() > m_config.ghostPairsExactUpTo;
                if (ghostsOnly) {
                    updateGhostPairsFromTree(m_world, *dbvt, m_ghosts, fixedTimeStep);
                    m_broadphasePairsStale = !dbvt->m_deferedcollide;  // the others' pairs, before a CPU-path step
                } else {
                    completeBroadphasePairs();  // after steps that synced without pair tests
                    updateBroadphaseAsStock(m_world, fixedTimeStep);
                }
                if (!m_ghosts.empty()) heldAwakeByGhosts(m_world, m_rows, &m_heldAwake);
                if (stockPairs) m_manifolds.notePairs(m_world.getDispatcher(), m_world.getPairCache(), m_rows, m_removed);
                m_report.ghostBroadphaseMs += msBetween(g0, Clock::now());
            }
            syncIn(*m_dev, changedRows());
            afterSyncIn();
            m_joints.upload(m_world, m_rows, *m_dev);  // limits, pivots, enabled, ... as the app left them
            if (m_ignored.update(m_rows, *m_dev)) {
                m_plan.hasIgnoredPairs = m_ignored.any();
                m_report.stages = m_plan.stages();
            }
            // The transforms this device call collides at, for the fill's refresh of old points
            // (one device substep: the reports are of it).
            if (m_config.fillDispatcherManifolds) {
                if (perBatch * std::max(m_config.internalSubsteps, 1) == 1) m_manifolds.noteCollidedAt(m_rows, m_world.getForceUpdateAllAabbs());
                else m_manifolds.forgetCollidedAt();
            }
            Clock::time_point t1 = Clock::now();
            // A change the callbacks made that the device cannot carry: this internal step and
            // the rest of the call run on the CPU path (the callbacks are called again there).
            auto abandoned = [&] {
                m_callbackReason = m_callbacks.reason();
                m_callbackReasonFor = ContactCallbacks::current();
                cpuPathFrom(b, batches, fixedTimeStep, m_callbackReason, true);
                *substepsDone = numSubSteps;
                return finishCall(profiled, false);
            };
            // Stock's clamping sweep, with the solved velocity: a hit would stop the body where
            // the device moved it on. The device's step is dropped (nothing of it has reached the
            // app's objects yet: this runs before the write-back, and before the actions, which
            // stock runs after integrateTransforms) and Bullet's own runs instead.
            auto solved = [&](btRigidBody* body) {
                const int r = m_rows.rowOf(body);
                if (r < 0) return body->getLinearVelocity();
                const BtgFloat4 v = m_readback.linVel[size_t(r)];
                return btVector3(v.x, v.y, v.z);
            };
            auto clampedByCcd = [&] { return ccd && ccdSweepHits(m_world, m_ccdBodies, fixedTimeStep, solved, &ccdHit); };
            if (m_plan.broadphaseLeaves) startLeafPairs();
            if (actions) {
                if (!runOnDevice(perBatch, fixedTimeStep, SubstepPart::BeforeActivation, betweenContacts)) return abandoned();
                if (m_plan.broadphaseLeaves) noteLeafPairs(perBatch);
                if (clampedByCcd()) {
                    cpuPathFrom(b, batches, fixedTimeStep, ccdHit, true);
                    *substepsDone = numSubSteps;
                    return finishCall(profiled, false);
                }
                m_joints.writeBack(*m_dev);
                writeBack(m_readback, false, false);
                fillManifolds();  // the actions see this internal step's contacts
                runActions(fixedTimeStep);
                runOnDevice(1, fixedTimeStep, SubstepPart::ActivationOnly);
            } else {
                if (!runOnDevice(perBatch, fixedTimeStep, SubstepPart::Whole, betweenContacts)) return abandoned();
                if (m_plan.broadphaseLeaves) noteLeafPairs(perBatch);
                if (clampedByCcd()) {
                    cpuPathFrom(b, batches, fixedTimeStep, ccdHit, true);
                    *substepsDone = numSubSteps;
                    return finishCall(profiled, false);
                }
                m_joints.writeBack(*m_dev);  // applied impulses, feedback, breaks
            }
            Clock::time_point t2 = Clock::now();
            writeBack(m_readback, b == batches - 1);
            if (!actions && b == batches - 1 && aabbsBesideFill()) fillBesideAabbSync();
            else if (!actions) fillManifolds();  // before the tick callback, which may read them
            m_report.syncInMs += msBetween(t0, t1);
            m_report.deviceMs += msBetween(t1, t2);
            m_report.writeBackMs += msBetween(t2, Clock::now());
            if (m_world.m_internalTickCallback) m_world.m_internalTickCallback(&m_world, fixedTimeStep);
        }
    } else {
        // Nothing to simulate this call, but what the app changed is still looked at: a body
        // made bad is named now, as on the CPU path, not at the next call that steps.
        Clock::time_point t0 = Clock::now();
        syncIn(*m_dev, changedRows());
        afterSyncIn();
        m_report.syncInMs += msBetween(t0, Clock::now());
    }
    *substepsDone = numSubSteps;
    return finishCall(profiled, true);
}

std::string GpuWorld::ccdReason() const
{
    // A step CCD acts in runs again on Bullet's own path: nothing of the device's may have
    // reached the app before (the contact callbacks inside the step; the pre-tick callback is
    // not called again there), and the sweeps need Bullet's broadphase where the bodies are. Actions run after the clamping check; ghosts' pairs, updated at the step's start as
    // stock's, are what Bullet's own step finds again.
    if (!m_config.syncBroadphaseAabbs)
        return "continuous collision detection (setCcdMotionThreshold) with Config::syncBroadphaseAabbs off (the "
               "sweeps need Bullet's broadphase where the bodies are)";
    if (m_config.internalSubsteps > 1)
        return "continuous collision detection (setCcdMotionThreshold) with Config::internalSubsteps > 1";
    if (ContactCallbacks::wanted(m_world) || ContactCallbacks::overlapFilter(m_world))
        return "continuous collision detection (setCcdMotionThreshold) beside contact callbacks that run before the "
               "solve or an overlap filter (a step CCD acts in runs again on the CPU path, which would call them "
               "twice)";
    return "";
}

void GpuWorld::reservePairsAndContacts(size_t rows, bool keepCache)
{
    // A first guess of one pair and one contact a body (a pile settles at about four, a scene
    // of bodies apart needs none): the buffers then grow from the counts of a step that
    // overflowed (pipeline.cpp's grow, which redoes that step), so memory follows the scene.
    DeviceWorld& w = *m_dev;
    w.pairCapacity = std::max(w.pairCapacity, std::max<size_t>(256, rows));
    w.contactCapacity = std::max(w.contactCapacity, std::max<size_t>(256, rows));
    w.pairs.reserveExact(w.ctx, w.pairCapacity);
    w.manifolds.reserveExact(w.ctx, w.pairCapacity);
    w.contacts.reserveExact(w.ctx, w.contactCapacity);
    w.contactCache.reserveExact(w.ctx, w.contactCapacity, keepCache);
}

bool GpuWorld::finishCall(bool profiled, bool gpuPath)
{
    Clock::time_point t3 = Clock::now();
    m_world.synchronizeMotionStates();
    m_world.clearForces();
    Clock::time_point t4 = Clock::now();
    // With ghosts (or an overlap filter) the broadphase holds stock's AABBs already (set at the
    // step's start): moving them here would add pairs, and ghost overlaps, stock does not have.
    if (m_config.syncBroadphaseAabbs && !broadphaseAsStock() && !m_aabbsSynced) syncBroadphaseAabbs();
    m_report.writeBackMs += msBetween(t3, t4);
    m_report.aabbSyncMs = msBetween(t4, Clock::now()) + m_aabbWaitMs;  // beside the fill: what it added
    m_aabbsSynced = false;
    m_aabbWaitMs = 0.0;
    m_report.stageMs.clear();  // empty on calls that were not profiled
    if (profiled) m_dev->profiler.collect(m_report.stageMs);
    m_report.launches = m_dev->profiler.launches();
    m_report.builtPrograms = m_ctx->builtPrograms();
    m_report.buildSeconds = m_ctx->buildSeconds();
    m_report.deviceBytes = cl::bytesInUse(*m_ctx);
    m_report.gpuPath = gpuPath;
    // The call is done whichever path finished it: the caller must not run it again.
    return true;
}

std::uint64_t GpuWorld::stateHash() const
{
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&](const void* p, size_t n) {
        const unsigned char* c = static_cast<const unsigned char*>(p);
        for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
    };
    const btCollisionObjectArray& objs = m_world.getCollisionObjectArray();
    for (int i = 0; i < objs.size(); ++i) {
        const btTransform& t = objs[i]->getWorldTransform();
        float v[12] = {t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z(), t.getBasis()[0][0], t.getBasis()[0][1],
                       t.getBasis()[0][2], t.getBasis()[1][0], t.getBasis()[1][1], t.getBasis()[1][2],
                       t.getBasis()[2][0], t.getBasis()[2][1], t.getBasis()[2][2]};
        mix(v, sizeof(v));
        if (const btRigidBody* rb = btRigidBody::upcast(objs[i])) {
            float u[6] = {rb->getLinearVelocity().x(), rb->getLinearVelocity().y(), rb->getLinearVelocity().z(),
                          rb->getAngularVelocity().x(), rb->getAngularVelocity().y(), rb->getAngularVelocity().z()};
            mix(u, sizeof(u));
        }
    }
    return h;
}

}  // namespace btgpu
