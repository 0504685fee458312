// aabb_sync_test.cpp — Bullet's broadphase kept current (Config::syncBroadphaseAabbs, the default)
// when, in a big world, the sync runs on a side thread beside the manifold fill: after every GPU
// step each proxy holds the AABB Bullet's own updateAabbs gives the bodies where the step left
// them (running it again changes no bit), ray tests find the bodies where they are, and the
// manifolds the fill made are there (the fill and the sync both ran, on the GPU path).
#include <gtest/gtest.h>

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>

#include <cstring>
#include <vector>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

TEST(AabbSync, BesideTheFillEveryProxyIsCurrentAfterEachStep)
{
    Scene scene(WorldKind::Gpu);  // defaults: manifolds filled, Bullet's broadphase kept current
    btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
    scene.addBody(&plane, 0, btVector3(0, 0, 0));
    btSphereShape* sphere = scene.sphereShape(0.5f);
    btBoxShape* box = scene.boxShape(btVector3(0.5f, 0.5f, 0.5f));
    const int side = 16;  // 4,096 bodies and the plane: a world big enough for the side thread
    for (int x = 0; x < side; ++x)
        for (int y = 0; y < side; ++y)
            for (int z = 0; z < side; ++z)
                scene.addBody((x + y + z) % 2 ? static_cast<btCollisionShape*>(sphere) : box, 1,
                              btVector3(x * 1.5f, 0.5f + y * 1.1f, z * 1.5f));
    ASSERT_GE(scene.world().getNumCollisionObjects(), 4096);
    auto* dbvt = dynamic_cast<btDbvtBroadphase*>(scene.world().getBroadphase());
    ASSERT_NE(dbvt, nullptr);
    int manifoldSteps = 0;
    for (int step = 0; step < 40; ++step) {
        scene.step();
        ASSERT_TRUE(scene.report()->gpuPath) << scene.report()->cpuPathReason;
        if (scene.world().getDispatcher()->getNumManifolds() > 1000) ++manifoldSteps;
        // Bullet's own pass again, its pair tests deferred as the sync's are: not one AABB moves.
        btCollisionObjectArray& objects = scene.world().getCollisionObjectArray();
        std::vector<btVector3> before;
        for (int i = 0; i < objects.size(); ++i) {
            before.push_back(objects[i]->getBroadphaseHandle()->m_aabbMin);
            before.push_back(objects[i]->getBroadphaseHandle()->m_aabbMax);
        }
        const bool deferred = dbvt->m_deferedcollide;
        dbvt->m_deferedcollide = true;
        scene.world().updateAabbs();
        dbvt->m_deferedcollide = deferred;
        for (int i = 0; i < objects.size(); ++i) {
            const btBroadphaseProxy* p = objects[i]->getBroadphaseHandle();
            ASSERT_EQ(std::memcmp(&before[size_t(2 * i)], &p->m_aabbMin, sizeof(btVector3)), 0) << "object " << i << ", step " << step;
            ASSERT_EQ(std::memcmp(&before[size_t(2 * i + 1)], &p->m_aabbMax, sizeof(btVector3)), 0) << "object " << i << ", step " << step;
        }
        // A ray straight down onto a body in the top layer finds that body.
        if (step % 10 == 9) {
            btRigidBody* top = scene.body(1 + (5 * side + side - 1) * side + 7);  // x 5, y top, z 7
            const btVector3 at = top->getWorldTransform().getOrigin();
            btCollisionWorld::ClosestRayResultCallback hit(at + btVector3(0, 30, 0), at - btVector3(0, 30, 0));
            scene.world().rayTest(hit.m_rayFromWorld, hit.m_rayToWorld, hit);
            ASSERT_TRUE(hit.hasHit());
            EXPECT_EQ(hit.m_collisionObject, top) << "step " << step;
        }
    }
    EXPECT_GT(manifoldSteps, 10) << "the bodies should be touching (the fill had manifolds to make)";
}
