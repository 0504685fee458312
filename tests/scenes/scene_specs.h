// scene_specs.h — the large scenes (cubes, spheres, mixed) as plain data (a list of bodies), so
// the scene library, the benchmark's btgpu, stock Bullet and Bullet3 backends all instantiate
// exactly the same bodies. Ground first (index 0, which Bullet3's solver treats as its static
// body), then other statics, then the dynamics.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace btgpu::scenes::spec {

// Mesh: the scene's triangle mesh (static only); Compound: a btCompoundShape of Scene::compounds;
// Capsule: a btCapsuleShape (Y axis) of `radius` and cylinder half height half[1].
enum class ShapeKind { Box, Sphere, Hull, Plane, Mesh, Compound, Capsule };

// A convex hull's points (local frame, m), as an app passes them to btConvexHullShape.
struct HullSpec {
    std::vector<float> points;  // x, y, z per point
    float margin = 0.04f;       // m (btConvexHullShape's default is 0.04)
    bool polyhedral = true;     // the app calls initializePolyhedralFeatures
};

// One child of a compound: a box or a sphere at its transform in the compound's frame.
struct ChildSpec {
    ShapeKind shape = ShapeKind::Box;
    float half[3] = {1, 1, 1};    // m (Box)
    float radius = 1;             // m (Sphere)
    float pos[3] = {0, 0, 0};     // m
    float rot[4] = {0, 0, 0, 1};  // quaternion (x, y, z, w)
};
struct CompoundSpec {
    std::vector<ChildSpec> children;
};
// A table: a top box (half extents 0.6, 0.05, 0.4) at y = 0.35 on four legs (half extents 0.05,
// 0.3, 0.05) at x = +-0.5, z = +-0.3; a dumbbell: spheres of radius 0.3 at x = +-0.5 on a bar
// (half extents 0.5, 0.08, 0.08).
CompoundSpec tableSpec();
CompoundSpec dumbbellSpec();

struct BodySpec {
    ShapeKind shape = ShapeKind::Box;
    float half[3] = {1, 1, 1};  // m, box half extents (Box)
    float radius = 1;           // m (Sphere, Capsule)
    int hull = -1;              // Hull: index in Scene::hulls (Plane: the plane y = pos[1], normal +y)
    int compound = -1;          // Compound: index in Scene::compounds
    float mass = 0;             // kg; 0 = static
    float pos[3] = {0, 0, 0};   // m, centre of mass; every body starts at rest
    float rot[4] = {0, 0, 0, 1};  // orientation quaternion (x, y, z, w); identity but in ragdolls
    float friction = 1;
    float restitution = 0;
    float linearDamping = 0;
    float angularDamping = 0;
};

// A joint between bodies a and b (indices into Scene::bodies), frames in the bodies' frames,
// added with disableCollisionsBetweenLinkedBodies as Bullet's RagdollDemo adds them.
struct JointSpec {
    enum class Kind { Hinge, ConeTwist };
    Kind kind = Kind::Hinge;
    int a = 0, b = 0;
    float frameA[7] = {0, 0, 0, 0, 0, 0, 1};  // origin (m), then rotation quaternion (x, y, z, w)
    float frameB[7] = {0, 0, 0, 0, 0, 0, 1};
    float limit[3] = {0, 0, 0};  // hinge: low, high (rad); cone-twist: swing span 1, 2, twist span
};

struct Scene {
    std::string name;                // e.g. "cubes 10x10x10"
    std::vector<BodySpec> bodies;
    std::vector<HullSpec> hulls;     // shapes of the Hull bodies
    std::vector<CompoundSpec> compounds;  // shapes of the Compound bodies
    // The one triangle mesh of ShapeKind::Mesh bodies: xyz per vertex (m), three per triangle.
    std::vector<float> meshVertices;
    std::vector<int> meshIndices;
    std::vector<JointSpec> joints;
    float gravity[3] = {0, -10, 0};  // m/s^2
    float dt = 1.0f / 60.0f;         // s, one substep per frame
    int iterations = 10;             // solver iterations
    int dynamicCount() const;
};

// NX×NY×NZ unit-half-extent cubes (or radius-1 spheres) stacked over a ground box.
Scene makeStack(int nx, int ny, int nz, ShapeKind shape);
// 32³ boxes of random half extents in [0.1, 2.5] over 16 static pillars (fixed seed).
Scene makeMixed(std::uint32_t seed = 12345u);
// Bullet's BenchmarkDemo test 8: `cells` Voronoi cells of a 2 m cube (sites on a Halton
// sequence), each a convex hull of many faces with polyhedral features and margin 0.04, mass =
// volume, friction 0.6, released 3.5 m up over a ground plane; 20 solver iterations. The demo also
// sets erp 0.8 and a global CFM, which btgpu does not serve: left at Bullet's defaults here.
Scene makeVoronoi(int cells = 90);
// Bench 5 on a rolling landscape mesh of quads x quads cells 200 m across (2 quads^2 triangles,
// the heights of landscapeHeight in mesh_scenes.h): `count` boxes and spheres dropped over it.
Scene makeLandscape(int count, int quads);
// One RagdollDemo ragdoll at `scale` (BenchmarkDemo's bench 3 uses 3.5): each part's capsule
// (radius, height: the cylinder's length), its centre in the ragdoll's frame and its roll about
// z; its 10 joints between parts 0..10 (frames in the parts' frames, limits).
struct RagdollPart {
    float radius, height, x, y, roll;
};
void ragdollLayout(float scale, RagdollPart parts[11], JointSpec joints[10]);
// `count` ragdolls (Bullet's RagdollDemo: 11 capsules, 5 hinges and 5 cone-twists) on a square
// grid 2 m apart over a ground box, pelvis 1 m up: they fall and sprawl.
Scene makeRagdolls(int count);
// `count` compound bodies, tables and dumbbells alternating (mass 1, friction 0.5) on a square
// lattice 2 m apart (at most 10 x 10 a layer, layers 1.2 m apart), released from 1 m onto a
// ground box of half extent 50 (top at y = 0).
Scene makeCompounds(int count);
// Sizes named by --n: 1000, 8000, 32768, 112500, 1000000; false if n is not one of them.
bool dimsForCount(long n, int dims[3]);

}  // namespace btgpu::scenes::spec
