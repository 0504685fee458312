// solver_feature_scenes.h — scenes for the solver settings beyond the defaults (rolling and
// spinning friction, friction direction modes, soft contacts, relaxation and cfm, anisotropic
// friction): each a body or two on a static ground box whose top face is at y = 0, gravity
// (0, -10, 0). Body 0 is the ground, body 1 the body the setting is about.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes::features {

// A sphere of radius 0.5, mass 1, rolling along +x at `speed` m/s (angular velocity to match) on
// the ground; rolling friction `rolling` on the sphere (the ground's friction 0.5 combines with it).
ScenePtr rollingSphere(WorldKind kind, const Config& config, btScalar rolling = btScalar(0.05), btScalar speed = 1);
// A capsule (radius 0.3, half height 0.4) lying along z, rolling along +x at 2 m/s, rolling
// friction 0.05: a two-point manifold.
ScenePtr rollingCapsule(WorldKind kind, const Config& config);
// A sphere of radius 0.5, mass 1, resting on the ground and spinning about the vertical at 20
// rad/s; spinning friction `spinning` and a little rolling friction (0.01: 3.24 adds the
// torsional row only with rolling friction).
ScenePtr spinningSphere(WorldKind kind, const Config& config, btScalar spinning = btScalar(0.1));
// A unit box, mass 1, sliding at (2, 0, 2) m/s on the ground (friction 0.3 on both).
ScenePtr slidingBox(WorldKind kind, const Config& config);
// A unit box of mass 1 resting on the ground, contact stiffness `stiffness` N/m and damping
// `damping` N s/m on the box (setContactStiffnessAndDamping).
ScenePtr softBox(WorldKind kind, const Config& config, btScalar stiffness = btScalar(2000), btScalar damping = btScalar(20));
// A BenchmarkDemo-like pile: `side` x `side` x `side` unit boxes dropped in a loose lattice.
ScenePtr boxPile(WorldKind kind, const Config& config, int side = 5);
// A unit box with anisotropic friction (1, 1, 0.1) (CF_ANISOTROPIC_FRICTION), turned 30 degrees
// about y, sliding at (2, 0, 2) m/s (friction 0.5 on both).
ScenePtr anisotropicBox(WorldKind kind, const Config& config);
// Two anisotropic bodies touching: body 0 the ground; body 1 a static 6 x 0.5 x 6 m slab turned
// 0.35 rad about y with friction (1, 1, 0.2) on its own axes; body 2 anisotropicBox's box
// (friction (1, 1, 0.1), turned 30 degrees) resting on the slab, given (2, 0, 2) m/s.
ScenePtr anisotropicPair(WorldKind kind, const Config& config);
// Two unit boxes of mass 1 on the ground (or a sphere of radius 0.5 on top with `sphere`): body 1
// resting on it, body 2 `drop` m above resting on body 1, with contact processing threshold
// `threshold` (setContactProcessingThreshold; the pair of the two takes it, the ground's pair
// keeps the default).
ScenePtr thresholdStack(WorldKind kind, const Config& config, btScalar threshold, btScalar drop = 0,
                        bool sphere = false);
// A unit box of mass 1 at rest on a static 10 x 1 x 10 m slab tilted `angle` rad about z
// (friction 0.5 on both: 0.25 combined, a cone of atan 0.25 = 0.245 rad); with `anchor` the box
// has CF_HAS_FRICTION_ANCHOR; the box never sleeps and starts sliding downhill at `speed` m/s. Body 1 the slab, body 2 the box (body 0 a
// ground far below).
ScenePtr anchorSlope(WorldKind kind, const Config& config, btScalar angle, bool anchor, btScalar speed = 0);
// A stack of `boxes` unit boxes of 1 kg resting on the slab of anchorSlope (bodies 2, 3, ...),
// never deactivated.
ScenePtr slopeStack(WorldKind kind, const Config& config, btScalar angle, int boxes);

}  // namespace btgpu::scenes::features
