// compound_scenes.h — scenes of btCompoundShape bodies, defined once for the regression tests,
// the benchmark and the demos: tables (a top box on four box legs) standing on a box ground,
// stacked, and on a mesh ground; a dumbbell (two spheres and a box bar) rolling; many tables
// and dumbbells dropped together.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes {

// A table (scene_specs.h tableSpec): a top box (half extents 0.6, 0.05, 0.4) at y = 0.35 on four legs (half extents 0.05,
// 0.3, 0.05) at x = +-0.5, z = +-0.3, y = 0; the body's origin 0.35 m above the legs' feet
// would stand at y = 0.3 on a ground whose top is y = 0. Owned by the scene.
btCompoundShape* tableShape(Scene& scene, bool dynamicTree = true);
constexpr double kTableFootDepth = 0.3;  // m, from the body's origin down to the feet
constexpr double kTableHeight = 0.7;     // m, feet to top

// `count` tables stacked, each released 1 cm above the one below (the first 1 cm above a box
// ground); bodies 1..count, body 0 the ground. Without their dynamic AABB trees
// (btCompoundShape(false)) two tables meet by stock's nested compound algorithms.
ScenePtr tableStack(WorldKind kind, const Config& config = Config::bulletMode(), int count = 1, bool dynamicTree = true);
// `count` unit boxes, each wrapped as game engines wrap a body to put its centre of mass at its
// origin (a btCompoundShape(false) of one child, shifted by (0.1, -0.2, 0)), stacked 1 cm apart
// on a box ground, each 2 cm further along x than the one below (bodies 1..count).
ScenePtr wrappedBoxStack(WorldKind kind, const Config& config = Config::bulletMode(), int count = 4);
// A table 1 cm above a flat triangle-mesh ground, or a flat heightfield (body 1; body 0 the ground).
// A table resting on a box ground and a ball resting beside one of its legs, 6 cm from it but
// inside the leg's AABB: stock holds an empty manifold for that child pair.
ScenePtr tableBesideSphere(WorldKind kind, const Config& config = Config::bulletMode());
ScenePtr tableOnMesh(WorldKind kind, const Config& config = Config::bulletMode());
ScenePtr tableOnHeightfield(WorldKind kind, const Config& config = Config::bulletMode());
// A cart of support-function children (GJK leaves): two cylinders (radius 0.3, half width 0.1,
// axes along z) at x = +-0.6 on a capsule axle (radius 0.05, along x), and a cone upright on top,
// 1 cm above a box ground (body 1).
ScenePtr convexCart(WorldKind kind, const Config& config = Config::bulletMode());
// A dumbbell: spheres of radius 0.3 at x = +-0.5 on a bar (box half extents 0.5, 0.08, 0.08),
// resting on a box ground and set rolling along +z at 1 m/s (body 1).
ScenePtr dumbbellRolling(WorldKind kind, const Config& config = Config::bulletMode());
constexpr double kDumbbellRadius = 0.3;    // m
constexpr double kDumbbellSpeed = 1.0;     // m/s
// scene_specs.h makeCompounds: `count` bodies, tables and dumbbells alternating on a square lattice 2 m apart, released in
// layers from 1 m up onto a box ground (the bench's `compounds` scene; bodies 1..count).
ScenePtr compoundDrop(WorldKind kind, const Config& config = Config::bulletMode(), int count = 100);

}  // namespace btgpu::scenes
