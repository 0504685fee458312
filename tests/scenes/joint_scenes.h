// joint_scenes.h — scenes with joints (issue 11), defined once for the tests, bench and demos:
// a pendulum, a hanging chain, a breaking joint, a jointed pair that falls asleep.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes {

// A sphere bob (radius 0.1, mass 1) on a btPoint2PointConstraint to Bullet's fixed body at
// (0, 5, 0), 1 m below the pivot, released at `degrees` from the vertical (in the x-y plane).
// No ground: the plan has no contact stages.
ScenePtr pendulum(WorldKind kind, const Config& config = Config::bulletMode(), double degrees = 30.0);
constexpr double kPendulumLength = 1.0;  // m
constexpr double kPendulumPivotY = 5.0;  // m

// `links` spheres (radius 0.05, mass 1) hanging 0.2 m apart below a static anchor box at
// y = 6 (body 1), each joined to the one above by a btPoint2PointConstraint at the midpoint;
// a ground box (body 0) far below. Starts at rest, exactly unstretched.
ScenePtr chain(WorldKind kind, const Config& config = Config::bulletMode(), int links = 20);
constexpr double kChainPitch = 0.2;   // m between link centres
constexpr double kChainAnchorY = 6.0;  // m, the anchor's centre (links start 0.2 below)

// The pendulum released horizontally (90°), its joint given a breaking impulse threshold of
// `threshold` N s: at the bottom of the swing the joint impulse per step is about
// m (g + v^2 / L) dt = 3 m g dt (0.5 N s), so thresholds below that break during the swing.
ScenePtr breakingPendulum(WorldKind kind, const Config& config = Config::bulletMode(), double threshold = 0.3);

// Two unit boxes (mass 1) side by side on a ground box, joined by a btPoint2PointConstraint
// at their touching faces' centre, released 1 cm above the ground: they land and fall asleep.
ScenePtr jointedPair(WorldKind kind, const Config& config = Config::bulletMode());

// A door (box of half extents 0.5, 1, 0.05; mass 5) hinged to Bullet's fixed body along the
// vertical line x = 0, z = 0 at its edge (body 1; a ground box below, body 0), driven by its
// angular motor at `speed` rad/s (max impulse `maxImpulse` N m s per step), limited to
// [lower, upper] rad when upper >= lower.
ScenePtr hingeDoor(WorldKind kind, const Config& config = Config::bulletMode(), double speed = 1.0, double maxImpulse = 0.5,
                   double lower = 1.0, double upper = -1.0);

// Two wheels (cylinders of radius 0.5, half height 0.1, mass 2, their axes vertical) hinged to
// Bullet's fixed body at x = -1 and x = +1.2, 2 m up (bodies 0 and 1), coupled by a
// btGearConstraint of `ratio` about their vertical axes (joint 2; joints 0 and 1 the hinges).
// Wheel 0 is driven by its hinge motor at `speed` rad/s (max impulse 1 N m s a step) when
// `speed` is not 0, else it starts spinning at 3 rad/s, free; the gear turns wheel 1 at
// -w0 / ratio (Bullet's gear row: axisA . wA + ratio axisB . wB = 0).
ScenePtr gearPair(WorldKind kind, const Config& config = Config::bulletMode(), double ratio = 2.0, double speed = 2.0);

// `count` ragdolls of scene_specs' makeRagdolls (11 capsules, 5 hinges, 5 cone-twists each, added
// with disableCollisionsBetweenLinkedBodies) dropping onto a ground box; the benchmark's scene.
ScenePtr ragdolls(WorldKind kind, const Config& config = Config::bulletMode(), int count = 4);

// btFixedConstraint (a btGeneric6DofSpring2Constraint with every axis locked): a box
// (half extents 0.2, mass 2; body 2) held 0.6 m beside a static anchor box at (0, 3, 0)
// (body 1) by a joint at their midpoint, a cantilever under gravity; and two boxes (mass 1 and
// 3; bodies 3 and 4) fixed side by side, released 0.5 m above the ground box (body 0).
ScenePtr fixedBoxes(WorldKind kind, const Config& config = Config::bulletMode());

// A btGeneric6DofSpring2Constraint from Bullet's fixed body to a box (half extents 0.3, 0.1,
// 0.2; mass 2; at (0, 2, 0)) with mixed axes: linear x limited to [-0.3, 0.3] and driven by its
// motor at 0.5 m/s (max 40 N), linear y and z locked, angular x and y locked, angular z free and
// driven by its motor at `spin` rad/s (max 3 N m), in rotation order `order` (RotateOrder). The
// motors move body B (the box) at -target against body A (the fixed body).
ScenePtr sixDofMotors(WorldKind kind, const Config& config = Config::bulletMode(), double spin = 2.0, int order = 0);

// btGeneric6DofSpring2Constraint springs from Bullet's fixed body, every other axis locked:
// body 0 a box (half extents 0.3, 0.1, 0.2; mass 2) at (0, 2, 0) on a linear y spring of
// `linStiffness` N/m (damping 0.2 N s/m, equilibrium 0.3 m below its start: it falls into the
// spring and bounces under gravity); body 1 the same box at (2, 2, 0) on an angular z spring
// of `angStiffness` N m/rad (damping 0.005, equilibrium 0.8 rad: it starts 0.8 rad off), its
// moment about z 1/15 kg m^2. `limited`: setStiffness/setDamping's limitIfNeeded.
ScenePtr sixDofSprings(WorldKind kind, const Config& config = Config::bulletMode(), double linStiffness = 200.0,
                       double angStiffness = 5.0, bool limited = true);

