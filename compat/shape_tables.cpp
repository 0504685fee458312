// shape_tables.cpp — conversion of btBoxShape, btConvexHullShape (and other polyhedral
// convex shapes), btSphereShape and btStaticPlaneShape.
#include "shape_tables.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>

#include <algorithm>
#include <cmath>

namespace btgpu {

namespace {

BtgFloat4 f4(const btVector3& v, float w = 0.0f) { return btgMake4(v.x(), v.y(), v.z(), w); }

void setLocalAabb(BtgShape& s, const btCollisionShape* shape)
{
    btVector3 mn, mx;
    btTransform id;
    id.setIdentity();
    shape->getAabb(id, mn, mx);
    s.localAabbMin = f4(mn);
    s.localAabbMax = f4(mx);
}

// The hull's faces, vertices and unique edges, appended to the tables.
bool appendPolyhedron(ShapeTables& t, BtgShape& s, const btConvexPolyhedron& poly, std::string* whyNot)
{
    if (poly.m_vertices.size() < 4 || poly.m_faces.size() < 4) {
        *whyNot = "degenerate convex hull (" + std::to_string(poly.m_vertices.size()) + " vertices, " +
                  std::to_string(poly.m_faces.size()) + " faces)";
        return false;
    }
    s.firstVertex = int(t.vertices.size());
    s.numVertices = poly.m_vertices.size();
    for (int i = 0; i < poly.m_vertices.size(); ++i) t.vertices.push_back(f4(poly.m_vertices[i]));
    s.firstFace = int(t.faces.size());
    s.numFaces = poly.m_faces.size();
    for (int i = 0; i < poly.m_faces.size(); ++i) {
        const btFace& f = poly.m_faces[i];
        if (f.m_indices.size() < 3) {
            *whyNot = "convex hull face with fewer than 3 vertices";
            return false;
        }
        BtgFace face{};
        face.plane = btgMake4(f.m_plane[0], f.m_plane[1], f.m_plane[2], f.m_plane[3]);
        face.firstIndex = int(t.indices.size());
        face.numIndices = f.m_indices.size();
        for (int k = 0; k < f.m_indices.size(); ++k) t.indices.push_back(f.m_indices[k]);
        t.faces.push_back(face);
    }
    s.firstEdge = int(t.edges.size());
    s.numEdges = poly.m_uniqueEdges.size();
    for (int i = 0; i < poly.m_uniqueEdges.size(); ++i) t.edges.push_back(f4(poly.m_uniqueEdges[i].normalized()));
    return true;
}

void appendBox(ShapeTables& t, BtgShape& s, const btVector3& h)
{
    s.firstVertex = int(t.vertices.size());
    s.numVertices = 8;
    for (int i = 0; i < 8; ++i)
        t.vertices.push_back(btgMake4((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z(), 0.0f));
    // Faces as vertex loops counter-clockwise seen from outside (bit i of a vertex number is
    // the sign of axis i).
    static const int loops[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
    static const float normals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const float ext[3] = {h.x(), h.y(), h.z()};
    s.firstFace = int(t.faces.size());
    s.numFaces = 6;
    for (int f = 0; f < 6; ++f) {
        BtgFace face{};
        int axis = f / 2;
        face.plane = btgMake4(normals[f][0], normals[f][1], normals[f][2], -ext[axis]);
        face.firstIndex = int(t.indices.size());
        face.numIndices = 4;
        for (int k = 0; k < 4; ++k) t.indices.push_back(loops[f][k]);
        t.faces.push_back(face);
    }
    s.firstEdge = int(t.edges.size());
    s.numEdges = 3;
    t.edges.push_back(btgMake4(1, 0, 0, 0));
    t.edges.push_back(btgMake4(0, 1, 0, 0));
    t.edges.push_back(btgMake4(0, 0, 1, 0));
}

}  // namespace

int ShapeTables::add(const btCollisionShape* shape, std::string* whyNot)
{
    auto it = rowOf.find(shape);
    if (it != rowOf.end()) return it->second;
    BtgShape s{};
    s.firstVertex = s.firstFace = s.firstEdge = 0;
    switch (shape->getShapeType()) {
        case BOX_SHAPE_PROXYTYPE: {
            auto* box = static_cast<const btBoxShape*>(shape);
            s.type = BTG_SHAPE_HULL;
            s.margin = 0.0f;  // Bullet keeps a box's margin inside its extents
            appendBox(*this, s, box->getHalfExtentsWithMargin());
            s.param = f4(box->getHalfExtentsWithMargin());
            setLocalAabb(s, shape);
            break;
        }
        case SPHERE_SHAPE_PROXYTYPE: {
            auto* sphere = static_cast<const btSphereShape*>(shape);
            s.type = BTG_SHAPE_SPHERE;
            s.param = btgMake4(sphere->getRadius(), 0, 0, 0);
            s.margin = 0.0f;
            setLocalAabb(s, shape);
            break;
        }
        case STATIC_PLANE_PROXYTYPE: {
            auto* plane = static_cast<const btStaticPlaneShape*>(shape);
            s.type = BTG_SHAPE_PLANE;
            s.param = f4(plane->getPlaneNormal().normalized(), plane->getPlaneConstant());
            s.localAabbMin = btgMake4(-1e30f, -1e30f, -1e30f, 0);
            s.localAabbMax = btgMake4(1e30f, 1e30f, 1e30f, 0);
            break;
        }
        case CONVEX_HULL_SHAPE_PROXYTYPE:
        case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE: {
            // Bullet's own face extraction (btConvexHullComputer); it stores the result on the
            // shape, as Bullet itself does when SAT collision is enabled.
            auto* hull = const_cast<btPolyhedralConvexShape*>(static_cast<const btPolyhedralConvexShape*>(shape));
            if (!hull->getConvexPolyhedron()) hull->initializePolyhedralFeatures();
            if (!hull->getConvexPolyhedron()) {
                *whyNot = "convex hull without polyhedral features";
                return -1;
            }
            s.type = BTG_SHAPE_HULL;
            s.margin = hull->getMargin();
            if (!appendPolyhedron(*this, s, *hull->getConvexPolyhedron(), whyNot)) return -1;
            setLocalAabb(s, shape);
            break;
        }
        default:
            *whyNot = std::string("unsupported shape '") + shape->getName() + "'";
            return -1;
    }
    int row = int(shapes.size());
    shapes.push_back(s);
    rowOf.emplace(shape, row);
    return row;
}

float boundingRadius(const BtgShape& s)
{
    if (s.type == BTG_SHAPE_PLANE) return 0.0f;
    float x = std::max(std::fabs(s.localAabbMin.x), std::fabs(s.localAabbMax.x));
    float y = std::max(std::fabs(s.localAabbMin.y), std::fabs(s.localAabbMax.y));
    float z = std::max(std::fabs(s.localAabbMin.z), std::fabs(s.localAabbMax.z));
    return std::sqrt(x * x + y * y + z * z);
}

}  // namespace btgpu
