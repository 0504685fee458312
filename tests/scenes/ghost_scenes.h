// ghost_scenes.h — ghost objects as apps use them: a trigger volume (CF_NO_CONTACT_RESPONSE)
// that boxes fall through, and Bullet's btKinematicCharacterController walking on a box ground
// into a step and a wall; defined once for the regression tests, the bench and the demos.
#pragma once
#include "scenes/scenes.h"

#include <BulletCollision/CollisionDispatch/btGhostObject.h>
#include <BulletDynamics/Character/btKinematicCharacterController.h>

#include <functional>
#include <memory>

namespace btgpu::scenes {

// A scene with ghost objects in it. The ghost pair callback (installed on the broadphase's pair
// cache, as apps do) outlives the world; the ghosts and the character leave the world before
// the scene goes.
struct GhostScene {
    std::unique_ptr<btGhostPairCallback> pairCallback;
    ScenePtr scene;
    std::vector<std::unique_ptr<btGhostObject>> ghosts;
    std::unique_ptr<btKinematicCharacterController> character;
    ~GhostScene();
    btGhostObject* ghost(int i = 0) const { return ghosts.at(size_t(i)).get(); }
    // Moves ghost i (setWorldTransform, as an app moves a trigger).
    void moveGhost(int i, const btVector3& origin);
};

// Makes the trigger's ghost object (an app's own subclass, say); nullptr: btPairCachingGhostObject.
using GhostMaker = std::function<btGhostObject*()>;

// The trigger, a 2 x 0.5 x 2 m half-extent box ghost with CF_NO_CONTACT_RESPONSE centred at
// y = 3 (SensorTrigger group, meeting everything else); nine 0.4 m half-extent boxes in nine
// columns (two across the trigger's edge at x = -2.2, one beside it at x = 3.5) dropped from 5
// to 12 m so they pass through it one after another; a static 20 x 1 x 20 m half-extent box
// ground far below (top at y = -60), so for 3 s nothing touches: Bullet's broadphase drops a
// pair lazily (a rotating share of its pairs each step), so its ghost lists are only stock's
// step by step while every body's AABB history is (see the README). Bodies: ground 0, boxes 1..9.
std::unique_ptr<GhostScene> triggerFall(WorldKind kind, const Config& config = Config::bulletMode(), const GhostMaker& make = nullptr);

// Bullet's kinematic character (a capsule of radius 0.3 m and cylinder height 1 m on a
// btPairCachingGhostObject with CF_CHARACTER_OBJECT, step height 0.35 m) dropped at the origin
// onto a static 20 x 1 x 20 m half-extent box ground with its top at y = 0; a 0.3 m high step (static box, z from 1 to 5) and a wall (static box
// 0.5 m thick at z = 8) ahead along +z. withBoxes adds two dynamic 0.4 m half-extent boxes on
// the ground: body 3 touching the capsule's side (at x = 0.7), body 4 far from it (x = 5).
std::unique_ptr<GhostScene> characterWalk(WorldKind kind, const Config& config = Config::bulletMode(), bool withBoxes = false);

// A ghost object as btCollisionObject starts (CF_STATIC_OBJECT, contact response) used as a
// platform: a 2 x 0.25 x 2 m half-extent box ghost with its top at y = 0, and a 0.4 m
// half-extent box (body 0, the only rigid body) dropped onto it from 1 m, off centre.
std::unique_ptr<GhostScene> ghostPlatform(WorldKind kind, const Config& config = Config::bulletMode());

}  // namespace btgpu::scenes
