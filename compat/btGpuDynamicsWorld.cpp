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
        int done = 0;
        if (m_gpu->step(timeStep, maxSubSteps, fixedTimeStep, &done)) return done;
    } catch (const std::exception& e) {
        m_gpu->failDevice(e.what());
    } catch (...) {
        m_gpu->failDevice("unknown exception");
    }
    try {
        return btDiscreteDynamicsWorld::stepSimulation(timeStep, maxSubSteps, fixedTimeStep);
    } catch (...) {
        return 0;
    }
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
    std::vector<btRigidBody*> bodies;
    if (m_synchronizeAllMotionStates) {
        for (int i = 0; i < m_collisionObjects.size(); ++i)
            if (btRigidBody* body = btRigidBody::upcast(m_collisionObjects[i])) bodies.push_back(body);
    } else {
        for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i)
            if (m_nonStaticRigidBodies[i]->isActive()) bodies.push_back(m_nonStaticRigidBodies[i]);
    }
    // Only Bullet's own motion state is known to be safe to set from several threads.
    std::vector<btRigidBody*> serial;
    std::vector<btRigidBody*> parallel;
    for (btRigidBody* body : bodies) {
        btMotionState* ms = body->getMotionState();
        if (ms && typeid(*ms) == typeid(btDefaultMotionState)) parallel.push_back(body);
        else serial.push_back(body);
    }
    btgpu::forEachChunk(parallel.size(), 4096, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) synchronizeSingleMotionState(parallel[i]);
    });
    for (btRigidBody* body : serial) synchronizeSingleMotionState(body);
}

const btgpu::Report& btGpuDynamicsWorld::report() const { return m_gpu->m_report; }
const btgpu::Config& btGpuDynamicsWorld::config() const { return m_gpu->m_config; }
bool btGpuDynamicsWorld::isGpuPath() const { return m_gpu->m_report.gpuPath; }
std::uint64_t btGpuDynamicsWorld::stateHash() const { return m_gpu->stateHash(); }
