// support_functions_test.cpp — every convex row's support functions and world AABB against the
// shape's own Bullet functions (localGetSupportingVertexWithoutMargin, getMargin, getAabb), for
// the shapes the GJK narrowphase meets by their support (capsules, cylinders, cones,
// multi-spheres, hulls without features, convex triangle meshes, uniformly scaled shapes, boxes).
#include "shape_tables.h"
#include "shared/aabb.h"
#include "shared/gjk.h"
#include "tolerances.h"

#include "../../compat/shape_tables.h"

#include <btBulletCollisionCommon.h>
#include <BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btMultiSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleMesh.h>
#include <BulletCollision/CollisionShapes/btUniformScalingShape.h>

#include <cmath>
#include <memory>
#include <gtest/gtest.h>

using namespace btgpu;

TEST(NarrowphaseGjk, SupportFunctionsAreBullets)
{
    // Every convex row's core support and margin against the shape's own (Bullet's
    // localGetSupportVertexWithoutMarginNonVirtual / getMarginNonVirtual, which its GJK calls),
    // the full support against localGetSupportVertexNonVirtual (its EPA) and the plane's against
    // localGetSupportingVertex (its convex–plane algorithm), over many directions; with local
    // scaling where Bullet allows it.
    std::vector<std::unique_ptr<btCollisionShape>> keep;
    std::vector<std::unique_ptr<btTriangleMesh>> meshes;
    auto own = [&](btConvexShape* s) {
        keep.emplace_back(s);
        return s;
    };
    std::vector<btConvexShape*> shapes = {
        own(new btCapsuleShape(.3, 1)), own(new btCapsuleShapeX(.2, .5)), own(new btCapsuleShapeZ(.25, .8)),
        own(new btCylinderShape(btVector3(.4, .6, .4))), own(new btCylinderShapeX(btVector3(.7, .3, .3))),
        own(new btCylinderShapeZ(btVector3(.2, .2, .9))), own(new btConeShape(.5, 1)), own(new btConeShapeX(.3, .8)),
        own(new btConeShapeZ(.4, .6)), own(new btBoxShape(btVector3(.5, .2, .3)))};
    {
        const btVector3 p[3] = {{-.4, 0, 0}, {.4, .1, 0}, {0, .3, .2}};
        const btScalar r[3] = {.3, .2, .25};
        shapes.push_back(own(new btMultiSphereShape(p, r, 3)));
        auto* mesh = new btTriangleMesh();
        meshes.emplace_back(mesh);
        mesh->addTriangle(btVector3(0, -.5, 0), btVector3(.4, .3, 0), btVector3(-.3, .3, .3));
        mesh->addTriangle(btVector3(0, -.5, 0), btVector3(-.3, .3, .3), btVector3(-.2, .3, -.4));
        shapes.push_back(own(new btConvexTriangleMeshShape(mesh)));
    }
    // scaled variants (Bullet folds the scaling into each shape's dimensions)
    const size_t plain = shapes.size();
    for (size_t i = 0; i < plain; ++i) {
        btConvexShape* s = shapes[i];
        btConvexShape* c = nullptr;
        switch (s->getShapeType()) {
            case CAPSULE_SHAPE_PROXYTYPE: c = own(new btCapsuleShape(.3, 1)); break;
            case CYLINDER_SHAPE_PROXYTYPE: c = own(new btCylinderShapeZ(btVector3(.2, .2, .9))); break;
            case CONE_SHAPE_PROXYTYPE: c = own(new btConeShapeX(.3, .8)); break;
            case MULTI_SPHERE_SHAPE_PROXYTYPE: {
                const btVector3 p[2] = {{-.4, 0, 0}, {.4, .1, 0}};
                const btScalar r[2] = {.3, .2};
                c = own(new btMultiSphereShape(p, r, 2));
                break;
            }
            default: break;
        }
        if (c) {
            c->setLocalScaling(btVector3(1.5, 0.7, 1.2));
            shapes.push_back(c);
        }
    }
    shapes.push_back(own(new btUniformScalingShape(shapes[0], 1.7)));
    shapes.push_back(own(new btUniformScalingShape(shapes[9], 0.6)));
    shapes.push_back(own(new btUniformScalingShape(own(new btSphereShape(.4)), 1.3)));
    shapes.push_back(own(new btUniformScalingShape(shapes[6], 2.0)));

    ShapeTables tables;
    for (btConvexShape* shape : shapes) {
        SCOPED_TRACE(shape->getName());
        std::string why;
        const int row = tables.add(shape, &why);
        ASSERT_GE(row, 0) << why;
        const BtgShape s = tables.shapes[size_t(row)];
        EXPECT_NEAR(btgCoreMargin(s), shape->getMarginNonVirtual(), 1e-6f);
        for (int k = 0; k < 200; ++k) {
            // directions spread over the sphere, the axes and their diagonals among them
            const float u = float(k) / 200.0f, theta = 6.2831853f * 37.0f * u, z = 1.0f - 2.0f * u;
            btVector3 d(std::sqrt(1 - z * z) * std::cos(theta), z, std::sqrt(1 - z * z) * std::sin(theta));
            if (k < 6) d = btVector3(k == 0 ? 1.f : k == 1 ? -1.f : 0.f, k == 2 ? 1.f : k == 3 ? -1.f : 0.f, k == 4 ? 1.f : k == 5 ? -1.f : 0.f);
            const btVector3 core = shape->localGetSupportVertexWithoutMarginNonVirtual(d);
            const btVector3 full = shape->localGetSupportVertexNonVirtual(d);
            const btVector3 plane = shape->localGetSupportingVertex(d);
            const BtgFloat4 dd = btgMake4(d.x(), d.y(), d.z(), 0);
            const BtgFloat4 c = btgSupportCore(s, tables.vertices.data(), dd);
            const BtgFloat4 f = btgSupportFull(s, tables.vertices.data(), dd);
            const BtgFloat4 p = btgSupportForPlane(s, tables.vertices.data(), dd);
            // equal support value along d (ties may pick another point of the same face)
            EXPECT_NEAR(btgDot3(c, dd), core.dot(d), 1e-5f) << "direction " << k;
            EXPECT_NEAR(btgDot3(f, dd), full.dot(d), 1e-5f) << "direction " << k;
            EXPECT_NEAR(btgDot3(p, dd), plane.dot(d), 1e-5f) << "direction " << k;
        }
    }
}

