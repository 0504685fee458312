// stock_chaos.h — stock's own chaos, the yardstick for chaotic scenes (a pile's collapse, a
// tower's fall): stock Bullet run tol::kChaosRuns times with every dynamic body's start nudged by
// up to tol::kChaosNudge (fixed seeds). For each named aggregate the btgpu value must lie within
// tol::kChaosFactor x the largest stock-to-stock distance, plus the aggregate's stated floor, of
// the stock runs' mean — not on one chance outcome of one stock run.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "scenes/scenes.h"

namespace btgpu::scenes {

// Moves every dynamic body's start (and its motion state) by up to `amount` m on each axis.
void nudge(Scene& scene, unsigned seed, double amount);
// The same for any list of bodies (a world loaded from a file: demos/compare), in list order.
void nudge(const std::vector<btRigidBody*>& bodies, unsigned seed, double amount);

// The aggregates compared against stock's chaos, at one time.
struct Aggregates {
    double meanHeight = 0.0;     // m, mean centre y of the dynamic bodies
    double spread = 0.0;         // m, rms horizontal distance of their centres from their centroid
    double kineticEnergy = 0.0;  // J, of the dynamic bodies
    double standing = 0.0;       // fraction of dynamic bodies whose centre is above `standingY`
};
Aggregates aggregates(const Scene& scene, double standingY = 0.0);
// The same over any list of bodies; heights along `up` (unit), spread in the plane across it.
Aggregates aggregates(const std::vector<btRigidBody*>& bodies, double standingY = 0.0,
                      const btVector3& up = btVector3(0, 1, 0));

struct ChaosBand {
    std::string name;
    double stockMean = 0.0;
    double stockSpread = 0.0;  // largest distance between two stock runs
    double floor = 0.0;        // stated absolute floor
    double bound() const;      // allowed distance from stockMean
    bool admits(double value) const;
};

// Stock runs of `make` (nudged, tol::kChaosRuns of them), each stepped `steps` times at 1/60 s,
// measured by `measure` into named values; one band per name, floors as given.
// One band per name from the stock runs' values (runs[r][k]: run r, value k), floors as given.
std::vector<ChaosBand> chaosBands(const std::vector<std::vector<double>>& runs, const std::vector<std::string>& names,
                                  const std::vector<double>& floors);
std::vector<ChaosBand> stockChaos(const std::function<ScenePtr(WorldKind)>& make, int steps,
                                  const std::function<std::vector<double>(const Scene&)>& measure,
                                  const std::vector<std::string>& names, const std::vector<double>& floors);

}  // namespace btgpu::scenes
