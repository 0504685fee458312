// btgpu_backend.cpp — btGpuDynamicsWorld through its public API only, built exactly as the
// stock Bullet backend (same bodies, broadphase, solver), with Config::profile on for
// per-stage device times. The split of each frame comes from the world's Report: the step
// column is the call's wall time less the host write-back (results into btRigidBody and motion
// states, plus Bullet's broadphase AABB sync when that is on).
#include <chrono>
#include <cstdio>

#include "bench_backend.h"
#include "bt_bodies.h"
#include "btgpu/btGpuDynamicsWorld.h"

namespace btgpu::bench {

namespace {

using Clock = std::chrono::steady_clock;

class BtgpuBackend : public Backend {
public:
    ~BtgpuBackend() override
    {
        if (m_bodies) m_bodies->leaveWithWorld();
        m_world.reset();
        m_bodies.reset();
        if (m_callback == "ground" || m_callback == "all") gContactAddedCallback = nullptr;
        if (m_callback == "processed") gContactProcessedCallback = nullptr;
    }
    std::string name() const override { return "btgpu"; }
    std::string device() const override { return m_world ? m_world->report().device : std::string(); }
    std::string notes() const override
    {
        std::string n = "btGpuDynamicsWorld, " + std::to_string(m_iterations) + " iterations, Config::profile on every 10th frame";
        if (m_world && !m_world->isGpuPath()) n += "; CPU PATH: " + m_world->report().cpuPathReason;
        if (m_world) n += "; redone steps " + std::to_string(m_world->report().redoneSteps) + "; colors " +
                          std::to_string(m_world->report().colors);
        if (!m_firstStep.empty()) n += "; " + m_firstStep;
        if (m_world) {
            // Bitwise fingerprint of the final state (same scene, device and binary: same hash).
            char hash[32];
            std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(m_world->stateHash()));
            n += std::string("; state hash ") + hash;
        }
        if (m_noAabbSync) n += "; Config::syncBroadphaseAabbs off";
        if (m_noManifolds) n += "; Config::fillDispatcherManifolds off";
        if (m_emptyManifolds) n += "; Config::stockEmptyManifolds (Bullet's broadphase on the host: Report::ghostBroadphaseMs)";
        if (m_noEmptyManifolds) n += "; Config::deviceEmptyManifolds off (manifolds with points only)";
        if (!m_callback.empty()) n += "; contact callback: " + m_callback + " (host part: Report::callbackMs)";
        if (m_jacobi) n += "; Jacobi with mass splitting";
        if (m_auto && m_world)
            n += std::string("; Config::solver = Auto: ran the ") +
                 (m_world->report().solver == btgpu::SolverKind::SoftStep ? "soft step" : "batched PGS (" + m_world->report().solverReason + ")");
        if (m_soft || (m_auto && m_world && m_world->report().solver == btgpu::SolverKind::SoftStep)) n += "; soft step, " + std::to_string(m_world ? m_world->report().softSubsteps : 0) + " substeps";
        n += "; step column = sync-in of app changes + device substeps + readback (Report::syncInMs + deviceMs); "
             "write-back column = results into btRigidBody + motion states (Report::writeBackMs)";
        if (!m_noAabbSync) n += " + Bullet's broadphase AABB sync (Report::aabbSyncMs)";
        return n;
    }

