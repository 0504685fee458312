// convex_scenes.h — scenes of the convex shapes Bullet collides by GJK (capsules, cylinders,
// cones of each axis, multi-spheres, convex triangle meshes, uniformly scaled and locally
// scaled shapes) on a box ground: resting, landing, rolling down a ramp, a small mixed pile.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes {

enum class ConvexKind { Capsule, Cylinder, Cone, MultiSphere, ConvexMesh, ScaledBox, ScaledHull, UniformCapsule };

// One body of `kind` (up axis `axis` for capsules, cylinders and cones) dropped from `height`
// onto a box ground, turned by `tilt` rad about z (pi/2 lays a y-axis capsule on its side).
ScenePtr convexLanding(WorldKind kind, ConvexKind shape, int axis, double tilt, double height,
                       const Config& config = Config());
// A cylinder (radius 0.5, half height 0.5, axis z) rolling down a box ramp tilted 15 degrees.
ScenePtr cylinderRamp(WorldKind kind, const Config& config = Config());
// 12 mixed convex bodies (capsules, cylinders, cones, a multi-sphere, a convex mesh, boxes,
// spheres) dropped in a loose column onto the ground.
ScenePtr convexPile(WorldKind kind, const Config& config = Config());

}  // namespace btgpu::scenes
