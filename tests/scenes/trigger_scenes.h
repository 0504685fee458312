// trigger_scenes.h — bodies that are detected but not solved, as games use them: a static
// CF_NO_CONTACT_RESPONSE box (a trigger read through the dispatcher's manifolds) that bodies
// fall through, and kinematic bodies whose custom filter masks ask for kinematic–kinematic and
// kinematic–static pairs. Defined once for the regression tests.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes {

// A 50 m ground box (top at y = 0, body 0); a static 2 x 0.5 x 2 m half-extent box trigger with
// CF_NO_CONTACT_RESPONSE centred at y = 3 (body 1); bodies 2..7 dropped through it onto the
// ground (three 0.3 m spheres and three 0.4 m half-extent boxes, from 4.5 to 7 m, 1.5 m or more
// apart, the last straddling the trigger's edge); body 8 a dynamic 0.3 m sphere with CF_NO_CONTACT_RESPONSE dropped through
// the trigger and the ground; body 9 a box resting on the ground under the trigger from the start.
ScenePtr staticTrigger(WorldKind kind, const Config& config = Config::bulletMode());

// Kinematic bodies (DISABLE_DEACTIVATION) in filter group 64 meeting every group: body 0 a
// static 1 m half-extent box at the origin; bodies 1 and 2 kinematic 0.5 m half-extent boxes
// starting at x = -3 and x = +3 at y = 2 (above the static box), moved by
// sweepKinematics; body 3 a kinematic 0.4 m sphere sweeping through the static box.
ScenePtr kinematicSweep(WorldKind kind, const Config& config = Config::bulletMode());
// Moves the kinematic bodies of kinematicSweep to where they are at time t (s), through their
// motion states, as an app drives them: boxes 1 and 2 towards each other at 1 m/s (they meet
// at t = 2.5 and pass through each other), the sphere along x through the static box.
void sweepKinematics(Scene& scene, double t);

}  // namespace btgpu::scenes
