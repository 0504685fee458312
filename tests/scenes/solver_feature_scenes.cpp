// solver_feature_scenes.cpp — the scenes of solver_feature_scenes.h.
#include "scenes/solver_feature_scenes.h"

namespace btgpu::scenes::features {

namespace {
btRigidBody* ground(Scene& scene, const Material& material = Material())
{
    return scene.addBody(scene.boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0), material);
}
}  // namespace

ScenePtr rollingSphere(WorldKind kind, const Config& config, btScalar rolling, btScalar speed)
{
    auto scene = std::make_unique<Scene>(kind, config, "rolling_sphere");
    ground(*scene);
    btRigidBody* ball = scene->addBody(scene->sphereShape(btScalar(0.5)), 1, btVector3(0, btScalar(0.5), 0));
    ball->setRollingFriction(rolling);
    ball->setLinearVelocity(btVector3(speed, 0, 0));
    ball->setAngularVelocity(btVector3(0, 0, -2 * speed));
    return scene;
}

ScenePtr rollingCapsule(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "rolling_capsule");
    ground(*scene);
    btTransform t(btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI), btVector3(0, btScalar(0.3), 0));
    btRigidBody* capsule = scene->addBody(scene->ownShape(new btCapsuleShape(btScalar(0.3), btScalar(0.8))), 1, t);
    capsule->setRollingFriction(btScalar(0.05));
    capsule->setLinearVelocity(btVector3(2, 0, 0));
    capsule->setAngularVelocity(btVector3(0, 0, btScalar(-2 / 0.3)));
    return scene;
}

ScenePtr spinningSphere(WorldKind kind, const Config& config, btScalar spinning)
{
    auto scene = std::make_unique<Scene>(kind, config, "spinning_sphere");
    ground(*scene);
    btRigidBody* ball = scene->addBody(scene->sphereShape(btScalar(0.5)), 1, btVector3(0, btScalar(0.5), 0));
    ball->setRollingFriction(btScalar(0.01));
    ball->setSpinningFriction(spinning);
    ball->setAngularVelocity(btVector3(0, 20, 0));
    return scene;
}

ScenePtr slidingBox(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "sliding_box");
    Material m;
    m.friction = btScalar(0.3);
    ground(*scene, m);
    btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(0, .5, 0), m);
    box->setLinearVelocity(btVector3(2, 0, 2));
    return scene;
}

ScenePtr softBox(WorldKind kind, const Config& config, btScalar stiffness, btScalar damping)
{
    auto scene = std::make_unique<Scene>(kind, config, "soft_box");
    ground(*scene);
    btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(0, .5, 0));
    box->setContactStiffnessAndDamping(stiffness, damping);
    return scene;
}

ScenePtr boxPile(WorldKind kind, const Config& config, int side)
{
    auto scene = std::make_unique<Scene>(kind, config, "box_pile");
    ground(*scene);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            for (int z = 0; z < side; ++z)
                scene->addBody(box, 1,
                               btVector3(btScalar(1.1 * (x - side / 2) + 0.05 * y), btScalar(0.55 + 1.2 * y),
                                         btScalar(1.1 * (z - side / 2) - 0.03 * y)));
    return scene;
}

ScenePtr anisotropicPair(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "anisotropic_pair");
    ground(*scene);
    btRigidBody* base = scene->addBody(scene->boxShape(btVector3(3, btScalar(0.25), 3)), 0,
                                       btTransform(btQuaternion(btVector3(0, 1, 0), btScalar(0.35)), btVector3(0, .25, 0)));
    base->setAnisotropicFriction(btVector3(1, 1, btScalar(0.2)));
    btTransform t(btQuaternion(btVector3(0, 1, 0), btScalar(SIMD_PI / 6)), btVector3(0, 1, 0));
    btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, t);
    box->setAnisotropicFriction(btVector3(1, 1, btScalar(0.1)));
    box->setLinearVelocity(btVector3(2, 0, 2));
    return scene;
}

ScenePtr anisotropicBox(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "anisotropic_box");
    ground(*scene);
    btTransform t(btQuaternion(btVector3(0, 1, 0), btScalar(SIMD_PI / 6)), btVector3(0, .5, 0));
    btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, t);
    box->setAnisotropicFriction(btVector3(1, 1, btScalar(0.1)));
    box->setLinearVelocity(btVector3(2, 0, 2));
    return scene;
}

ScenePtr thresholdStack(WorldKind kind, const Config& config, btScalar threshold, btScalar drop, bool sphere)
{
    auto scene = std::make_unique<Scene>(kind, config, "threshold_stack");
    ground(*scene);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    scene->addBody(box, 1, btVector3(0, .5, 0));
    btCollisionShape* topShape = sphere ? static_cast<btCollisionShape*>(scene->sphereShape(btScalar(0.5))) : box;
    btRigidBody* top = scene->addBody(topShape, 1, btVector3(0, btScalar(1.5) + drop, 0));
    top->setContactProcessingThreshold(threshold);
    return scene;
}

namespace {
// A ground far below, a 10 x 1 x 10 m slab tilted `angle` about z (body 1), and `boxes` unit
// boxes of 1 kg stacked on it (bodies 2, 3, ...), never deactivated (asleep they would stop
// creeping either way).
ScenePtr slopeWithBoxes(WorldKind kind, const Config& config, btScalar angle, int boxes, const char* name)
{
    auto scene = std::make_unique<Scene>(kind, config, name);
    scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -60, 0));
    const btQuaternion tilt(btVector3(0, 0, 1), angle);
    const btVector3 up = quatRotate(tilt, btVector3(0, 1, 0));
    scene->addBody(scene->boxShape(btVector3(5, .5, 5)), 0, btTransform(tilt, btVector3(0, 0, 0)));
    for (int i = 0; i < boxes; ++i) {
        btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1,
                                          btTransform(tilt, up * btScalar(1.0 + i)));
        box->setActivationState(DISABLE_DEACTIVATION);
    }
    return scene;
}
}  // namespace

ScenePtr anchorSlope(WorldKind kind, const Config& config, btScalar angle, bool anchor, btScalar speed)
{
    ScenePtr scene = slopeWithBoxes(kind, config, angle, 1, "anchor_slope");
    btRigidBody* box = scene->body(2);
    box->setLinearVelocity(quatRotate(btQuaternion(btVector3(0, 0, 1), angle), btVector3(-speed, 0, 0)));
    if (anchor) box->setCollisionFlags(box->getCollisionFlags() | btCollisionObject::CF_HAS_FRICTION_ANCHOR);
    return scene;
}

ScenePtr slopeStack(WorldKind kind, const Config& config, btScalar angle, int boxes)
{
    return slopeWithBoxes(kind, config, angle, boxes, "slope_stack");
}

}  // namespace btgpu::scenes::features
