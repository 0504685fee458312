// stock_chaos.cpp — nudged stock runs and the bands they give.
#include "scenes/stock_chaos.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "tolerances.h"

namespace btgpu::scenes {

void nudge(Scene& scene, unsigned seed, double amount) { nudge(scene.bodies(), seed, amount); }

void nudge(const std::vector<btRigidBody*>& bodies, unsigned seed, double amount)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-amount, amount);
    for (btRigidBody* b : bodies) {
        if (b->getInvMass() == 0) continue;
        btTransform t = b->getWorldTransform();
        t.setOrigin(t.getOrigin() + btVector3(btScalar(u(rng)), btScalar(u(rng)), btScalar(u(rng))));
        b->setWorldTransform(t);
        b->setInterpolationWorldTransform(t);
        if (b->getMotionState()) b->getMotionState()->setWorldTransform(t);
    }
}

Aggregates aggregates(const Scene& scene, double standingY) { return aggregates(scene.bodies(), standingY); }

// A centre's coordinates in the frame of `up`: height along it, and the two across it (x and z
// themselves when up is +y, so that case is exactly the scene library's own measure).
static void upFrame(const btVector3& p, const btVector3& up, double& h, double& u, double& v)
{
    if (up == btVector3(0, 1, 0)) {
        h = p.y(), u = p.x(), v = p.z();
        return;
    }
    btVector3 e1, e2;
    btPlaneSpace1(up, e1, e2);
    h = double(p.x()) * up.x() + double(p.y()) * up.y() + double(p.z()) * up.z();
    u = double(p.x()) * e1.x() + double(p.y()) * e1.y() + double(p.z()) * e1.z();
    v = double(p.x()) * e2.x() + double(p.y()) * e2.y() + double(p.z()) * e2.z();
}

Aggregates aggregates(const std::vector<btRigidBody*>& bodies, double standingY, const btVector3& up)
{
    Aggregates a;
    double sx = 0, sz = 0;
    int n = 0;
    for (const btRigidBody* b : bodies) {
        if (b->getInvMass() == 0) continue;
        double h, x, z;
        upFrame(b->getWorldTransform().getOrigin(), up, h, x, z);
        a.meanHeight += h;
        sx += x;
        sz += z;
        a.standing += h > standingY ? 1.0 : 0.0;
        const double m = 1.0 / b->getInvMass();
        a.kineticEnergy += 0.5 * m * b->getLinearVelocity().length2();
        ++n;
    }
    if (n == 0) return a;
    a.meanHeight /= n;
    a.standing /= n;
    const double cx = sx / n, cz = sz / n;
    for (const btRigidBody* b : bodies) {
        if (b->getInvMass() == 0) continue;
        double h, x, z;
        upFrame(b->getWorldTransform().getOrigin(), up, h, x, z);
        a.spread += (x - cx) * (x - cx) + (z - cz) * (z - cz);
    }
    a.spread = std::sqrt(a.spread / n);
    return a;
}

double ChaosBand::bound() const { return tol::kChaosFactor * stockSpread + floor; }
bool ChaosBand::admits(double value) const { return std::fabs(value - stockMean) <= bound(); }

std::vector<ChaosBand> stockChaos(const std::function<ScenePtr(WorldKind)>& make, int steps,
                                  const std::function<std::vector<double>(const Scene&)>& measure,
                                  const std::vector<std::string>& names, const std::vector<double>& floors)
{
    std::vector<std::vector<double>> runs;
    for (int r = 0; r < tol::kChaosRuns; ++r) {
        ScenePtr scene = make(WorldKind::Stock);
        nudge(*scene, unsigned(r + 1), tol::kChaosNudge);
        for (int i = 0; i < steps; ++i) scene->step();
        runs.push_back(measure(*scene));
    }
    return chaosBands(runs, names, floors);
}

std::vector<ChaosBand> chaosBands(const std::vector<std::vector<double>>& runs, const std::vector<std::string>& names,
                                  const std::vector<double>& floors)
{
    std::vector<ChaosBand> bands(names.size());
    if (runs.empty()) return bands;
    for (size_t k = 0; k < names.size(); ++k) {
        ChaosBand& b = bands[k];
        b.name = names[k];
        b.floor = k < floors.size() ? floors[k] : 0.0;
        double lo = runs[0][k], hi = runs[0][k], sum = 0;
        for (const std::vector<double>& v : runs) {
            lo = std::min(lo, v[k]);
            hi = std::max(hi, v[k]);
            sum += v[k];
        }
        b.stockMean = sum / double(runs.size());
        b.stockSpread = hi - lo;
    }
    return bands;
}

}  // namespace btgpu::scenes
