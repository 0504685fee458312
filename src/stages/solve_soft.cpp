// solve_soft.cpp — host launcher of the soft step: edges into per-color ranges, then either
// every pass in one launch (resident groups on a GPU, one group for small scenes on a CPU) or
// per pass and color one launch (body passes one launch each), the last color serially.
#include "stages/solve_soft.h"

#include "cl/program.h"
#include "stages/prims/scan.h"
#include "stages/resident.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace btgpu {

namespace {
// As solve_constraints: up to this many contacts a CPU device takes the whole stage in one
// launch on one work-group.
constexpr int kOneGroupMaxContacts = 4096;
// Where the CPU device takes the sweeps eight contacts a work-item (wideSweeps), the per-colour
// launches win above about a thousand contacts (PoCL, 2 cores, cubes of 343 / 1,000: frame
// 8.9 / 19.1 ms against one group's 8.7 / 24.7; 125: 5.8 against 3.4, the launches' host cost).
constexpr int kOneGroupMaxContactsWide = 1024;
// ... and as many bodies: one group runs the substeps' body passes on one core (PoCL cubes
// 32,768 while they fall, few contacts: frame 87.6 ms against b4e1194's 33.2).
constexpr int kOneGroupMaxBodiesWide = 4096;
// Past one group, the one-launch kernel (a group a core, grid barriers between the colours) only
// up to this many contacts; above it the per-colour launches. The one-launch kernel saves the
// launches' host cost (about 300 a step), which wins in small scenes, but its groups spin at
// every barrier for each other: a core slowed by anything else on the machine stalls both, and
// its compiled code runs slower than the per-colour kernels' (one group alone 86 ms a step at
// cubes 8,000, where two take 42-46 and the launches 36). PoCL, 2 cores, 2026-12-06, solve
// stage one launch / launches, alternating runs: cubes 729 (2,400 contacts) 5.7 / 4.2 ms at
// equal frames; 1,000 7.6-7.8 / 5.3-5.4 (frame 10.9-11.1 / 10.1-10.2); 8,000 61-63 / 36-37
// (and 42-83 / 36 on other runs: the spin's spread); 32,768 326-356 / 179-197. Both give the
// same bits (state hashes). And only up to kOneGroupMaxBodiesWide bodies: its body passes over
// many bodies lose as well (cubes falling, few contacts, frame one launch / launches, 45-50
// frames: 32,768 90.5-96.6 / 53.2-62.0 ms, 8,000 27.1-30.7 / 17.7-25.7; 4,096 even, 14.3-14.7 /
// 13.5-15.1).
constexpr int kResidentMaxContactsWide = 2048;
constexpr int kMaxSubsteps = 256;

// A CPU device takes the solve and relax sweeps eight contacts a work-item (soft_wide.h): it
// runs each work-item's rows as scalar code, and the sweeps were its soft step's cost. Not
// where a pass reads the soft contacts between the sweeps (every substep's gather) or the order
// is not the colours' and points' own. BTGPU_SOFT_WIDE=0: the scalar sweeps there too (an
// experiment knob, for measuring).
bool wideSweeps(cl::Context& ctx, const BtgSoftParams& params)
{
    static const bool off = [] {
        const char* e = std::getenv("BTGPU_SOFT_WIDE");
        return e && e[0] == '0';
    }();
    return !ctx.device().isGpu && !off && !params.gather && !params.interleave && params.orderSeed == 0u &&
           !(params.heldMassRatio > 0.0f);
}

// The substep fields of the step's scalars: the base count, and how it grows with the mass
// ratio. An explicit substep count is kept; m_numIterations' grows unless the light bodies are
// held (the other cure: held at 64 substeps a 1,000:1 pair sinks metres).
BtgSoftParams substepFields(const SoftStepConfig& c, int iterations)
{
    BtgSoftParams p{};
    p.substeps = std::clamp(c.substeps > 0 ? c.substeps : iterations, 1, kMaxSubsteps);
    p.rootRatioSubsteps = c.substeps > 0 || c.heldMassRatio > 0.0f ? 0.0f : std::max(c.substepsPerRootMassRatio, 0.0f);
    p.maxSubsteps = std::clamp(c.maxSubsteps, p.substeps, kMaxSubsteps);
    return p;
}

// Work-items a resident group takes (resident.h): about one per contact of a colour over the
// groups, 64 to 256 with a group per compute unit. H200, solve stage ms at 256 / 128 / 64
// work-items a group (132 groups): cubes 1,000 2.27 / 2.27 / 1.95, 8,000 - / 2.74 / 2.23, 32,768
// 4.91 / 4.12 / 5.64, 112,500 5.96 / 6.44 / 8.72 (at 32,768, 124,000 contacts in 14 colours, 72 a
// compute unit): the rule takes 64, 64, 128 and 256. Fewer groups (softGroups) take up to 1,024
// work-items each, so that a colour still fits them in one round.
size_t softGroupSize(const DeviceWorld& w, int numColors, bool quad, size_t groups)
{
    const size_t units = std::max<cl_uint>(w.ctx.device().computeUnits, 1);
    const size_t perColor = size_t(std::max(w.lastContactCount, 0)) / size_t(std::max(numColors - 1, 1));
    const size_t want = (quad ? 4 : 1) * perColor / std::max<size_t>(groups, 1);
    const size_t cap = groups < units ? 1024 : 256;
    size_t size = 64;
    while (size < want && size < cap) size *= 2;
    return size;
}

// A read in flight into host memory the caller holds: waited for (and its event released) at
// wait() or, should a launch throw first, when the caller's frame unwinds.
struct ReadWait {
    cl_event event = nullptr;
    void wait()
    {
        if (!event) return;
        const cl_int err = clWaitForEvents(1, &event);
        clReleaseEvent(event);
        event = nullptr;
        BTGPU_CL_CHECK(err);
    }
    ~ReadWait()
    {
        if (!event) return;
        clWaitForEvents(1, &event);
        clReleaseEvent(event);
    }
};

// The soft step's resident groups on a GPU: one per compute unit (DeviceWorld::softResidentGroups
// sets another count, for tests). Fewer groups in small scenes lose, though every group arrives
// at each of the step's some 300 grid barriers: H100, 2026-12-07, median frame ms over 300,
// a group per unit / one group of up to 1,024 work-items / one group read through plain loads
// (its barriers order them on one compute unit): cubes 125 1.63 / 1.68 / 1.68, 1,000 2.27 / 4.55 /
// 4.51, ragdolls 20 1.27 / 1.57 / 1.50, voronoi 2.38 / 2.66 / 2.50; the same state hashes. A
// small scene's phases wait on their dependent loads, not on the barrier's arrivals.
size_t softGroups(const DeviceWorld& w)
{
    const size_t all = residentSolveGroups(w);
    return w.softResidentGroups > 0 ? std::min(w.softResidentGroups, all) : all;
}

// Whether the resident solve and relax sweeps take a contact on four work-items (NVIDIA's GPUs:
// soft_quad_rows.h, shfl.sync across the quad): a colour then waits for a quarter of each
// contact's per-point arithmetic. H100, 2026-12-06, solve stage median ms without / with, the
// same state hashes: cubes 1,000 1.71 / 1.51, 32,768 4.22 / 3.78, 112,500 3.63 / 3.48. Not with
// held pairs (their rows write the support's impulses: one work-item must). BTGPU_SOFT_QUAD=0
// turns it off (for measuring).
bool softQuad(const DeviceWorld& w, const BtgSoftParams& params)
{
    static const bool off = [] {
        const char* e = std::getenv("BTGPU_SOFT_QUAD");
        return e && e[0] == '0';
    }();
    return w.ctx.device().isNvidiaGpu() && !(params.heldMassRatio > 0.0f) && !off;
}

// The resident launch's flow (DeviceWorld::softFlow): 0 off, 1 the sweeps' colours, 2 also the
// substeps' body passes. Off by default; BTGPU_SOFT_FLOW=1 or 2 acts on CPU devices only: on an
// H100 (2026-12-05, cubes 32,768) flow 1 took the solve from 5.2 to 6.7 ms and flow 2 to 26.8,
// and their state hashes differed from run to run there (the per-body count waits race on a GPU
// at that size), so the knob leaves a GPU's launches alone.
int softFlow(const DeviceWorld& w)
{
    using R = DeviceWorld::Resident;
    static const int knob = [] {
        const char* e = std::getenv("BTGPU_SOFT_FLOW");
        return e && (e[0] == '1' || e[0] == '2') ? e[0] - '0' : 0;
    }();
    if (w.softFlow == R::On) return 2;
    if (w.softFlow == R::Off) return 0;
    return w.ctx.device().isGpu ? 0 : knob;
}

}  // namespace

