// barrels_test.cpp — hull barrels dropped nearly upright (tests/scenes/barrel_scenes.h): how
// many end standing is decided by the first impact, so btgpu's hull contacts must resolve it as
// stock does (within stock's own chaos) and no worse than stock against small steps.
#include <gtest/gtest.h>

#include <cstdio>

#include "btgpu/btGpuDynamicsWorld.h"
#include "scenes/barrel_scenes.h"
#include "scenes/stock_chaos.h"
#include "tolerances.h"

namespace btgpu::test {
namespace {

using scenes::BarrelDrop;
using scenes::WorldKind;

constexpr int kSteps = 240;  // 4 s at 1/60 s: every barrel has landed and settled

double gpuUpright(const BarrelDrop& drop, int* offPathSteps, const Config& config = Config::bulletMode())
{
    auto gpu = scenes::barrelDrop(WorldKind::Gpu, config, drop);
    for (int s = 0; s < kSteps; ++s) {
        gpu->step();
        if (!gpu->gpuWorld()->isGpuPath()) ++*offPathSteps;
    }
    return scenes::uprightFraction(*gpu);
}

TEST(Barrels, UprightFractionWithinStocksChaos)
{
    for (bool polyhedral : {false, true}) {
        BarrelDrop drop;
        drop.polyhedral = polyhedral;
        const auto bands = scenes::stockChaos(
            [&](WorldKind kind) { return scenes::barrelDrop(kind, Config::bulletMode(), drop); }, kSteps,
            [](const scenes::Scene& s) { return std::vector<double>{scenes::uprightFraction(s)}; }, {"upright"},
            {tol::kChaosStandingFloor});
        int offPath = 0;
        const double gpu = gpuUpright(drop, &offPath);
        std::printf("barrels (polyhedral %d): upright btgpu %.2f, stock %.2f +- %.2f\n", polyhedral, gpu,
                    bands[0].stockMean, bands[0].bound());
        EXPECT_EQ(offPath, 0);
        EXPECT_TRUE(bands[0].admits(gpu)) << "btgpu " << gpu << ", stock " << bands[0].stockMean << " +- "
                                          << bands[0].bound() << " (polyhedral " << polyhedral << ")";
    }
}

}  // namespace

// The soft step (issue 13's candidate default) on the same drop, against the same chaos of stock.
TEST(Barrels, SoftStepUprightFractionWithinStocksChaos)
{
    BarrelDrop drop;
    const auto bands = scenes::stockChaos(
        [&](WorldKind kind) { return scenes::barrelDrop(kind, Config::bulletMode(), drop); }, kSteps,
        [](const scenes::Scene& s) { return std::vector<double>{scenes::uprightFraction(s)}; }, {"upright"},
        {tol::kChaosStandingFloor});
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    int offPath = 0;
    const double gpu = gpuUpright(drop, &offPath, soft);
    std::printf("barrels, soft step: upright btgpu %.2f, stock %.2f +- %.2f\n", gpu, bands[0].stockMean, bands[0].bound());
    EXPECT_EQ(offPath, 0);
    EXPECT_TRUE(bands[0].admits(gpu)) << "btgpu " << gpu << ", stock " << bands[0].stockMean << " +- " << bands[0].bound();
}

}  // namespace btgpu::test