    bool setUp(const Scene& scene, const Options& options, std::string*) override
    {
        m_dt = scene.dt;
        m_iterations = scene.iterations;
        m_requireGpu = options.requireGpuPath;
        btgpu::Config config;
        config.profile = true;
        config.profileEvery = 10;  // stage times from every 10th frame; the others run unprofiled
        config.syncBroadphaseAabbs = !options.noAabbSync;
        m_noAabbSync = options.noAabbSync;
        config.fillDispatcherManifolds = !options.noManifolds;
        m_noManifolds = options.noManifolds;
        config.stockEmptyManifolds = options.emptyManifolds;
        m_emptyManifolds = options.emptyManifolds;
        config.deviceEmptyManifolds = !options.noEmptyManifolds;
        m_noEmptyManifolds = options.noEmptyManifolds;
        if (options.jacobi) config.solver = btgpu::SolverKind::JacobiMassSplitting;
        m_jacobi = options.jacobi;
        if (options.soft) config.solver = btgpu::SolverKind::SoftStep;
        if (options.softSubsteps > 0) config.softStep.substeps = options.softSubsteps;
        if (options.autoSolver) config.solver = btgpu::SolverKind::Auto;
        if (options.bulletMode) config.solver = btgpu::SolverKind::BatchedPgs;
        m_auto = config.solver == btgpu::SolverKind::Auto;  // the library's default, or asked for
        m_soft = options.soft;
        m_world.reset(new btGpuDynamicsWorld(&m_infra.dispatcher, &m_infra.broadphase, &m_infra.solver, &m_infra.config,
                                        config));
        m_bodies.reset(new BtBodies);
        m_bodies->build(scene, options, m_world.get());
        m_callback = options.contactCallback;
        if (m_callback == "ground" || m_callback == "all") {
            gContactAddedCallback = [](btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int,
                                       const btCollisionObjectWrapper*, int, int) {
                cp.m_combinedRestitution = cp.m_combinedRestitution * btScalar(0.5);
                return true;
            };
            btCollisionObjectArray& objs = m_world->getCollisionObjectArray();
            for (int i = 0; i < objs.size(); ++i) {
                if (m_callback == "ground" && !objs[i]->isStaticObject()) continue;
                objs[i]->setCollisionFlags(objs[i]->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
                if (m_callback == "ground") break;
            }
        } else if (m_callback == "processed") {
            gContactProcessedCallback = [](btManifoldPoint&, void*, void*) { return true; };
        }
        return true;
    }

    FrameTime step() override
    {
        auto t0 = Clock::now();
        m_world->stepSimulation(m_dt, 1, m_dt);
        double total = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        const btgpu::Report& r = m_world->report();
        double host = r.writeBackMs + r.aabbSyncMs;
        if (m_steps++ == 0) {
            // Where the first step's one-time work went (the notes say it): the rows built from
            // scratch fall in the checks, the programs' builds in the device part.
            char first[256];
            std::snprintf(first, sizeof first,
                          "first step %.0f ms: checks and rows built %.0f, sync-in %.0f, device part %.0f (of it "
                          "%zu program builds %.0f), write-back %.0f",
                          total, r.checkMs, r.syncInMs, r.deviceMs, r.builtPrograms.size(), 1000.0 * r.buildSeconds,
                          r.writeBackMs);
            m_firstStep = first;
        }
        return {total - host, host};
    }

    std::string checkAfterFirstFrame() override
    {
        if (m_requireGpu && !m_world->isGpuPath())
            return "not on the GPU path (" + m_world->report().cpuPathReason + ")";
        return {};
    }

    void poses(std::vector<Pose>& out) override { m_bodies->poses(out); }

    void info(FrameInfo& out, bool) override
    {
        const btgpu::Report& r = m_world->report();
        out.stageMs = r.stageMs;  // device stages: profiled frames only
        // Host zones: every frame (their medians are over all frames).
        out.stageMs["host: checks (CPU-path rules, shape changes)"] = r.checkMs;
        out.stageMs["host: sync-in (compare rows, upload)"] = r.syncInMs;
        out.stageMs["host: enqueue + wait + readback"] = r.deviceMs;
        out.stageMs["host: write-back"] = r.writeBackMs;
        out.stageMs["host: write-back, of it the manifold fill"] = r.manifoldFillMs;
        if (!m_noAabbSync) out.stageMs["host: Bullet's broadphase AABB sync"] = r.aabbSyncMs;
        if (!m_callback.empty()) out.stageMs["host: contact callbacks (in enqueue + wait)"] = r.callbackMs;
        out.pairs = r.pairs;
        out.manifolds = r.contacts;
        out.deviceBytes = static_cast<long long>(r.deviceBytes);
        for (const btgpu::Issue& i : r.issues)
            if (i.kind == btgpu::Issue::Kind::Overflow) out.overflow = i.message;  // grown and redone, not lost
    }

private:
    BtInfrastructure m_infra;
    std::unique_ptr<btGpuDynamicsWorld> m_world;
    std::unique_ptr<BtBodies> m_bodies;
    float m_dt = 1.0f / 60;
    int m_iterations = 10;
    long m_steps = 0;
    std::string m_firstStep;  // the first step's parts (notes)
    bool m_requireGpu = false;
    bool m_noAabbSync = false;
    bool m_noManifolds = false;
    bool m_emptyManifolds = false;
    bool m_noEmptyManifolds = false;
    bool m_jacobi = false;
    bool m_soft = false;
    bool m_auto = false;
    std::string m_callback;  // Options::contactCallback (its globals put back in the destructor)
};

}  // namespace

std::unique_ptr<Backend> makeBtgpuBackend() { return std::make_unique<BtgpuBackend>(); }

}  // namespace btgpu::bench
