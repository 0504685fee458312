// demo_scenes.h — the scenes of Bullet's example browser that the demos show (BenchmarkDemo's
// eight tests, RagdollDemo, a raycast vehicle on a heightfield, compound shapes), defined once
// here for the demos, the benchmark and the tests. Plain-data scenes (scene_specs.h,
// benchmark_specs.h) become a Scene through fromSpec, exactly as the benchmark builds them.
#pragma once
#include <vector>

#include "scenes/scene_specs.h"
#include "scenes/scenes.h"

class btRaycastVehicle;

namespace btgpu::scenes {

// Any plain-data scene on stock or btgpu: one shape per distinct size, damping, rotations and
// joints (added with disableCollisionsBetweenLinkedBodies) as tests/bench/bt_bodies.cpp does.
ScenePtr fromSpec(WorldKind kind, const Config& config, const spec::Scene& data, const std::string& name);

// BenchmarkDemo test 1 (3,008 boxes falling into a pile), 2 (1,076 boxes in a pyramid, walls
// and a tower), 4 (960 convex barrels), 8 (Voronoi pieces of a cube); benchmark_specs.h.
ScenePtr benchPile(WorldKind kind, const Config& config = Config::bulletMode(), int layers = 47);
ScenePtr benchStacks(WorldKind kind, const Config& config = Config::bulletMode());
ScenePtr benchHulls(WorldKind kind, const Config& config = Config::bulletMode(), int layers = 15);
// Test 2's round tower alone, `rings` (8) rings of 24 boxes (spec::makeBenchTower).
ScenePtr benchTower(WorldKind kind, const Config& config = Config::bulletMode(), int rings = 8);
ScenePtr voronoiPieces(WorldKind kind, const Config& config = Config::bulletMode(), int cells = 90);
// BenchmarkDemo test 5's lattice: `layers` (10) layers of 10 x 10 bodies, each a box (half
// extent 0.75, 1.5, 2.25), a sphere (radius 0.75, 1.5, 2.25) or a capsule (radius 0.5, 1, 1.5,
// height 1, 2, 3), mass 0.5, 1 or 1.5, chosen by a fixed-seed generator; 5 m apart in x and z,
// from 45 m up, over BenchmarkDemo's ground box (test 5 drops them on its mesh instead:
// the landscape scene of mesh_scenes.h is that one).
ScenePtr benchMixedShapes(WorldKind kind, const Config& config = Config::bulletMode(), int layers = 10);
// RagdollDemo: `count` ragdolls of real capsules (makeRagdolls' bodies and joints, each box
// there a btCapsuleShape of the same radius and length here), 2 m apart, dropping.
ScenePtr capsuleRagdolls(WorldKind kind, const Config& config = Config::bulletMode(), int count = 9);
// BenchmarkDemo test 3: 136 RagdollDemo ragdolls of capsules at scale 3.5 in rows of 16, 15, ...,
// 1 (6 m apart, each row 7 m higher and 2 m farther back), over BenchmarkDemo's ground box; the
// joints' frames scaled with the bodies. (The `ragdolls` scene of joint_scenes.h, boxes on a grid,
// is the benchmark's.)
ScenePtr benchRagdolls(WorldKind kind, const Config& config = Config::bulletMode(), int rows = 16);
// A few compound bodies (a table: top and four legs; an L of two boxes; a dumbbell of two
// spheres on a box bar), `count` of them in a loose column over a ground box.
ScenePtr compoundPile(WorldKind kind, const Config& config = Config::bulletMode(), int count = 24);

// Bullet's VehicleDemo on a rolling btHeightfieldTerrainShape (129 x 129 points, 1 m apart): a
// box chassis (half extents 1, 0.5, 2; mass 800) on a btRaycastVehicle with four wheels (radius
// 0.5), added with addAction, driven by beforeStep (engine force on the rear wheels, a slow
// steering sweep); a few boxes on the terrain. `vehicle` gets the vehicle (owned by the scene).
ScenePtr raycastVehicle(WorldKind kind, const Config& config = Config::bulletMode(), btRaycastVehicle** vehicle = nullptr);

// BenchmarkDemo test 7's ray fan: `count` rays from (x, 50, 0) spread evenly round y, each
// `length` m across and ending at y = -50; `x` sweeps back and forth at 10 m/s in [-20, 20].
struct RayFan {
    std::vector<btVector3> from, to;
    double sweep = 1.0;  // +1 or -1
    void move(double dt);
};
RayFan benchmarkRays(int count = 500, double length = 24.0);
// Casts every ray (closest hit); per ray the hit fraction (1 when nothing is hit).
std::vector<double> castRays(const btCollisionWorld& world, const RayFan& rays);

}  // namespace btgpu::scenes