float pushSpeedFor(const SoftStepConfig& c, const BtgStepParams& params)
{
    if (c.pushSpeed > 0.0f) return c.pushSpeed;
    // Stock pushes a penetration shallower than the split-impulse threshold with real velocity
    // (erp x depth / dt) and a deeper one by split impulse (positions only): the most velocity a
    // penetration gets there is erp x |threshold| / dt. Without split impulse every penetration
    // is pushed with real velocity, unbounded: Box2D's cap then.
    constexpr float kBox2dContactSpeed = 3.0f;
    if (!params.splitImpulse || !(params.dt > 0.0f)) return kBox2dContactSpeed;
    const float v = params.erp * std::fabs(params.splitPenetrationThreshold) / params.dt;
    return v > 0.0f ? std::min(v, kBox2dContactSpeed) : kBox2dContactSpeed;
}

int softSubsteps(const SoftStepConfig& c, int iterations, float massRatio)
{
    return btgSoftSubstepsFor(substepFields(c, iterations), massRatio);
}

BtgSoftParams makeSoftParams(const SoftStepConfig& c, const BtgStepParams& params, int iterations)
{
    BtgSoftParams p = substepFields(c, iterations);
    p.dt = params.dt;
    p.hertz = c.contactHertz;
    p.zeta = c.dampingRatio;
    p.warmstartFactor = params.warmstartFactor;
    p.pushSpeed = pushSpeedFor(c, params);
    p.restitutionThreshold = params.restitutionThreshold;
    p.frictionInSolve = c.frictionInSolve ? 1 : 0;
    p.maxSag = std::max(c.maxSag, 0.0f);
    p.heldMassRatio = std::max(c.heldMassRatio, 0.0f);
    p.orderSeed = params.randomSeed;
    p.interleave = (params.solverFlags & BTG_SOLVER_INTERLEAVE) != 0u ? 1 : 0;
    p.processingThreshold = (params.solverFlags & BTG_SOLVER_PROCESSING_THRESHOLD) != 0u ? 1 : 0;
    btgSoftCfmSpring(&p, params.globalCfm, params.erp2, params.dt);
    p.rolling = (params.solverFlags & BTG_SOLVER_ROLLING_FRICTION) != 0u ? 1 : 0;
    p.anisotropic = (params.solverFlags & BTG_SOLVER_ANISOTROPIC_FRICTION) != 0u ? 1 : 0;
    p.twoDirections = params.twoFrictionDirections ? 1 : 0;
    p.gather = btgSoftGathers(p);
    return btgSoftParamsWith(p, p.substeps);
}

