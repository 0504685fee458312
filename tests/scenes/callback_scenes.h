// callback_scenes.h — scenes for Bullet's contact callbacks (gContactAddedCallback and the
// manifold events): a ball over a trampoline box (the box has CF_CUSTOM_MATERIAL_CALLBACK, the
// app's callback gives its contacts their restitution) and a box sliding over a flagged floor
// (the callback sets the friction), and a box sliding over a triangle mesh's internal edges. The callbacks themselves are the app's globals, set by the
// test on both worlds alike.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes {

// Body 0: a static 3 x 0.25 x 3 m half-extent box with its top at y = 0 and
// CF_CUSTOM_MATERIAL_CALLBACK; body 1: a ball (radius 0.5, mass 1, restitution 0, friction 0.5)
// released at rest with its centre at y = dropHeight.
ScenePtr trampoline(WorldKind kind, const Config& config = Config::bulletMode(), btScalar dropHeight = 3);
// Body 0: a static 20 m half-extent box ground (top at y = 0) with CF_CUSTOM_MATERIAL_CALLBACK;
// body 1: a 0.5 m half-extent box (mass 1, friction 1) resting on it, given 4 m/s along x.
ScenePtr slidingBox(WorldKind kind, const Config& config = Config::bulletMode());
// Body 0: a static flat triangle-mesh ground (16 x 16 quads of 1 m, gridMesh) whose internal
// edges Bullet's btGenerateInternalEdgeInfo has recorded, with CF_CUSTOM_MATERIAL_CALLBACK (an
// app's callback calls btAdjustInternalEdgeContacts); body 1: a 0.5 m half-extent box resting on
// it at x = -6, given 5 m/s along x, so it slides over many internal edges.
ScenePtr edgeSlide(WorldKind kind, const Config& config = Config::bulletMode());
// Body 0: the ground box; body 1: a 0.5 m half-extent box resting on it (user index 8); body 2:
// the same box released 3 m above it (user index 7), for an overlap filter that refuses the pair.
ScenePtr boxOverBox(WorldKind kind, const Config& config = Config::bulletMode());
// Capsules (support-function shapes: a persistent manifold adding one point a step, as stock's
// convex–convex algorithm): body 0 the trampoline's flagged pad, body 1 an upright capsule
// (radius 0.3, half height 0.5, angular factor 0) released with its centre at y = 3.
ScenePtr capsuleTrampoline(WorldKind kind, const Config& config = Config::bulletMode());
// Body 0 a flagged 20 m half-extent ground box; 12 capsules (radius 0.25, 1.5 m long) in three
// crossed layers of four falling onto it.
ScenePtr capsulePile(WorldKind kind, const Config& config = Config::bulletMode());
// edgeSlide's flagged internal-edge mesh with an upright capsule (angular factor 0) resting on it
// at x = -6, given 5 m/s along x.
ScenePtr capsuleEdgeSlide(WorldKind kind, const Config& config = Config::bulletMode());

}  // namespace btgpu::scenes
