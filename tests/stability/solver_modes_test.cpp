// solver_modes_test.cpp — issue 13's targets on stock Bullet and on btgpu's two solver modes
// (bullet: SolverKind::BatchedPgs; soft: SolverKind::SoftStep), deactivation off, Bullet's
// defaults (10 iterations, dt 1/60, one step a frame): mass ratios and a heavy plank (10 s,
// penetration <= 1% of the smallest box, no box farther than 5 cm from its start), exact towers
// and pyramids (no box farther than 5 cm in 10 s); and jointed scenes in the soft mode (a
// hanging chain holds its links together, ragdolls land and settle). Each row is recorded for
// the three engines; the soft mode's cases assert what it earns, and both btgpu modes must stay
// on the GPU path on every step; the soft step is deterministic. BTGPU_STABILITY_SOFT_SUBSTEPS=N runs the soft mode with N
// substeps instead of m_numIterations (to measure the mapping).
#include "scenes/joint_scenes.h"
#include "stability/stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace btgpu;
using namespace btgpu::stability;
namespace st = btgpu::scenes::stability;

namespace {

Config modeConfig(SolverKind solver)
{
    Config c = Config::bulletMode();
    c.solver = solver;
    // The measurement of the substep mapping (README's table): any other count than the default
    // m_numIterations. Recorded, not asserted differently.
    if (const char* n = std::getenv("BTGPU_STABILITY_SOFT_SUBSTEPS")) c.softStep.substeps = std::atoi(n);
    // The same for the springs' sag bound (SoftStepConfig::maxSag, m).
    if (const char* m = std::getenv("BTGPU_STABILITY_SOFT_MAXSAG")) c.softStep.maxSag = float(std::atof(m));
    return c;
}

// The issue's criteria for resting unit boxes: 10 s without sleeping, penetration within 1% of
// the smallest box (whole run), no dynamic body farther than 5 cm from its start.
Criteria target(double smallest = 1)
{
    Criteria c;
    c.seconds = 10;
    c.noSleep = true;
    c.penetration = tol::kPenetrationFraction * smallest;
    c.measureFrom = 0;
    c.move = tol::kTopDriftFraction * smallest;
    return c;
}

enum class Earned { Yes, No };

bool has(const std::vector<std::string>& stages, const std::string& name)
{
    return std::find(stages.begin(), stages.end(), name) != stages.end();
}

// Runs the case on the three engines and records each; `soft` says whether the soft mode is
// asserted to pass (a case it does not earn is recorded, not failed).
void runModes(const std::string& name, const Builder& make, const Criteria& c, Earned soft)
{
    const Outcome stock = run(make, WorldKind::Stock, c);
    const Outcome bullet = run(make, WorldKind::Gpu, c, modeConfig(SolverKind::BatchedPgs));
    const Outcome softStep = run(make, WorldKind::Gpu, c, modeConfig(SolverKind::SoftStep));
    recordAs(name, "stock", stock, figure(stock));
    recordAs(name, "btgpu bullet", bullet, figure(bullet));
    recordAs(name, "btgpu soft", softStep, figure(softStep));
    EXPECT_TRUE(bullet.gpuEveryStep) << name << ": bullet mode left the GPU path";
    EXPECT_TRUE(softStep.gpuEveryStep) << name << ": soft mode left the GPU path";
    EXPECT_TRUE(has(bullet.stages, "solve_constraints") && !has(bullet.stages, "solve_soft")) << name;
    EXPECT_TRUE(has(softStep.stages, "solve_soft") && has(softStep.stages, "soft_transforms") &&
                !has(softStep.stages, "solve_constraints") && !has(softStep.stages, "integrate_transforms"))
        << name;
    // What the default mapping (substeps = m_numIterations) earns; another count is measured only.
    if (soft == Earned::Yes && !std::getenv("BTGPU_STABILITY_SOFT_SUBSTEPS") && !std::getenv("BTGPU_STABILITY_SOFT_MAXSAG"))
        EXPECT_TRUE(softStep.pass) << name << ", soft mode: " << softStep.why;
}

}  // namespace

