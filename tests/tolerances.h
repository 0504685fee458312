// tolerances.h — every numeric bound the tests use, in one place, with its reason.
#pragma once

namespace btgpu::tol {
// Float stages against their CPU reference: same formulas, contraction off on both sides;
// only sqrt/sin/cos/divide may round differently on the device (OpenCL allows a few ulp).
constexpr float kStageAbs = 1e-4f;       // m or m/s, for quantities of order 1
constexpr float kStageRel = 1e-4f;
// Contact sets: points may be ordered differently and a clip corner moves with rounding.
constexpr float kContactPoint = 1e-3f;   // m
constexpr float kContactDepth = 1e-4f;   // m
constexpr float kNormalDot = 0.9999f;    // cosine between normals

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
// A bounce's apex depends on the impact speed at the step the contact appears and on the
// restitution threshold: 5 % of stock's apex.
constexpr double kBounceApexRel = 0.05;
// A stack of 8 unit boxes must not creep: the top box moves less than this in 5 s (on both).
constexpr double kStackDrift = 0.05;         // m
// BasicDemo's 125 boxes at rest (8 s, all asleep): the pile's mean height within 5 % of the
// range stock Bullet itself gives at 8, 10 and 12 iterations, and no box centre more than 2 cm
// below its resting height (half extent 0.1) — i.e. sunk into the ground. The block's collapse
// is chaotic: stock's resting mean height is 0.175 (8 iterations), 0.205 (10), 0.182 (12),
// 0.356 (20), 0.406 (two friction directions); one stock run is one chance outcome.
constexpr double kPileMeanHeightRel = 0.05;
constexpr double kSinkDepth = 0.02;          // m
// Boxes pushed by a kinematic box slide with friction; small differences in when contacts
// appear grow into centimetres: 10 cm of stock's positions.
constexpr double kPushedPosition = 0.1;      // m
// Motion-state transforms with substeps and interpolation (no contacts): as free fall.
constexpr double kInterpolatedTransform = 1e-4;  // m, and per matrix element of the basis
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
