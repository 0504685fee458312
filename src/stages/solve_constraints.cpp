// solve_constraints.cpp — host launcher of the solve stage: warm start, `iterations` velocity
// passes (each the joints' colors, then the contacts'; more when a joint overrides its
// iterations upwards) and (split impulse) `iterations` push passes, each one launch per color,
// the last color on a single work-item. Zeroes pushLin/pushAng itself before the push passes.
#include "stages/solve_constraints.h"

#include "cl/program.h"
#include "shared/contact_rows.h"
#include "shared/soft_rows.h"
#include "stages/resident.h"

#include <algorithm>
#include <cstdlib>

namespace btgpu {

namespace {
// Up to this many contacts (as of the last readback) a CPU device solves everything in one
// launch on one work-group: below it launch overhead outweighs the parallelism of one launch
// per color. (On a GPU one lone group is slow: 1,000 cubes took 8.5 ms that way on an H200.)
constexpr int kOneGroupMaxContacts = 4096;
// ... and where the per-colour launches take the wide sweeps (pgsWide), up to this many: PoCL,
// 2 cores, 150 frames, two rounds, frame ms with the limit at 4,096 / 1,024 / 256: cubes 343
// 5.5-5.8 / 6.0-6.6 / 5.9-6.9, 512 7.6-9.0 / 7.7-8.3 / 7.7-8.3, 1,000 (3,300 contacts) 12.9-13.1 /
// 11.2-11.3 / 11.0-11.6.
constexpr int kOneGroupMaxContactsWide = 2048;

// The resident launch's flow (DeviceWorld::pgsFlow): off by default; BTGPU_PGS_FLOW=1 acts on CPU
// devices only (on an H100 at cubes 32,768 it took the solve from 2.3 to 11.1 ms, its state hash
// differing from run to run: see softFlow in solve_soft.cpp).
bool pgsFlow(const DeviceWorld& w)
{
    using R = DeviceWorld::Resident;
    static const bool knob = [] {
        const char* e = std::getenv("BTGPU_PGS_FLOW");
        return e && e[0] == '1';
    }();
    if (w.pgsFlow != R::Auto) return w.pgsFlow == R::On;
    return knob && !w.ctx.device().isGpu;
}

// solve_local (solve_constraints.cl): the solve on one work-group, every body's velocities in its
// local memory, on a GPU up to this many contacts (as of the last readback). Each colour phase of
// the resident solve is a chain of dependent loads (velocities through L2) and a grid barrier,
// about 3.5 us on an H100 whatever the scene's size (125 cubes: 186 phases, 0.7 ms); one group
// with local velocities and a work-group barrier shortens the chain, until one compute unit's
// throughput is what limits. H100, 2026-12-06, solve stage ms (local / resident, two runs):
// cubes 125 0.49 / 0.75, 512 (about 1,600 contacts) 0.85 / 1.00, ragdolls 20 0.33 / 0.49,
// ragdolls 100 (1,100 bodies, forced) 0.70 / 0.76; cubes 1,000 (3,300 contacts, forced) 1.55
// against 1.14: past this count the resident solve's many compute units win.
constexpr int kLocalMaxContacts = 2048;
constexpr size_t kLocalMaxGroup = 1024;
bool pgsLocal(const DeviceWorld& w, size_t bodies, bool flow)
{
    using R = DeviceWorld::Resident;
    if (w.pgsLocal == R::Off || flow || bodies == 0) return false;
    // BTGPU_PGS_LOCAL=0 / 1: never / wherever the velocities fit (an experiment knob)
    static const int knob = [] {
        const char* e = std::getenv("BTGPU_PGS_LOCAL");
        return e && e[0] ? (e[0] == '0' ? 0 : 1) : -1;
    }();
    if (knob == 0 && w.pgsLocal != R::On) return false;
    // two float4 a body, and a little for what the compiler keeps there itself
    if (2 * sizeof(BtgFloat4) * bodies + 1024 > w.ctx.device().localMemBytes) return false;
    if (w.pgsLocal == R::On || knob == 1) return true;
    return useResident(w) && w.ctx.device().isGpu && w.lastContactCount <= kLocalMaxContacts;
}

// A CPU device takes the warm-start, normal and friction sweeps eight contacts a work-item
// (pgs_wide.h): it runs each work-item's rows as scalar code, and the sweeps were about half of
// its frame. Only the rows the wide sweeps serve (no contact cfm, rolling, anisotropic or anchored
// friction, interleave, SOLVER_RANDMIZE_ORDER). BTGPU_PGS_WIDE=0: the scalar sweeps there too (an
// experiment knob, for measuring).
bool pgsWide(const cl::Context& ctx, const BtgStepParams& params, int rows)
{
    static const bool off = [] {
        const char* e = std::getenv("BTGPU_PGS_WIDE");
        return e && e[0] == '0';
    }();
    return !ctx.device().isGpu && !off && (rows & ~BTG_ROWS_TWO_FRICTION) == 0 && params.randomSeed == 0u;
}
}  // namespace

void solveConstraints(DeviceWorld& w, const BtgStepParams& params, int iterations, int numColors)
{
    cl::Context& ctx = w.ctx;
    size_t slots = std::min({w.edgeCapacity, w.edges.capacity(), w.edgeColor.capacity()});
    int edgeCapacity = int(slots);
    if (numColors < 1) numColors = 1;
    size_t bodies = size_t(std::max(w.numBodies, 0));
    if (params.splitImpulse && bodies > 0) {
        w.pushLin.zero(ctx, bodies);
        w.pushAng.zero(ctx, bodies);
    } else {  // bound, not read
        w.pushLin.reserve(ctx, 1);
        w.pushAng.reserve(ctx, 1);
    }
    if (slots == 0) return;
    cl::Program& prog = ctx.program("solve_constraints");
    // The optional rows the passes read (BTG_ROWS_*): without two friction directions the
    // second friction rows have no mass, without cfm normalCfm is zero: not read at all.
    const int rows = btgRowFlags(params);
    w.rollingContacts.reserve(ctx, 1);
    w.frictionDirs.reserve(ctx, 1);
    w.frictionAnchors.reserve(ctx, 1);
    // Edges sorted into per-color ranges once, so each color's launch reads only its own.
    SolverScratch& sc = w.solverScratch;
    // Two lists (see color_count): the contacts, and the contacts with a push target; with
    // joints a third, the joints' edges.
    const int numJoints = w.numJoints;
    const int numLists = numJoints > 0 ? 3 : 2;
    const size_t ranges = size_t(numLists) * (size_t(numColors) + 1);
    const int orderStride = edgeCapacity;
    sc.colorCount.reserve(ctx, ranges);
    sc.colorStart.reserve(ctx, ranges);
    sc.colorOrder.reserve(ctx, size_t(numLists) * slots);
    sc.colorCount.zero(ctx, ranges);
    // Bound buffers even without joints.
    w.joints.reserve(ctx, 1);
    w.jointState.reserve(ctx, 1);
    w.jointRows.reserve(ctx, 1);
    if (ctx.device().isGpu) {
        cl::Launch(ctx, prog.kernel("color_count"), &w.profiler).arg(w.edgeColor).arg(w.contacts).arg(w.counters)
            .arg(edgeCapacity).arg(sc.colorCount).arg(numColors).arg(numJoints).run(slots);
        cl::Launch(ctx, prog.kernel("color_offsets"), &w.profiler).arg(sc.colorCount).arg(sc.colorStart)
            .arg(numColors).arg(numLists).run(1, 1);
        cl::Launch(ctx, prog.kernel("color_fill"), &w.profiler).arg(w.edgeColor).arg(w.contacts).arg(w.counters)
            .arg(edgeCapacity).arg(sc.colorStart).arg(sc.colorCount).arg(sc.colorOrder).arg(numColors)
            .arg(orderStride).arg(numJoints).run(slots);
    } else {
        // a CPU device: one work-item, the edges in index order (color_lists_serial)
        cl::Launch(ctx, prog.kernel("color_lists_serial"), &w.profiler).arg(w.edgeColor).arg(w.contacts)
            .arg(w.counters).arg(edgeCapacity).arg(sc.colorCount).arg(sc.colorStart).arg(sc.colorOrder).arg(numColors)
            .arg(orderStride).arg(numJoints).arg(numLists).run(1, 1);
    }
    // Velocity iterations: the contacts', or a joint's larger override.
    const int velocityPasses = std::max(iterations, numJoints > 0 ? w.jointIterations : 0);
    // Every pass and color in one launch: on a GPU over one group per compute unit (each
    // contact is a chain of dependent loads, so more work-items in flight beat cheaper
    // barriers: H200, 1,000 cubes: 1.7 ms with 132 groups, 2.2 with 2; 112,500: 3.1 against
    // 7.1 with groups sized for four contacts a work-item; fewer in small scenes, where the
    // barriers' arrivals cost more: residentPgsGroups); on a CPU over one group for small
    // scenes, where launch overhead would dominate (a lone group needs no grid barrier). Groups
    // of 128 work-items on a GPU (H200, solve stage ms at 256 / 128 / 64 work-items a group:
    // cubes 32,768 2.92 / 2.36 / 2.73, 112,500 4.20 / 3.81 / 4.46).
    const bool resident = useResident(w);
    // A CPU device's wide sweeps (pgs_wide_passes.h): the contacts packed into blocks of lanes
    // (in the soft step's scratch: the two solvers never share a step) and each body's record,
    // once a step; the impulses unpacked after the last sweep.
    const bool wide = pgsWide(ctx, params, rows);
    auto widePack = [&] {
        sc.reserveWide(ctx, slots, numColors, BTG_PGS_WIDE_FIELDS);
        cl::Launch(ctx, prog.kernel("pgs_wide_offsets"), &w.profiler).arg(sc.colorStart).arg(sc.softWideStart)
            .arg(numColors).run(1, 1);
        sc.wideBodies.reserve(ctx, 4 * std::max<size_t>(bodies, 1));
        sc.wideKinds.reserve(ctx, std::max<size_t>(bodies, 1));
        cl::Launch(ctx, prog.kernel("pgs_wide_bodies"), &w.profiler).arg(int(bodies)).arg(w.props)
            .arg(w.invInertiaWorld).arg(sc.wideBodies).arg(sc.wideKinds).run(bodies);
        cl::Launch(ctx, prog.kernel("pgs_wide_pack"), &w.profiler).arg(w.contacts).arg(sc.colorStart).arg(sc.colorOrder)
            .arg(numColors).arg(sc.softWideStart).arg(sc.softWideBlock).arg(sc.softWideLanes).run(slots);
    };
    auto wideUnpack = [&] {
        cl::Launch(ctx, prog.kernel("pgs_wide_unpack"), &w.profiler).arg(w.contacts).arg(sc.colorStart)
            .arg(sc.colorOrder).arg(numColors).arg(sc.softWideStart).arg(sc.softWideBlock).arg(sc.softWideLanes)
            .run(slots);
    };
    if (pgsLocal(w, bodies, pgsFlow(w))) {
        cl_kernel k = prog.kernel("solve_local");
        // As large as the kernel allows (its registers cap it: clang's sm_90 build uses 242 a
        // work-item, which leaves 256 of the 1,024). BTGPU_RESIDENT_GROUP_SIZE, the experiment
        // knob, sets it here too. H100, solve stage ms asking 1,024 / 512 / 256 / 128 / 64
        // work-items, two runs: cubes 125 0.51 at every size, 512 cubes 0.85 / 0.85 / 0.85 /
        // 1.13 / 1.70 (the first three likely one size, the cap's).
        const size_t group = residentSolveGroupSize(cl::kernelGroupLimit(ctx, k), true, kLocalMaxGroup);
        cl::Launch(ctx, k, &w.profiler).arg(w.edgeColor).arg(w.contacts).arg(w.rollingContacts).arg(w.frictionDirs)
            .arg(w.frictionAnchors).arg(w.counters).arg(edgeCapacity).arg(sc.colorStart).arg(sc.colorOrder)
            .arg(w.props).arg(w.invInertiaWorld).arg(w.linVel).arg(w.angVel).arg(w.pushLin).arg(w.pushAng)
            .arg(numColors).arg(orderStride).arg(iterations).arg(params.splitImpulse ? 1 : 0).arg(rows)
            .arg(w.joints).arg(w.jointState).arg(w.jointRows).arg(numJoints).arg(w.jointIterations)
            .arg(cl_uint(params.randomSeed)).arg(int(bodies)).local(bodies * sizeof(BtgFloat4))
            .local(bodies * sizeof(BtgFloat4))
            .run(group, group);
        return;
    }
    const int oneGroupMax = wide ? kOneGroupMaxContactsWide : kOneGroupMaxContacts;
    // With the wide sweeps a CPU device takes the whole solve in one launch too, a group a core
    // with grid barriers between the colours (as the soft step's): the per-colour path enqueues
    // some 400 launches a step.
    const bool wideResident = wide && w.lastContactCount > oneGroupMax && residentAllowed(w);
    if (resident || wideResident || w.lastContactCount <= oneGroupMax) {
        cl_kernel k = prog.kernel(wideResident ? "solve_resident_wide" : "solve_resident");
        size_t groups = resident ? residentPgsGroups(w) : (wideResident ? residentSolveGroups(w) : 1);
        // The flow (solve_constraints.cl): every sweep ordered by the bodies' counts instead of a
        // grid barrier per colour; on a CPU device in groups of one work-item.
        const bool flow = resident && groups > 1 && pgsFlow(w) && params.randomSeed == 0u && numColors - 1 <= 32;
        // the wide sweeps' work-items take a chunk of eight contacts each, a few hundred chunks a
        // colour: small groups
        // A CPU device's lone group (a small scene): one work-item, which walks each colour's
        // contacts in order as the group's work-items would split them (the same bits: a
        // colour's contacts share no body). A group of 128 there paid for its barriers' loops
        // over mostly idle work-items, a colour or two of contacts a phase: PoCL, cubes 125,
        // solve stage 0.85-1.26 -> 0.63 ms.
        const bool lone = !ctx.device().isGpu && !resident && !wideResident;
        size_t group = (flow && !ctx.device().isGpu) || lone
                           ? 1
                           : (wideResident ? size_t(8) : residentSolveGroupSize(cl::kernelGroupLimit(ctx, k), resident, 128));
        if (wideResident) {
            widePack();
        } else {
            sc.softWideStart.reserve(ctx, 1);
            sc.softWideBlock.reserve(ctx, 1);
            sc.softWideLanes.reserve(ctx, 1);
            sc.wideBodies.reserve(ctx, 1);
            sc.wideKinds.reserve(ctx, 1);
        }
        if (flow) {
            sc.pgsFlowMasks.reserve(ctx, 4 * bodies);
            sc.pgsFlowMasks.zero(ctx, 4 * bodies);
            sc.pgsFlowDone.reserve(ctx, 2 * bodies);
            sc.pgsFlowDone.zero(ctx, 2 * bodies);
            cl::Launch(ctx, prog.kernel("solve_flow_masks"), &w.profiler).arg(w.counters).arg(edgeCapacity)
                .arg(numJoints).arg(numColors).arg(numLists).arg(sc.colorStart).arg(sc.colorOrder).arg(orderStride)
                .arg(w.edgeColor).arg(w.contacts).arg(w.joints).arg(w.props).arg(sc.pgsFlowMasks)
                .run(size_t(numLists) * slots);
        } else {
            sc.pgsFlowMasks.reserve(ctx, 4);
            sc.pgsFlowDone.reserve(ctx, 2);
        }
        cl::Launch(ctx, k, &w.profiler).arg(w.edgeColor).arg(w.contacts).arg(w.rollingContacts).arg(w.frictionDirs).arg(w.frictionAnchors)
            .arg(w.counters).arg(edgeCapacity)
            .arg(sc.colorStart)
            .arg(sc.colorOrder).arg(w.props).arg(w.invInertiaWorld).arg(w.linVel).arg(w.angVel).arg(w.pushLin)
            .arg(w.pushAng).arg(gridBarrier(w)).arg(numColors).arg(orderStride).arg(iterations)
            .arg(params.splitImpulse ? 1 : 0).arg(rows).arg(gridBarrierSpins(w)).arg(w.joints).arg(w.jointState)
            .arg(w.jointRows).arg(numJoints).arg(w.jointIterations).arg(cl_uint(params.randomSeed))
            .arg(sc.pgsFlowMasks).arg(sc.pgsFlowDone).arg(flow ? 1 : 0).arg(0).arg(wideResident ? 1 : 0)
            .arg(sc.softWideStart).arg(sc.softWideBlock).arg(sc.softWideLanes).arg(sc.wideBodies).arg(sc.wideKinds)
            .run(groups * group, group);
        if (wideResident) wideUnpack();
        return;
    }
    // Per-color launches stride over their range: a few work-groups per compute unit.
    const size_t rangeItems = std::min(slots, size_t(std::max<cl_uint>(ctx.device().computeUnits, 1)) * 256);
    cl_kernel parallel = prog.kernel("solve_color_range");
    cl_kernel serial = prog.kernel("solve_color_serial");
    // phase 1: the joints' edges, 0: the contacts' (see solve_resident).
    const cl_uint seed = params.randomSeed;
    cl_kernel wideSweep = wide ? prog.kernel("solve_color_wide") : nullptr;
    const size_t wideItems = (rangeItems + BTG_SOFT_WIDE - 1) / BTG_SOFT_WIDE;
    if (wide) widePack();
    auto pass = [&](int mode, int phase, int iteration, cl::DeviceArray<BtgFloat4>& lin, cl::DeviceArray<BtgFloat4>& ang) {
        // SOLVER_RANDMIZE_ORDER: the sweep's colours in its permuted order (the leftovers last),
        // as the one-launch kernel takes them
        const uint key = btgPassKey(seed, mode, phase, iteration);
        for (int ci = 0; ci < numColors; ++ci) {
            const int color = ci == numColors - 1 ? ci : btgPermute(key, numColors - 1, ci);
            // The last color holds the coloring's leftovers (usually none: the serial kernel
            // then returns at once).
            const bool wideMode = mode == BTG_PASS_WARM_START || mode == BTG_PASS_NORMALS || mode == BTG_PASS_FRICTION;
            if (wide && phase == 0 && wideMode && color != numColors - 1) {
                // groups of eight chunks: a CPU device runs a group on one core
                cl::Launch(ctx, wideSweep, &w.profiler).arg(sc.colorStart).arg(sc.softWideStart).arg(sc.softWideBlock)
                    .arg(sc.softWideLanes).arg(color).arg(mode).arg(rows & BTG_ROWS_TWO_FRICTION ? 1 : 0)
                    .arg(sc.wideBodies).arg(sc.wideKinds).arg(lin).arg(ang).run(wideItems, 8);
            } else if (color == numColors - 1) {
                cl::Launch(ctx, serial, &w.profiler).arg(w.edgeColor).arg(w.contacts).arg(w.rollingContacts)
                    .arg(w.frictionDirs).arg(w.frictionAnchors).arg(w.counters)
                    .arg(edgeCapacity).arg(w.props)
                    .arg(w.invInertiaWorld).arg(lin).arg(ang).arg(color).arg(mode).arg(rows).arg(w.joints)
                    .arg(w.jointState).arg(w.jointRows).arg(numJoints).arg(phase).arg(iteration).arg(seed).run(1, 1);
            } else {
                cl::Launch(ctx, parallel, &w.profiler).arg(w.contacts).arg(sc.sortedContacts).arg(wide ? 0 : 1).arg(w.rollingContacts).arg(w.frictionDirs).arg(w.frictionAnchors)
                    .arg(sc.colorStart)
                    .arg(sc.colorOrder)
                    .arg(w.props).arg(w.invInertiaWorld).arg(lin).arg(ang).arg(color).arg(mode).arg(rows)
                    .arg(numColors).arg(orderStride).arg(w.counters).arg(edgeCapacity).arg(w.joints).arg(w.jointState)
                    .arg(w.jointRows).arg(numJoints).arg(phase).arg(iteration).arg(seed).run(rangeItems, 64);
            }
        }
    };
    // bound in every launch of solve_color_range; one placeholder element where the wide sweeps
    // take the velocity sweeps (it is then not read)
    sc.sortedContacts.reserve(ctx, wide ? 1 : slots);
    if (!wide) {
        cl::Launch(ctx, prog.kernel("contacts_gather"), &w.profiler).arg(w.contacts).arg(sc.colorStart)
            .arg(sc.colorOrder).arg(numColors).arg(sc.sortedContacts).run(slots);
    }
    pass(BTG_PASS_WARM_START, 0, -1, w.linVel, w.angVel);
    for (int it = 0; it < velocityPasses; ++it) {
        if (numJoints > 0) pass(BTG_PASS_VELOCITY, 1, it, w.linVel, w.angVel);
        if (it < iterations) {
            // every contact's normal rows, then every friction row (counters.h); interleaved,
            // each point's friction right after its normal
            if (rows & BTG_ROWS_INTERLEAVE) {
                pass(BTG_PASS_VELOCITY, 0, it, w.linVel, w.angVel);
            } else {
                pass(BTG_PASS_NORMALS, 0, it, w.linVel, w.angVel);
                pass(BTG_PASS_FRICTION, 0, it, w.linVel, w.angVel);
            }
            if (rows & BTG_ROWS_ROLLING) pass(BTG_PASS_ROLLING, 0, it, w.linVel, w.angVel);
        }
    }
    if (params.splitImpulse && !ctx.device().isGpu) {
        // A CPU device: the push passes (the contacts with a push target: usually few) in one
        // launch on one group, solve_resident from its first push pass, not one launch a colour
        // (PoCL: 130 launches a step, mostly of empty colours, each its host and wake-up cost).
        cl_kernel k = prog.kernel("solve_resident");
        const size_t group = residentSolveGroupSize(cl::kernelGroupLimit(ctx, k), false, 128);
        sc.pgsFlowMasks.reserve(ctx, 4);
        sc.pgsFlowDone.reserve(ctx, 2);
        cl::Launch(ctx, k, &w.profiler).arg(w.edgeColor).arg(w.contacts).arg(w.rollingContacts).arg(w.frictionDirs)
            .arg(w.frictionAnchors).arg(w.counters).arg(edgeCapacity).arg(sc.colorStart).arg(sc.colorOrder)
            .arg(w.props).arg(w.invInertiaWorld).arg(w.linVel).arg(w.angVel).arg(w.pushLin).arg(w.pushAng)
            .arg(gridBarrier(w)).arg(numColors).arg(orderStride).arg(iterations).arg(1).arg(rows)
            .arg(gridBarrierSpins(w)).arg(w.joints).arg(w.jointState).arg(w.jointRows).arg(numJoints)
            .arg(w.jointIterations).arg(cl_uint(params.randomSeed)).arg(sc.pgsFlowMasks).arg(sc.pgsFlowDone).arg(0)
            .arg(1 + velocityPasses).arg(0).arg(sc.softWideStart).arg(sc.softWideBlock).arg(sc.softWideLanes)
            .arg(sc.wideBodies).arg(sc.wideKinds)
            .run(group, group);
    } else if (params.splitImpulse) {
        for (int it = 0; it < iterations; ++it) pass(BTG_PASS_PUSH, 0, iterations + it, w.pushLin, w.pushAng);
    }
    if (wide)
        wideUnpack();
    else
        cl::Launch(ctx, prog.kernel("contacts_scatter"), &w.profiler).arg(w.contacts).arg(sc.colorStart)
            .arg(sc.colorOrder).arg(numColors).arg(sc.sortedContacts).run(slots);
}

}  // namespace btgpu
