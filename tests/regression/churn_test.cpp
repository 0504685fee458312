// churn_test.cpp — a game's traffic: bodies added and removed every step beside a settled pile.
// The rows of untouched bodies stay, with their device state and warm-start cache, so the pile
// moves as it would without the traffic; the per-step cost of the traffic is printed against
// the same world without it.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <deque>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

constexpr int kColumns = 20;   // x and z
constexpr int kHeight = 5;     // boxes per tower: 20 x 20 x 5 = 2,000
constexpr int kTraffic = 100;  // bodies added and removed per step

double msSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

namespace {

// Towers of exactly touching unit boxes on a wide ground, kept awake so the solver holds them
// every step (sleeping would hide a lost warm start).
std::vector<btRigidBody*> buildPile(scenes::Scene& scene)
{
    scene.addBody(scene.boxShape(btVector3(200, 50, 200)), 0, btVector3(0, -50, 0));
    btBoxShape* unit = scene.boxShape(btVector3(0.5f, 0.5f, 0.5f));
    std::vector<btRigidBody*> pile;
    for (int x = 0; x < kColumns; ++x)
        for (int z = 0; z < kColumns; ++z)
            for (int k = 0; k < kHeight; ++k) {
                btRigidBody* b = scene.addBody(unit, 1, btVector3(1.1f * x, 0.5f + k, 1.1f * z));
                b->setActivationState(DISABLE_DEACTIVATION);
                pile.push_back(b);
            }
    return pile;
}

}  // namespace

// The same pile in two worlds, one of them with 100 spheres added and 100 removed every step
// far from it: the pile's bodies, touched by nothing, end where the quiet world's do.
TEST(Churn, PileStaysWhileBodiesComeAndGo)
{
    scenes::Scene quiet(WorldKind::Gpu), busy(WorldKind::Gpu);
    std::vector<btRigidBody*> quietPile = buildPile(quiet), busyPile = buildPile(busy);
    for (int i = 0; i < 60; ++i) {  // settle
        quiet.step();
        busy.step();
    }
    btSphereShape* ball = busy.sphereShape(0.3f);
    std::deque<std::vector<btRigidBody*>> waves;
    double quietMs = 0, busyMs = 0;
    const int steps = 300;
    for (int i = 0; i < steps; ++i) {
        // Spheres dropped far from the pile, each removed three steps after it came.
        std::vector<btRigidBody*> wave;
        for (int k = 0; k < kTraffic; ++k)
            wave.push_back(busy.addBody(ball, 1, btVector3(100.0f + float(k % 10), 5.0f + float(i % 3), float(k / 10))));
        waves.push_back(wave);
        if (waves.size() > 3) {
            for (btRigidBody* b : waves.front()) busy.removeBody(b);
            waves.pop_front();
        }
        auto t0 = std::chrono::steady_clock::now();
        busy.step();
        busyMs += msSince(t0);
        t0 = std::chrono::steady_clock::now();
        quiet.step();
        quietMs += msSince(t0);
        ASSERT_TRUE(busy.gpuWorld()->isGpuPath()) << busy.report()->cpuPathReason;
    }
    double worst = 0;
    size_t worstBody = 0;
    for (size_t i = 0; i < busyPile.size(); ++i) {
        double d = (busyPile[i]->getWorldTransform().getOrigin() - quietPile[i]->getWorldTransform().getOrigin()).length();
        if (d > worst) worst = d, worstBody = i;
    }
    std::printf("churn: %d bodies added and %d removed a step beside a pile of %zu: %.2f ms a step (%.2f without "
                "the traffic); the pile ended at most %.4f mm from the quiet world's (body %zu); %d redone steps\n",
                kTraffic, kTraffic, busyPile.size(), busyMs / steps, quietMs / steps, 1e3 * worst, worstBody,
                busy.report()->redoneSteps);
    EXPECT_LT(worst, 1e-3) << "pile body " << worstBody << " moved";
    EXPECT_TRUE(scenes::allFinite(busy));
}

// Shapes that first come with a body added mid-run reach the device as appended table rows:
// a hull and a sphere added after the world has stepped land as on stock.
TEST(Churn, NewShapesMidRunLandAsStock)
{
    SideBySide s(scenes::restingBox);
    s.step(10);
    s.both([](Scene& scene) {
        std::vector<btVector3> points;
        for (int i = 0; i < 8; ++i) points.emplace_back((i & 1) ? 0.4f : -0.4f, (i & 2) ? 0.3f : -0.3f, (i & 4) ? 0.5f : -0.5f);
        scene.addBody(scene.hullShape(points), 1, btVector3(3, 2, 0));
        scene.addBody(scene.sphereShape(0.25f), 1, btVector3(-3, 2, 0));
    });
    s.step(90);
    ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
    for (int i = 2; i <= 3; ++i)
        EXPECT_NEAR(s.gpuY(i), s.stockY(i), 0.01) << "body " << i << ": btgpu " << s.gpuY(i) << ", stock " << s.stockY(i);
}