TEST(SolverModes, MassRatioTen)
{
    runModes("mass ratio 10:1, 10 s", [](WorldKind k, const Config& c) { return st::massRatio(k, c, 10); }, target(),
             Earned::Yes);
}
TEST(SolverModes, MassRatioHundred)
{
    runModes("mass ratio 100:1, 10 s", [](WorldKind k, const Config& c) { return st::massRatio(k, c, 100); }, target(),
             Earned::Yes);
}
// Without more substeps (SoftStepConfig::substepsPerRootMassRatio 0) the light box rings under
// the heavy one at 10 substeps and it falls off (88-108 mm, 1.5-2 m; the 1-D model
// tests/stability/soft_mass_ratio_model.py shows why); the default takes 64 and it stands.
TEST(SolverModes, MassRatioThousand)
{
    runModes("mass ratio 1000:1, 10 s", [](WorldKind k, const Config& c) { return st::massRatio(k, c, 1000); },
             target(), Earned::Yes);
}
TEST(SolverModes, HeavyPlank)
{
    // At 10 substeps 16 mm into the boxes, the plank rocking 12 cm; the default takes 40 for
    // its 400:1 and holds it, and so does holding the light boxes (HeavyPlankHeld).
    runModes("plank 400 kg on 2 boxes, 10 s", st::heavyPlank, target(), Earned::Yes);
}

// What holding the light body earns at the default 10 substeps (SoftStepConfig::heldMassRatio
// 100, opt-in: see Config.h for why it is not the default).
void runSoftHeld(const std::string& name, const Builder& make)
{
    Config config = modeConfig(SolverKind::SoftStep);
    config.softStep.heldMassRatio = 100.0f;
    config.softStep.substepsPerRootMassRatio = 0.0f;  // 10 substeps, however heavy
    const Outcome soft = run(make, WorldKind::Gpu, target(), config);
    recordAs(name, "btgpu soft, held", soft, figure(soft));
    EXPECT_TRUE(soft.gpuEveryStep) << name;
    EXPECT_TRUE(has(soft.stages, "solve_soft")) << name;
    if (!std::getenv("BTGPU_STABILITY_SOFT_SUBSTEPS") && !std::getenv("BTGPU_STABILITY_SOFT_MAXSAG"))
        EXPECT_TRUE(soft.pass) << name << ", soft mode, light body held: " << soft.why;
}
TEST(SolverModes, MassRatioThousandHeld)
{
    runSoftHeld("mass ratio 1000:1, 10 s", [](WorldKind k, const Config& c) { return st::massRatio(k, c, 1000); });
}
TEST(SolverModes, HeavyPlankHeld)
{
    runSoftHeld("plank 400 kg on 2 boxes, 10 s", st::heavyPlank);
}

TEST(SolverModes, TowerTen)
{
    runModes("tower 10 exact, 10 s", [](WorldKind k, const Config& c) { return st::tower(k, c, 10); }, target(),
             Earned::Yes);
}
TEST(SolverModes, TowerTwenty)
{
    runModes("tower 20 exact, 10 s", [](WorldKind k, const Config& c) { return st::tower(k, c, 20); }, target(),
             Earned::Yes);
}
TEST(SolverModes, TowerThirty)
{
    runModes("tower 30 exact, 10 s", [](WorldKind k, const Config& c) { return st::tower(k, c, 30); }, target(),
             Earned::Yes);
}
TEST(SolverModes, PyramidTwenty)
{
    runModes("pyramid base 20, 10 s", [](WorldKind k, const Config& c) { return st::pyramid(k, c, 20); }, target(),
             Earned::Yes);
}
TEST(SolverModes, PyramidFifty)
{
    if (!fullMode()) GTEST_SKIP() << "BTGPU_STABILITY_FULL=1 runs it";
    // Earned since SoftStepConfig::maxSag is 1 mm (H200 and PoCL: farthest move 41 mm).
    runModes("pyramid base 50, 10 s", [](WorldKind k, const Config& c) { return st::pyramid(k, c, 50); }, target(),
             Earned::Yes);
}

// Joints in the soft mode: a hanging chain of 20 point-to-point links, 5 s; its worst stretch
// (distance between neighbours less the pitch) within 1 cm and under half the bullet mode's
// (Bullet's 10 iterations leave a chain of 20 stretched by centimetres; stock is measured alike).
TEST(SolverModes, ChainHoldsInSoftMode)
{
    double stretch[3] = {0, 0, 0};
    const char* names[3] = {"stock", "btgpu bullet", "btgpu soft"};
    for (int m = 0; m < 3; ++m) {
        const WorldKind kind = m == 0 ? WorldKind::Stock : WorldKind::Gpu;
        scenes::ScenePtr s =
            scenes::chain(kind, modeConfig(m == 2 ? SolverKind::SoftStep : SolverKind::BatchedPgs), 20);
        bool gpu = true;
        for (int step = 0; step < 300; ++step) {
            s->step(btScalar(1) / 60, 1, btScalar(1) / 60);
            if (kind == WorldKind::Gpu) gpu = gpu && s->report()->gpuPath;
        }
        ASSERT_TRUE(scenes::allFinite(*s)) << names[m];
        EXPECT_TRUE(gpu) << names[m];
        for (int i = 2; i + 1 < int(s->bodies().size()); ++i) {
            const double d =
                (s->body(i + 1)->getWorldTransform().getOrigin() - s->body(i)->getWorldTransform().getOrigin()).length();
            stretch[m] = std::max(stretch[m], std::fabs(d - 0.2));
        }
        RecordProperty(std::string(names[m]) + "_stretch_m", std::to_string(stretch[m]));
        std::printf("[ chain ] %-12s worst link stretch %.3g mm\n", names[m], stretch[m] * 1e3);
    }
    EXPECT_LT(stretch[2], 0.01);
    EXPECT_LT(stretch[2], 0.5 * stretch[1]);
}

