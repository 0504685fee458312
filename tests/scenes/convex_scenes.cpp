// convex_scenes.cpp — the convex GJK scenes of convex_scenes.h, built the same way on stock
// Bullet and on btgpu.
#include "scenes/convex_scenes.h"

#include <BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btMultiSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleMesh.h>
#include <BulletCollision/CollisionShapes/btUniformScalingShape.h>

#include <cmath>
#include <memory>

namespace btgpu::scenes {

namespace {

btRigidBody* ground(Scene& scene)
{
    return scene.addBody(scene.boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
}

// The triangle mesh outlives the shape that reads it: kept with the scene's shapes.
struct OwnedMeshShape : btConvexTriangleMeshShape {
    std::unique_ptr<btTriangleMesh> mesh;
    explicit OwnedMeshShape(btTriangleMesh* m) : btConvexTriangleMeshShape(m), mesh(m) {}
};
struct OwnedScaling : btUniformScalingShape {
    std::unique_ptr<btConvexShape> child;
    OwnedScaling(btConvexShape* c, btScalar f) : btUniformScalingShape(c, f), child(c) {}
};

// An octahedron-like mesh with a flat square bottom (rests on a face).
btConvexTriangleMeshShape* meshShape(Scene& scene)
{
    auto* mesh = new btTriangleMesh();
    const btVector3 b[4] = {{-.4, -.3, -.4}, {.4, -.3, -.4}, {.4, -.3, .4}, {-.4, -.3, .4}};
    const btVector3 top(0, .5, 0);
    mesh->addTriangle(b[0], b[2], b[1]);
    mesh->addTriangle(b[0], b[3], b[2]);
    for (int i = 0; i < 4; ++i) mesh->addTriangle(b[i], b[(i + 1) % 4], top);
    return scene.ownShape(new OwnedMeshShape(mesh));
}

btCollisionShape* makeShape(Scene& scene, ConvexKind shape, int axis)
{
    switch (shape) {
        case ConvexKind::Capsule:
            if (axis == 0) return scene.ownShape(new btCapsuleShapeX(.3, 1.0));
            if (axis == 2) return scene.ownShape(new btCapsuleShapeZ(.3, 1.0));
            return scene.ownShape(new btCapsuleShape(.3, 1.0));
        case ConvexKind::Cylinder:
            if (axis == 0) return scene.ownShape(new btCylinderShapeX(btVector3(.6, .4, .4)));
            if (axis == 2) return scene.ownShape(new btCylinderShapeZ(btVector3(.4, .4, .6)));
            return scene.ownShape(new btCylinderShape(btVector3(.4, .6, .4)));
        case ConvexKind::Cone:
            if (axis == 0) return scene.ownShape(new btConeShapeX(.5, 1.0));
            if (axis == 2) return scene.ownShape(new btConeShapeZ(.5, 1.0));
            return scene.ownShape(new btConeShape(.5, 1.0));
        case ConvexKind::MultiSphere: {
            // four feet and a head: rests on the four feet, as a table
            const btVector3 pos[5] = {{-.3, 0, -.3}, {.3, 0, -.3}, {.3, 0, .3}, {-.3, 0, .3}, {0, .3, 0}};
            const btScalar radii[5] = {.2, .2, .2, .2, .3};
            return scene.ownShape(new btMultiSphereShape(pos, radii, 5));
        }
        case ConvexKind::ConvexMesh: return meshShape(scene);
        case ConvexKind::ScaledBox: {
            btBoxShape* box = scene.ownShape(new btBoxShape(btVector3(.5, .5, .5)));
            box->setLocalScaling(btVector3(1.5, .4, .8));
            return box;
        }
        case ConvexKind::ScaledHull: {
            const std::vector<btVector3> points = {{-.5, -.3, -.4}, {.5, -.3, -.4}, {.5, -.3, .4}, {-.5, -.3, .4},
                                                   {-.4, .3, -.3},  {.4, .3, -.3},  {.4, .3, .3},  {-.4, .3, .3}};
            btConvexHullShape* hull = scene.hullShape(points);
            hull->setLocalScaling(btVector3(1.3, .7, 1.1));
            return hull;
        }
        case ConvexKind::UniformCapsule:
            return scene.ownShape(new OwnedScaling(new btCapsuleShape(.2, .6), 1.5));
        case ConvexKind::ScaledCapsule:
        case ConvexKind::ScaledCylinder:
        case ConvexKind::ScaledCone:
        case ConvexKind::ScaledMultiSphere: {
            const ConvexKind base = shape == ConvexKind::ScaledCapsule    ? ConvexKind::Capsule
                                    : shape == ConvexKind::ScaledCylinder ? ConvexKind::Cylinder
                                    : shape == ConvexKind::ScaledCone     ? ConvexKind::Cone
                                                                          : ConvexKind::MultiSphere;
            btCollisionShape* s = makeShape(scene, base, axis);
            // 0.7 along the shape's axis, 1.3 across it: Bullet's cylinder takes its radius
            // from one radial axis only, so unequal radial scaling has no round meaning there
            btVector3 scaling(1.3, 1.3, 1.3);
            scaling[axis] = btScalar(.7);
            if (base == ConvexKind::MultiSphere) scaling = btVector3(1.5, .7, 1.2);
            s->setLocalScaling(scaling);
            return s;
        }
        case ConvexKind::ScaledSphere: {
            btSphereShape* s = scene.sphereShape(.4);
            s->setLocalScaling(btVector3(1.5, .7, 1.2));
            return s;
        }
    }
    return nullptr;
}

}  // namespace

ScenePtr convexLanding(WorldKind kind, ConvexKind shape, int axis, double tilt, double height, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "convex_landing");
    ground(*scene);
    btTransform t;
    t.setIdentity();
    t.setOrigin(btVector3(0, btScalar(height), 0));
    t.setRotation(btQuaternion(btVector3(0, 0, 1), btScalar(tilt)));
    scene->addBody(makeShape(*scene, shape, axis), 1, t);
    return scene;
}

ScenePtr cylinderRamp(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "cylinder_ramp");
    const btScalar angle = btScalar(15.0 * M_PI / 180.0);
    btTransform ramp;
    ramp.setIdentity();
    ramp.setRotation(btQuaternion(btVector3(0, 0, 1), -angle));  // downhill towards +x
    ramp.setOrigin(btVector3(0, -1, 0));
    scene->addBody(scene->boxShape(btVector3(20, 1, 5)), 0, ramp);
    // The cylinder's axis along z, resting on the ramp's top face just above it.
    const btVector3 up = ramp.getBasis() * btVector3(0, 1, 0);
    btTransform t;
    t.setIdentity();
    t.setOrigin(ramp.getOrigin() + up * btScalar(1.0 + 0.5 + 0.01) + ramp.getBasis() * btVector3(-8, 0, 0));
    scene->addBody(scene->ownShape(new btCylinderShapeZ(btVector3(.5, .5, .5))), 1, t);
    return scene;
}

ScenePtr convexPile(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "convex_pile");
    ground(*scene);
    const ConvexKind kinds[6] = {ConvexKind::Capsule, ConvexKind::Cylinder, ConvexKind::Cone,
                                 ConvexKind::MultiSphere, ConvexKind::ConvexMesh, ConvexKind::ScaledBox};
    for (int i = 0; i < 12; ++i) {
        btTransform t;
        t.setIdentity();
        t.setOrigin(btVector3(btScalar(0.3 * std::sin(i * 1.7)), btScalar(1.0 + 1.1 * i), btScalar(0.3 * std::cos(i * 2.3))));
        t.setRotation(btQuaternion(btVector3(1, 0, 1).normalized(), btScalar(0.4 * i)));
        btCollisionShape* shape = i % 4 == 3 ? static_cast<btCollisionShape*>(scene->sphereShape(.3))
                                             : makeShape(*scene, kinds[i % 6], i % 3);
        scene->addBody(shape, 1, t);
    }
    return scene;
}

}  // namespace btgpu::scenes
