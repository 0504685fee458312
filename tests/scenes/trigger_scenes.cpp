// trigger_scenes.cpp — the trigger and kinematic-filter scenes of trigger_scenes.h.
#include "scenes/trigger_scenes.h"

namespace btgpu::scenes {

ScenePtr staticTrigger(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "static_trigger");
    scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
    btRigidBody* trigger = scene->addBody(scene->boxShape(btVector3(2, btScalar(0.5), 2)), 0, btVector3(0, 3, 0));
    trigger->setCollisionFlags(trigger->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
    btCollisionShape* sphere = scene->sphereShape(btScalar(0.3));
    btCollisionShape* box = scene->boxShape(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
    // Apart from each other (1.5 m or more), so that nothing but the trigger and the ground
    // touches them: the last box straddles the trigger's edge at x = 2.
    const btVector3 at[6] = {{-1.5f, 4.5f, -1}, {0, 5, -1}, {1.5f, 5.5f, -1}, {-1.5f, 6, 1}, {0, 6.5f, 1}, {2.2f, 7, 1}};
    for (int i = 0; i < 6; ++i) scene->addBody(i < 3 ? sphere : box, 1, at[i]);
    btRigidBody* passer = scene->addBody(scene->sphereShape(btScalar(0.3)), 1, btVector3(-0.7f, 6, 0));
    passer->setCollisionFlags(passer->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
    scene->addBody(box, 1, btVector3(0.9f, 0.4f, 0));
    return scene;
}

namespace {
btTransform at(const btVector3& origin)
{
    btTransform t;
    t.setIdentity();
    t.setOrigin(origin);
    return t;
}
}  // namespace

ScenePtr kinematicSweep(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "kinematic_sweep");
    scene->addBody(scene->boxShape(btVector3(1, 1, 1)), 0, btVector3(0, 0, 0));
    btCollisionShape* box = scene->boxShape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
    scene->addKinematic(box, at(btVector3(-3, 2, 0)));
    scene->addKinematic(box, at(btVector3(3, 2, 0)));
    scene->addKinematic(scene->sphereShape(btScalar(0.4)), at(btVector3(-3, 0, 0)));
    // Custom masks, as an app sets them on the proxies: every pair among these may collide.
    for (int i = 0; i < 4; ++i) {
        btBroadphaseProxy* proxy = scene->body(i)->getBroadphaseHandle();
        proxy->m_collisionFilterGroup = 64;
        proxy->m_collisionFilterMask = -1;
    }
    return scene;
}

void sweepKinematics(Scene& scene, double t)
{
    const btScalar s = btScalar(t);
    const btVector3 where[3] = {btVector3(-3 + s, 2, 0), btVector3(3 - s, 2, 0), btVector3(-3 + btScalar(1.2) * s, 0, btScalar(0.2))};
    for (int i = 0; i < 3; ++i) scene.body(1 + i)->getMotionState()->setWorldTransform(at(where[i]));
}

}  // namespace btgpu::scenes