// Four ragdolls (hinges and cone-twists) dropped on the ground in the soft mode: finite, speeds
// within the fall's bound, on the GPU path every step, and nearly at rest after 6 s
// (KE/M below 1e-3 J/kg; the bullet mode is recorded beside it). 6 s since the soft step lays
// capsules on the ground afresh (round_contacts.h): with no GJK point a few micrometres off,
// the symmetric drop stays in its plane and its last limb falls at 5 s (KE/M 1.2e-3 then; all
// asleep at 5.5 s; before, 8.5e-5 at 5 s and asleep at 6.5 s).
TEST(SolverModes, RagdollsLandInSoftMode)
{
    Criteria c;
    c.seconds = 6;
    const auto make = [](WorldKind k, const Config& cf) { return scenes::ragdolls(k, cf, 4); };
    const Outcome stock = run(make, WorldKind::Stock, c);
    const Outcome bullet = run(make, WorldKind::Gpu, c, modeConfig(SolverKind::BatchedPgs));
    const Outcome soft = run(make, WorldKind::Gpu, c, modeConfig(SolverKind::SoftStep));
    recordAs("4 ragdolls, 5 s", "stock", stock, figure(stock));
    recordAs("4 ragdolls, 5 s", "btgpu bullet", bullet, figure(bullet));
    recordAs("4 ragdolls, 5 s", "btgpu soft", soft, figure(soft));
    EXPECT_TRUE(soft.gpuEveryStep);
    EXPECT_TRUE(soft.pass) << soft.why;
    EXPECT_LT(soft.finalKePerMass, 1e-3);
    // and still at rest later: limbs that jitter on (a hinge relaxed without its bias had them at
    // 0.4 m/s after 8 s, KE/M up to 5e-3, with 4.2e-4 at 6 s by its phase) fail one of these
    for (double later : {7.0, 8.0}) {
        Criteria l = c;
        l.seconds = later;
        const Outcome o = run(make, WorldKind::Gpu, l, modeConfig(SolverKind::SoftStep));
        EXPECT_LT(o.finalKePerMass, 1e-3) << "at " << later << " s";
    }
}

// A mass ratio past what SoftStepConfig::maxSubsteps (128) holds (100,000:1 needs 633): the
// step takes the cap and says so once (Issue::Kind::Difference), on the GPU path.
TEST(SolverModes, SubstepCapIsReported)
{
    scenes::ScenePtr s = st::massRatio(WorldKind::Gpu, modeConfig(SolverKind::SoftStep), 100000);
    for (int step = 0; step < 5; ++step) {
        s->step(btScalar(1) / 60, 1, btScalar(1) / 60);
        ASSERT_TRUE(s->report()->gpuPath) << s->report()->cpuPathReason;
    }
    EXPECT_EQ(128, s->report()->softSubsteps);
    int said = 0;
    for (const Issue& i : s->report()->issues)
        if (i.kind == Issue::Kind::Difference && i.message.find("SoftStepConfig::maxSubsteps (128)") != std::string::npos &&
            i.message.find(" needs 633 ") != std::string::npos)
            ++said;
    EXPECT_EQ(1, said);
}

// Same scene, device and binary: the soft step's states are bitwise the same, step by step (two
// worlds of a pyramid side by side, 120 steps). Of base 30 (465 bodies): on a GPU its bodies
// span more than one work-group, so the warm-start gather reads soft contacts another compute
// unit wrote (a stale cached read there made the pyramid of 50 fail and differ run to run
// before those reads went through BTG_SHARED).
TEST(SolverModes, SoftStepIsDeterministic)
{
    const auto make = [] { return st::pyramid(WorldKind::Gpu, modeConfig(SolverKind::SoftStep), 30); };
    scenes::ScenePtr a = make(), b = make();
    for (int step = 0; step < 120; ++step) {
        a->step(btScalar(1) / 60, 1, btScalar(1) / 60);
        b->step(btScalar(1) / 60, 1, btScalar(1) / 60);
        ASSERT_TRUE(a->report()->gpuPath && b->report()->gpuPath);
        for (std::size_t i = 0; i < a->bodies().size(); ++i) {
            const btTransform& ta = a->bodies()[i]->getWorldTransform();
            const btTransform& tb = b->bodies()[i]->getWorldTransform();
            ASSERT_EQ(0, std::memcmp(&ta, &tb, sizeof(btTransform))) << "body " << i << ", step " << step;
        }
    }
}

