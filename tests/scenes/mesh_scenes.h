// mesh_scenes.h — scenes on triangle-mesh ground (btBvhTriangleMeshShape), defined once for the
// regression tests, the benchmark and the demos: bodies resting and dropped on a flat mesh
// (two parts, 16- and 32-bit indices), one mesh shared by two ground bodies, and a landscape
// like Bullet's BenchmarkDemo bench 5 (a convex mix on a rolling triangle-mesh terrain).
#pragma once
#include "scenes/scenes.h"

class btBvhTriangleMeshShape;
class btHeightfieldTerrainShape;
class btTriangleIndexVertexArray;

namespace btgpu::scenes {

// The app's mesh data behind a btBvhTriangleMeshShape (owned by the scene).
struct MeshData {
    std::vector<float> vertices;
    std::vector<unsigned short> shortIndices;  // part 0 (PHY_SHORT, as BenchmarkDemo's landscape)
    std::vector<int> intIndices;               // part 1 (PHY_INTEGER), when two parts
    std::vector<float> vertices1;
    btTriangleIndexVertexArray* array = nullptr;
};

// A square grid mesh of n x n quads of side `cell`, centred at the origin. Flat: y = 0; else
// the landscape's rolling heights (landscapeHeight). With twoParts the x < 0 half is part 0
// (16-bit indices) and the x > 0 half part 1 (32-bit). The scene owns data and shape.
btBvhTriangleMeshShape* gridMesh(Scene& scene, int n, float cell, bool flat, bool twoParts, MeshData** data = nullptr);
float landscapeHeight(float x, float z);  // m

// A box (half extent 0.5) at x = -2 and a sphere (radius 0.5) at x = 2 released 0.1 m above a
// flat two-part mesh ground (bodies 1 and 2; body 0 the ground).
ScenePtr restOnMesh(WorldKind kind, const Config& config = Config::bulletMode());
// 100 bodies, boxes (half extent 0.3) and spheres (radius 0.3) alternating on a 10 x 10 grid
// 1.5 m apart, released 1 m above a flat mesh ground: they land apart (bodies 1..100).
ScenePtr dropOnMesh(WorldKind kind, const Config& config = Config::bulletMode());
// One flat mesh shape on two static ground bodies at x = -10 and x = 10, a box and a sphere
// over each (bodies 2..5).
ScenePtr sharedMesh(WorldKind kind, const Config& config = Config::bulletMode());
// A btHeightfieldTerrainShape ground of n x n grid points 1 m apart, up axis y, flat at y = 0
// (float heights, all 0; the scene owns the array, which a test may change between steps).
btHeightfieldTerrainShape* flatHeightfield(Scene& scene, int n, std::vector<float>** heights = nullptr);
// restOnMesh and dropOnMesh on a flat heightfield instead of the mesh.
ScenePtr restOnHeightfield(WorldKind kind, const Config& config = Config::bulletMode());
ScenePtr dropOnHeightfield(WorldKind kind, const Config& config = Config::bulletMode());
// A capsule (radius 0.3, 1 m long) and a cylinder (half extents 0.3, 0.5, 0.3) on their sides
// and a cone (radius 0.4, height 1) upright and a hull without polyhedral features (a box of
// half extents 0.4, 0.3, 0.4 plus its margin), released 0.1 m above a flat two-part mesh
// ground or a flat heightfield (bodies 1..4; body 0 the ground).
ScenePtr convexRestOnMesh(WorldKind kind, const Config& config = Config::bulletMode());
ScenePtr convexRestOnHeightfield(WorldKind kind, const Config& config = Config::bulletMode());
// Bench 5's layout on a rolling mesh terrain of quads x quads cells (200 m across): boxes,
// spheres and hulls dropped in a lattice of `count` bodies. 100 quads: 20,000 triangles; 708:
// about 1,000,000.
ScenePtr landscape(WorldKind kind, const Config& config = Config::bulletMode(), int count = 1000, int quads = 100);

}  // namespace btgpu::scenes
