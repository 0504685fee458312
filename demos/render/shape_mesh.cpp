// shape_mesh.cpp — tessellation of each shape type (shape_mesh.h). Round shapes get smooth
// normals from the analytic surface; flat ones one normal per triangle.
#include "render/shape_mesh.h"

#include <BulletCollision/CollisionShapes/btShapeHull.h>
#include <LinearMath/btConvexHullComputer.h>

#include <cmath>
#include <map>
#include <tuple>

namespace btgpu::render {

namespace {

constexpr int kSegments = 24;  // around a round shape
constexpr int kRings = 12;     // pole to pole on a sphere

void vertex(Mesh& m, const btVector3& p, const btVector3& n)
{
    m.positions.insert(m.positions.end(), {p.x(), p.y(), p.z()});
    const btVector3 u = n.length2() > 0 ? n.normalized() : btVector3(0, 1, 0);
    m.normals.insert(m.normals.end(), {u.x(), u.y(), u.z()});
}

// A triangle with its own vertex normals, wound counter-clockwise seen from where they point
// (two-sided lighting then keeps them facing out).
void smooth(Mesh& m, const btVector3& a, const btVector3& na, const btVector3& b, const btVector3& nb, const btVector3& c,
            const btVector3& nc)
{
    if ((b - a).cross(c - a).dot(na + nb + nc) >= 0) vertex(m, a, na), vertex(m, b, nb), vertex(m, c, nc);
    else vertex(m, a, na), vertex(m, c, nc), vertex(m, b, nb);
}

void flat(Mesh& m, const btVector3& a, const btVector3& b, const btVector3& c)
{
    const btVector3 n = (b - a).cross(c - a);
    if (n.length2() < 1e-20f) return;
    vertex(m, a, n), vertex(m, b, n), vertex(m, c, n);
}

// Axis-aligned frames for shapes with an up axis: e[0] along it, e[1], e[2] across.
void axes(int up, btVector3 e[3])
{
    const btVector3 unit[3] = {btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)};
    e[0] = unit[up], e[1] = unit[(up + 1) % 3], e[2] = unit[(up + 2) % 3];
}

// A surface of revolution about e[0]: profile points (height along the axis, radius) with the
// profile normal (along, across) at each; consecutive points joined by bands of quads.
void revolve(Mesh& m, const btVector3 e[3], const std::vector<btVector3>& profile, const std::vector<btVector3>& normal)
{
    auto at = [&](size_t k, int s, bool n) {
        const double a = 2 * SIMD_PI * s / kSegments;
        const btVector3 across = e[1] * btScalar(std::cos(a)) + e[2] * btScalar(std::sin(a));
        const btVector3& v = n ? normal[k] : profile[k];
        return e[0] * v.x() + across * v.y();
    };
    for (size_t k = 0; k + 1 < profile.size(); ++k)
        for (int s = 0; s < kSegments; ++s) {
            const btVector3 p00 = at(k, s, false), p01 = at(k, s + 1, false), p10 = at(k + 1, s, false),
                            p11 = at(k + 1, s + 1, false);
            const btVector3 n00 = at(k, s, true), n01 = at(k, s + 1, true), n10 = at(k + 1, s, true),
                            n11 = at(k + 1, s + 1, true);
            if ((p00 - p01).length2() > 1e-12f) smooth(m, p00, n00, p01, n01, p11, n11);
            if ((p10 - p11).length2() > 1e-12f) smooth(m, p00, n00, p11, n11, p10, n10);
        }
}

// Two hemispheres of radius r at +-half along e[0] joined by a cylinder (r = 0 half = 0: none).
void capsule(Mesh& m, const btVector3 e[3], btScalar r, btScalar half)
{
    std::vector<btVector3> profile, normal;
    for (int i = 0; i <= kRings; ++i) {
        const double a = SIMD_PI * i / kRings;  // from the -axis pole to the +axis pole
        const btScalar c = btScalar(-std::cos(a)), s = btScalar(std::sin(a));
        const btScalar offset = i < kRings / 2 ? -half : i > kRings / 2 ? half : btScalar(0);
        if (i == kRings / 2 && half > 0) {
            profile.push_back(btVector3(-half, r, 0)), normal.push_back(btVector3(0, 1, 0));
            profile.push_back(btVector3(half, r, 0)), normal.push_back(btVector3(0, 1, 0));
            continue;
        }
        profile.push_back(btVector3(offset + r * c, r * s, 0));
        normal.push_back(btVector3(c, s, 0));
    }
    revolve(m, e, profile, normal);
}

void box(Mesh& m, const btVector3& h)
{
    const btVector3 c[8] = {{-h.x(), -h.y(), -h.z()}, {h.x(), -h.y(), -h.z()}, {h.x(), h.y(), -h.z()}, {-h.x(), h.y(), -h.z()},
                            {-h.x(), -h.y(), h.z()},  {h.x(), -h.y(), h.z()},  {h.x(), h.y(), h.z()},  {-h.x(), h.y(), h.z()}};
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
    for (const auto& f : faces) flat(m, c[f[0]], c[f[1]], c[f[2]]), flat(m, c[f[0]], c[f[2]], c[f[3]]);
}

void hull(Mesh& m, const std::vector<btVector3>& points)
{
    btConvexHullComputer hc;
    if (points.size() < 4) return;
    hc.compute(&points[0].x(), sizeof(btVector3), int(points.size()), 0, 0);  // returns the shrink, 0 here
    for (int f = 0; f < hc.faces.size(); ++f) {
        const btConvexHullComputer::Edge* first = &hc.edges[hc.faces[f]];
        const btVector3 a = hc.vertices[first->getSourceVertex()];
        const btConvexHullComputer::Edge* e = first->getNextEdgeOfFace();
        for (; e->getNextEdgeOfFace() != first; e = e->getNextEdgeOfFace())
            flat(m, a, hc.vertices[e->getSourceVertex()], hc.vertices[e->getTargetVertex()]);
    }
}

struct TriangleCollector : btTriangleCallback {
    Mesh* mesh;
    void processTriangle(btVector3* t, int, int) override { flat(*mesh, t[0], t[1], t[2]); }
};

void shapeInto(Mesh& m, const btCollisionShape& shape, const btTransform& to, float extent);

// Terrain: each vertex gets the mean normal of the triangles meeting at its position where they
// bend by less than about 45 degrees (rolling ground looks smooth, real edges stay sharp).
void smoothCreases(Mesh& m)
{
    std::map<std::tuple<float, float, float>, btVector3> sum;
    auto key = [&](size_t i) { return std::make_tuple(m.positions[i], m.positions[i + 1], m.positions[i + 2]); };
    for (size_t i = 0; i < m.positions.size(); i += 3)
        sum[key(i)] += btVector3(m.normals[i], m.normals[i + 1], m.normals[i + 2]);
    for (size_t i = 0; i < m.positions.size(); i += 3) {
        const btVector3 own(m.normals[i], m.normals[i + 1], m.normals[i + 2]);
        const btVector3 mean = sum[key(i)].safeNormalize();
        if (mean.dot(own) < 0.7f) continue;
        m.normals[i] = mean.x(), m.normals[i + 1] = mean.y(), m.normals[i + 2] = mean.z();
    }
}

void append(Mesh& m, const Mesh& part, const btTransform& to)
{
    for (size_t i = 0; i < part.positions.size(); i += 3) {
        const btVector3 p = to * btVector3(part.positions[i], part.positions[i + 1], part.positions[i + 2]);
        const btVector3 n = to.getBasis() * btVector3(part.normals[i], part.normals[i + 1], part.normals[i + 2]);
        vertex(m, p, n);
    }
}

void shapeInto(Mesh& out, const btCollisionShape& shape, const btTransform& to, float extent)
{
    Mesh m;
    btVector3 e[3];
    switch (shape.getShapeType()) {
    case BOX_SHAPE_PROXYTYPE:
        box(m, static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin());
        break;
    case SPHERE_SHAPE_PROXYTYPE:
        axes(1, e);
        capsule(m, e, static_cast<const btSphereShape&>(shape).getRadius(), 0);
        break;
    case CAPSULE_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btCapsuleShape&>(shape);
        axes(c.getUpAxis(), e);
        capsule(m, e, c.getRadius(), c.getHalfHeight());
        break;
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btCylinderShape&>(shape);
        const int up = c.getUpAxis();
        axes(up, e);
        const btScalar h = c.getHalfExtentsWithMargin()[up], r = c.getRadius();
        revolve(m, e, {btVector3(-h, 0, 0), btVector3(-h, r, 0), btVector3(-h, r, 0), btVector3(h, r, 0), btVector3(h, r, 0), btVector3(h, 0, 0)},
                {btVector3(-1, 0, 0), btVector3(-1, 0, 0), btVector3(0, 1, 0), btVector3(0, 1, 0), btVector3(1, 0, 0), btVector3(1, 0, 0)});
        break;
    }
    case CONE_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btConeShape&>(shape);
        axes(c.getConeUpIndex(), e);
        const btScalar h = c.getHeight() / 2, r = c.getRadius();
        const btVector3 side = btVector3(r, 2 * h, 0).normalized();
        revolve(m, e, {btVector3(-h, 0, 0), btVector3(-h, r, 0), btVector3(-h, r, 0), btVector3(h, 0, 0)},
                {btVector3(-1, 0, 0), btVector3(-1, 0, 0), side, side});
        break;
    }
    case CONVEX_HULL_SHAPE_PROXYTYPE: {
        const auto& h = static_cast<const btConvexHullShape&>(shape);
        std::vector<btVector3> points;
        for (int i = 0; i < h.getNumPoints(); ++i) points.push_back(h.getScaledPoint(i));
        hull(m, points);
        break;
    }
    case STATIC_PLANE_PROXYTYPE: {
        const auto& p = static_cast<const btStaticPlaneShape&>(shape);
        const btVector3 n = p.getPlaneNormal();
        btVector3 u, v;
        btPlaneSpace1(n, u, v);
        const btVector3 o = n * p.getPlaneConstant();
        const btScalar s = extent;
        flat(m, o - u * s - v * s, o + u * s - v * s, o + u * s + v * s);
        flat(m, o - u * s - v * s, o + u * s + v * s, o - u * s + v * s);
        if ((m.positions.size() > 0) && btVector3(m.normals[0], m.normals[1], m.normals[2]).dot(n) < 0) {
            m = Mesh();
            flat(m, o - u * s - v * s, o + u * s + v * s, o + u * s - v * s);
            flat(m, o - u * s - v * s, o - u * s + v * s, o + u * s + v * s);
        }
        break;
    }
    case COMPOUND_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btCompoundShape&>(shape);
        for (int i = 0; i < c.getNumChildShapes(); ++i) shapeInto(m, *c.getChildShape(i), c.getChildTransform(i), extent);
        break;
    }
    default:
        if (shape.isConcave()) {
            btVector3 lo, hi;
            shape.getAabb(btTransform::getIdentity(), lo, hi);
            lo.setMax(btVector3(-extent, -extent, -extent)), hi.setMin(btVector3(extent, extent, extent));
            TriangleCollector collect;
            collect.mesh = &m;
            static_cast<const btConcaveShape&>(shape).processAllTriangles(&collect, lo, hi);
            smoothCreases(m);
        } else if (shape.isConvex()) {
            // Multi-spheres, convex meshes, scaled shapes: the hull of the support points in
            // many directions (btShapeHull), margin included.
            btShapeHull sampled(static_cast<const btConvexShape*>(&shape));
            sampled.buildHull(shape.getMargin());
            std::vector<btVector3> points(sampled.getVertexPointer(), sampled.getVertexPointer() + sampled.numVertices());
            hull(m, points);
        }
        break;
    }
    append(out, m, to);
}

}  // namespace

Mesh meshForShape(const btCollisionShape& shape, float extent)
{
    Mesh m;
    shapeInto(m, shape, btTransform::getIdentity(), extent);
    return m;
}

}  // namespace btgpu::render
