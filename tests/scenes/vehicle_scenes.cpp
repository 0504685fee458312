// vehicle_scenes.cpp — the raycast vehicle scene: Bullet's vehicle demo values as facts, the
// code our own.
#include "scenes/vehicle_scenes.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include <cmath>

namespace btgpu::scenes {

VehicleScene::~VehicleScene()
{
    if (scene && vehicle) scene->world().removeAction(vehicle.get());
}

void VehicleScene::drive(btScalar engineForce, btScalar steering)
{
    for (int w = 0; w < 2; ++w) vehicle->setSteeringValue(steering, w);
    for (int w = 2; w < 4; ++w) {
        vehicle->applyEngineForce(engineForce, w);
        vehicle->setBrake(0, w);
    }
}

namespace {

btCollisionShape* waveHeightfield(Scene& scene)
{
    const int n = 128;
    std::vector<float>* heights = scene.ownData(new std::vector<float>(size_t(n * n)));
    for (int z = 0; z < n; ++z)
        for (int x = 0; x < n; ++x)
            (*heights)[size_t(z * n + x)] = 0.2f + 0.2f * std::sin(0.15f * float(z)) * std::cos(0.05f * float(x));
    auto* shape = new btHeightfieldTerrainShape(n, n, heights->data(), btScalar(1), btScalar(0), btScalar(0.4), 1,
                                                PHY_FLOAT, false);
    return scene.ownShape(shape);
}

}  // namespace

std::unique_ptr<VehicleScene> raycastVehicle(WorldKind kind, const Config& config, VehicleGround ground)
{
    auto v = std::make_unique<VehicleScene>();
    v->scene = std::make_unique<Scene>(kind, config, "raycast_vehicle");
    Scene& s = *v->scene;
    Material groundMaterial;
    groundMaterial.friction = 1;
    if (ground == VehicleGround::Box) {
        s.addBody(s.boxShape(btVector3(100, 1, 100)), 0, btVector3(0, -1, 0), groundMaterial);
    } else {
        // The shape is centred on its height range's middle (0.2 m): the body sits there.
        s.addBody(waveHeightfield(s), 0, btVector3(0, btScalar(0.2), 0), groundMaterial);
    }
    const btScalar chassisHeight = btScalar(1.4);
    v->chassis = s.addBody(s.boxShape(btVector3(1, btScalar(0.5), 2)), 800, btVector3(0, chassisHeight, 0));
    v->chassis->setActivationState(DISABLE_DEACTIVATION);

    btRaycastVehicle::btVehicleTuning tuning;
    v->raycaster = std::make_unique<btDefaultVehicleRaycaster>(&s.world());
    v->vehicle = std::make_unique<btRaycastVehicle>(tuning, v->chassis, v->raycaster.get());
    v->vehicle->setCoordinateSystem(0, 1, 2);
    const btScalar radius = btScalar(0.5), width = btScalar(0.4), rest = btScalar(0.6), connection = btScalar(0.2);
    const btVector3 down(0, -1, 0), axle(-1, 0, 0);
    const btVector3 points[4] = {
        btVector3(1 - btScalar(0.3) * width, connection, 2 - radius),   // front left
        btVector3(-1 + btScalar(0.3) * width, connection, 2 - radius),  // front right
        btVector3(-1 + btScalar(0.3) * width, connection, -2 + radius), // rear right
        btVector3(1 - btScalar(0.3) * width, connection, -2 + radius),  // rear left
    };
    for (int w = 0; w < 4; ++w) {
        btWheelInfo& wheel = v->vehicle->addWheel(points[w], down, axle, rest, radius, tuning, w < 2);
        wheel.m_suspensionStiffness = 20;
        wheel.m_wheelsDampingRelaxation = btScalar(2.3);
        wheel.m_wheelsDampingCompression = btScalar(4.4);
        wheel.m_frictionSlip = 1000;
        wheel.m_rollInfluence = btScalar(0.1);
    }
    s.world().addAction(v->vehicle.get());
    return v;
}

}  // namespace btgpu::scenes