// btGeneric6DofSpring2Constraint servos from Bullet's fixed body (box of sixDofMotors, at
// (0, 2, 0)): linear x ranged [-0.5, 0.5] to servo target 0.2 m at 0.5 m/s (max 40 N), angular
// z free to servo target `angle` rad at 2 rad/s (max 3 N m), the rest locked.
ScenePtr sixDofServos(WorldKind kind, const Config& config = Config::bulletMode(), double angle = 1.0);

// btHinge2Constraint suspensions as constructed (spring on its linear z, 4 pi^2 N/m; limits,
// steering range) with a damper of 1 N s/m (setDamping(2, 1)): a chassis box (half extents 1,
// 0.1, 0.5; mass 4; body 1) 0.6 m above four sphere wheels (radius 0.25, mass 0.5; bodies
// 2..5) resting on a ground box (body 0) at (+-0.8, 0.25, +-0.5), each joined at its centre
// (axis 1 up, axis 2 the axle along z); the chassis sinks onto its springs and settles (about
// 0.25 m lower) without reaching the ground.
ScenePtr hinge2Wheels(WorldKind kind, const Config& config = Config::bulletMode());

// btGeneric6DofConstraint (the old one) from Bullet's fixed body to the box of sixDofMotors
// (body 0, at (0, 2, 0)): linear x limited to [-0.3, 0.3] and driven by its motor at 0.5 m/s
// (max 40 N), linear y and z locked, angular x and y locked, angular z free and driven at `spin`
// rad/s (max 3 N m); `frameOffset`: setUseFrameOffset (Bullet's default on).
ScenePtr generic6DofMotors(WorldKind kind, const Config& config = Config::bulletMode(), double spin = 2.0,
                           bool frameOffset = true);

// A btUniversalConstraint pendulum: a box (half extents 0.1, 0.4, 0.1; mass 1; body 1) hanging
// from a static anchor box at (0, 3, 0) (body 0) by a universal joint at (0, 2.9, 0) with axis 1
// along x and axis 2 along z, released turned 0.5 rad about x and 0.3 about z and spinning
// about y (which the joint locks): it swings about both axes.
ScenePtr universalPendulum(WorldKind kind, const Config& config = Config::bulletMode());

// btGeneric6DofSpringConstraint springs from Bullet's fixed body, every other axis locked: body
// 0 a box (sixDofSprings' box) at (0, 2, 0) on a linear y spring of `linStiffness` N/m, body 1
// at (2, 2, 0) on an angular z spring of `angStiffness` N m/rad, both with setDamping
// `damping` (1: none), equilibria 0.3 m below and 0.8 rad off the start; no gravity.
ScenePtr generic6DofSprings(WorldKind kind, const Config& config = Config::bulletMode(), double linStiffness = 200.0,
                            double angStiffness = 5.0, double damping = 1.0);

// A btConeTwistConstraint with its motor on, without gravity: a cube (half extent 0.2; mass 2;
// body 1) below a static anchor box at (0, 3, 0) (body 0), joined at its top face, the joint
// frames' twist axis x pointing down, limits setLimit(0.8, 0.8, 0.5), driven to
// coneMotorTarget() (in constraint space: a swing of 0.4 rad about z and a twist of 0.3 rad)
// with setMaxMotorImpulse(0.02) N m s; `variant` 1 sets setMaxMotorImpulseNormalized(0.02),
// setAngularOnly and setDamping(0.2) instead, which 3.24's getInfo2 does not read (only the
// obsolete solve does).
ScenePtr coneTwistMotor(WorldKind kind, const Config& config = Config::bulletMode(), int variant = 0);
btQuaternion coneMotorTarget();

// Bullet's BenchmarkDemo test 3 (createTest3): RagdollDemo ragdolls at scale 3.5 made of
// capsules (scene_specs' ragdollLayout), in a pyramid of `rows` rows (16: 136 ragdolls, 1,496
// bodies, 1,360 joints): row r (0-based) holds rows - r ragdolls 6 m apart along x, centred,
// at y = 1 + 7 r and z = -2 r; each part mass 1, damping 0.05 / 0.85, deactivation time 0.8,
// sleeping thresholds 1.6 / 2.5; a ground box of half extents 250, 50, 250 at y = -50 (body 0);
// 5 solver iterations. The demo also sets SOLVER_ENABLE_FRICTION_DIRECTION_CACHING, which in
// Bullet 3.24 changes only anisotropic friction's directions (README, btContactSolverInfo): left
// off here (on both worlds).
ScenePtr bench3Ragdolls(WorldKind kind, const Config& config = Config::bulletMode(), int rows = 16);

// Bullet's own ExtendedTutorials/NewtonsCradle example: `count` pendula, each a sphere of radius
// 1 (mass 1) pinned at its centre by a btPoint2PointConstraint at y = 15 and a second sphere 8
// below it, held by a btSliderConstraint whose limits are all 0 (a rigid rod); the pendula 2.1
// apart along -x (0.1 gaps), the lower spheres frictionless with restitution 1, deactivation off,
// gravity -10. Body 2 i is pendulum i's top sphere, 2 i + 1 its lower one (the example pushes
// pendulum 0 with 30 N while a key is held).
ScenePtr newtonsCradle(WorldKind kind, const Config& config = Config::bulletMode(), int count = 5);

}  // namespace btgpu::scenes
