// vehicle_scenes.h — Bullet's raycast vehicle (btRaycastVehicle, an action) as the
// ForkLift/Vehicle demos build it, on a box ground or a rolling heightfield, and an app's own
// action; defined once for the regression tests, the bench and the demos.
#pragma once
#include "scenes/scenes.h"

#include <BulletDynamics/Vehicle/btRaycastVehicle.h>

#include <memory>

namespace btgpu::scenes {

enum class VehicleGround { Box, Heightfield };

// A scene with one btRaycastVehicle in it. The vehicle and its raycaster are the scene's: the
// action leaves the world before the scene (and its bodies) go.
struct VehicleScene {
    ScenePtr scene;
    std::unique_ptr<btVehicleRaycaster> raycaster;
    std::unique_ptr<btRaycastVehicle> vehicle;
    btRigidBody* chassis = nullptr;
    ~VehicleScene();
    // Engine force on the two rear wheels and steering on the two front ones (the demos'
    // controls), as an app sets them between steps.
    void drive(btScalar engineForce, btScalar steering = 0);
};

// The chassis (a 1 x 0.5 x 2 m half-extent box of 800 kg, DISABLE_DEACTIVATION as the demos
// set it) with four wheels of radius 0.5 m (suspension rest length 0.6 m, stiffness 20,
// damping 2.3/4.4, friction slip 1000, roll influence 0.1), resting above the ground at the
// origin facing +z. Box ground: a static 100 x 1 x 100 m half-extent box with its top at y = 0.
// Heightfield: 128 x 128 float heights 1 m apart, gentle waves (up to 0.4 m) along z.
std::unique_ptr<VehicleScene> raycastVehicle(WorldKind kind, const Config& config = Config::bulletMode(),
                                             VehicleGround ground = VehicleGround::Box);

}  // namespace btgpu::scenes
