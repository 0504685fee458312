// convex_rows.cpp — btCapsuleShape, btCylinderShape, btConeShape (each axis), btMultiSphereShape,
// btConvexTriangleMeshShape and btUniformScalingShape as support-function rows. Bullet folds
// local scaling into each shape's own dimensions (capsule radius and half height, cylinder half
// extents, cone radius and height, a mesh's scaled vertices), so the rows hold those; a
// multi-sphere keeps its scaling, which its support function applies per component.
#include "convex_rows.h"

#include "shape_checks.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btMultiSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <BulletCollision/CollisionShapes/btUniformScalingShape.h>

#include <algorithm>
#include <array>

namespace btgpu {

namespace {

BtgFloat4 f4(const btVector3& v, float w = 0.0f) { return btgMake4(v.x(), v.y(), v.z(), w); }

// Every vertex of a mesh's triangles, as Bullet's support callback visits them (scaled by the
// mesh interface), each once.
struct VertexCollector : btInternalTriangleIndexCallback {
    std::vector<std::array<float, 3>> points;
    void internalProcessTriangleIndex(btVector3* triangle, int, int) override
    {
        for (int i = 0; i < 3; ++i) points.push_back({triangle[i].x(), triangle[i].y(), triangle[i].z()});
    }
};

void appendPoints(std::vector<std::array<float, 3>> points, float factor, BtgShape& s, std::vector<BtgFloat4>& vertices)
{
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    s.firstVertex = int(vertices.size());
    s.numVertices = int(points.size());
    for (const auto& p : points) vertices.push_back(btgMake4(p[0] * factor, p[1] * factor, p[2] * factor, 0.0f));
}

// A btUniformScalingShape's row: its child's, every length times the factor (Bullet's support
// of the child times the factor, margin times the factor).
bool uniformScalingRow(const btUniformScalingShape* u, float f, BtgShape& s, std::vector<BtgFloat4>& vertices,
                       std::string* whyNot)
{
    const btConvexShape* child = u->getChildShape();
    const float g = f * u->getUniformScalingFactor();
    switch (child->getShapeType()) {
        case BOX_SHAPE_PROXYTYPE: {
            auto* box = static_cast<const btBoxShape*>(child);
            s.convexType = BTG_CONVEX_BOX;
            s.param = f4(box->getHalfExtentsWithMargin() * g, box->getMargin() * g);
            s.margin = box->getMargin() * g;
            return true;
        }
        case SPHERE_SHAPE_PROXYTYPE:
            s.convexType = BTG_CONVEX_SPHERE;
            s.margin = static_cast<const btSphereShape*>(child)->getRadius() * g;
            s.param = btgMake4(s.margin, 0.0f, 0.0f, 0.0f);
            return true;
        case CONVEX_HULL_SHAPE_PROXYTYPE:
        case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE: {
            int n = 0;
            const btVector3* points = hullPoints(child, &n);
            if (n <= 0 || !points) {
                *whyNot = "uniform scaling of a convex hull without points";
                return false;
            }
            std::vector<std::array<float, 3>> scaled;
            const btVector3& sc = child->getLocalScaling();
            for (int i = 0; i < n; ++i) {
                btVector3 p = points[i] * sc;
                scaled.push_back({p.x(), p.y(), p.z()});
            }
            s.convexType = BTG_CONVEX_POINTS;
            s.margin = child->getMargin() * g;
            appendPoints(std::move(scaled), g, s, vertices);
            return true;
        }
        default:
            // the child's row scaled; a scaled capsule is no btCapsuleShape to Bullet (the flags
            // are set by the caller)
            if (isSupportShapeType(child->getShapeType())) return convexRow(child, g, s, vertices, whyNot);
            *whyNot = std::string("uniform scaling of unsupported shape '") + child->getName() + "'";
            return false;
    }
}

}  // namespace

bool isSupportShapeType(int type)
{
    return type == CAPSULE_SHAPE_PROXYTYPE || type == CYLINDER_SHAPE_PROXYTYPE || type == CONE_SHAPE_PROXYTYPE ||
           type == MULTI_SPHERE_SHAPE_PROXYTYPE || type == CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE ||
           type == UNIFORM_SCALING_SHAPE_PROXYTYPE;
}

bool isFeaturelessHull(const btCollisionShape* shape)
{
    const int type = shape->getShapeType();
    return (type == CONVEX_HULL_SHAPE_PROXYTYPE || type == CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE) &&
           !static_cast<const btPolyhedralConvexShape*>(shape)->getConvexPolyhedron();
}

bool convexRow(const btCollisionShape* shape, float factor, BtgShape& s, std::vector<BtgFloat4>& vertices,
               std::string* whyNot)
{
    s.type = BTG_SHAPE_CONVEX;
    s.convexFlags = 0u;
    s.upAxis = 1;
    const float f = factor;
    switch (shape->getShapeType()) {
        case CAPSULE_SHAPE_PROXYTYPE: {
            auto* c = static_cast<const btCapsuleShape*>(shape);
            s.convexType = BTG_CONVEX_CAPSULE;
            s.convexFlags = BTG_CONVEX_FLAG_CAPSULE;  // Bullet's closed form takes btCapsuleShape pairs only
            s.upAxis = c->getUpAxis();
            s.param = btgMake4(c->getRadius() * f, c->getHalfHeight() * f, 0.0f, 0.0f);
            s.margin = c->getMargin() * f;  // the radius (Bullet keeps them equal)
            return true;
        }
        case CYLINDER_SHAPE_PROXYTYPE: {
            auto* c = static_cast<const btCylinderShape*>(shape);
            s.convexType = BTG_CONVEX_CYLINDER;
            s.upAxis = c->getUpAxis();
            s.param = f4(c->getHalfExtentsWithoutMargin() * f);
            s.margin = c->getMargin() * f;
            return true;
        }
        case CONE_SHAPE_PROXYTYPE: {
            auto* c = static_cast<const btConeShape*>(shape);
            s.convexType = BTG_CONVEX_CONE;
            s.upAxis = c->getConeUpIndex();
            const float r = c->getRadius(), h = c->getHeight();
            // btConeShape's m_sinAngle, as its constructor and setLocalScaling compute it
            s.param = btgMake4(r * f, h * f, r / std::sqrt(r * r + h * h), 0.0f);
            s.margin = c->getMargin() * f;
            s.convexFlags = BTG_CONVEX_FLAG_AABB_SLOW;  // btConeShape keeps getAabbSlow
            return true;
        }
        case MULTI_SPHERE_SHAPE_PROXYTYPE: {
            auto* m = static_cast<const btMultiSphereShape*>(shape);
            s.convexType = BTG_CONVEX_SPHERES;
            s.param = f4(m->getLocalScaling() * f);
            s.margin = m->getMargin() * f;
            s.firstVertex = int(vertices.size());
            s.numVertices = m->getSphereCount();
            for (int i = 0; i < m->getSphereCount(); ++i) vertices.push_back(f4(m->getSpherePosition(i), m->getSphereRadius(i)));
            return true;
        }
        case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE: {
            auto* m = static_cast<const btConvexTriangleMeshShape*>(shape);
            if (m->getConvexPolyhedron()) {
                // Bullet then clips it against hulls that have features too, and runs GJK else.
                *whyNot = "convex triangle mesh with polyhedral features (initializePolyhedralFeatures)";
                return false;
            }
            VertexCollector collect;
            const btVector3 big(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
            m->getMeshInterface()->InternalProcessAllTriangles(&collect, -big, big);
            if (collect.points.empty()) {
                *whyNot = "convex triangle mesh without triangles";
                return false;
            }
            s.convexType = BTG_CONVEX_POINTS;
            s.margin = m->getMargin() * f;
            appendPoints(std::move(collect.points), f, s, vertices);
            return true;
        }
        case CONVEX_HULL_SHAPE_PROXYTYPE:
        case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE: {
            // A hull without polyhedral features: stock collides it by GJK on its scaled points
            // (btConvexHullShape::localGetSupportingVertex), so it is a support-function row.
            int n = 0;
            const btVector3* points = hullPoints(shape, &n);
            if (n <= 0 || !points) {
                *whyNot = "convex hull without points";
                return false;
            }
            std::vector<std::array<float, 3>> scaled;
            const btVector3& sc = shape->getLocalScaling();
            for (int i = 0; i < n; ++i) {
                btVector3 p = points[i] * sc;
                scaled.push_back({p.x(), p.y(), p.z()});
            }
            s.convexType = BTG_CONVEX_POINTS;
            s.margin = shape->getMargin() * f;
            appendPoints(std::move(scaled), f, s, vertices);
            return true;
        }
        case UNIFORM_SCALING_SHAPE_PROXYTYPE: {
            if (!uniformScalingRow(static_cast<const btUniformScalingShape*>(shape), f, s, vertices, whyNot)) return false;
            // btUniformScalingShape::getAabbSlow: the core's support along the world axes plus the
            // margin (rows with vertex tables keep the rotated local box: a superset)
            const bool table = s.convexType == BTG_CONVEX_POINTS || s.convexType == BTG_CONVEX_SPHERES;
            s.convexFlags = table ? 0u : BTG_CONVEX_FLAG_AABB_SUPPORT;
            return true;
        }
        default:
            *whyNot = std::string("unsupported shape '") + shape->getName() + "'";
            return false;
    }
}

}  // namespace btgpu
