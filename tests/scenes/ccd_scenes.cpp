// ccd_scenes.cpp — see ccd_scenes.h.
#include "scenes/ccd_scenes.h"

namespace btgpu::scenes {

ScenePtr ballAtWall(WorldKind kind, const Config& config, btScalar speed, bool wall)
{
    auto scene = std::make_unique<Scene>(kind, config, wall ? "ball_at_wall" : "ball_in_flight");
    scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
    scene->addBody(scene->boxShape(btVector3(btScalar(0.02), 2, 2)), 0,
                   wall ? btVector3(5, 2, 0) : btVector3(5, 2, 80));
    btRigidBody* ball = scene->addBody(scene->sphereShape(btScalar(0.1)), 1, btVector3(0, wall ? 1 : 20, 0));
    ball->setLinearVelocity(btVector3(speed, 0, 0));
    ball->setCcdMotionThreshold(btScalar(0.1));
    ball->setCcdSweptSphereRadius(btScalar(0.08));
    return scene;
}

}  // namespace btgpu::scenes
