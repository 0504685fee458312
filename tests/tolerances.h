// tolerances.h — every numeric bound the tests use, in one place, with its reason.
#pragma once
#include <cmath>

namespace btgpu::tol {
// Float stages against their CPU reference: same formulas, contraction off on both sides;
// only sqrt/sin/cos/divide may round differently on the device (OpenCL allows a few ulp).
constexpr float kStageAbs = 1e-4f;       // m or m/s, for quantities of order 1
constexpr float kStageRel = 1e-4f;
// Contact sets: points may be ordered differently and a clip corner moves with rounding.
constexpr float kContactPoint = 1e-3f;   // m
constexpr float kContactDepth = 1e-4f;   // m
constexpr float kNormalDot = 0.9999f;    // cosine between normals
// A GPU contact routine against Bullet's own algorithm run in the test for the same pose
// (issue 10's bounds): the deepest point's normal within 1 degree, its depth within 1 mm.
constexpr float kStockNormalDot = 0.99984770f;  // cos(1 degree)
constexpr float kStockDepth = 1e-3f;            // m

// --- regression: btGpuDynamicsWorld against stock btDiscreteDynamicsWorld, same scene --------
// Free fall has no contacts: both integrate v += g dt, x += v dt in float; only summation order
// and rounding differ, which stays far below 0.1 mm over 120 steps from heights of ~30 m.
constexpr double kFreeFallPosition = 1e-4;   // m
// Bodies at rest on the ground or landed flat: the GPU solver (batched, not Bullet's serial
// order) may settle a contact at a slightly different penetration; 1 mm is well inside the
// contact slop Bullet itself keeps (ERP pushes out only part of the penetration per step).
constexpr double kRestHeight = 1e-3;         // m
// A box landing flat after a vertical impulse: stock's box-box manifold tips it (0.05 rad)
// and it slides ~1.3 cm sideways; a landing that stays put is no worse. The GPU box's
// sideways drift may not exceed stock's by more than this.
constexpr double kExtraDrift = 1e-3;         // m
// A box held on a slope inside its friction cone creeps a fraction of a millimetre in seconds
// (PGS friction converges incompletely; friction anchors pull it back): the GPU path's creep
// within this of stock's.
constexpr double kAnchorCreep = 1e-4;        // m
// A box sliding 0.2-1 m to rest with friction anchors (kept points drag it back): where it stops
// within this of stock's.
constexpr double kAnchorSlide = 1e-3;        // m
// A box or sphere placed at rest on a flat mesh or heightfield stays where it is: on both
// engines at most a few mm of sideways drift over 2 s (one GJK point a triangle a frame, kept in
// a persistent manifold); 1 cm bounds it. Bodies that land rock further on both: judged against
// stock's own chaos (mesh_test.cpp, expectDriftWithinStocksChaos).
constexpr double kMeshDrift = 0.01;          // m
// m: a body's rest height against stock's on a mesh, where either may rest on one GJK point a
// triangle a few mm deep (stock's btConvexConcaveCollisionAlgorithm, followed by both)
constexpr double kMeshRestHeight = 0.005;
// A bounce's apex depends on the impact speed at the step the contact appears and on the
// restitution threshold: 5 % of stock's apex.
constexpr double kBounceApexRel = 0.05;
// A cylinder rolling down a ramp: distance travelled in 3 s against stock's (issue 10).
constexpr double kRollDistanceRel = 0.05;
// The same rollers in the soft step (SolverKind::SoftStep: not stock's solver; its rolling rows
// act once a substep from zero where stock's iterate ten times a step): distance and stopping
// step against stock's. Measured: sphere +0.7 %, capsule +4.8 % (its two points share the
// load otherwise through the substeps).
constexpr double kSoftRollDistanceRel = 0.10;
// A box sliding with anisotropic friction in the soft step (its friction rows along Bullet's
// scaled directions, solved once a substep in the relax): travel against stock's. Measured: one
// direction 0.4-0.5 %; two directions (SOLVER_USE_2_FRICTION_DIRECTIONS: the scaled directions
// are not orthogonal, and the two bounded rows settle into another corner than stock's ten
// sequential iterations) 0.5 % on the slab, 5.2 % on the ground.
constexpr double kSoftSlideDistanceRel = 0.10;
// m: how much further than stock's a box at rest on a slope inside its friction cone may creep
// in the soft step in 4 s (SolverFeatures.SoftStepHoldsABoxOnASlope). Measured: 0.01-0.07 mm
// (stock 0.01-0.77 mm); without the friction's warm start across steps 1.4-17.5 mm.
constexpr double kSoftSlopeCreep = 0.0005;
// A stack of two boxes resting on such a slope (SolverFeatures.SoftStepHoldsAStackOnASlope): the
// share of stock's downhill travel in 4 s the soft step's boxes may creep. Its friction between
// two dynamic bodies starts at zero each step (warm-started, even at half or as the points' mean,
// it rocks the exact towers of 20 and 30), so the top box creeps in each step's first substep.
// Measured at 0.1 / 0.2 rad: lower box 0.56 / 0.93 mm, top 4.9 / 10.9 mm; stock 28 / 278 and
// 130 / 1,083 mm: 0.3-4% of stock's.
constexpr double kSoftStackCreepOfStock = 0.1;
// Relative: how far the soft step's box tumbling near its intermediate axis (no contacts, 2 s) may
// end from the bullet mode's and stock's, in rotational energy drift and in angular velocity
// (SoftStepMotion.TumblingBoxTurnsAsTheBulletMode). Measured over 2 s: stock -0.030488, the bullet
// mode and the soft step -0.030481; with the forces' angular change shared out over the substeps
// (before 2026-12-05) the soft step's -0.064084.
constexpr double kSoftFreeTurnEnergy = 0.002;
// A sphere slowed by spinning friction: its time to spin down, relative to stock's.
constexpr double kSpinDownRel = 0.05;
// A box resting on a soft contact (contact stiffness and damping, or m_globalCfm): its depth,
// relative to stock's.
constexpr double kSoftDepthRel = 0.05;
// A stack of 8 unit boxes must not creep: the top box moves less than this in 5 s (on both).
constexpr double kStackDrift = 0.05;         // m
// A compound table at rest stays level: a 1.2 m top tipped by this is 2.4 mm higher at one end
// (measured: 0.00035 rad on the third of three stacked tables, stock 0.00049).
constexpr double kRestTilt = 2e-3;           // rad
// A resting compound keeps its place beside stock's (sideways and up).
constexpr double kRestPlace = 0.01;          // m
// Stock's own chaos (tests/scenes/stock_chaos.h), the yardstick for chaotic scenes: stock run
// kChaosRuns times with every dynamic body's start nudged by up to kChaosNudge (fixed seeds);
// btgpu's aggregate must lie within kChaosFactor x the largest stock-to-stock distance, plus the
// aggregate's stated floor, of the stock mean. One stock run is one chance outcome: BasicDemo's
// resting mean height is 0.205 unnudged, 0.129-0.178 over eight nudges of 0.1 mm.
constexpr int kChaosRuns = 8;
constexpr double kChaosNudge = 1e-4;         // m, on each axis
constexpr double kChaosFactor = 3.0;
// Floors of the aggregates, for scenes whose stock runs happen to agree closely: 1 cm of mean
// height or horizontal spread, 1e-3 J of kinetic energy, one body in 100 standing.
constexpr double kChaosHeightFloor = 0.01;   // m
constexpr double kChaosSpreadFloor = 0.01;   // m
constexpr double kChaosEnergyFloor = 1e-3;   // J
constexpr double kChaosStandingFloor = 0.01;
// btgpu_compare (demos/compare) also bands, against the same stock runs: the number of touching
// pairs (manifolds with points; 2, as a pair starts or stops touching a step earlier on either
// side of the threshold), the fraction of bodies at rest (one in 100, as standing) and each
// body's position (1 cm, as the mean height).
constexpr double kChaosContactsFloor = 2.0;
constexpr double kChaosAtRestFloor = 0.01;
constexpr double kChaosPositionFloor = 0.01;  // m
// BenchmarkDemo test 2's round tower: its boxes' mean drift from the tower's axis, and the top
// ring's. 5 mm: stock's own nudged runs spread by about 1 mm; the friction sweep after every
// contact's normals (Bullet's order) is what keeps btgpu there (35 mm outward without it).
constexpr double kChaosRadialFloor = 0.005;  // m
// No box centre of BasicDemo's pile more than 2 cm below its resting height (half extent 0.1),
// i.e. sunk into the ground.
constexpr double kSinkDepth = 0.02;          // m
// Boxes pushed by a kinematic box slide with friction; small differences in when contacts
// appear grow into centimetres: 10 cm of stock's positions.
constexpr double kPushedPosition = 0.1;      // m
// Motion-state transforms with substeps and interpolation (no contacts): as free fall.
constexpr double kInterpolatedTransform = 1e-4;  // m, and per matrix element of the basis

// --- joints (tests/regression/joints_test.cpp) ---------------------------------------------
// The bounds: a pendulum's period within 1 % of stock's; a 20-link chain's stretch
// within 5 % of stock's plus 1 mm.
constexpr double kPendulumPeriodRel = 0.01;
constexpr double kChainStretchRel = 0.05;
constexpr double kChainStretchAbs = 1e-3;   // m
// Against physics, with the joint's rows converged (100 iterations): the period within 1 % of
// the physical pendulum's series (measured 0.25 % on both engines), the arm within 5 mm of its
// length through the swing (measured 1.7 mm; ERP 0.2 corrects the drift).
constexpr double kPendulumPhysicsRel = 0.01;
constexpr double kJointDrift = 5e-3;        // m
// A chain at rest: links hang with no speed to speak of (mm/s).
constexpr double kChainStillSpeed = 5e-3;   // m/s
// One joint without contacts: the same rows as stock in another float order; the bob stays
// within 1 mm of stock's and its impulses within 1 %.
constexpr double kJointPosition = 1e-3;     // m
constexpr double kJointImpulseRel = 0.01;
// A pair falls asleep within this many steps of stock's (the GPU island timer takes the
// least of the pair's timers, stock's the island's; settling differs by a step or two).
constexpr double kSleepStepSlack = 10;
// Two bodies whose contact (20 cm deep) fights their joint: the outcome hangs on the solver's
// contact order and split impulse, which the batched solve does not share with stock; 3 cm.
constexpr double kJointContactFight = 0.03;  // m
// The hinge bounds: a motor reaches its target speed within 2 % in 1 s; a door stops
// within 1 degree of its limit (and of stock's angle).
constexpr double kMotorSpeedRel = 0.02;
constexpr double kHingeLimitAngle = M_PI / 180.0;  // rad
// The slider bound: a slider driven into its limit stops within 1 mm of it.
constexpr double kSliderLimit = 1e-3;  // m
// A stretched 20-link chain cut in the middle recoils, and a joint re-enabled 0.5 m off its
// pivot snaps shut in a few steps; in those transients the batched solve and stock's serial
// order part by up to 1.5 cm (measured; the same with the whole joint table uploaded).
constexpr double kJointSnap = 0.03;  // m
// Ragdolls landing in a heap are chaotic (which limb lands first decides the sprawl): their
// mean centre height within 3 cm of stock's (measured 0.137 stock, 0.132 btgpu); no joint's
// frames further apart at any step than 3 cm or twice stock's worst (at impact the 10
// iterations let both stretch a joint 8.4 cm).
constexpr double kRagdollMeanHeight = 0.03;  // m
constexpr double kRagdollJointGap = 0.03;    // m
}  // namespace btgpu::tol

