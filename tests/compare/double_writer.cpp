// double_writer.cpp — writes tests/compare/double_scene.h's scene with Bullet's double build
// (BULLETd files), which compare_test.cpp loads through the float importer and btgpu_compare.
// Usage: btgpu_double_writer FILE
#include <btBulletDynamicsCommon.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "double_scene.h"

static_assert(sizeof(btScalar) == 8, "the double build of Bullet");

int main(int argc, char** argv)
{
    using namespace btgpu::double_scene;
    if (argc != 2) return 2;
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
    world.setGravity(btVector3(0, -10, 0));
    btBoxShape ground(btVector3(50, 50, 50)), box(btVector3(0.5, 0.5, 0.5));
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    btTransform t;
    t.setIdentity();
    t.setOrigin(btVector3(0, -50, 0));
    bodies.emplace_back(new btRigidBody(0, nullptr, &ground));
    bodies.back()->setWorldTransform(t);
    world.addRigidBody(bodies.back().get());
    for (int i = 0; i < kBoxes; ++i) {
        btVector3 inertia;
        box.calculateLocalInertia(kMass, inertia);
        bodies.emplace_back(new btRigidBody(kMass, nullptr, &box, inertia));
        btRigidBody* b = bodies.back().get();
        t.setOrigin(btVector3(1.5 * i, 0.5, 0));
        b->setWorldTransform(t);
        b->setLinearVelocity(btVector3(kVelocityX, 0, kVelocityZPerBody * i));
        b->setDamping(kLinearDamping, kAngularDamping);
        b->setSleepingThresholds(kLinearSleep, kAngularSleep);
        world.addRigidBody(b);
    }
    btDefaultSerializer serializer;
    world.serialize(&serializer);
    std::FILE* f = std::fopen(argv[1], "wb");
    const bool ok = f && std::fwrite(serializer.getBufferPointer(), size_t(serializer.getCurrentBufferSize()), 1, f) == 1;
    if (f) std::fclose(f);
    for (auto& b : bodies) world.removeRigidBody(b.get());
    return ok ? 0 : 1;
}
