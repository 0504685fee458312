// shape_tables.cpp — face planes by Newell's method, loops turned outward-CCW by the hull's
// centroid, unique edge directions deduplicated up to sign.
#include "shape_tables.h"

#include <algorithm>
#include <cmath>

namespace btgpu::test {

namespace {
BtgShape blankShape(int type)
{
    BtgShape s{};
    s.type = type;
    s.breakingThreshold = kTestBreakingThreshold;
    return s;
}
}  // namespace

int ShapeTables::addSphere(float radius)
{
    BtgShape s = blankShape(BTG_SHAPE_SPHERE);
    s.param = btgMake4(radius, 0, 0, 0);
    s.localAabbMin = btgMake4(-radius, -radius, -radius, 0);
    s.localAabbMax = btgMake4(radius, radius, radius, 0);
    shapes.push_back(s);
    return int(shapes.size()) - 1;
}

int ShapeTables::addPlane(BtgFloat4 normal, float constant)
{
    BtgShape s = blankShape(BTG_SHAPE_PLANE);
    BtgFloat4 n = btgNormalize3(normal);
    s.param = btgMake4(n.x, n.y, n.z, constant);
    shapes.push_back(s);
    return int(shapes.size()) - 1;
}

int ShapeTables::addBox(BtgFloat4 h)
{
    std::vector<BtgFloat4> v;
    for (int i = 0; i < 8; ++i)
        v.push_back(btgMake4(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z, 0));
    const int row = addHull(v, {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}});
    // as compat/shape_tables.cpp makes a btBoxShape's row: its own kind, a zero-margin GJK core
    shapes[size_t(row)].type = BTG_SHAPE_BOX;
    shapes[size_t(row)].convexType = BTG_CONVEX_BOX;
    shapes[size_t(row)].param = btgMake4(h.x, h.y, h.z, 0);
    return row;
}

int ShapeTables::addPrism(int sides, float radius, float halfHeight, float margin)
{
    std::vector<BtgFloat4> v;
    for (int ring = 0; ring < 2; ++ring)
        for (int i = 0; i < sides; ++i) {
            float a = 2.0f * 3.14159265f * float(i) / float(sides);
            v.push_back(btgMake4(radius * std::cos(a), ring ? halfHeight : -halfHeight, radius * std::sin(a), 0));
        }
    std::vector<std::vector<int>> loops(2);
    for (int i = 0; i < sides; ++i) {
        loops[0].push_back(i);
        loops[1].push_back(sides + i);
        int j = (i + 1) % sides;
        loops.push_back({i, j, sides + j, sides + i});
    }
    return addHull(v, loops, margin);
}

int ShapeTables::addTetrahedron(float s, float margin)
{
    std::vector<BtgFloat4> v = {btgMake4(s, s, s, 0), btgMake4(s, -s, -s, 0), btgMake4(-s, s, -s, 0), btgMake4(-s, -s, s, 0)};
    return addHull(v, {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}, margin);
}

int ShapeTables::addHull(const std::vector<BtgFloat4>& verts, const std::vector<std::vector<int>>& loops, float margin)
{
    BtgShape s = blankShape(BTG_SHAPE_HULL);
    s.firstVertex = int(vertices.size());
    s.numVertices = int(verts.size());
    s.firstFace = int(faces.size());
    s.numFaces = int(loops.size());
    s.firstEdge = int(edges.size());
    s.margin = margin;
    BtgFloat4 centroid = btgZero4(), lo = verts[0], hi = verts[0];
    for (const BtgFloat4& p : verts) {
        centroid += p * (1.0f / float(verts.size()));
        lo = btgMake4(std::fmin(lo.x, p.x), std::fmin(lo.y, p.y), std::fmin(lo.z, p.z), 0);
        hi = btgMake4(std::fmax(hi.x, p.x), std::fmax(hi.y, p.y), std::fmax(hi.z, p.z), 0);
    }
    BtgFloat4 grow = btgMake4(margin, margin, margin, 0);
    s.localAabbMin = lo - grow;
    s.localAabbMax = hi + grow;
    vertices.insert(vertices.end(), verts.begin(), verts.end());
    for (std::vector<int> loop : loops) {
        BtgFloat4 n = btgZero4(), c = btgZero4();
        for (size_t k = 0; k < loop.size(); ++k) {
            BtgFloat4 a = verts[loop[k]], b = verts[loop[(k + 1) % loop.size()]];
            n += btgMake4((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y), 0);
            c += a * (1.0f / float(loop.size()));
        }
        n = btgNormalize3(n);
        if (btgDot3(n, c - centroid) < 0) {
            n = -n;
            std::reverse(loop.begin(), loop.end());
        }
        BtgFace f{};
        f.plane = btgMake4(n.x, n.y, n.z, -btgDot3(n, c));
        f.firstIndex = int(indices.size());
        f.numIndices = int(loop.size());
        faces.push_back(f);
        indices.insert(indices.end(), loop.begin(), loop.end());
        for (size_t k = 0; k < loop.size(); ++k) {
            BtgFloat4 e = btgNormalize3(verts[loop[(k + 1) % loop.size()]] - verts[loop[k]]);
            bool known = false;
            for (int i = s.firstEdge; i < int(edges.size()) && !known; ++i)
                known = std::fabs(btgDot3(edges[i], e)) > 0.9999f;
            if (!known) edges.push_back(e);
        }
    }
    s.numEdges = int(edges.size()) - s.firstEdge;
    shapes.push_back(s);
    return int(shapes.size()) - 1;
}

ref::ShapeTablesView ShapeTables::view() const
{
    ref::ShapeTablesView v;
    v.shapes = shapes.data();
    v.hullVertices = vertices.data();
    v.hullFaces = faces.data();
    v.hullIndices = indices.data();
    v.hullEdges = edges.data();
    return v;
}

void ShapeTables::upload(DeviceWorld& w) const
{
    w.shapes.upload(w.ctx, shapes);
    w.hullVertices.upload(w.ctx, vertices);
    w.hullFaces.upload(w.ctx, faces);
    w.hullIndices.upload(w.ctx, indices);
    w.hullEdges.upload(w.ctx, edges);
    w.numShapes = int(shapes.size());
}

}  // namespace btgpu::test
