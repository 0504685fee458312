// ghost_scenes.cpp — the trigger-volume and character-controller scenes (ghost_scenes.h).
#include "scenes/ghost_scenes.h"

#include <BulletCollision/CollisionShapes/btCapsuleShape.h>

namespace btgpu::scenes {

GhostScene::~GhostScene()
{
    if (scene) {
        if (character) scene->world().removeAction(character.get());
        for (auto& g : ghosts) scene->world().removeCollisionObject(g.get());
    }
    character.reset();
    ghosts.clear();
    scene.reset();  // the world, and its pair cache that points at the callback, go first
}

void GhostScene::moveGhost(int i, const btVector3& origin)
{
    btTransform t = ghost(i)->getWorldTransform();
    t.setOrigin(origin);
    ghost(i)->setWorldTransform(t);
}

namespace {

std::unique_ptr<GhostScene> withGround(WorldKind kind, const Config& config, const char* name, btScalar top)
{
    auto g = std::make_unique<GhostScene>();
    g->pairCallback = std::make_unique<btGhostPairCallback>();
    g->scene = std::make_unique<Scene>(kind, config, name);
    g->scene->world().getBroadphase()->getOverlappingPairCache()->setInternalGhostPairCallback(g->pairCallback.get());
    g->scene->addBody(g->scene->boxShape(btVector3(20, 1, 20)), 0, btVector3(0, top - 1, 0));
    return g;
}

}  // namespace

std::unique_ptr<GhostScene> triggerFall(WorldKind kind, const Config& config, const GhostMaker& make)
{
    auto g = withGround(kind, config, "trigger_fall", -60);
    Scene& s = *g->scene;
    btGhostObject* trigger = make ? make() : new btPairCachingGhostObject();
    g->ghosts.emplace_back(trigger);
    trigger->setCollisionShape(s.boxShape(btVector3(2, btScalar(0.5), 2)));
    trigger->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 3, 0)));
    trigger->setCollisionFlags(trigger->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
    s.world().addCollisionObject(trigger, btBroadphaseProxy::SensorTrigger,
                                 btBroadphaseProxy::AllFilter & ~btBroadphaseProxy::SensorTrigger);
    const btScalar xs[3] = {btScalar(-2.2), 0, btScalar(1.5)}, zs[3] = {btScalar(-1.5), 0, btScalar(1.2)};
    btCollisionShape* box = s.boxShape(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
    for (int k = 0; k < 9; ++k) {
        const btScalar x = k == 8 ? btScalar(3.5) : xs[k % 3];  // the last one passes beside it
        s.addBody(box, 1, btVector3(x, btScalar(5) + btScalar(0.9) * btScalar(k), zs[(k / 3) % 3]));
    }
    return g;
}

std::unique_ptr<GhostScene> characterWalk(WorldKind kind, const Config& config, bool withBoxes)
{
    auto g = withGround(kind, config, "character_walk", 0);
    Scene& s = *g->scene;
    s.addBody(s.boxShape(btVector3(1, btScalar(0.15), 2)), 0, btVector3(0, btScalar(0.15), 3));  // the step
    s.addBody(s.boxShape(btVector3(2, 2, btScalar(0.25))), 0, btVector3(0, 2, 8));               // the wall
    auto* ghost = new btPairCachingGhostObject();
    g->ghosts.emplace_back(ghost);
    auto* capsule = s.ownShape(new btCapsuleShape(btScalar(0.3), 1));
    ghost->setCollisionShape(capsule);
    ghost->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(0.85), 0)));
    ghost->setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
    s.world().addCollisionObject(ghost, btBroadphaseProxy::CharacterFilter,
                                 btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter);
    g->character = std::make_unique<btKinematicCharacterController>(ghost, capsule, btScalar(0.35), btVector3(0, 1, 0));
    s.world().addAction(g->character.get());
    if (withBoxes) {
        btCollisionShape* box = s.boxShape(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
        s.addBody(box, 1, btVector3(btScalar(0.7), btScalar(0.4), 0));
        s.addBody(box, 1, btVector3(5, btScalar(0.4), 0));
    }
    return g;
}

std::unique_ptr<GhostScene> ghostPlatform(WorldKind kind, const Config& config)
{
    auto g = std::make_unique<GhostScene>();
    g->pairCallback = std::make_unique<btGhostPairCallback>();
    g->scene = std::make_unique<Scene>(kind, config, "ghost_platform");
    Scene& s = *g->scene;
    s.world().getBroadphase()->getOverlappingPairCache()->setInternalGhostPairCallback(g->pairCallback.get());
    auto* platform = new btPairCachingGhostObject();
    g->ghosts.emplace_back(platform);
    platform->setCollisionShape(s.boxShape(btVector3(2, btScalar(0.25), 2)));
    platform->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(-0.25), 0)));
    s.world().addCollisionObject(platform);
    s.addBody(s.boxShape(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4))), 1, btVector3(btScalar(0.5), btScalar(1.4), btScalar(-0.3)));
    return g;
}

}  // namespace btgpu::scenes
