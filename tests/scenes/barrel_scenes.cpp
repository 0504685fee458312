// barrel_scenes.cpp — the barrel drop (barrel_scenes.h).
#include "scenes/barrel_scenes.h"

#include <cmath>
#include <random>

namespace btgpu::scenes {

ScenePtr barrelDrop(WorldKind kind, const Config& config, const BarrelDrop& drop)
{
    auto scene = std::make_unique<Scene>(kind, config, "barrels");
    btBoxShape* groundShape = scene->boxShape(btVector3(50, 50, 50));
    std::vector<btVector3> points;
    for (int k = 0; k < kBarrelSides; ++k) {
        const double a = 2.0 * M_PI * k / kBarrelSides;
        for (int s = -1; s <= 1; s += 2)
            points.emplace_back(btScalar(kBarrelRadius * std::cos(a)), btScalar(s * kBarrelHalfHeight),
                                btScalar(kBarrelRadius * std::sin(a)));
    }
    btConvexHullShape* hull = scene->hullShape(points);
    if (drop.polyhedral) {
        groundShape->initializePolyhedralFeatures();
        hull->initializePolyhedralFeatures();
    }
    scene->addBody(groundShape, 0, btVector3(0, -50, 0));
    std::mt19937 rng(1234);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(drop.count))));
    for (int i = 0; i < drop.count; ++i) {
        const double tilt = drop.maxTiltDegrees * M_PI / 180.0 * unit(rng);
        const double azimuth = 2.0 * M_PI * unit(rng);
        btTransform t;
        t.setIdentity();
        t.setOrigin(btVector3(btScalar((i % side - side / 2) * kBarrelPitch),
                              btScalar(kBarrelHalfHeight + 0.05 + drop.dropHeight),
                              btScalar((i / side - side / 2) * kBarrelPitch)));
        t.setRotation(btQuaternion(btVector3(btScalar(std::cos(azimuth)), 0, btScalar(std::sin(azimuth))),
                                   btScalar(tilt)));
        scene->addBody(hull, 1, t);
    }
    return scene;
}

double uprightFraction(const Scene& scene, double degrees)
{
    int barrels = 0, upright = 0;
    for (const btRigidBody* b : scene.bodies()) {
        if (b->getInvMass() == 0) continue;
        ++barrels;
        if (std::fabs(b->getWorldTransform().getBasis().getColumn(1).y()) > std::cos(degrees * M_PI / 180.0)) ++upright;
    }
    return barrels ? double(upright) / barrels : 0.0;
}

}  // namespace btgpu::scenes
