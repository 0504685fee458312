// callback_scenes.cpp — see callback_scenes.h.
#include "scenes/callback_scenes.h"

#include "scenes/mesh_scenes.h"

#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>

namespace btgpu::scenes {

ScenePtr trampoline(WorldKind kind, const Config& config, btScalar dropHeight)
{
    auto scene = std::make_unique<Scene>(kind, config, "trampoline");
    btRigidBody* pad = scene->addBody(scene->boxShape(btVector3(3, .25, 3)), 0, btVector3(0, -.25, 0));
    pad->setCollisionFlags(pad->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    scene->addBody(scene->sphereShape(.5), 1, btVector3(0, dropHeight, 0));
    return scene;
}

ScenePtr slidingBox(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "sliding_box");
    Material grip;
    grip.friction = 1;
    btRigidBody* floor = scene->addBody(scene->boxShape(btVector3(20, 20, 20)), 0, btVector3(0, -20, 0), grip);
    floor->setCollisionFlags(floor->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(-10, .5, 0), grip);
    box->setLinearVelocity(btVector3(4, 0, 0));
    return scene;
}

namespace {

// A flat 16 x 16-quad triangle-mesh ground whose internal edges btGenerateInternalEdgeInfo has
// recorded, flagged CF_CUSTOM_MATERIAL_CALLBACK (for btAdjustInternalEdgeContacts).
void edgeMeshGround(Scene& scene)
{
    btBvhTriangleMeshShape* mesh = gridMesh(scene, 16, 1.0f, true, false);
    btTriangleInfoMap* edges = scene.ownData(new btTriangleInfoMap());
    btGenerateInternalEdgeInfo(mesh, edges);
    btRigidBody* ground = scene.addBody(mesh, 0, btVector3(0, 0, 0));
    ground->setCollisionFlags(ground->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
}

}  // namespace

ScenePtr edgeSlide(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "edge_slide");
    edgeMeshGround(*scene);
    btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(-6, .5, .3));
    box->setLinearVelocity(btVector3(5, 0, 0));
    return scene;
}

ScenePtr capsuleTrampoline(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "capsule_trampoline");
    btRigidBody* pad = scene->addBody(scene->boxShape(btVector3(3, .25, 3)), 0, btVector3(0, -.25, 0));
    pad->setCollisionFlags(pad->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    btRigidBody* c = scene->addBody(scene->ownShape(new btCapsuleShape(.3f, 1.0f)), 1, btVector3(0, 3, 0));
    c->setAngularFactor(btVector3(0, 0, 0));  // stays upright, as a character's capsule
    return scene;
}

ScenePtr capsulePile(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "capsule_pile");
    btRigidBody* ground = scene->addBody(scene->boxShape(btVector3(20, 20, 20)), 0, btVector3(0, -20, 0));
    ground->setCollisionFlags(ground->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    btCapsuleShape* capsule = scene->ownShape(new btCapsuleShapeX(.25f, 1.0f));
    for (int layer = 0; layer < 3; ++layer)
        for (int i = 0; i < 4; ++i) {
            const btScalar across = btScalar(0.6 * i - 0.9), y = btScalar(0.3 + 0.55 * layer);
            const bool turned = layer % 2 == 1;  // along z, side by side along x
            const btQuaternion turn(btVector3(0, 1, 0), btScalar(turned ? 1.5707963 : 0.0));
            scene->addBody(capsule, 1,
                           btTransform(turn, turned ? btVector3(across, y, btScalar(0.05)) : btVector3(btScalar(0.05 * layer), y, across)));
        }
    return scene;
}

ScenePtr capsuleEdgeSlide(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "capsule_edge_slide");
    edgeMeshGround(*scene);
    btRigidBody* c = scene->addBody(scene->ownShape(new btCapsuleShape(.3f, 1.0f)), 1, btVector3(-6, .8, .3));
    c->setAngularFactor(btVector3(0, 0, 0));
    c->setLinearVelocity(btVector3(5, 0, 0));
    return scene;
}

ScenePtr boxOverBox(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "box_over_box");
    scene->addBody(scene->boxShape(btVector3(20, 20, 20)), 0, btVector3(0, -20, 0));
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    scene->addBody(box, 1, btVector3(0, .5, 0))->setUserIndex(8);
    scene->addBody(box, 1, btVector3(.2f, 3, 0))->setUserIndex(7);
    return scene;
}

}  // namespace btgpu::scenes
