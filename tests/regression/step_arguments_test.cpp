// step_arguments_test.cpp — stepSimulation's time arguments on both paths: odd ones simulate
// nothing and are named, and after an OpenCL failure (here: running out of device memory at
// Config::deviceMemoryLimit) the call's fixed steps are still taken, on the CPU path.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

const float kNan = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

struct Args {
    float timeStep;
    int maxSubSteps;
    float fixedTimeStep;
};

// Every body's transform, velocities and motion-state transform, as raw bytes.
std::vector<float> snapshot(Scene& scene)
{
    std::vector<float> out;
    for (btRigidBody* b : scene.bodies()) {
        btTransform ms;
        b->getMotionState()->getWorldTransform(ms);
        for (const btTransform* t : {&b->getWorldTransform(), &ms}) {
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) out.push_back(t->getBasis()[r][c]);
            for (int c = 0; c < 3; ++c) out.push_back(t->getOrigin()[c]);
        }
        for (int c = 0; c < 3; ++c) out.push_back(b->getLinearVelocity()[c]);
        for (int c = 0; c < 3; ++c) out.push_back(b->getAngularVelocity()[c]);
    }
    return out;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST(StepArguments, OddArgumentsSimulateNothingAndAreNamed)
{
    const Args odd[] = {
        {kNan, 1, 1 / 60.f},   {kInf, 1, 1 / 60.f},     {-kInf, 1, 1 / 60.f},  {1e30f, 1, 1 / 60.f},
        {-1 / 60.f, 1, 1 / 60.f}, {1 / 60.f, 1, 0.0f},  {1 / 60.f, 1, kNan},   {1 / 60.f, 1, -1 / 60.f},
        {1 / 60.f, 1, 1e-30f}, {1 / 60.f, -1, 1 / 60.f}, {kNan, 0, 1 / 60.f},  {1e30f, 0, 1 / 60.f},
        {-1 / 60.f, 0, 1 / 60.f},
    };
    for (bool cpu : {false, true}) {
        SCOPED_TRACE(cpu ? "CPU path" : "GPU path");
        Config config = Config::bulletMode();
        config.forceCpu = cpu;
        ScenePtr scene = scenes::dropRow(WorldKind::Gpu, config);
        for (int i = 0; i < 10; ++i) scene->step();
        for (const Args& a : odd) {
            SCOPED_TRACE(::testing::Message() << "stepSimulation(" << a.timeStep << ", " << a.maxSubSteps << ", "
                                              << a.fixedTimeStep << ")");
            const std::vector<float> before = snapshot(*scene);
            const size_t issues = scene->report()->issues.size();
            EXPECT_EQ(scene->world().stepSimulation(a.timeStep, a.maxSubSteps, a.fixedTimeStep), 0);
            EXPECT_TRUE(sameBits(before, snapshot(*scene))) << "a body or motion state changed";
            ASSERT_GT(scene->report()->issues.size(), issues) << "not reported";
            EXPECT_EQ(scene->report()->issues.back().kind, Issue::Kind::BadArgument);
            EXPECT_NE(scene->report()->issues.back().message.find("stepSimulation("), std::string::npos);
            // A good call afterwards steps as usual.
            EXPECT_EQ(scene->world().stepSimulation(1 / 60.f, 1, 1 / 60.f), 1);
        }
        EXPECT_TRUE(scenes::allFinite(*scene));
    }
}

// Out of device memory in the middle of a call: reported, and the world goes on from where it
// was on the CPU path, taking the fixed step the call owes (the GPU path had already moved the
// local time on).
TEST(StepArguments, OutOfDeviceMemoryKeepsTheCallsTime)
{
    Config probe = Config::bulletMode();
    ScenePtr sized = scenes::dropRow(WorldKind::Gpu, probe);
    sized->step(1 / 120.f, 1, 1 / 60.f);  // builds the rows, takes no fixed step yet
    const size_t bytes = sized->report()->deviceBytes;
    ASSERT_GT(bytes, 0u);

    Config config = Config::bulletMode();
    config.deviceMemoryLimit = bytes;  // the first device step needs more (its scratch buffers)
    SideBySide s(scenes::dropRow, config);
    int stockSteps = 0, gpuSteps = 0;
    for (int i = 0; i < 6; ++i) {
        stockSteps += s.stock->step(1 / 120.f, 1, 1 / 60.f);
        gpuSteps += s.gpu->step(1 / 120.f, 1, 1 / 60.f);
    }
    EXPECT_EQ(gpuSteps, stockSteps);
    EXPECT_FALSE(s.onGpu());
    EXPECT_NE(s.gpu->report()->cpuPathReason.find("device memory limit"), std::string::npos)
        << s.gpu->report()->cpuPathReason;
    EXPECT_EQ(s.gpu->report()->deviceBytes, 0u);
    bool named = false;
    for (const Issue& issue : s.gpu->report()->issues) named |= issue.kind == Issue::Kind::OpenCL;
    EXPECT_TRUE(named);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(s.distance(i), 0.0) << "body " << i;
}
