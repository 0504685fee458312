// shape_checks.cpp — shape parameter checks and fingerprints for the shape kinds the GPU path
// takes (box, sphere, static plane, convex hull, convex point cloud, capsule, cylinder, cone,
// multi-sphere, convex triangle mesh, uniform scaling, BVH triangle meshes, heightfields). Other kinds never reach
// the tables (the world runs on the CPU path), so they check as "" and hash by type.
#include "shape_checks.h"

#include "mesh_tables.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/BroadphaseCollision/btDbvt.h>
#include <BulletCollision/CollisionShapes/btConvexPointCloudShape.h>
#include <BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btMultiSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <BulletCollision/CollisionShapes/btUniformScalingShape.h>

#include <cmath>
#include <cstring>
#include <functional>

namespace btgpu {

namespace {

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
bool sized(const btVector3& v)
{
    return std::fabs(v.x()) <= kMaxShapeSize && std::fabs(v.y()) <= kMaxShapeSize && std::fabs(v.z()) <= kMaxShapeSize;
}

}  // namespace

const btVector3* hullPoints(const btCollisionShape* shape, int* count)
{
    switch (shape->getShapeType()) {
        case CONVEX_HULL_SHAPE_PROXYTYPE: {
            auto* hull = static_cast<const btConvexHullShape*>(shape);
            *count = hull->getNumPoints();
            // Bullet's getUnscaledPoints takes &array[0]: undefined on an empty hull.
            return *count > 0 ? hull->getUnscaledPoints() : nullptr;
        }
        case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE: {
            auto* cloud = static_cast<const btConvexPointCloudShape*>(shape);
            *count = cloud->getNumPoints();
            return *count > 0 ? cloud->getUnscaledPoints() : nullptr;
        }
        default:
            *count = 0;
            return nullptr;
    }
}

namespace {

std::string checkScalingAndMargin(const btCollisionShape* shape)
{
    const btVector3& s = shape->getLocalScaling();
    if (!finite(s) || !sized(s)) return "non-finite or huge local scaling";
    float m = shape->getMargin();
    if (!std::isfinite(m) || m < 0.0f || m > kMaxShapeSize) return "negative or non-finite collision margin";
    return "";
}

bool usable(float x) { return std::isfinite(x) && x >= 0.0f && x <= kMaxShapeSize; }

// A mesh's triangles' vertices, as Bullet's support function visits them (scaled).
struct MeshVisitor : btInternalTriangleIndexCallback {
    std::function<void(const btVector3&)> visit;
    void internalProcessTriangleIndex(btVector3* triangle, int, int) override
    {
        for (int i = 0; i < 3; ++i) visit(triangle[i]);
    }
};
void forEachMeshVertex(const btConvexTriangleMeshShape* mesh, const std::function<void(const btVector3&)>& visit)
{
    MeshVisitor v;
    v.visit = visit;
    const btVector3 big(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
    mesh->getMeshInterface()->InternalProcessAllTriangles(&v, -big, big);
}

}  // namespace

std::string badShapeInput(const btCollisionShape* shape)
{
    switch (shape->getShapeType()) {
        case CAPSULE_SHAPE_PROXYTYPE: {
            auto* c = static_cast<const btCapsuleShape*>(shape);
            if (!usable(c->getRadius())) return "negative, non-finite or huge capsule radius";
            if (!usable(c->getHalfHeight())) return "negative, non-finite or huge capsule height";
            return checkScalingAndMargin(shape);
        }
        case CYLINDER_SHAPE_PROXYTYPE: {
            std::string why = checkScalingAndMargin(shape);
            if (!why.empty()) return why;
            const btVector3 h = static_cast<const btCylinderShape*>(shape)->getHalfExtentsWithMargin();
            if (!usable(h.x()) || !usable(h.y()) || !usable(h.z())) return "negative, non-finite or huge cylinder half extents";
            const btVector3 c = static_cast<const btCylinderShape*>(shape)->getHalfExtentsWithoutMargin();
            if (c.x() < 0.0f || c.y() < 0.0f || c.z() < 0.0f) return "cylinder margin larger than its half extents";
            return "";
        }
        case CONE_SHAPE_PROXYTYPE: {
            auto* c = static_cast<const btConeShape*>(shape);
            if (!usable(c->getRadius())) return "negative, non-finite or huge cone radius";
            if (!usable(c->getHeight())) return "negative, non-finite or huge cone height";
            if (c->getRadius() == 0.0f && c->getHeight() == 0.0f) return "cone of zero radius and height";
            return checkScalingAndMargin(shape);
        }
        case MULTI_SPHERE_SHAPE_PROXYTYPE: {
            std::string why = checkScalingAndMargin(shape);
            if (!why.empty()) return why;
            auto* m = static_cast<const btMultiSphereShape*>(shape);
            if (m->getSphereCount() <= 0) return "multi-sphere without spheres";
            for (int i = 0; i < m->getSphereCount(); ++i) {
                const btVector3 p = m->getSpherePosition(i) * m->getLocalScaling();
                if (!finite(p) || !sized(p)) return "non-finite or huge multi-sphere position " + std::to_string(i);
                if (!usable(m->getSphereRadius(i))) return "negative, non-finite or huge multi-sphere radius " + std::to_string(i);
            }
            return "";
        }
        case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE: {
            std::string why = checkScalingAndMargin(shape);
            if (!why.empty()) return why;
            bool bad = false;
            forEachMeshVertex(static_cast<const btConvexTriangleMeshShape*>(shape),
                              [&](const btVector3& p) { bad = bad || !finite(p) || !sized(p); });
            return bad ? "non-finite or huge convex triangle mesh vertex" : "";
        }
        case UNIFORM_SCALING_SHAPE_PROXYTYPE: {
            auto* u = static_cast<const btUniformScalingShape*>(shape);
            const float f = u->getUniformScalingFactor();
            if (!std::isfinite(f) || f <= 0.0f || f > kMaxShapeSize) return "non-positive, non-finite or huge uniform scaling factor";
            std::string why = badShapeInput(u->getChildShape());
            return why.empty() ? "" : "uniform scaling child: " + why;
        }
        case BOX_SHAPE_PROXYTYPE: {
            std::string why = checkScalingAndMargin(shape);
            if (!why.empty()) return why;
            btVector3 h = static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin();
            if (!finite(h) || !sized(h)) return "non-finite or huge box half extents";
            if (h.x() < 0.0f || h.y() < 0.0f || h.z() < 0.0f) return "negative box half extents";
            return "";
        }
        case SPHERE_SHAPE_PROXYTYPE: {
            float r = static_cast<const btSphereShape*>(shape)->getRadius();
            if (!std::isfinite(r) || r < 0.0f || r > kMaxShapeSize) return "negative, non-finite or huge sphere radius";
            return checkScalingAndMargin(shape);
        }
        case STATIC_PLANE_PROXYTYPE: {
            auto* plane = static_cast<const btStaticPlaneShape*>(shape);
            const btVector3& n = plane->getPlaneNormal();
            if (!finite(n) || n.length2() < 1e-12f) return "zero or non-finite plane normal";
            if (!std::isfinite(plane->getPlaneConstant()) || std::fabs(plane->getPlaneConstant()) > kMaxShapeSize)
                return "non-finite or huge plane constant";
            if (!finite(plane->getLocalScaling())) return "non-finite local scaling";
            return "";
        }
        case CONVEX_HULL_SHAPE_PROXYTYPE:
        case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE: {
            std::string why = checkScalingAndMargin(shape);
            if (!why.empty()) return why;
            int n = 0;
            const btVector3* points = hullPoints(shape, &n);
            if (n <= 0 || !points) return "convex hull without points";
            const btVector3& s = shape->getLocalScaling();
            for (int i = 0; i < n; ++i) {
                btVector3 p = points[i] * s;
                if (!finite(p) || !sized(p)) return "non-finite or huge convex hull point " + std::to_string(i);
            }
            return "";
        }
        case TERRAIN_SHAPE_PROXYTYPE: {
            const btHeightfieldTerrainShape* h = heightfieldOf(shape);
            if (!h) return "";
            std::string why = checkScalingAndMargin(shape);
            return why.empty() ? badHeightfieldInput(h) : why;
        }
        case TRIANGLE_MESH_SHAPE_PROXYTYPE:
        case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE: {
            const btBvhTriangleMeshShape* mesh = bvhMeshOf(shape);
            if (!mesh) return "";  // not a mesh the GPU path takes: refused with its reason
            std::string why = checkScalingAndMargin(shape);
            if (!why.empty()) return why;
            const btVector3& s = shape->getLocalScaling();
            if (s.x() == 0.0f || s.y() == 0.0f || s.z() == 0.0f) return "zero local scaling of a triangle mesh";
            return badMeshInput(mesh);
        }
        default:
            return "";
    }
}

std::uint64_t shapeFingerprint(const btCollisionShape* shape)
{
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&](const void* p, size_t n) {
        const unsigned char* c = static_cast<const unsigned char*>(p);
        for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
    };
    auto mixVec = [&](const btVector3& v) {
        float f[3] = {v.x(), v.y(), v.z()};
        mix(f, sizeof(f));
    };
    int type = shape->getShapeType();
    mix(&type, sizeof(type));
    switch (type) {
        case BOX_SHAPE_PROXYTYPE: {
            mixVec(static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin());
            const int featured = static_cast<const btBoxShape*>(shape)->getConvexPolyhedron() != nullptr;
            mix(&featured, sizeof(featured));
            break;
        }
        case SPHERE_SHAPE_PROXYTYPE: {
            float r = static_cast<const btSphereShape*>(shape)->getRadius();
            mix(&r, sizeof(r));
            break;
        }
        case STATIC_PLANE_PROXYTYPE: {
            auto* plane = static_cast<const btStaticPlaneShape*>(shape);
            mixVec(plane->getPlaneNormal());
            float c = plane->getPlaneConstant();
            mix(&c, sizeof(c));
            break;
        }
        case CONVEX_HULL_SHAPE_PROXYTYPE:
        case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE: {
            int n = 0;
            const btVector3* points = hullPoints(shape, &n);
            mix(&n, sizeof(n));
            for (int i = 0; i < n; ++i) mixVec(points[i]);
            // features given later (initializePolyhedralFeatures) change how stock collides it
            const int featured = static_cast<const btPolyhedralConvexShape*>(shape)->getConvexPolyhedron() != nullptr;
            mix(&featured, sizeof(featured));
            break;
        }
        case CAPSULE_SHAPE_PROXYTYPE: {
            auto* c = static_cast<const btCapsuleShape*>(shape);
            float v[2] = {c->getRadius(), c->getHalfHeight()};
            int up = c->getUpAxis();
            mix(v, sizeof(v));
            mix(&up, sizeof(up));
            break;
        }
        case CYLINDER_SHAPE_PROXYTYPE: {
            auto* c = static_cast<const btCylinderShape*>(shape);
            mixVec(c->getHalfExtentsWithoutMargin());
            int up = c->getUpAxis();
            mix(&up, sizeof(up));
            break;
        }
        case CONE_SHAPE_PROXYTYPE: {
            auto* c = static_cast<const btConeShape*>(shape);
            float v[2] = {c->getRadius(), c->getHeight()};
            int up = c->getConeUpIndex();
            mix(v, sizeof(v));
            mix(&up, sizeof(up));
            break;
        }
        case MULTI_SPHERE_SHAPE_PROXYTYPE: {
            auto* m = static_cast<const btMultiSphereShape*>(shape);
            int n = m->getSphereCount();
            mix(&n, sizeof(n));
            for (int i = 0; i < n; ++i) {
                mixVec(m->getSpherePosition(i));
                float r = m->getSphereRadius(i);
                mix(&r, sizeof(r));
            }
            break;
        }
        case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE: {
            auto* m = static_cast<const btConvexTriangleMeshShape*>(shape);
            int features = m->getConvexPolyhedron() != nullptr;
            mix(&features, sizeof(features));
            forEachMeshVertex(m, mixVec);
            break;
        }
        case COMPOUND_SHAPE_PROXYTYPE: {
            // Its children (each one's own print, its transform and its tree leaf), the local
            // AABB stock pairs it by, and the revision add/removeChildShape bump: any change
            // between steps makes a new row, read again.
            auto* c = static_cast<const btCompoundShape*>(shape);
            int n = c->getNumChildShapes(), revision = c->getUpdateRevision();
            int tree = c->getDynamicAabbTree() != nullptr;
            mix(&n, sizeof(n));
            mix(&revision, sizeof(revision));
            mix(&tree, sizeof(tree));
            btVector3 lo, hi;
            c->getAabb(btTransform::getIdentity(), lo, hi);
            mixVec(lo);
            mixVec(hi);
            for (int i = 0; i < n; ++i) {
                const btCollisionShape* child = c->getChildShape(i);
                mix(&child, sizeof(child));
                std::uint64_t print = shapeFingerprint(child);
                mix(&print, sizeof(print));
                const btTransform& t = c->getChildTransform(i);
                mixVec(t.getOrigin());
                for (int r = 0; r < 3; ++r) mixVec(t.getBasis()[r]);
                const btDbvtNode* node = const_cast<btCompoundShape*>(c)->getChildList()[i].m_node;
                if (node) {
                    mixVec(node->volume.Mins());
                    mixVec(node->volume.Maxs());
                }
            }
            break;
        }
        case UNIFORM_SCALING_SHAPE_PROXYTYPE: {
            auto* u = static_cast<const btUniformScalingShape*>(shape);
            float f = u->getUniformScalingFactor();
            mix(&f, sizeof(f));
            std::uint64_t child = shapeFingerprint(u->getChildShape());
            mix(&child, sizeof(child));
            break;
        }
        case TRIANGLE_MESH_SHAPE_PROXYTYPE:
        case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE: {
            // Every vertex, index and BVH node: the app may edit its vertices and refit the tree.
            const btBvhTriangleMeshShape* mesh = bvhMeshOf(shape);
            std::uint64_t m = mesh ? meshFingerprint(mesh) : 0;
            mix(&m, sizeof(m));
            break;
        }
        case TERRAIN_SHAPE_PROXYTYPE: {
            // Every height of the app's array, and the grid's parameters.
            const btHeightfieldTerrainShape* h = heightfieldOf(shape);
            std::uint64_t m = h ? heightfieldFingerprint(h) : 0;
            mix(&m, sizeof(m));
            break;
        }
        default:
            return h;
    }
    mixVec(shape->getLocalScaling());
    float m = shape->getMargin();
    mix(&m, sizeof(m));
    return h;
}

}  // namespace btgpu
