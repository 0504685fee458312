// bullet_backend.cpp — the stock CPU baseline: btDiscreteDynamicsWorld with btDbvtBroadphase
// and btSequentialImpulseConstraintSolver, same iterations as the scene. The step is timed
// whole; synchronizeMotionStates (the write-back into motion states) is timed on its own.
#include <chrono>

#include "bench_backend.h"
#include "bt_bodies.h"

namespace btgpu::bench {

namespace {

using Clock = std::chrono::steady_clock;

// Times the motion-state write-back, which stepSimulation calls once per call.
class TimedWorld : public btDiscreteDynamicsWorld {
public:
    using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
    double syncMs = 0;
    void synchronizeMotionStates() override
    {
        auto t0 = Clock::now();
        btDiscreteDynamicsWorld::synchronizeMotionStates();
        syncMs += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    }
};

class BulletBackend : public Backend {
public:
    ~BulletBackend() override
    {
        if (m_bodies) m_bodies->leaveWithWorld();
        m_world.reset();
        m_bodies.reset();
    }
    std::string name() const override { return "bullet"; }
    std::string device() const override { return "CPU (1 thread)"; }
    std::string notes() const override
    {
        return "btDbvtBroadphase + btSequentialImpulseConstraintSolver, " + std::to_string(m_iterations) +
               " iterations" + (m_noSleep ? ", sleeping off" : ", sleeping on (Bullet default)");
    }

    bool setUp(const Scene& scene, const Options& options, std::string*) override
    {
        m_dt = scene.dt;
        m_iterations = scene.iterations;
        m_noSleep = options.noSleep;
        m_world.reset(new TimedWorld(&m_infra.dispatcher, &m_infra.broadphase, &m_infra.solver, &m_infra.config));
        m_bodies.reset(new BtBodies);
        m_bodies->build(scene, options, m_world.get());
        return true;
    }

    FrameTime step() override
    {
        m_world->syncMs = 0;
        auto t0 = Clock::now();
        m_world->stepSimulation(m_dt, 1, m_dt);
        double total = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        return {total - m_world->syncMs, m_world->syncMs};
    }

    void poses(std::vector<Pose>& out) override { m_bodies->poses(out); }
    void info(FrameInfo& out, bool detailed) override { BtBodies::contacts(m_world.get(), out, detailed); }

private:
    BtInfrastructure m_infra;
    std::unique_ptr<TimedWorld> m_world;
    std::unique_ptr<BtBodies> m_bodies;
    float m_dt = 1.0f / 60;
    int m_iterations = 10;
    bool m_noSleep = false;
};

}  // namespace

std::unique_ptr<Backend> makeBulletBackend() { return std::make_unique<BulletBackend>(); }

}  // namespace btgpu::bench
