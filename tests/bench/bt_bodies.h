// bt_bodies.h — instantiates a bench Scene as Bullet rigid bodies (shapes shared per size,
// a btDefaultMotionState per dynamic body) in any btDiscreteDynamicsWorld, and reads poses,
// pairs and contacts back; shared by the stock Bullet and btgpu backends. Joints (ragdolls) are
// added with disableCollisionsBetweenLinkedBodies.
#pragma once
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "bench_backend.h"

namespace btgpu::bench {

// The objects every Bullet world needs besides the world itself.
struct BtInfrastructure {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
};

class BtBodies {
public:
    ~BtBodies();
    // Before the world is deleted, in place of removing every body from it: the joints leave,
    // the bodies are let go with the world (see bt_bodies.cpp), and the destructor then deletes
    // them without touching it.
    void leaveWithWorld();
    void build(const Scene& scene, const Options& options, btDiscreteDynamicsWorld* world);
    void poses(std::vector<Pose>& out) const;
    // Broadphase pairs, manifolds with points and their points, as the dispatcher holds them.
    static void contacts(btDiscreteDynamicsWorld* world, FrameInfo& out, bool points);

private:
    btDiscreteDynamicsWorld* m_world = nullptr;
    std::unique_ptr<btTriangleIndexVertexArray> m_mesh;  // before the shapes that point into it
    std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
    std::vector<std::unique_ptr<btMotionState>> m_motionStates;
    std::vector<std::unique_ptr<btRigidBody>> m_bodies;
    std::vector<std::unique_ptr<btTypedConstraint>> m_joints;
};

}  // namespace btgpu::bench