TEST(NarrowphaseGjk, AabbsAreBullets)
{
    // btgBodyAabb of every convex row against the shape's own getAabb in turned poses: equal
    // (within 0.1 mm) for all, but a uniformly scaled point set, whose box may only be larger.
    std::vector<std::unique_ptr<btCollisionShape>> keep;
    std::vector<std::unique_ptr<btTriangleMesh>> meshes;
    auto own = [&](btConvexShape* s) {
        keep.emplace_back(s);
        return s;
    };
    btConvexShape* hull = own(new btConvexHullShape());
    for (const btVector3& p : {btVector3(-.5, -.3, -.4), btVector3(.5, -.3, -.4), btVector3(0, .5, 0), btVector3(.1, 0, .6)})
        static_cast<btConvexHullShape*>(hull)->addPoint(p);
    const btVector3 mp[2] = {{-.4, 0, 0}, {.4, .1, 0}};
    const btScalar mr[2] = {.3, .2};
    std::vector<std::pair<btConvexShape*, bool>> shapes = {
        {own(new btCapsuleShape(.3, 1)), true},          {own(new btCapsuleShapeX(.2, .5)), true},
        {own(new btCylinderShapeZ(btVector3(.2, .2, .9))), true}, {own(new btConeShape(.5, 1)), true},
        {own(new btConeShapeX(.3, .8)), true},           {own(new btConeShapeZ(.4, .6)), true},
        {own(new btMultiSphereShape(mp, mr, 2)), true},
    };
    shapes.push_back({own(new btUniformScalingShape(shapes[0].first, 1.7)), true});
    shapes.push_back({own(new btUniformScalingShape(shapes[3].first, 0.8)), true});
    shapes.push_back({own(new btUniformScalingShape(own(new btBoxShape(btVector3(.3, .2, .5))), 1.4)), true});
    shapes.push_back({own(new btUniformScalingShape(own(new btSphereShape(.4)), 1.3)), true});
    shapes.push_back({own(new btUniformScalingShape(hull, 1.2)), false});
    ShapeTables tables;
    for (auto [shape, exact] : shapes) {
        SCOPED_TRACE(shape->getName());
        std::string why;
        const int row = tables.add(shape, &why);
        ASSERT_GE(row, 0) << why;
        for (int k = 0; k < 12; ++k) {
            btTransform t;
            t.setIdentity();
            t.setOrigin(btVector3(btScalar(k), btScalar(0.5 * k), btScalar(-k)));
            t.setRotation(btQuaternion(btVector3(btScalar(1 + k), btScalar(2 - k), btScalar(0.5 * k)).normalized(),
                                       btScalar(0.37 * k)));
            btVector3 mn, mx;
            shape->getAabb(t, mn, mx);
            const btQuaternion q = t.getRotation();
            BtgAabb a = btgBodyAabb(btgMake4(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z(), 0),
                                    btgMake4(q.x(), q.y(), q.z(), q.w()), tables.shapes[size_t(row)], 0u, 0.0f);
            const float lo[3] = {a.lo.x, a.lo.y, a.lo.z}, hi[3] = {a.hi.x, a.hi.y, a.hi.z};
            for (int i = 0; i < 3; ++i) {
                EXPECT_LE(lo[i], mn[i] + 1e-4f) << "pose " << k << " axis " << i;
                EXPECT_GE(hi[i], mx[i] - 1e-4f) << "pose " << k << " axis " << i;
                if (exact) {
                    EXPECT_NEAR(lo[i], mn[i], 1e-4f) << "pose " << k << " axis " << i;
                    EXPECT_NEAR(hi[i], mx[i], 1e-4f) << "pose " << k << " axis " << i;
                }
            }
        }
    }
}
