// btGpuDynamicsWorld.h — the drop-in: a btDiscreteDynamicsWorld whose rigid bodies are
// simulated by OpenCL kernels. Replace `new btDiscreteDynamicsWorld(d, b, s, c)` with
// `new btGpuDynamicsWorld(d, b, s, c)`; everything else in the app keeps working. Scenes the
// GPU path cannot handle yet (other shapes, constraints, actions, Bullet settings it does not
// follow: compat/cpu_path_rules.cpp) run on the base class's CPU path, said once on stderr and
// in report().
#pragma once
#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <memory>

#include "btgpu/Config.h"
#include "btgpu/Report.h"

static_assert(sizeof(btScalar) == 4, "btgpu needs the single-precision (float) build of Bullet");

namespace btgpu {
class GpuWorld;
}

class btGpuDynamicsWorld : public btDiscreteDynamicsWorld {
public:
    btGpuDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* pairCache, btConstraintSolver* constraintSolver,
                       btCollisionConfiguration* collisionConfiguration, const btgpu::Config& config = btgpu::Config());
    ~btGpuDynamicsWorld() override;

    // Bullet's fixed-step, substep and interpolation semantics; all substeps of one call run
    // on the device with one readback. Never throws: problems go to report().
    int stepSimulation(btScalar timeStep, int maxSubSteps = 1, btScalar fixedTimeStep = btScalar(1.) / btScalar(60.)) override;

    void addRigidBody(btRigidBody* body) override;
    void addRigidBody(btRigidBody* body, int group, int mask) override;
    void removeRigidBody(btRigidBody* body) override;
    void addCollisionObject(btCollisionObject* object, int group = btBroadphaseProxy::StaticFilter,
                            int mask = btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter) override;
    void removeCollisionObject(btCollisionObject* object) override;
    void addConstraint(btTypedConstraint* constraint, bool disableCollisionsBetweenLinkedBodies = false) override;
    void removeConstraint(btTypedConstraint* constraint) override;
    void addAction(btActionInterface* action) override;
    void removeAction(btActionInterface* action) override;
    void setGravity(const btVector3& gravity) override;
    // Bullet's synchronizeMotionStates, with the bodies whose motion state is Bullet's own
    // btDefaultMotionState updated in parallel (an app's own motion states serially, in order).
    void synchronizeMotionStates() override;
    // Bullet's clearForces (after a GPU step the write-back pass has already done it).
    void clearForces() override;

    const btgpu::Report& report() const;
    const btgpu::Config& config() const;
    // True when the last step ran on the OpenCL pipeline.
    bool isGpuPath() const;
    // FNV-1a hash of every body's transform and velocities (bitwise): same scene, device and
    // binary give the same sequence of hashes.
    std::uint64_t stateHash() const;

private:
    friend class btgpu::GpuWorld;
    // The base class's stepSimulation (the CPU path).
    int baseStepSimulation(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep);
    std::unique_ptr<btgpu::GpuWorld> m_gpu;
};
