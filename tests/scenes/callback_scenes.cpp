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

ScenePtr edgeSlide(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "edge_slide");
    btBvhTriangleMeshShape* mesh = gridMesh(*scene, 16, 1.0f, true, false);
    btTriangleInfoMap* edges = scene->ownData(new btTriangleInfoMap());
    btGenerateInternalEdgeInfo(mesh, edges);
    btRigidBody* ground = scene->addBody(mesh, 0, btVector3(0, 0, 0));
    ground->setCollisionFlags(ground->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(-6, .5, .3));
    box->setLinearVelocity(btVector3(5, 0, 0));
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