void solveSoft(DeviceWorld& w, BtgSoftParams params, int numColors)
{
    cl::Context& ctx = w.ctx;
    const size_t slots = std::min({w.edgeCapacity, w.edges.capacity(), w.edgeColor.capacity()});
    const int numBodies = std::max(w.numBodies, 0);
    if (numBodies == 0) return;
    const int edgeCapacity = int(slots);
    numColors = std::max(numColors, 1);
    // A spring row's impulse is the step's, applied once (btgSoftJointSolve): the carried warm
    // start would apply its last substep's share again, so the substeps gather. (Joints turn their
    // linear rows each substep, btgSoftTurnLinearRows; their relax moves the bodies' carry marks
    // by what the turn changes, so the carry stays the gather's warm start.) BTGPU_SOFT_GATHER=1
    // gathers every substep anyway (to measure, and to test the carry against).
    const char* gatherEnv = std::getenv("BTGPU_SOFT_GATHER");
    const bool forceGather = gatherEnv && std::strcmp(gatherEnv, "1") == 0;
    if (w.jointSprings > 0 || forceGather) params.gather = 1;
    cl::Program& prog = ctx.program("solve_soft");
    SolverScratch& sc = w.solverScratch;
    // exactly: the slots grow geometrically already (contactCapacity), and the store and the
    // reports may have grown this storage to their own size (SolverScratch::rowsAs)
    sc.softContacts.reserveExact(ctx, std::max<size_t>(slots, 1));
    sc.softBodies.reserve(ctx, size_t(BTG_SOFT_BODY_ROWS) * size_t(numBodies));
    sc.softSolver.reserve(ctx, size_t(BTG_SOFT_SOLVER_ROWS) * size_t(numBodies));
    // Bound buffers even without contacts or joints.
    w.contacts.reserve(ctx, 1);
    w.joints.reserve(ctx, 1);
    w.jointState.reserve(ctx, 1);
    w.jointRows.reserve(ctx, 1);
    w.rollingContacts.reserve(ctx, 1);  // read with BtgSoftParams::rolling only (prepare_contacts fills it then)
    // The contact callbacks' materials apply_contact_materials took this substep: the soft
    // contacts take their restitution from them (their friction is already the contacts').
    const int materials = w.appliedMaterials;
    w.appliedMaterials = 0;
    w.contactManifolds.reserve(ctx, 1);
    w.contactMaterials.reserve(ctx, 1);
    w.frictionDirs.reserve(ctx, 1);  // read with BtgSoftParams::anisotropic only (prepare_contacts fills it then)
    // The bodies' edge lists (the warm start's gather): none until the edges are listed below.
    sc.softListStart.reserve(ctx, size_t(numBodies) + 1);
    sc.softListStart.zero(ctx, size_t(numBodies) + 1);
    sc.softListCursor.reserve(ctx, size_t(numBodies));
    sc.softListEntries.reserve(ctx, 2 * std::max<size_t>(slots, 1));
    sc.edgeSlot.reserve(ctx, std::max<size_t>(slots, 1));
    auto soft = [&](cl::Launch& l) -> cl::Launch& {
        return l.arg(w.contacts).arg(sc.softContacts).arg(w.props).arg(w.invInertiaWorld).arg(w.linVel0)
            .arg(w.angVel0).arg(w.linVel).arg(w.angVel).arg(sc.softBodies).arg(sc.softSolver).arg(w.joints).arg(w.jointState)
            .arg(w.jointRows).arg(sc.softListStart).arg(sc.softListEntries).arg(sc.edgeSlot).arg(w.counters)
            .arg(w.rollingContacts).arg(w.contactManifolds).arg(w.contactMaterials).arg(materials).arg(w.frictionDirs)
            .arg(params);
    };
    cl_kernel bodies = prog.kernel("soft_bodies");
    // the substeps' passes by kernels compiled for their mode (soft_bodies_velocity, ...)
    auto bodyPass = [&](int mode) {
        const char* own = mode == BTG_SOFT_BODY_VELOCITY ? "soft_bodies_velocity"
                          : mode == BTG_SOFT_BODY_CARRY  ? "soft_bodies_carry"
                          : mode == BTG_SOFT_BODY_POSITION ? "soft_bodies_position"
                                                           : nullptr;
        cl::Launch l(ctx, own ? prog.kernel(own) : bodies, &w.profiler);
        l.arg(numBodies);
        if (!own) l.arg(mode);
        soft(l).run(size_t(numBodies));
    };
    // The bodies' solver records for the step (soft_solver_body reads them).
    cl::Launch(ctx, prog.kernel("soft_solver_bodies"), &w.profiler).arg(numBodies).arg(w.props).arg(w.invInertiaWorld)
        .arg(sc.softSolver).run(size_t(numBodies));
    if (slots == 0) {
        // Nothing to solve yet (no edge slots): the bodies still take their substeps.
        bodyPass(BTG_SOFT_BODY_BEGIN);
        for (int s = 0; s < params.substeps; ++s) {
            bodyPass(BTG_SOFT_BODY_VELOCITY);
            bodyPass(BTG_SOFT_BODY_POSITION);
        }
        bodyPass(BTG_SOFT_BODY_END);
        return;
    }
    sc.colorCount.reserve(ctx, size_t(numColors) + 1);
    sc.colorStart.reserve(ctx, size_t(numColors) + 1);
    sc.colorOrder.reserve(ctx, slots);
    sc.colorCount.zero(ctx, size_t(numColors) + 1);
    cl::Launch(ctx, prog.kernel("soft_color_count"), &w.profiler).arg(w.edgeColor).arg(w.counters).arg(edgeCapacity)
        .arg(sc.colorCount).arg(numColors).arg(w.edges).arg(w.props).run(slots);
    cl::Launch(ctx, prog.kernel("soft_color_offsets"), &w.profiler).arg(sc.colorCount).arg(sc.colorStart)
        .arg(numColors).run(1, 1);
    cl::Launch(ctx, prog.kernel("soft_color_fill"), &w.profiler).arg(w.edgeColor).arg(w.counters).arg(edgeCapacity)
        .arg(sc.colorStart).arg(sc.colorCount).arg(sc.colorOrder).arg(numColors).arg(sc.edgeSlot).run(slots);
    // Each body's edges, sorted: count, scan, fill, sort.
    const int numJoints = w.numJoints;
    sc.softListCursor.zero(ctx, size_t(numBodies));
    cl::Launch(ctx, prog.kernel("soft_list_count"), &w.profiler).arg(w.counters).arg(edgeCapacity).arg(numJoints)
        .arg(w.edgeColor).arg(w.edges).arg(w.joints).arg(w.jointState).arg(w.props).arg(sc.softListCursor).run(slots);
    sc.softListStart.copyRangeFrom(ctx, sc.softListCursor, size_t(numBodies));
    exclusiveScan(ctx, &w.profiler, sc.softListStart, size_t(numBodies) + 1, sc.softListScan);
    sc.softListCursor.zero(ctx, size_t(numBodies));
    cl::Launch(ctx, prog.kernel("soft_list_fill"), &w.profiler).arg(w.counters).arg(edgeCapacity).arg(numJoints)
        .arg(w.edgeColor).arg(w.edges).arg(w.joints).arg(w.jointState).arg(w.props).arg(sc.softListCursor)
        .arg(sc.softListStart).arg(sc.softListEntries).run(slots);
    cl::Launch(ctx, prog.kernel("soft_list_sort"), &w.profiler).arg(numBodies).arg(sc.softListStart)
        .arg(sc.softListEntries).run(size_t(numBodies));
    const bool resident = useResident(w);
    const bool wideOn = wideSweeps(ctx, params) && numColors > 1;
    if (wideOn) {
        sc.reserveWide(ctx, slots, numColors, BTG_SOFT_WIDE_FIELDS);
        cl::Launch(ctx, prog.kernel("soft_wide_offsets"), &w.profiler).arg(sc.colorStart).arg(sc.softWideStart)
            .arg(numColors).run(1, 1);
    } else {
        sc.softWideStart.reserve(ctx, 1);
        sc.softWideBlock.reserve(ctx, 1);
        sc.softWideLanes.reserve(ctx, 1);
    }
    // With the wide sweeps a CPU device takes the whole stage in one launch too, a group a core
    // with grid barriers between the colours, up to kResidentMaxContactsWide contacts: the
    // per-colour path enqueues about 300 launches a step (host cost about 1.5 ms a frame on PoCL).
    const bool wideOneGroup = w.lastContactCount <= kOneGroupMaxContactsWide && numBodies <= kOneGroupMaxBodiesWide;
    const bool wideResident =
        wideOn && residentAllowed(w) && !wideOneGroup && w.lastContactCount <= kResidentMaxContactsWide &&
        numBodies <= kOneGroupMaxBodiesWide;
    const bool oneGroup = wideOn ? wideOneGroup : w.lastContactCount <= kOneGroupMaxContacts;
    if (resident || wideResident || oneGroup) {
        const bool many = resident || wideResident;
        const size_t groups = resident ? softGroups(w) : many ? residentSolveGroups(w) : 1;
        cl_kernel k = prog.kernel("soft_resident");
        const int flow = resident && groups > 1 ? softFlow(w) : 0;
        const int wideIn = wideOn && flow == 0;
        int quad = resident && flow == 0 && softQuad(w, params) ? 1 : 0;
        // A CPU device runs a group's work-items one after another: the flow's waits there need
        // groups of one; its wide sweeps take a chunk of eight contacts a work-item, a few
        // hundred chunks a colour, so small groups.
        const size_t group = flow && !ctx.device().isGpu
                                 ? 1
                                 : wideResident && !resident ? size_t(8)
                                                             : residentSolveGroupSize(cl::kernelGroupLimit(ctx, k), many,
                                                                                      softGroupSize(w, numColors, quad != 0, groups));
        if (group % 32 != 0) quad = 0;  // a quad's four work-items must share a warp
        if (flow) {
            // the ranks, then the kinematic flag after them (soft_flow_ranks)
            sc.softFlowRank.reserve(ctx, 2 * slots + 1);
            sc.softFlowRank.fill(ctx, 0u, 2 * slots, 1);
            sc.softFlowDone.reserve(ctx, size_t(numBodies));
            sc.softFlowDeg.reserve(ctx, size_t(numBodies));
            cl::Launch(ctx, prog.kernel("soft_flow_ranks"), &w.profiler).arg(w.counters).arg(edgeCapacity)
                .arg(numJoints).arg(numColors).arg(sc.colorStart).arg(sc.colorOrder).arg(w.edgeColor).arg(w.edges)
                .arg(w.joints).arg(w.jointState).arg(w.props).arg(sc.softListStart).arg(sc.softListEntries)
                .arg(sc.softFlowRank)
                .run(slots);
            if (flow == 2)
                cl::Launch(ctx, prog.kernel("soft_flow_degrees"), &w.profiler).arg(numBodies).arg(numJoints)
                    .arg(numColors).arg(w.counters).arg(edgeCapacity).arg(w.edgeColor).arg(sc.softListStart)
                    .arg(sc.softListEntries).arg(sc.softFlowDeg).run(size_t(numBodies));
        } else {
            sc.softFlowRank.reserve(ctx, 2 * slots + 1);
            sc.softFlowDone.reserve(ctx, 1);
            sc.softFlowDeg.reserve(ctx, 1);
        }
        // its own barrier words, zeroed for each launch: soft_resident's barrier count only grows
        sc.softBarrier.zero(ctx, BTG_GRID_BARRIER_WORDS);
        cl::Launch l(ctx, k, &w.profiler);
        l.arg(w.edgeColor).arg(edgeCapacity).arg(sc.colorStart).arg(sc.colorOrder).arg(sc.softBarrier)
            .arg(numColors).arg(numJoints).arg(numBodies).arg(gridBarrierSpins(w)).arg(sc.softFlowRank)
            .arg(sc.softFlowDone).arg(sc.softFlowDeg).arg(flow).arg(sc.softWideStart).arg(sc.softWideBlock)
            .arg(sc.softWideLanes).arg(wideIn).arg(quad);
        soft(l).run(groups * group, group);
        return;
    }
    // Launch by launch, the host enqueues the substeps: it waits for the mass ratio the count
    // noted (soft_resident reads it on the device), and reads the colours' ranges and the
    // batching's counts with it, to enqueue no launch that would find nothing to do: the empty
    // colours (the batching's slack, two a sweep) and the leftovers' serial walk when there are
    // none. A launch costs a CPU device tens of microseconds even so (PoCL: 20 sweeps a step).
    std::vector<uint> counts(kNumCounters, 0u);
    std::vector<uint> starts(size_t(numColors) + 1, 0u);
    sc.colorStart.download(ctx, starts.data(), starts.size());
    w.counters.download(ctx, counts.data(), counts.size());
    if (params.rootRatioSubsteps > 0.0f) {
        float ratio = 0.0f;
        std::memcpy(&ratio, &counts[kSoftMassRatio], sizeof ratio);
        const int substeps = btgSoftSubstepsFor(params, ratio);
        if (substeps != params.substeps) params = btgSoftParamsWith(params, substeps);
    }
    auto emptyColor = [&](int c) { return starts[size_t(c)] == starts[size_t(c) + 1]; };
    // soft_color_serial's own early return, known here
    const bool noLeftovers = counts[kLeftovers] == 0u && counts[kColorsUsed] <= uint(numColors - 1);
    const size_t rangeItems = std::min(slots, size_t(std::max<cl_uint>(ctx.device().computeUnits, 1)) * 256);
    cl_kernel range = prog.kernel("soft_color_range"), serial = prog.kernel("soft_color_serial");
    cl_kernel wide = wideOn ? prog.kernel("soft_color_wide") : nullptr;
    const size_t wideItems = (rangeItems + BTG_SOFT_WIDE - 1) / BTG_SOFT_WIDE;
    // key: a solve or relax sweep's order (SOLVER_RANDMIZE_ORDER), as soft_resident takes it
    // Prepare where it notes no supports, and store, touch each edge alone: prepare by contact,
    // the store's regular colours in one launch, as soft_resident takes them (PoCL cubes 8,000: 24
    // launches a step fewer).
    const bool heldPrepare = params.heldMassRatio > 0.0f;
    auto edgePass = [&](int mode, cl_uint key) {
        const int base = btgSoftBaseMode(mode);
        const bool sweep = wide && (base == BTG_SOFT_SOLVE || base == BTG_SOFT_RELAX);
        const bool store = base == BTG_SOFT_STORE;
        if (base == BTG_SOFT_PREPARE && !heldPrepare) {
            // every contact in its own order, the leftovers with them (soft_prepare_by_contact)
            cl::Launch l(ctx, prog.kernel("soft_prepare_by_contact"), &w.profiler);
            l.arg(w.edgeColor).arg(edgeCapacity).arg(numJoints);
            soft(l).run(slots);
            return;
        }
        if (store && numColors > 1) {
            cl::Launch l(ctx, range, &w.profiler);
            l.arg(sc.colorStart).arg(sc.colorOrder).arg(edgeCapacity).arg(numJoints).arg(0).arg(numColors - 1).arg(mode).arg(key);
            soft(l).run(rangeItems, 64);
        }
        for (int ci = store ? numColors - 1 : 0; ci < numColors; ++ci) {
            if (ci == numColors - 1) {
                if (noLeftovers) continue;
                cl::Launch l(ctx, serial, &w.profiler);
                l.arg(w.edgeColor).arg(edgeCapacity).arg(numJoints).arg(ci).arg(mode).arg(key);
                soft(l).run(1, 1);
            } else if (emptyColor(btgPermute(key, numColors - 1, ci))) {
                continue;
            } else if (sweep) {
                // groups of eight chunks: a CPU device runs a group on one core, and a colour
                // has a few hundred chunks to share out
                cl::Launch l(ctx, wide, &w.profiler);
                l.arg(sc.colorStart).arg(sc.colorOrder).arg(sc.softWideStart).arg(sc.softWideBlock)
                    .arg(sc.softWideLanes).arg(edgeCapacity).arg(numJoints).arg(ci).arg(mode).arg(key);
                soft(l).run(wideItems, 8);
            } else {
                const int color = btgPermute(key, numColors - 1, ci);
                cl::Launch l(ctx, range, &w.profiler);
                l.arg(sc.colorStart).arg(sc.colorOrder).arg(edgeCapacity).arg(numJoints).arg(color).arg(color + 1).arg(mode).arg(key);
                soft(l).run(rangeItems, 64);
            }
        }
    };
    // the wide lanes from the soft contacts, after the first substep's gather (which reads their
    // impulses and writes their totals), and back before restitution
    auto widePack = [&] {
        cl::Launch l(ctx, prog.kernel("soft_wide_pack"), &w.profiler);
        l.arg(sc.colorStart).arg(sc.colorOrder).arg(sc.softWideStart).arg(sc.softWideBlock).arg(sc.softWideLanes)
            .arg(edgeCapacity).arg(numJoints).arg(numColors);
        soft(l).run(slots);
    };
    auto wideUnpack = [&] {
        cl::Launch(ctx, prog.kernel("soft_wide_unpack"), &w.profiler).arg(sc.colorStart).arg(sc.softWideStart)
            .arg(sc.softWideBlock).arg(sc.softWideLanes).arg(numColors).arg(sc.softContacts).run(slots);
    };
    bodyPass(BTG_SOFT_BODY_BEGIN);
    edgePass(BTG_SOFT_PREPARE, 0u);
    // Whether prepare found a contact that may bounce, read behind it while the substeps are
    // enqueued: when none does, the restitution pass (a launch a colour, each returning at once)
    // is not enqueued at all, as soft_resident skips it.
    cl_uint bounce = 1u;
    ReadWait bounceRead;  // declared after `bounce`: a launch that throws still waits for the read first
    w.counters.readAsync(ctx, &bounce, 1, kSoftBounce, &bounceRead.event);
    for (int s = 0; s < params.substeps; ++s) {
        bodyPass(btgSoftVelocityMode(params, s));  // and the warm start (gathered, or carried)
        if (s == 0 && wide) widePack();
        edgePass(btgSoftSweepMode(params, s, 0), btgSoftSweepKey(params, s, 0));
        bodyPass(BTG_SOFT_BODY_POSITION);
        edgePass(btgSoftSweepMode(params, s, 1), btgSoftSweepKey(params, s, 1));
    }
    if (wide) wideUnpack();
    bounceRead.wait();
    if (bounce != 0u) edgePass(BTG_SOFT_RESTITUTION, 0u);
    edgePass(BTG_SOFT_STORE, 0u);
    bodyPass(BTG_SOFT_BODY_END);
}

void softTransforms(DeviceWorld& w)
{
    const int n = std::max(w.numBodies, 0);
    if (n == 0 || w.solverScratch.softBodies.capacity() < size_t(BTG_SOFT_BODY_ROWS) * size_t(n)) return;
    cl::Program& prog = w.ctx.program("solve_soft");
    cl::Launch(w.ctx, prog.kernel("soft_transforms"), &w.profiler).arg(n).arg(w.props).arg(w.solverScratch.softBodies)
        .arg(w.linVel).arg(w.angVel).arg(w.pos).arg(w.rot).arg(w.counters).run(size_t(n));
}

}  // namespace btgpu
