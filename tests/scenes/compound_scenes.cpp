// compound_scenes.cpp — the compound scenes (tables, a dumbbell, a dropped mix): child shapes
// and compounds owned by the scene, mass and inertia as Scene::addBody gives them
// (btCompoundShape::calculateLocalInertia, the app's own choice on both worlds).
#include "scenes/compound_scenes.h"

#include "scenes/mesh_scenes.h"
#include "scenes/scene_specs.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>

#include <cmath>

namespace btgpu::scenes {

namespace {

btRigidBody* boxGround(Scene& scene)
{
    return scene.addBody(scene.boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
}

// A compound of a spec's children, each child shape owned by the scene; with or without its
// dynamic AABB tree.
btCompoundShape* compoundOf(Scene& scene, const spec::CompoundSpec& c, bool dynamicTree = true)
{
    auto* shape = scene.ownShape(new btCompoundShape(dynamicTree));
    for (const spec::ChildSpec& ch : c.children) {
        btCollisionShape* child =
            ch.shape == spec::ShapeKind::Sphere
                ? static_cast<btCollisionShape*>(scene.sphereShape(ch.radius))
                : static_cast<btCollisionShape*>(scene.boxShape(btVector3(ch.half[0], ch.half[1], ch.half[2])));
        const btTransform t(btQuaternion(ch.rot[0], ch.rot[1], ch.rot[2], ch.rot[3]),
                            btVector3(ch.pos[0], ch.pos[1], ch.pos[2]));
        shape->addChildShape(t, child);
    }
    return shape;
}

btCompoundShape* dumbbellShape(Scene& scene) { return compoundOf(scene, spec::dumbbellSpec()); }

}  // namespace

btCompoundShape* tableShape(Scene& scene, bool dynamicTree) { return compoundOf(scene, spec::tableSpec(), dynamicTree); }

ScenePtr tableStack(WorldKind kind, const Config& config, int count, bool dynamicTree)
{
    auto scene = std::make_unique<Scene>(kind, config, "table_stack");
    boxGround(*scene);
    btCompoundShape* table = tableShape(*scene, dynamicTree);
    for (int i = 0; i < count; ++i)
        scene->addBody(table, 1, btVector3(0, btScalar(kTableFootDepth + (kTableHeight + .01) * i + .01), 0));
    return scene;
}

ScenePtr wrappedBoxStack(WorldKind kind, const Config& config, int count)
{
    auto scene = std::make_unique<Scene>(kind, config, "wrapped_box_stack");
    boxGround(*scene);
    btBoxShape* box = scene->boxShape(btVector3(0.5f, 0.5f, 0.5f));
    // The engine's pattern: one child, shifted so that the body's origin is its centre of mass.
    auto* wrapper = scene->ownShape(new btCompoundShape(false, 1));
    wrapper->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0.1f, -0.2f, 0)), box);
    for (int i = 0; i < count; ++i) scene->addBody(wrapper, 1, btVector3(btScalar(-0.1 + 0.02 * i), btScalar(0.71 + 1.01 * i), 0));
    return scene;
}

ScenePtr tableBesideSphere(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "table_beside_sphere");
    boxGround(*scene);
    scene->addBody(tableShape(*scene), 1, btVector3(0, btScalar(kTableFootDepth), 0));
    // Off the (+x, +z) leg's outer edge diagonally: 6 cm from the leg, inside its AABB's reach.
    const btScalar off = btScalar(0.55 + 0.185), offZ = btScalar(0.35 + 0.185);
    scene->addBody(scene->sphereShape(btScalar(0.2)), 1, btVector3(off, btScalar(0.2), offZ));
    return scene;
}

ScenePtr tableOnMesh(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "table_on_mesh");
    scene->addBody(gridMesh(*scene, 16, 1.0f, true, true), 0, btVector3(0, 0, 0));
    scene->addBody(tableShape(*scene), 1, btVector3(btScalar(.2), btScalar(kTableFootDepth + .01), btScalar(.1)));
    return scene;
}

ScenePtr tableOnHeightfield(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "table_on_heightfield");
    scene->addBody(flatHeightfield(*scene, 17), 0, btVector3(0, 0, 0));
    scene->addBody(tableShape(*scene), 1, btVector3(btScalar(.2), btScalar(kTableFootDepth + .01), btScalar(.1)));
    return scene;
}

ScenePtr convexCart(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "convex_cart");
    boxGround(*scene);
    auto* cart = scene->ownShape(new btCompoundShape());
    btCollisionShape* wheel = scene->ownShape(new btCylinderShapeZ(btVector3(btScalar(.3), btScalar(.3), btScalar(.1))));
    btTransform t = btTransform::getIdentity();
    for (float x : {-.6f, .6f}) {
        t.setOrigin(btVector3(x, 0, 0));
        cart->addChildShape(t, wheel);
    }
    cart->addChildShape(btTransform::getIdentity(), scene->ownShape(new btCapsuleShapeX(btScalar(.05), btScalar(1.2))));
    t.setOrigin(btVector3(0, btScalar(.3), 0));
    cart->addChildShape(t, scene->ownShape(new btConeShape(btScalar(.2), btScalar(.4))));
    scene->addBody(cart, 2, btVector3(0, btScalar(.31), 0));
    return scene;
}

ScenePtr dumbbellRolling(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "dumbbell_rolling");
    boxGround(*scene);
    btRigidBody* d = scene->addBody(dumbbellShape(*scene), 1, btVector3(0, btScalar(kDumbbellRadius), 0));
    d->setLinearVelocity(btVector3(0, 0, btScalar(kDumbbellSpeed)));
    // Rolling along +z about the x axis: omega x (-r y) = v z.
    d->setAngularVelocity(btVector3(btScalar(-kDumbbellSpeed / kDumbbellRadius), 0, 0));
    return scene;
}

ScenePtr compoundDrop(WorldKind kind, const Config& config, int count)
{
    auto scene = std::make_unique<Scene>(kind, config, "compounds");
    const spec::Scene data = spec::makeCompounds(count);
    std::vector<btCompoundShape*> shapes;
    for (const spec::CompoundSpec& c : data.compounds) shapes.push_back(compoundOf(*scene, c));
    for (const spec::BodySpec& b : data.bodies) {
        btCollisionShape* shape = b.shape == spec::ShapeKind::Compound
                                      ? static_cast<btCollisionShape*>(shapes[size_t(b.compound)])
                                      : scene->boxShape(btVector3(b.half[0], b.half[1], b.half[2]));
        scene->addBody(shape, b.mass, btVector3(b.pos[0], b.pos[1], b.pos[2]), Material{b.friction, b.restitution});
    }
    return scene;
}

}  // namespace btgpu::scenes
