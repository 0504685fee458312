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
}  // namespace btgpu::tol
