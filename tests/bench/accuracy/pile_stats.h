// pile_stats.h — the statistics the pile is compared by (mean height, deepest ground
// penetration, kinetic energy), header-only and templated on the body type so the float
// tool and the double-precision reference program compute them with the same code.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

namespace btgpu::accuracy {

struct PileStats {
    double meanHeight = 0;    // m, mean centre y of the dynamic bodies
    double penetration = 0;   // m, deepest box corner below the ground top (y = 0), 0 if none
    double kineticEnergy = 0; // J, translational + rotational, all bodies
};

// Bodies are boxes (btBoxShape); Body is btRigidBody of whichever precision is compiled.
template <class Body, class BoxShape>
PileStats pileStats(const std::vector<Body*>& bodies)
{
    PileStats s;
    int n = 0;
    for (const Body* b : bodies) {
        if (b->getInvMass() <= 0) continue;
        const auto& t = b->getWorldTransform();
        const auto& basis = t.getBasis();
        const auto half = static_cast<const BoxShape*>(b->getCollisionShape())->getHalfExtentsWithMargin();
        double reach = 0;  // how far the box extends below its centre
        for (int j = 0; j < 3; ++j) reach += std::fabs(double(basis[1][j])) * double(half[j]);
        s.penetration = std::max(s.penetration, reach - double(t.getOrigin().y()));
        s.meanHeight += double(t.getOrigin().y());
        const auto v = b->getLinearVelocity();
        const auto wLocal = b->getAngularVelocity() * basis;  // world -> body frame
        const auto inertia = b->getLocalInertia();
        double rot = 0;
        for (int j = 0; j < 3; ++j) rot += double(inertia[j]) * double(wLocal[j]) * double(wLocal[j]);
        s.kineticEnergy += 0.5 * (double(v.length2()) / double(b->getInvMass()) + rot);
        ++n;
    }
    if (n) s.meanHeight /= n;
    return s;
}

// Reference file (btgpu_accuracy_reference writes, btgpu_accuracy reads): lines starting '#'
// carry "# dims NX NY NZ", "# seconds S", "# settings ..."; then a header line and rows
// "t_s,mean_height_m,penetration_m,kinetic_energy_J" every kPileSampleSeconds.
constexpr double kPileSampleSeconds = 0.1;

}  // namespace btgpu::accuracy
