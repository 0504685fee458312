// convex_scenes.h — scenes of the convex shapes Bullet collides by GJK (capsules, cylinders,
// cones of each axis, multi-spheres, convex triangle meshes, uniformly scaled and locally
// scaled shapes) on a box ground: resting, landing, rolling down a ramp, a small mixed pile.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes {

enum class ConvexKind {
    Capsule, Cylinder, Cone, MultiSphere, ConvexMesh, ScaledBox, ScaledHull, UniformCapsule,
    // setLocalScaling on each: 0.7 along a capsule's, cylinder's or cone's axis and 1.3 across,
    // (1.5, 0.7, 1.2) on a sphere and a multi-sphere (Bullet's own rule per shape: a capsule
    // scales its radius by one radial axis, a cone by the mean of the two, a sphere by x)
    ScaledCapsule, ScaledCylinder, ScaledCone, ScaledSphere, ScaledMultiSphere
};

// One body of `kind` (up axis `axis` for capsules, cylinders and cones) dropped from `height`
// onto a box ground, turned by `tilt` rad about z (pi/2 lays a y-axis capsule on its side).
ScenePtr convexLanding(WorldKind kind, ConvexKind shape, int axis, double tilt, double height,
                       const Config& config = Config::bulletMode());
// A cylinder (radius 0.5, half height 0.5, axis z) rolling down a box ramp tilted 15 degrees.
ScenePtr cylinderRamp(WorldKind kind, const Config& config = Config::bulletMode());
// 12 mixed convex bodies (capsules, cylinders, cones, a multi-sphere, a convex mesh, boxes,
// spheres) dropped in a loose column onto the ground.
ScenePtr convexPile(WorldKind kind, const Config& config = Config::bulletMode());

}  // namespace btgpu::scenes
