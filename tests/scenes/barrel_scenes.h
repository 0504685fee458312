// barrel_scenes.h — hull barrels (16-sided prisms) dropped nearly upright onto a box ground, far
// apart: whether a barrel ends standing depends on how the first impact is resolved (one rim
// point first, as a small time step resolves it, or the whole base at once), so the standing
// fraction tests the contact generation of hull pairs against stock and against small steps.
#pragma once
#include "scenes/scenes.h"

namespace btgpu::scenes {

struct BarrelDrop {
    int count = 100;             // barrels, on a square grid kBarrelPitch apart
    double maxTiltDegrees = 5.0; // each barrel's axis tilted by up to this (uniform, fixed seed)
    double dropHeight = 5.0;     // m: bottom rim's height above the ground at release (plus 5 cm)
    bool polyhedral = false;     // the app calls initializePolyhedralFeatures on hull and ground
};
constexpr int kBarrelSides = 16;
constexpr double kBarrelRadius = 0.4;      // m, of the vertices
constexpr double kBarrelHalfHeight = 0.6;  // m
constexpr double kBarrelPitch = 3.0;       // m

// The ground box (half extent 50, top at y = 0) is body 0; barrels follow, mass 1, friction 0.5.
ScenePtr barrelDrop(WorldKind kind, const Config& config = Config::bulletMode(), const BarrelDrop& drop = BarrelDrop());
// Fraction of the barrels whose axis is within `degrees` of vertical.
double uprightFraction(const Scene& scene, double degrees = 20.0);

}  // namespace btgpu::scenes
