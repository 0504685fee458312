// pipeline.cpp — the step: each substep runs the plan's stage list (Plan::substep, in the
// talk's order: integrate/predict → AABBs → pairs → contacts → forces → contact cache →
// constraint setup → batching → PGS → store the cache → integrate transforms → deactivation),
// and a call runs its substeps with one readback, redone after a buffer overflowed. Stages
// absent from the plan are neither built nor launched.
#include "pipeline.h"

#include "stages/broadphase_leaves.h"
#include "stages/color_constraints.h"
#include "stages/contact_cache.h"
#include "stages/contact_callbacks.h"
#include "stages/expand_compounds.h"
#include "stages/filter_pairs.h"
#include "stages/find_pairs.h"
#include "stages/integrate.h"
#include "stages/midphase.h"
#include "stages/narrowphase.h"
#include "stages/narrowphase_gjk.h"
#include "stages/prepare_contacts.h"
#include "stages/prepare_joints.h"
#include "stages/report_contacts.h"
#include "stages/solve_constraints.h"
#include "stages/solve_jacobi.h"
#include "stages/solve_soft.h"
#include "stages/sync_bodies.h"
#include "stages/update_aabbs.h"
#include "stages/update_activation.h"

#include <algorithm>
#include <cstring>

namespace btgpu {

namespace {

void fillCounters(DeviceWorld& w, int first, int count, uint value) { w.counters.fill(w.ctx, value, size_t(first), size_t(count)); }

void runStage(Stage stage, DeviceWorld& w, const Plan& plan, const StepSettings& s)
{
    const BtgStepParams& p = s.params;
    switch (stage) {
        case Stage::Integrate: predictMotion(w, p.dt); break;
        case Stage::BroadphaseLeaves: updateLeaves(w, w.leaves.threshold, p.dt); break;
        case Stage::UpdateAabbs: updateAabbs(w, p.contactThreshold); break;
        case Stage::UniformGrid:
        case Stage::SortSweep: smallBodyPairs(w, plan.broadphase, plan.cellSize); break;
        case Stage::FindPairs: finishPairs(w, plan.kinds, !plan.hasCompounds); break;
        case Stage::ExpandCompounds: expandCompounds(w, plan.kinds); break;
        case Stage::Midphase: midphase(w); break;
        case Stage::Narrowphase:
        case Stage::NarrowphaseSat:
        case Stage::NarrowphaseGjk: narrowphaseProgram(w, plan.kinds, narrowphaseProgramOf(stage)); break;
        case Stage::NarrowphaseMesh: narrowphaseMesh(w, plan.kinds); break;
        case Stage::FilterPairs: filterPairs(w); break;
        case Stage::ApplyForces: applyForces(w, p.dt, p.maxGyroscopicForce, plan.solver != SolverKind::SoftStep); break;
        case Stage::ContactCache:
            buildContacts(w, p);
            // before the wake: the flags the pairs were found with say which were not collided
            noteCarried(w, p.deactivationTime > 0.0f);
            // With deactivation on, sleeping bodies a moving one touches wake before their rows
            // are made (stock activates the island before its solve).
            if (p.deactivationTime > 0.0f) {
                w.profiler.stage = stageName(Stage::UpdateActivation);  // its kernels' stage, in profiles
                wakeTouched(w);
            }
            break;
        case Stage::PrepareContacts: prepareContacts(w, p, plan.solver == SolverKind::SoftStep); break;
        case Stage::ContactCallbacks: applyContactMaterials(w, p); break;
        case Stage::PrepareJoints: prepareJoints(w, s.joints); break;
        case Stage::FinishJoints: finishJoints(w, s.joints); break;
        case Stage::ColorConstraints: colorConstraints(w, s.maxColors, plan.solver == SolverKind::BatchedPgs); break;
        case Stage::SolveConstraints: solveConstraints(w, p, s.iterations, w.numColors); break;
        case Stage::SolveJacobi: solveJacobi(w, p, s.iterations); break;
        case Stage::SolveSoft: {
            w.softParams = makeSoftParams(s.soft, p, s.iterations);
            solveSoft(w, w.softParams, w.numColors);
            break;
        }
        case Stage::StoreContactCache: {
            // The count waits for the persistent manifolds' store where there is one; a cache
            // stored without them beside it leaves those stale.
            const bool persistent = keepsPersistentManifolds(plan.kinds, w.speculativeContacts);
            storeContactCache(w, !persistent, plan.solver == SolverKind::SoftStep);
            if (!persistent) w.gjkCacheCurrent = false;
            break;
        }
        case Stage::StorePersistentManifolds:
            storePersistentManifolds(w, plan.kinds, p.solverFlags);
            countCache(w);
            break;
        case Stage::ReportContacts: reportContacts(w, plan.solver == SolverKind::SoftStep); break;
        case Stage::IntegrateTransforms: integrateTransforms(w, p.dt, p.splitTurnErp); break;
        case Stage::SoftTransforms: softTransforms(w); break;
        case Stage::UpdateActivation: updateActivation(w, p.dt, p.deactivationTime); break;
    }
}

// The plan's stages in order; each names its launches in the profile.
void runSubstep(DeviceWorld& w, const Plan& plan, const std::vector<Stage>& stages, const StepSettings& s,
                SubstepPart part, bool last)
{
    if (part == SubstepPart::ActivationOnly) {
        // The deactivation walks the graph the first part built: its counts stay.
        w.profiler.stage = stageName(Stage::UpdateActivation);
        runStage(Stage::UpdateActivation, w, plan, s);
        return;
    }
    // The second half of a split substep goes on from the contact list with the counts the
    // first half left.
    w.speculativeContacts = plan.solver == SolverKind::SoftStep;  // the midphase and narrowphase read it
    bool running = s.split != ContactsSplit::FromContacts;
    if (running) {
        fillCounters(w, kPairCount, 2, 0u);  // pair and contact counts
        fillCounters(w, kEdgeCount, 1, 0u);  // the constraint graph, rebuilt by the stages that add edges
        fillCounters(w, kSoftMassRatio, 1, 0u);  // noted afresh by the soft step's soft_color_count
    }
    for (Stage stage : stages) {
        if (stage == Stage::ContactCache) {
            if (s.split == ContactsSplit::UntilContacts) return;
            running = true;
        }
        if (!running) continue;
        if (part == SubstepPart::BeforeActivation && stage == Stage::UpdateActivation) continue;
        if (stage == Stage::ReportContacts && !last) continue;  // the app sees the call's last substep
        w.profiler.stage = stageName(stage);
        runStage(stage, w, plan, s);
        if (stage == Stage::BroadphaseLeaves && last) leafPairs(w, 2.0f * plan.cellSize);  // the pairs the app sees: the call's last substep's
    }
}

}  // namespace

void runSubsteps(DeviceWorld& w, const Plan& plan, const StepSettings& s)
{
    if (w.numBodies == 0) return;
    // The last call's reports, mapped for the fill on a CPU device, may lie over the soft
    // step's rows, which its solve writes: unmapped before any stage runs.
    unmapReports(w);
    if (s.lastPart == SubstepPart::ActivationOnly) {
        runSubstep(w, plan, {}, s, SubstepPart::ActivationOnly, true);
        return;
    }
    // A redo starts from the cache as the call found it. One substep leaves the cache alone
    // when it overflows; of several, an early one may store it before a later one overflows,
    // so the call keeps a copy. Counted here, where every substep is known (Config::
    // internalSubsteps included).
    w.contactCacheKept = plan.kinds.any() && s.substeps > 1 && w.contactCache.capacity() > 0;
    if (w.contactCacheKept) {
        w.contactCacheAtCall.reserveExact(w.ctx, w.contactCache.capacity());
        w.contactCacheAtCall.copyFrom(w.ctx, w.contactCache, w.contactCache.capacity());
    } else {
        w.contactCacheAtCall.release();
    }
    if (w.contactCacheKept && w.gjkCache.capacity() > 0) {
        w.gjkCacheAtCall.reserveExact(w.ctx, w.gjkCache.capacity());
        w.gjkCacheAtCall.copyFrom(w.ctx, w.gjkCache, w.gjkCache.capacity());
    } else {
        w.gjkCacheAtCall.release();
    }
    const std::vector<Stage> stages = plan.substep();
    // SOLVER_RANDMIZE_ORDER: each substep its own solve-order stream, the call's seed onwards
    // (the host advances it by the call's substeps once the call is done, so a redo repeats it).
    StepSettings sub = s;
    for (int i = 0; i < s.substeps; ++i) {
        if (s.params.randomSeed != 0u) sub.params.randomSeed = s.params.randomSeed + uint(i);
        runSubstep(w, plan, stages, sub, i == s.substeps - 1 ? s.lastPart : SubstepPart::Whole, i == s.substeps - 1);
    }
}

void resetStatus(DeviceWorld& w)
{
    fillCounters(w, kStatus, 1, 0u);
    fillCounters(w, kNanBody, 1, 0xffffffffu);
}

void takeSnapshot(DeviceWorld& w, Snapshot& s)
{
    size_t n = size_t(w.numBodies);
    s.pos.copyFrom(w.ctx, w.pos, n);
    s.rot.copyFrom(w.ctx, w.rot, n);
    s.linVel.copyFrom(w.ctx, w.linVel, n);
    s.angVel.copyFrom(w.ctx, w.angVel, n);
    s.counters.copyFrom(w.ctx, w.counters, kNumCounters);
    if (w.numJoints > 0) s.jointState.copyFrom(w.ctx, w.jointState, size_t(w.numJoints));
}

void restoreSnapshot(DeviceWorld& w, Snapshot& s)
{
    size_t n = size_t(w.numBodies);
    w.pos.copyFrom(w.ctx, s.pos, n);
    w.rot.copyFrom(w.ctx, s.rot, n);
    w.linVel.copyFrom(w.ctx, s.linVel, n);
    w.angVel.copyFrom(w.ctx, s.angVel, n);
    if (w.contactCacheKept) {
        size_t m = std::min(w.contactCacheAtCall.capacity(), w.contactCache.capacity());
        w.contactCache.copyRangeFrom(w.ctx, w.contactCacheAtCall, m);
    }
    if (w.contactCacheKept && w.gjkCacheAtCall.capacity() > 0) {
        size_t m = std::min(w.gjkCacheAtCall.capacity(), w.gjkCache.capacity());
        w.gjkCache.copyRangeFrom(w.ctx, w.gjkCacheAtCall, m);
    }
    w.counters.copyFrom(w.ctx, s.counters, kNumCounters);
    if (w.numJoints > 0) w.jointState.copyFrom(w.ctx, s.jointState, size_t(w.numJoints));
}

namespace {

// Grows the pair and contact buffers from an overflowed call's full counts (the kernels count
// past capacity). Contacts take what they need plus an eighth, pairs a quarter: the contact
// list is the largest buffer (384 + 112 + 4 bytes a slot with its cache entry and manifold
// slot, and an 8 + 4 byte graph edge), and every growth is at least 1.25x, so redos stay few.
void grow(DeviceWorld& w, const BodyReadback& rb, bool pairOverflow, bool contactOverflow, bool subPairOverflow)
{
    // Sub-pairs: what the midphase found plus a quarter; of the pairs found when those overflowed.
    if (subPairOverflow || pairOverflow) {
        size_t sub = rb.counters[kSubPairCount];
        if (pairOverflow) sub = sub * rb.counters[kPairCount] / std::max<size_t>(w.pairCapacity, 1);
        w.subPairCapacity = std::max(w.subPairCapacity + w.subPairCapacity / 4, sub + sub / 4 + 64);
    }
    size_t pairs = rb.counters[kPairCount];
    size_t contacts = rb.counters[kContactCount];
    if (pairOverflow) contacts = contacts * pairs / std::max<size_t>(w.pairCapacity, 1);  // of the pairs found
    if (pairOverflow) w.pairCapacity = std::max(w.pairCapacity + w.pairCapacity / 4, pairs + pairs / 4 + 64);
    if (contactOverflow || contacts > w.contactCapacity)
        w.contactCapacity = std::max(w.contactCapacity + w.contactCapacity / 4, contacts + contacts / 8 + 64);
    w.pairs.reserveExact(w.ctx, w.pairCapacity);
    w.manifolds.reserveExact(w.ctx, w.pairCapacity);
    w.pairManifolds.reserveExact(w.ctx, w.pairCapacity);
    w.contacts.reserveExact(w.ctx, w.contactCapacity);
    w.contactManifolds.reserveExact(w.ctx, w.contactCapacity);
    w.contactCache.reserveExact(w.ctx, w.contactCapacity, true);
}

}  // namespace

namespace {

// The first half of a split call: true when the host may step in (no buffer overflowed);
// otherwise rb.counters hold the status and counts that overflowed.
bool runUntilContacts(DeviceWorld& w, const Plan& plan, const StepSettings& s, BodyReadback& rb)
{
    StepSettings first = s;
    first.split = ContactsSplit::UntilContacts;
    runSubsteps(w, plan, first);
    rb.counters.resize(w.ctx, kNumCounters);
    w.counters.download(w.ctx, rb.counters.data(), kNumCounters);
    const uint overflow = BTG_STATUS_PAIR_OVERFLOW | BTG_STATUS_CONTACT_OVERFLOW | BTG_STATUS_SUB_PAIR_OVERFLOW |
                          BTG_STATUS_GRID_BARRIER_TIMEOUT;
    return (rb.counters[kStatus] & overflow) == 0;
}

}  // namespace

CallOutcome runCall(DeviceWorld& w, const Plan& plan, const StepSettings& s, Snapshot& snapshot, BodyReadback& rb,
                    const std::function<bool()>& betweenContacts)
{
    CallOutcome out;
    resetStatus(w);
    takeSnapshot(w, snapshot);
    const bool split = betweenContacts && s.substeps == 1 && plan.kinds.any() && s.lastPart != SubstepPart::ActivationOnly;
    // Growth is geometric, so this settles after a few tries.
    for (int attempt = 0;; ++attempt) {
        if (!split) {
            runSubsteps(w, plan, s);
            syncOut(w, rb);
        } else if (runUntilContacts(w, plan, s, rb)) {
            if (!betweenContacts()) {
                out.abandoned = true;
                return out;
            }
            StepSettings second = s;
            second.split = ContactsSplit::FromContacts;
            runSubsteps(w, plan, second);
            syncOut(w, rb);
        }
        const uint status = rb.counters[kStatus];
        const bool pairOverflow = status & BTG_STATUS_PAIR_OVERFLOW;
        const bool contactOverflow = status & BTG_STATUS_CONTACT_OVERFLOW;
        const bool subPairOverflow = status & BTG_STATUS_SUB_PAIR_OVERFLOW;
        const bool barrierTimeout = status & BTG_STATUS_GRID_BARRIER_TIMEOUT;
        if (barrierTimeout && attempt < 8) {
            // This device does not keep all work-groups of a launch resident: the one-launch
            // batching and solve are off for good, and the call is redone with per-round launches.
            restoreSnapshot(w, snapshot);
            w.resident = DeviceWorld::Resident::Off;
            ++out.redone;
            out.events.push_back({CallEvent::Kind::ResidentOff,
                                  "one-launch batching/solve timed out at a grid barrier on this device; per-round "
                                  "launches from now on; step redone"});
        } else if ((pairOverflow || contactOverflow || subPairOverflow) && attempt < 8) {
            // Back to the state before the call first (the warm-start cache as it was), then
            // grow, keeping the cache's contents.
            restoreSnapshot(w, snapshot);
            grow(w, rb, pairOverflow, contactOverflow, subPairOverflow);
            ++out.redone;
            out.events.push_back({CallEvent::Kind::Grew, "pair/contact/sub-pair buffers grew to " +
                                                             std::to_string(w.pairCapacity) + "/" +
                                                             std::to_string(w.contactCapacity) + "/" +
                                                             std::to_string(w.subPairCapacity) + "; step redone"});
        } else {
            break;
        }
        takeSnapshot(w, snapshot);  // the restored state, for a further redo
        resetStatus(w);
    }
    // The next call colors as many rounds as this one needed plus slack; leftovers (solved
    // serially, slow on a GPU) double the rounds.
    const int used = int(rb.counters[kColorsUsed]);
    w.lastColorsUsed = used;
    int rounds = std::max(used + 2, 4);
    if (rb.counters[kLeftovers] > 0) rounds = std::max(rounds, 2 * w.colorRounds);
    w.colorRounds = std::min(rounds, std::max(s.maxColors - 1, 1));
    w.lastContactCount = int(rb.counters[kContactCount]);
    float ratio = 0.0f;
    std::memcpy(&ratio, &rb.counters[kSoftMassRatio], sizeof ratio);
    w.lastSoftSubsteps = plan.solver == SolverKind::SoftStep ? btgSoftSubstepsFor(w.softParams, ratio) : 0;
    w.lastSoftMassRatio = plan.solver == SolverKind::SoftStep ? ratio : 0.0f;
    return out;
}

}  // namespace btgpu