// A 1,000 kg box dropped 5 cm onto a 1 kg box 45 cm off its centre (its centre still over the
// light box, 5 cm from its edge).
struct EdgeDrop {
    double fastestLight = 0;  // m/s: the light box's fastest
    double lowestLight = 1;   // m: the light box's centre at its lowest (0.5 resting on the ground)
    double lastSpeed = 0;     // m/s: the faster of the two at the end
    double heavyHeight = 0;   // m: the heavy box's centre at the end
    int substeps = 0;         // the most Report::softSubsteps took
};
EdgeDrop dropHeavyNearTheEdge(const Config& config)
{
    scenes::ScenePtr s = st::massRatio(WorldKind::Gpu, config, 1000);
    btTransform t = s->body(2)->getWorldTransform();
    t.setOrigin(t.getOrigin() + btVector3(btScalar(0.45), btScalar(0.05), 0));
    s->body(2)->setCenterOfMassTransform(t);
    s->body(2)->getMotionState()->setWorldTransform(t);
    for (btRigidBody* b : s->bodies()) b->setActivationState(DISABLE_DEACTIVATION);
    EdgeDrop d;
    for (int step = 0; step < 600; ++step) {
        s->step(btScalar(1) / 60, 1, btScalar(1) / 60);
        EXPECT_TRUE(s->report()->gpuPath);
        if (!s->report()->gpuPath) break;
        d.substeps = std::max(d.substeps, s->report()->softSubsteps);
        d.fastestLight = std::max(d.fastestLight, double(s->body(1)->getLinearVelocity().length()));
        d.lowestLight = std::min(d.lowestLight, double(s->body(1)->getWorldTransform().getOrigin().y()));
    }
    for (int i : {1, 2})
        d.lastSpeed = std::max({d.lastSpeed, double(s->body(i)->getLinearVelocity().length()),
                                double(s->body(i)->getAngularVelocity().length())});
    d.heavyHeight = double(s->body(2)->getWorldTransform().getOrigin().y());
    std::printf("heavy box dropped near the light one's edge: light box fastest %.3f m/s, lowest %.4f m; at 10 s "
                "the fastest body %.4f m/s (or rad/s), the heavy box at %.3f m; %d substeps\n",
                d.fastestLight, d.lowestLight, d.lastSpeed, d.heavyHeight, d.substeps);
    return d;
}

// The default soft step takes the substeps the mass ratio needs (64 for 1,000:1) and the drop
// ends at rest, the light box neither thrown nor pressed into the ground. Whether the heavy box
// stays on or tips off this close to the edge is not asserted: at 42 substeps it stays on but
// the pair rocks and walks a metre in 10 s; at 64 and more (84, 168) it tips off, as stock
// does at 1/600 s and 200 iterations.
TEST(SolverModes, HeavyDroppedNearTheEdgeSettles)
{
    const EdgeDrop d = dropHeavyNearTheEdge(modeConfig(SolverKind::SoftStep));
    EXPECT_EQ(64, d.substeps) << "the least n with n^2 >= 2^2 x 1000";
    EXPECT_LT(d.fastestLight, 2.0) << "the light box was thrown";
    EXPECT_GT(d.lowestLight, 0.49) << "the light box was pressed into the ground";
    EXPECT_LT(d.lastSpeed, 0.01) << "still moving after 10 s";
}

// Known failure of the held light body (why heldMassRatio is opt-in): held at 10 substeps, the
// heavy box tips off and the light box is thrown (tens of m/s) and falls through the ground.
// Run with --gtest_also_run_disabled_tests.
TEST(SolverModes, DISABLED_HeldHeavyDroppedNearTheEdge)
{
    Config config = modeConfig(SolverKind::SoftStep);
    config.softStep.heldMassRatio = 100.0f;
    config.softStep.substepsPerRootMassRatio = 0.0f;
    const EdgeDrop d = dropHeavyNearTheEdge(config);
    EXPECT_LT(d.fastestLight, 2.0) << "the light box was thrown";
    EXPECT_GT(d.lowestLight, 0.49) << "the light box was pressed into the ground";
}