// --- stability suite (tests/stability/): both engines judged by the same bounds -------------
namespace btgpu::tol {
// At rest: kinetic energy per kilogram of dynamic mass (J/kg); 1e-4 is an rms speed of ~1.4 cm/s,
// well above the jitter of a settled Bullet stack and far below anything a viewer sees move.
constexpr double kSettledKePerMass = 1e-4;
// Penetration at rest, as a fraction of the smallest body dimension (the 1 %).
constexpr double kPenetrationFraction = 0.01;
// Stack tops may drift this fraction of the box size (the 5 %).
constexpr double kTopDriftFraction = 0.05;
// The long resting 8-box stack: the top moves less than 1 cm (the bound), and the total
// energy (kinetic + potential, g = 10) never exceeds its start by more than 1e-3 of m g L of the
// stack (8 boxes x 1 kg x 10 x 1 m): every box lifted by 1 mm at once, far above float rounding.
constexpr double kLongRestDrift = 0.01;  // m
constexpr double kEnergyRise = 0.08;     // J
// Boxes released overlapping by 25 % must separate without being shot out: no body above 5 m/s.
constexpr double kSeparationSpeed = 5;   // m/s
// The same small pile at the origin and at (1e4, 0, 1e4): positions relative to the pile's origin
// agree within 5 % of the box size (float spacing there is ~1 mm, so this is no rounding bound).
constexpr double kFarPileAlike = 0.05;   // m
}  // namespace btgpu::tol
