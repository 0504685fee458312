// shape_checks.h — what the world reads off an app's collision shape without changing it: the
// check that its parameters are usable (finite, sensible sizes), and a fingerprint that tells
// when the app has changed the shape in place (setLocalScaling, setMargin, edited hull points)
// since the GPU tables were built.
#pragma once
#include <cstdint>
#include <string>

class btCollisionShape;
class btVector3;

namespace btgpu {

// "" when the shape's parameters can be simulated, else what is wrong with them (a NaN hull
// point, a negative radius, a size beyond kMaxShapeSize). Reads only: never runs Bullet code
// that computes on the shape's data.
std::string badShapeInput(const btCollisionShape* shape);

// Sizes (m) beyond this are refused: their squares would overflow float in the narrowphase.
constexpr float kMaxShapeSize = 1e18f;

// The unscaled points of a convex hull or point cloud shape (and their count), else nullptr.
const btVector3* hullPoints(const btCollisionShape* shape, int* count);

// A hash of everything the GPU tables take from the shape (type, scaling, margin, extents,
// radius, plane, hull points). Equal fingerprints: the tables still hold.
std::uint64_t shapeFingerprint(const btCollisionShape* shape);

}  // namespace btgpu
