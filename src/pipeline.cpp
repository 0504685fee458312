// pipeline.cpp — one substep, top to bottom, as the talk lays it out: integrate/predict →
// AABBs → pairs → contacts → forces → contact cache → constraint setup → batching → PGS →
// store the cache for the next substep → integrate transforms → deactivation.
// Config::solver = JacobiMassSplitting puts one Jacobi mass-splitting stage in place of
// batching + PGS. Stages absent from the plan are neither built nor launched.
#include "pipeline.h"

#include "stages/color_constraints.h"
#include "stages/contact_cache.h"
#include "stages/find_pairs.h"
#include "stages/integrate.h"
#include "stages/narrowphase.h"
#include "stages/prepare_contacts.h"
#include "stages/solve_constraints.h"
#include "stages/solve_jacobi.h"
#include "stages/update_aabbs.h"
#include "stages/update_activation.h"

#include <algorithm>

namespace btgpu {

namespace {

void fillCounters(DeviceWorld& w, int first, int count, uint value) { w.counters.fill(w.ctx, value, size_t(first), size_t(count)); }

void runSubstep(DeviceWorld& w, const Plan& plan, const StepSettings& s)
{
    const BtgStepParams& p = s.params;
    const bool collide = plan.kinds.any();
    fillCounters(w, kPairCount, 2, 0u);  // pair and contact counts
    predictMotion(w, p.dt);
    if (collide) {
        updateAabbs(w, p.contactThreshold);
        findPairs(w, plan.broadphase, plan.cellSize);
        narrowphase(w, plan.kinds);
    }
    applyForces(w, p.dt);
    if (collide) {
        buildContacts(w, p);
        prepareContacts(w, p);
        if (s.solver == SolverKind::JacobiMassSplitting) {
            solveJacobi(w, p, s.iterations);
        } else {
            colorConstraints(w, s.maxColors);
            solveConstraints(w, p, s.iterations, w.numColors);
        }
        storeContactCache(w);  // before the bodies move: the cache keys use A's rotation now
    }
    integrateTransforms(w, p.dt, p.splitTurnErp);
    updateActivation(w, p.dt, p.deactivationTime);
}

}  // namespace

void runSubsteps(DeviceWorld& w, const Plan& plan, const StepSettings& s)
{
    if (w.numBodies == 0) return;
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
    for (int i = 0; i < s.substeps; ++i) runSubstep(w, plan, s);
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
    w.counters.copyFrom(w.ctx, s.counters, kNumCounters);
}

}  // namespace btgpu
