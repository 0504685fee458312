// stability_scenes.h — the stiff and extreme scenes of the stability suite (tests/stability/):
// mass ratios, towers, pyramids, deep initial overlap, fast small bodies, extreme scales and
// far-from-origin piles, and the "beyond reason" scenes. Built on Scene, like scenes.h, so each
// runs on stock Bullet and on btgpu alike. Every ground is a static box whose top face is at
// y = origin.y (0 unless said); gravity is (0, -10, 0).
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes::stability {

// A unit box (half extent 0.5) of mass 1 on the ground, and on it a unit box of mass `topMass`.
ScenePtr massRatio(WorldKind kind, const Config& config, btScalar topMass);
// A plank of half extents 10 x 0.5 x 10 and mass 400 resting on two unit boxes of mass 1 at
// x = -8 and x = +8 (body 1, 2: the supports; body 3: the plank).
ScenePtr heavyPlank(WorldKind kind, const Config& config);
// `count` unit boxes stacked exactly touching; with `offset` each is shifted in x and z by
// +-offset (a fixed pseudo-random pattern), as boxes placed by hand would be.
ScenePtr tower(WorldKind kind, const Config& config, int count, btScalar offset = 0);
// A 2-D pyramid (in the x-y plane) of unit boxes, `base` boxes in the bottom row. `pitch` is the
// distance between neighbours, along x within a row and along y between rows: 1 is exactly
// touching, 0.75 makes neighbours overlap by 25 % of the box size. The bottom row touches the ground.
ScenePtr pyramid(WorldKind kind, const Config& config, int base, btScalar pitch = 1);
// A sphere of radius 0.05 (mass 1, body 1) at x = -1 moving at `speed` along +x towards a static
// wall 0.2 thick (half extents 0.1 x 5 x 5, centred on the origin, body 0). No ground.
ScenePtr bulletVsWall(WorldKind kind, const Config& config, btScalar speed = 50);
// Three boxes of edge `size` (mass 1) stacked exactly on a ground large enough for them.
ScenePtr scaledStack(WorldKind kind, const Config& config, btScalar size);
// A small pile of unit boxes around `origin` (a ground box under it, top face at origin.y): a
// 2x2 layer and one box on top, each released 5 cm above where it rests.
ScenePtr smallPile(WorldKind kind, const Config& config, const btVector3& origin);
// A unit box (mass 1) released at y = 5 moving straight down at `speed`.
ScenePtr fastDrop(WorldKind kind, const Config& config, btScalar speed);
// `count` unit boxes (mass 1) all at the same spot, centre (0, 0.5, 0), on the ground.
ScenePtr onePlace(WorldKind kind, const Config& config, int count);

}  // namespace btgpu::scenes::stability
