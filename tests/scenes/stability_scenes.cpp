// stability_scenes.cpp — builders of the stability suite's scenes (see stability_scenes.h).
#include "scenes/stability_scenes.h"

#include <algorithm>
#include <cstdint>

namespace btgpu::scenes::stability {

namespace {

btRigidBody* addGround(Scene& scene, btScalar halfExtent, const btVector3& origin = btVector3(0, 0, 0))
{
    return scene.addBody(scene.boxShape(btVector3(halfExtent, halfExtent, halfExtent)), 0,
                         origin - btVector3(0, halfExtent, 0));
}

}  // namespace

ScenePtr massRatio(WorldKind kind, const Config& config, btScalar topMass)
{
    auto scene = std::make_unique<Scene>(kind, config, "mass_ratio");
    addGround(*scene, 50);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    scene->addBody(box, 1, btVector3(0, .5, 0));
    scene->addBody(box, topMass, btVector3(0, 1.5, 0));
    return scene;
}

ScenePtr heavyPlank(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "heavy_plank");
    addGround(*scene, 50);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    scene->addBody(box, 1, btVector3(-8, .5, 0));
    scene->addBody(box, 1, btVector3(8, .5, 0));
    scene->addBody(scene->boxShape(btVector3(10, .5, 10)), 400, btVector3(0, 1.5, 0));
    return scene;
}

ScenePtr tower(WorldKind kind, const Config& config, int count, btScalar offset)
{
    auto scene = std::make_unique<Scene>(kind, config, "tower");
    addGround(*scene, 50);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    std::uint32_t state = 12345u;  // a fixed LCG: the same pattern on both engines and every run
    auto sign = [&state]() {
        state = state * 1664525u + 1013904223u;
        return (state >> 16) & 1u ? btScalar(1) : btScalar(-1);
    };
    for (int i = 0; i < count; ++i) {
        const btScalar dx = offset * sign(), dz = offset * sign();
        scene->addBody(box, 1, btVector3(dx, btScalar(.5 + i), dz));
    }
    return scene;
}

ScenePtr pyramid(WorldKind kind, const Config& config, int base, btScalar pitch)
{
    auto scene = std::make_unique<Scene>(kind, config, "pyramid");
    addGround(*scene, std::max<btScalar>(50, btScalar(base)));
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    for (int row = 0; row < base; ++row) {
        const int n = base - row;
        for (int i = 0; i < n; ++i)
            scene->addBody(box, 1,
                           btVector3(pitch * (btScalar(i) - btScalar(n - 1) / 2), btScalar(.5) + pitch * btScalar(row), 0));
    }
    return scene;
}

ScenePtr bulletVsWall(WorldKind kind, const Config& config, btScalar speed)
{
    auto scene = std::make_unique<Scene>(kind, config, "bullet_vs_wall");
    scene->addBody(scene->boxShape(btVector3(.1, 5, 5)), 0, btVector3(0, 0, 0));
    btRigidBody* ball = scene->addBody(scene->sphereShape(btScalar(.05)), 1, btVector3(-1, 0, 0));
    ball->setLinearVelocity(btVector3(speed, 0, 0));
    return scene;
}

ScenePtr scaledStack(WorldKind kind, const Config& config, btScalar size)
{
    auto scene = std::make_unique<Scene>(kind, config, "scaled_stack");
    addGround(*scene, std::max<btScalar>(50, 5 * size));
    const btScalar h = size / 2;
    btBoxShape* box = scene->boxShape(btVector3(h, h, h));
    for (int i = 0; i < 3; ++i) scene->addBody(box, 1, btVector3(0, h + size * btScalar(i), 0));
    return scene;
}

ScenePtr smallPile(WorldKind kind, const Config& config, const btVector3& origin)
{
    auto scene = std::make_unique<Scene>(kind, config, "small_pile");
    addGround(*scene, 50, origin);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    const btScalar lift = btScalar(.05);
    for (int x = 0; x < 2; ++x)
        for (int z = 0; z < 2; ++z)
            scene->addBody(box, 1, origin + btVector3(btScalar(x) - btScalar(.5), btScalar(.5) + lift, btScalar(z) - btScalar(.5)));
    scene->addBody(box, 1, origin + btVector3(0, btScalar(1.5) + 2 * lift, 0));
    return scene;
}

ScenePtr fastDrop(WorldKind kind, const Config& config, btScalar speed)
{
    auto scene = std::make_unique<Scene>(kind, config, "fast_drop");
    addGround(*scene, 50);
    btRigidBody* box = scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(0, 5, 0));
    box->setLinearVelocity(btVector3(0, -speed, 0));
    return scene;
}

ScenePtr onePlace(WorldKind kind, const Config& config, int count)
{
    auto scene = std::make_unique<Scene>(kind, config, "one_place");
    addGround(*scene, 50);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    for (int i = 0; i < count; ++i) scene->addBody(box, 1, btVector3(0, .5, 0));
    return scene;
}

}  // namespace btgpu::scenes::stability
