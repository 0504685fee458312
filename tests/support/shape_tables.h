// shape_tables.h — host-side builder of the shape tables (shapes, hull vertices, faces,
// face-index loops, unique edge directions) for tests: spheres, planes, boxes, prisms, a
// tetrahedron and hand-listed convex hulls; uploads them into a DeviceWorld.
#pragma once
#include "reference/narrowphase.h"
#include "shared/types.h"
#include "world/device_world.h"

#include <vector>

namespace btgpu::test {

// Every test shape's contact breaking threshold, m (Bullet's absolute default).
constexpr float kTestBreakingThreshold = 0.02f;

struct ShapeTables {
    std::vector<BtgShape> shapes;
    std::vector<BtgFloat4> vertices;
    std::vector<BtgFace> faces;
    std::vector<int> indices;
    std::vector<BtgFloat4> edges;

    int addSphere(float radius);
    // Points p with normal.p = constant (shape-local) lie on the plane.
    int addPlane(BtgFloat4 normal, float constant);
    int addBox(BtgFloat4 halfExtents);
    // A convex hull (centre of mass at the origin) from its vertices and face loops; loops may
    // be listed in either winding (they are turned counter-clockwise seen from outside).
    int addHull(const std::vector<BtgFloat4>& verts, const std::vector<std::vector<int>>& loops, float margin = 0.0f);
    // Regular n-gon prism along y: 2n vertices, n + 2 faces.
    int addPrism(int sides, float radius, float halfHeight, float margin = 0.0f);
    // Regular tetrahedron with vertices at s*(1,1,1), s*(1,-1,-1), s*(-1,1,-1), s*(-1,-1,1).
    int addTetrahedron(float s, float margin = 0.0f);

    ref::ShapeTablesView view() const;
    void upload(DeviceWorld& w) const;
};

}  // namespace btgpu::test
