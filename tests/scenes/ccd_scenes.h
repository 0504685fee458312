// ccd_scenes.h — scenes for Bullet's continuous collision detection (setCcdMotionThreshold,
// setCcdSweptSphereRadius): a fast ball shot at a thin wall it would pass through in one step,
// and the same ball in free flight with nothing to hit.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes {

// Body 0: a static 50 m half-extent ground box (top at y = 0); body 1: a static wall 4 cm thick
// (half extents 0.02, 2, 2) at x = 5; body 2: a ball (radius 0.1, mass 1) at (0, 1, 0) moving at
// `speed` m/s along x (2 m a step at the default 120), CCD motion threshold 0.1, swept radius
// 0.08. With `wall` false there is no wall (body 1 is a far-off static box) and the ball starts
// 20 m up, clear of the ground for a second.
ScenePtr ballAtWall(WorldKind kind, const Config& config = Config::bulletMode(), btScalar speed = 120, bool wall = true);

}  // namespace btgpu::scenes
