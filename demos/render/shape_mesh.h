// shape_mesh.h — a Bullet collision shape as triangles with normals in its own frame, for the
// renderer: boxes, spheres, capsules, cylinders and cones tessellated from their dimensions,
// hulls from their points, any other convex shape from its support function, triangle meshes and
// heightfields from their triangles, planes as a large quad, compounds from their children.
// No OpenGL here (the render test checks meshes without a context).
#pragma once
#include <btBulletCollisionCommon.h>

#include <vector>

namespace btgpu::render {

struct Mesh {
    std::vector<float> positions;  // x, y, z per vertex, three vertices per triangle
    std::vector<float> normals;    // unit, per vertex
    int triangles() const { return int(positions.size() / 9); }
};

// The shape's triangles. `extent` (m) bounds what is drawn of unbounded shapes (planes).
Mesh meshForShape(const btCollisionShape& shape, float extent = 200.0f);

}  // namespace btgpu::render
