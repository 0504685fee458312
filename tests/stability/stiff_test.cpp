// stiff_test.cpp — stiff resting scenes on stock Bullet and on btgpu: mass ratios, a heavy plank
// on two small boxes, towers (exact and with +-1 cm offsets), pyramids, other time steps, and a
// long rest. Each must stay finite, bounded, settle, not sink and not creep (stability.h).
#include "stability/stability.h"

using namespace btgpu;
using namespace btgpu::stability;
namespace st = btgpu::scenes::stability;

namespace {

// Resting criteria for scenes of unit boxes: settled by `settleBy`, penetration <= 1 cm,
// the top body drifting less than 5 cm sideways and sinking no more than 1 cm per box under it
// (the top body is the last one, body `topBody` = the number of boxes under and including it).
Criteria resting(double seconds, double settleBy, int topBody, double smallest = 1)
{
    Criteria c;
    c.seconds = seconds;
    c.settleBy = settleBy;
    c.penetration = tol::kPenetrationFraction * smallest;
    c.driftBody = topBody;
    c.drift = tol::kTopDriftFraction * smallest;
    c.drop = c.penetration * topBody;
    return c;
}

void massRatioCase(btScalar m)
{
    runEngines("mass ratio " + std::to_string(int(m)) + ":1",
            [m](WorldKind k, const Config& c) { return st::massRatio(k, c, m); }, resting(3, 2, 2));
}

void towerCase(int count, btScalar offset)
{
    const std::string name = "tower " + std::to_string(count) + (offset > 0 ? " offset 1 cm" : " exact");
    runEngines(name, [count, offset](WorldKind k, const Config& c) { return st::tower(k, c, count, offset); },
            resting(fullMode() ? 8 : 5, 4, count));
}

}  // namespace

TEST(MassRatio, Ten) { massRatioCase(10); }
TEST(MassRatio, Hundred) { massRatioCase(100); }
TEST(MassRatio, Thousand) { massRatioCase(1000); }

// Stock fails this at 10 iterations; btgpu passes it with shorter device steps (the app's
// steps, motion states and interpolation unchanged). 1000:1 is not earned yet: with 32 internal
// substeps it holds (penetration 6e-5 mm, drift 5 mm) but jitters until it sleeps at 2 s.
TEST(MassRatio, HundredWithInternalSubsteps)
{
    runEarned("mass ratio 100:1", [](WorldKind k, const Config& c) { return st::massRatio(k, c, 100); },
              resting(3, 2, 2), 4);
}

TEST(MassRatio, HeavyPlankOnTwoBoxes)
{
    // The plank (body 3) is 1 thick: the smallest dimension of every body is 1.
    Criteria c = resting(3, 2, 3);
    c.drop = 2 * c.penetration;  // a box and the ground under it
    runEngines("plank 400 kg on 2 boxes", st::heavyPlank, c);
}

TEST(Tower, TenExact) { towerCase(10, 0); }
TEST(Tower, TwentyExact) { towerCase(20, 0); }
TEST(Tower, TenOffset) { towerCase(10, btScalar(0.01)); }
TEST(Tower, ThirtyExact)
{
    if (!fullMode()) GTEST_SKIP() << "BTGPU_STABILITY_FULL=1 runs it";
    towerCase(30, 0);
}
TEST(Tower, TwentyOffset)
{
    if (!fullMode()) GTEST_SKIP() << "BTGPU_STABILITY_FULL=1 runs it";
    towerCase(20, btScalar(0.01));
}
TEST(Tower, ThirtyOffset)
{
    if (!fullMode()) GTEST_SKIP() << "BTGPU_STABILITY_FULL=1 runs it";
    towerCase(30, btScalar(0.01));
}

TEST(Pyramid, BaseTwenty)
{
    // The apex is the last body: 20 * 21 / 2 = 210 boxes after the ground.
    Criteria c = resting(5, 4, 210);
    c.drop = 20 * c.penetration;  // one contact per row
    runEngines("pyramid base 20", [](WorldKind k, const Config& cf) { return st::pyramid(k, cf, 20); }, c);
}

TEST(Pyramid, BaseFifty)
{
    if (!fullMode()) GTEST_SKIP() << "BTGPU_STABILITY_FULL=1 runs it";
    Criteria c = resting(8, 6, 1275);
    c.drop = 50 * c.penetration;
    runEngines("pyramid base 50", [](WorldKind k, const Config& cf) { return st::pyramid(k, cf, 50); }, c);
}

TEST(TimeStep, Thirtieth)
{
    Criteria c = resting(5, 4, 10);
    c.timeStep = btScalar(1) / btScalar(30);
    runEngines("tower 10, dt 1/30", [](WorldKind k, const Config& cf) { return st::tower(k, cf, 10); }, c);
}

TEST(TimeStep, Thousandth)
{
    Criteria c = resting(fullMode() ? 5 : 2, 1, 10);
    c.timeStep = btScalar(1) / btScalar(1000);
    runEngines("tower 10, dt 1/1000", [](WorldKind k, const Config& cf) { return st::tower(k, cf, 10); }, c);
}

TEST(LongRest, EightBoxStack)
{
    // Sleeping is turned off: the solver itself must hold the stack still, step after step.
    const int steps = fullMode() ? 10000 : 1000;
    Criteria c = resting(steps / 60.0, 2, 8);
    c.drift = tol::kLongRestDrift;
    c.energyNeverGrows = true;
    c.noSleep = true;
    runEngines("8-box stack, " + std::to_string(steps) + " steps",
            [](WorldKind k, const Config& cf) { return scenes::boxStack(k, cf, 8); }, c);
}
