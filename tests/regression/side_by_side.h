// side_by_side.h — runs one scene on stock btDiscreteDynamicsWorld and on btGpuDynamicsWorld
// in the same process, applying every app change to both, so a regression test compares the
// two body by body (Scene keeps bodies in creation order on both worlds).
#pragma once
#include <functional>
#include <vector>

#include "btgpu/btGpuDynamicsWorld.h"
#include "scenes/scenes.h"
#include "tolerances.h"

namespace btgpu::test {

using scenes::Scene;
using scenes::ScenePtr;
using scenes::WorldKind;
using SceneBuilder = std::function<ScenePtr(WorldKind, const Config&)>;

constexpr btScalar kStep = btScalar(1) / btScalar(60);

struct SideBySide {
    ScenePtr stock;
    ScenePtr gpu;

    explicit SideBySide(const SceneBuilder& make, const Config& config = Config::bulletMode())
        : stock(make(WorldKind::Stock, config)), gpu(make(WorldKind::Gpu, config))
    {
    }
    // The same change, made by the app between steps, on both worlds.
    void both(const std::function<void(Scene&)>& change)
    {
        change(*stock);
        change(*gpu);
    }
    void step(int count = 1, btScalar timeStep = kStep, int maxSubSteps = 1, btScalar fixedTimeStep = kStep)
    {
        for (int i = 0; i < count; ++i) {
            stock->step(timeStep, maxSubSteps, fixedTimeStep);
            gpu->step(timeStep, maxSubSteps, fixedTimeStep);
        }
    }
    // Distance between the two worlds' positions of scene body i.
    double distance(int i) const
    {
        return (stock->body(i)->getWorldTransform().getOrigin() - gpu->body(i)->getWorldTransform().getOrigin())
            .length();
    }
    double gpuY(int i) const { return gpu->body(i)->getWorldTransform().getOrigin().y(); }
    double stockY(int i) const { return stock->body(i)->getWorldTransform().getOrigin().y(); }
    bool onGpu() const { return gpu->gpuWorld()->isGpuPath(); }
};

// The heights at which a bouncing body turned back up, from its height each step (the apexes
// after each bounce).
inline std::vector<double> bounceApexes(const std::vector<double>& y)
{
    std::vector<double> out;
    bool bounced = false;
    for (size_t i = 1; i + 1 < y.size(); ++i) {
        if (y[i] < y[i - 1] && y[i] < y[i + 1]) bounced = true;
        if (bounced && y[i] > y[i - 1] && y[i] >= y[i + 1]) out.push_back(y[i]);
    }
    return out;
}

}  // namespace btgpu::test
