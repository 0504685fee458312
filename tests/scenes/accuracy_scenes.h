// accuracy_scenes.h — the reference scenes of btgpu_accuracy: scenes with a known answer
// (analytic trajectory, stopping distance, bounce apexes, conserved momentum, exact rest),
// built as many far-apart copies in one world so a step costs something on a GPU, and the
// 1,000-box pile whose layout the double-precision reference program builds too.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "scenes/scenes.h"

namespace btgpu::scenes {

// A built accuracy scene: the world plus what its error measure needs to know.
struct AccuracyScene {
    ScenePtr scene;
    int copies = 1;
    int bodiesPerCopy = 1;  // dynamic bodies per copy, consecutive in scene.bodies() after the ground
    int firstBody = 0;      // index in scene.bodies() of the first dynamic body (0 or 1: the ground)
    // Resting contacts as (upper, lower) scene body indices, lower -1 for the ground (top y = 0);
    // each box has half extent 0.5 in y. Only resting scenes fill it.
    std::vector<std::pair<int, int>> supports;
};

// Copies sit on a square grid this far apart (m). Not 50 m: 1,000 copies at 50 m reach ±800 m,
// where a float position resolves only 6e-5 m, the size of the errors some scenes measure.
constexpr double kCopySpacing = 12.0;

// Boxes (half extent 0.5) released at y = 30, at rest; 2 s of free fall, no ground.
AccuracyScene accuracyFreeFall(WorldKind kind, const Config& config, int copies);
// Spheres (radius 0.5) thrown from y = 10 at (5, 10, 0) m/s from x = -5 of their cell; no ground.
AccuracyScene accuracyProjectile(WorldKind kind, const Config& config, int copies);
constexpr double kProjectileSpeed[3] = {5.0, 10.0, 0.0};  // m/s
// Unit boxes resting on the ground (friction 1) with friction 0.5, given 5 m/s along x.
AccuracyScene accuracySlidingBox(WorldKind kind, const Config& config, int copies);
constexpr double kSlideSpeed = 5.0;     // m/s
constexpr double kSlideFriction = 0.5;  // box 0.5 x ground 1
// Spheres (radius 0.5, restitution 0.5 on a ground of restitution 1) released with centre at y = 5.
AccuracyScene accuracyBouncingSphere(WorldKind kind, const Config& config, int copies);
constexpr double kBounceDropY = 5.0, kBounceRadius = 0.5, kBounceRestitution = 0.5;
// Boxes of half extents (1, 0.5, 0.25), no gravity, spinning at kTumbleRate about an axis
// 0.01 rad off y (the intermediate principal axis): they flip periodically (Dzhanibekov).
AccuracyScene accuracyTumblingBox(WorldKind kind, const Config& config, int copies);
constexpr double kTumbleRate = 5.0;  // rad/s
// `height` unit boxes stacked exactly touching on the ground.
AccuracyScene accuracyStack(WorldKind kind, const Config& config, int copies, int height = 10);
// A 2-D pyramid of unit boxes, `base` boxes in its bottom row, rows 5 cm apart side to side
// (so only vertical faces of neighbours never touch), each row exactly resting on the one below.
AccuracyScene accuracyPyramid(WorldKind kind, const Config& config, int copies, int base = 20);
// The chaotic pile (see pileLayout), one copy, on a ground of half extent 50 (friction 0.5 x 0.5).
AccuracyScene accuracyPile(WorldKind kind, const Config& config, int nx, int ny, int nz);

// --- the pile's layout, Bullet-free so btgpu_accuracy_reference (double Bullet) builds the
// same bodies. Boxes of half extent 0.5, mass 1, friction 0.5, restitution 0. ---
struct PileBody {
    double position[3];
    double rotation[4];  // quaternion x, y, z, w
};
// nx*ny*nz boxes on a lattice of pitch 1.5, odd layers shifted half a pitch, each turned by a
// fixed pseudo-random rotation of up to 0.3 rad and moved up to 0.1 m (never overlapping): they fall into a heap
// whose details depend chaotically on everything (hence a statistical comparison).
inline std::vector<PileBody> pileLayout(int nx, int ny, int nz)
{
    std::vector<PileBody> out;
    std::uint32_t state = 12345u;
    auto uniform = [&state]() {  // in [-1, 1): a fixed LCG so both programs get the same numbers
        state = state * 1664525u + 1013904223u;
        return double(state >> 8) / double(1u << 23) - 1.0;
    };
    const double pitch = 1.5;
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x)
            for (int z = 0; z < nz; ++z) {
                const double shift = (y % 2) ? 0.5 * pitch : 0.0;
                PileBody b;
                b.position[0] = pitch * (x - 0.5 * (nx - 1)) + shift + 0.1 * uniform();
                b.position[1] = 1.0 + pitch * y;
                b.position[2] = pitch * (z - 0.5 * (nz - 1)) + shift + 0.1 * uniform();
                double axis[3] = {uniform(), uniform(), uniform()};
                const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]) + 1e-12;
                const double half = 0.15 * uniform();  // half the angle: up to 0.3 rad
                for (int k = 0; k < 3; ++k) b.rotation[k] = std::sin(half) * axis[k] / len;
                b.rotation[3] = std::cos(half);
                out.push_back(b);
            }
    return out;
}
constexpr double kPileFriction = 0.5;
constexpr double kPileGroundHalfExtent = 50.0;

}  // namespace btgpu::scenes
