// btGpuDynamicsWorld.cpp — the public class: Bullet's world API, forwarding structure changes
// to GpuWorld and choosing per call between the GPU path and the base class's CPU path.
// Nothing here throws into the app.
#include "btgpu/btGpuDynamicsWorld.h"

#include "gpu_world.h"
#include "parallel_rows.h"

#include <typeinfo>
#include <vector>

#include <iostream>

btGpuDynamicsWorld::btGpuDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* pairCache,
                                       btConstraintSolver* constraintSolver,
                                       btCollisionConfiguration* collisionConfiguration, const btgpu::Config& config)
    : btDiscreteDynamicsWorld(dispatcher, pairCache, constraintSolver, collisionConfiguration),
      m_gpu(std::make_unique<btgpu::GpuWorld>(*this, config))
{
}

btGpuDynamicsWorld::~btGpuDynamicsWorld() = default;

int btGpuDynamicsWorld::stepSimulation(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
    try {
        // Refused arguments simulate nothing on either path: every body and motion state stays.
        if (!m_gpu->acceptStep(timeStep, maxSubSteps, fixedTimeStep)) return 0;
        // The GPU path sets the local time before its device work; after a failure the base
        // class counts this call's time itself, from where it was.
        const btScalar localTime = m_localTime, fixedStep = m_fixedTimeStep;
        try {
            int done = 0;
            if (m_gpu->step(timeStep, maxSubSteps, fixedTimeStep, &done)) return done;
        } catch (const std::exception& e) {
            m_localTime = localTime;
            m_fixedTimeStep = fixedStep;
            m_gpu->failDevice(e.what());
        } catch (...) {
            m_localTime = localTime;
            m_fixedTimeStep = fixedStep;
            m_gpu->failDevice("unknown exception");
        }
        return m_gpu->stepOnCpuPath(timeStep, maxSubSteps, fixedTimeStep);
    } catch (...) {
        return 0;
    }
}

int btGpuDynamicsWorld::baseStepSimulation(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
    return btDiscreteDynamicsWorld::stepSimulation(timeStep, maxSubSteps, fixedTimeStep);
}

void btGpuDynamicsWorld::addRigidBody(btRigidBody* body)
{
    btDiscreteDynamicsWorld::addRigidBody(body);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::addRigidBody(btRigidBody* body, int group, int mask)
{
    btDiscreteDynamicsWorld::addRigidBody(body, group, mask);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::removeRigidBody(btRigidBody* body)
{
    m_gpu->removed(body);
    btDiscreteDynamicsWorld::removeRigidBody(body);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::addCollisionObject(btCollisionObject* object, int group, int mask)
{
    btDiscreteDynamicsWorld::addCollisionObject(object, group, mask);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::removeCollisionObject(btCollisionObject* object)
{
    m_gpu->removed(object);
    btDiscreteDynamicsWorld::removeCollisionObject(object);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::addConstraint(btTypedConstraint* constraint, bool disableCollisionsBetweenLinkedBodies)
{
    btDiscreteDynamicsWorld::addConstraint(constraint, disableCollisionsBetweenLinkedBodies);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::removeConstraint(btTypedConstraint* constraint)
{
    btDiscreteDynamicsWorld::removeConstraint(constraint);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::addAction(btActionInterface* action)
{
    btDiscreteDynamicsWorld::addAction(action);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::removeAction(btActionInterface* action)
{
    btDiscreteDynamicsWorld::removeAction(action);
    m_gpu->structureChanged();
}

void btGpuDynamicsWorld::setGravity(const btVector3& gravity)
{
    // The base class sets each body's gravity; the next step sees the changed rows.
    btDiscreteDynamicsWorld::setGravity(gravity);
}

void btGpuDynamicsWorld::synchronizeMotionStates()
{
    // The bodies the base class visits: every rigid body, or the active non-static ones.
    const bool all = m_synchronizeAllMotionStates;
    const size_t n = size_t(all ? m_collisionObjects.size() : m_nonStaticRigidBodies.size());
    auto bodyAt = [&](size_t i) -> btRigidBody* {
        if (all) return btRigidBody::upcast(m_collisionObjects[int(i)]);
        btRigidBody* body = m_nonStaticRigidBodies[int(i)];
        return body->isActive() ? body : nullptr;
    };
    // Only Bullet's own motion state is known to be safe to set from several threads: those are
    // set in parallel chunks; the app's own motion states are called after, serially, in order.
    // Right after a GPU step's write-back, Bullet's own ones are already set (same pass).
    const bool ownDone = m_gpu->fusedWriteBackPending();
    const size_t minPerThread = btgpu::kBodyRowsPerThread;
    std::vector<std::vector<btRigidBody*>> serial(btgpu::chunkCount(n, minPerThread));
    btgpu::forEachChunk(n, minPerThread, [&](size_t begin, size_t end, int chunk) {
        for (size_t i = begin; i < end; ++i) {
            btRigidBody* body = bodyAt(i);
            if (!body) continue;
            btMotionState* ms = body->getMotionState();
            if (ms && typeid(*ms) == typeid(btDefaultMotionState)) {
                if (!ownDone) synchronizeSingleMotionState(body);
            } else if (ms) {
                serial[chunk].push_back(body);
            }
        }
    });
    for (const std::vector<btRigidBody*>& bodies : serial)
        for (btRigidBody* body : bodies) synchronizeSingleMotionState(body);
}

void btGpuDynamicsWorld::clearForces()
{
    if (m_gpu->takeFusedWriteBack()) return;
    btDiscreteDynamicsWorld::clearForces();
}

const btgpu::Report& btGpuDynamicsWorld::report() const { return m_gpu->m_report; }
const btgpu::Config& btGpuDynamicsWorld::config() const { return m_gpu->m_config; }
bool btGpuDynamicsWorld::isGpuPath() const { return m_gpu->m_report.gpuPath; }
std::uint64_t btGpuDynamicsWorld::stateHash() const { return m_gpu->stateHash(); }
