// inside_step.cpp — the host's part inside a GPU-path call, between or beside the device's:
// Bullet's own broadphase kept where the bodies are (and its pairs completed before a CPU-path
// step), the app's dispatcher manifolds, the app's contact callbacks between a step's contacts
// and its solve, the app's actions between a step and its deactivation, and following what an
// action or callback added, removed or changed inside a call.
#include "gpu_world.h"

#include <chrono>
#include <iostream>
#include <typeinfo>

namespace btgpu {

btDbvtBroadphase* GpuWorld::dbvtBroadphase() const
{
    btBroadphaseInterface* bp = m_world.getBroadphase();
    return bp && typeid(*bp) == typeid(btDbvtBroadphase) ? static_cast<btDbvtBroadphase*>(bp) : nullptr;
}

void GpuWorld::syncBroadphaseAabbs()
{
    // Bullet's dbvt broadphase, unless its collisions are deferred, tests each proxy setAabb
    // moves against both of its trees and adds what it meets to the pair cache: the broadphase
    // step of a CPU step, paid proxy by proxy (45 of 51 ms a step for 32,768 falling boxes),
    // for pairs nothing on the GPU path reads and that only its pair update would remove. Only
    // the AABBs are wanted here (ray and sweep tests), so those collisions wait, as the app's
    // setting would let them wait, until the CPU path needs the pairs (completeBroadphasePairs).
    btDbvtBroadphase* dbvt = dbvtBroadphase();
    const bool deferred = dbvt && dbvt->m_deferedcollide;
    if (dbvt) dbvt->m_deferedcollide = true;
    m_world.updateAabbs();
    if (dbvt) dbvt->m_deferedcollide = deferred;
    if (dbvt && !deferred) m_broadphasePairsStale = true;
}

void GpuWorld::completeBroadphasePairs()
{
    // Before Bullet's own step after GPU steps: one deferred pair update finds every pair among
    // the proxies that moved (tree against tree, the overlaps gone removed), so the pair cache
    // is the one stock's broadphase would hold and its incremental updates go on from there.
    btDbvtBroadphase* dbvt = dbvtBroadphase();
    if (!dbvt || !m_broadphasePairsStale) return;
    dbvt->m_deferedcollide = true;
    dbvt->calculateOverlappingPairs(m_world.getDispatcher());
    dbvt->m_deferedcollide = false;
    m_broadphasePairsStale = false;
}

bool GpuWorld::aabbsBesideFill() const
{
    const btDispatcher* dispatcher = m_world.getDispatcher();
    return m_config.fillDispatcherManifolds && m_config.syncBroadphaseAabbs && !broadphaseAsStock() &&
           dbvtBroadphase() && dispatcher && typeid(*dispatcher) == typeid(btCollisionDispatcher) &&
           fusedWriteBackPending() && m_world.getNumCollisionObjects() >= 4096;
}

void GpuWorld::fillManifolds(const std::function<void()>& beforeEvents)
{
    awaitReports(*m_dev, m_readback);  // their read travelled while the bodies were written back
    if (!m_config.fillDispatcherManifolds) return;
    const auto t0 = std::chrono::steady_clock::now();
    m_manifolds.fill(m_world.getDispatcher(), m_rows, m_readback, m_removed, beforeEvents);
    m_report.manifoldFillMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void GpuWorld::fillBesideAabbSync()
{
    // The call's broadphase AABB sync (Bullet's serial updateAabbs; finishCall's otherwise) on
    // the side thread while the pool fills the manifolds: the sync reads the bodies' transforms
    // and writes Bullet's broadphase only, the fill reads shapes and writes the dispatcher's
    // manifolds; it waits for the sync before reading activation or calling the app's callbacks.
    using Clock = std::chrono::steady_clock;
    m_side.start([this] { syncBroadphaseAabbs(); });
    // Never left running past here, whatever the fill throws.
    struct Joined {
        SideTask& side;
        ~Joined()
        {
            try {
                side.wait();
            } catch (...) {
            }
        }
    } joined{m_side};
    auto waitForSync = [this] {
        const Clock::time_point w0 = Clock::now();
        m_side.wait();
        m_aabbWaitMs += std::chrono::duration<double, std::milli>(Clock::now() - w0).count();
    };
    fillManifolds(waitForSync);
    waitForSync();  // (the fill returns early without contacts)
    m_aabbsSynced = true;
}

void GpuWorld::leaveGpuPath()
{
    // The pairs first (stock's algorithms hang on them), then the contacts handed over (which
    // gives back every manifold of the GPU path's).
    completeBroadphasePairs();
    m_manifolds.handToStock(m_world);
}

void GpuWorld::dropCpuPathManifolds()
{
    // The pair cache's algorithms (made by CPU-path steps, or by the app's own collision calls)
    // hold manifolds of the bodies as they were then: freed, as stock frees them when a pair
    // goes, so the dispatcher holds only the GPU path's. A later CPU-path step makes them anew.
    btDispatcher* dispatcher = m_world.getDispatcher();
    btOverlappingPairCache* cache = m_world.getBroadphase() ? m_world.getBroadphase()->getOverlappingPairCache() : nullptr;
    if (!cache || !dispatcher) return;
    btBroadphasePairArray& pairs = cache->getOverlappingPairArray();
    for (int i = 0; i < pairs.size(); ++i)
        if (pairs[i].m_algorithm) cache->cleanOverlappingPair(pairs[i], dispatcher);
}

std::function<bool()> GpuWorld::contactHostPart()
{
    const bool filtered = m_overlapFilter;
    const bool wanted = ContactCallbacks::wanted(m_world);
    const bool any = wanted || filtered;
    if (any != m_plan.contactCallbacks) {
        m_plan.contactCallbacks = any;
        m_report.stages = m_plan.stages();
    }
    if (!any) return {};
    return [this, filtered, wanted] {
        const auto c0 = std::chrono::steady_clock::now();
        if (filtered) m_callbacks.keepStockPairs(*m_dev, m_rows, m_world);
        const bool carried = !wanted || m_callbacks.run(*m_dev, m_rows, m_removed, m_manifolds);
        m_report.callbackMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - c0).count();
        m_report.contactCallbacks += wanted ? m_callbacks.calls() : 0;
        return carried;
    };
}

void GpuWorld::runActions(btScalar dt)
{
    // Where Bullet runs updateActions: after integrateTransforms, before the deactivation. The
    // broadphase AABBs enclose the bodies where this step put them, so the actions' ray and
    // sweep tests find what stock's find (stock's AABBs span the step's predicted motion).
    // With ghosts the step's start set stock's own AABBs, predicted motion included.
    if (!broadphaseAsStock()) syncBroadphaseAabbs();
    m_world.updateActions(dt);
    // Velocities, impulses, forces and transforms the actions set, and bodies they woke. What
    // they added or removed joins or leaves the rows at the next internal step (removed
    // objects are skipped until then).
    syncIn(*m_dev, changedRows());
    afterSyncIn();
}

bool GpuWorld::followWithinCall(int batch, int batches, btScalar fixedTimeStep)
{
    int bodyIndex = -1;
    std::string why = cpuPathReason(&bodyIndex);
    // Auto's solver is chosen where a call starts: one that would change within the call's
    // internal steps (a tick callback started or stopped using what only the batched PGS
    // serves) hands the rest of the call to the CPU path; the next call switches.
    if (why.empty() && solverToRun() != m_solver)
        why = "Config::solver = Auto would switch solvers within a stepSimulation call's internal steps (" +
              (m_autoReason.empty() ? std::string("the soft step serves the world again") : m_autoReason) +
              "): the rest of the call runs on the CPU path, the next call on the other solver";
    if (why.empty()) {
        if (m_rowsStale) followRows();
        return true;
    }
    cpuPathFrom(batch, batches, fixedTimeStep, why);
    return false;
}

void GpuWorld::cpuPathFrom(int batch, int batches, btScalar fixedTimeStep, const std::string& why, bool preTickCalled)
{
    // As a call that starts on the CPU path, but from this internal step on: Bullet's own
    // internal steps (they run the pre-tick and tick callbacks), with the gravity stepSimulation
    // applies before its loop (the GPU path keeps gravity on the device).
    const std::string from = " (from internal step " + std::to_string(batch + 1) + " of " + std::to_string(batches) + ")";
    std::cerr << "btgpu: running on the CPU path: " << why << from << "\n";
    report({Issue::Kind::Fallback, why + from});
    m_onCpuPath = true;
    m_report.cpuPathReason = why + from;
    m_needsRebuild = true;
    leaveGpuPath();
    completeBroadphasePairs();
    m_world.applyGravity();
    for (int b = batch; b < batches; ++b) {
        // This internal step's pre-tick callback already ran on the GPU path's side (the step
        // was started there, then handed over): stock calls it once a step.
        const btInternalTickCallback preTick = m_world.m_internalPreTickCallback;
        if (b == batch && preTickCalled) m_world.m_internalPreTickCallback = nullptr;
        m_world.internalSingleStepSimulation(fixedTimeStep);
        if (b == batch && preTickCalled) m_world.m_internalPreTickCallback = preTick;
    }
}

}  // namespace btgpu
