// app.cpp — the smallest app built against an installed btgpu: a box dropped on a ground box
// in a btGpuDynamicsWorld for 120 steps; prints where it rests and which path ran.
#include <btBulletDynamicsCommon.h>
#include <btgpu/btGpuDynamicsWorld.h>

#include <cstdio>

int main()
{
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btGpuDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
    btBoxShape groundShape(btVector3(10, 1, 10)), boxShape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
    btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
    ground.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
    btVector3 inertia;
    boxShape.calculateLocalInertia(1, inertia);
    btDefaultMotionState motion(btTransform(btQuaternion::getIdentity(), btVector3(0, 2, 0)));
    btRigidBody box(btRigidBody::btRigidBodyConstructionInfo(1, &motion, &boxShape, inertia));
    world.addRigidBody(&ground);
    world.addRigidBody(&box);
    for (int i = 0; i < 120; ++i) world.stepSimulation(btScalar(1) / 60, 0);
    std::printf("box at y = %.3f, %s path\n", double(box.getWorldTransform().getOrigin().y()),
                world.isGpuPath() ? "GPU" : "CPU");
    world.removeRigidBody(&box);
    world.removeRigidBody(&ground);
    return 0;
}
