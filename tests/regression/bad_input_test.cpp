// bad_input_test.cpp — bad bodies on both paths: every kind of unusable input (NaN in a body's
// state or settings, in its shape, in the world's gravity; sizes Bullet itself takes out) is
// named with the body's index and kept out, well-formed bodies far away fall exactly as on a
// clean stock world, and nothing is computed on the app's shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

const float kNan = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

bool names(const Report& report, int index, Issue::Kind kind = Issue::Kind::BadBody)
{
    for (const Issue& issue : report.issues)
        if (issue.kind == kind && issue.bodyIndex == index) return true;
    return false;
}

bool finiteBody(const btRigidBody* b)
{
    const btTransform& t = b->getWorldTransform();
    for (int r = 0; r < 3; ++r)
        if (!std::isfinite(t.getBasis()[r].length2())) return false;
    return std::isfinite(t.getOrigin().length2()) && std::isfinite(b->getLinearVelocity().length2()) &&
           std::isfinite(b->getAngularVelocity().length2());
}

// A ground, a good box falling at x = -20 (body 1), and the body under test at x = +20
// (body 2) resting on the ground beside a good neighbour box touching it (body 3).
struct Layout {
    btCollisionShape* shape = nullptr;  // the test body's shape; a unit box when null
};
ScenePtr layout(WorldKind kind, const Config& config, const std::function<btCollisionShape*(Scene&)>& shapeOf)
{
    auto scene = std::make_unique<Scene>(kind, config);
    scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
    btBoxShape* unit = scene->boxShape(btVector3(0.5f, 0.5f, 0.5f));
    scene->addBody(unit, 1, btVector3(-20, 3, 0));
    btCollisionShape* shape = shapeOf ? shapeOf(*scene) : unit;
    scene->addBody(shape, 1, btVector3(20, 0.5f, 0));
    scene->addBody(unit, 1, btVector3(21, 0.5f, 0));
    return scene;
}

struct BadCase {
    const char* name;
    std::function<void(btRigidBody*)> spoil;                // applied to body 2 between steps
    std::function<btCollisionShape*(Scene&)> shape = {};    // body 2's shape, made bad up front
};

std::vector<BadCase> badCases()
{
    return {
        {"NaN linear velocity", [](btRigidBody* b) { b->setLinearVelocity(btVector3(kNan, 0, 0)); }},
        {"Inf angular velocity", [](btRigidBody* b) { b->setAngularVelocity(btVector3(0, kInf, 0)); }},
        {"NaN position", [](btRigidBody* b) {
             btTransform t = b->getWorldTransform();
             t.setOrigin(btVector3(kNan, 0, 0));
             b->setWorldTransform(t);
         }},
        {"NaN force", [](btRigidBody* b) { b->applyCentralForce(btVector3(0, kNan, 0)); }},
        {"NaN gravity", [](btRigidBody* b) { b->setGravity(btVector3(0, kNan, 0)); }},
        {"NaN linear damping", [](btRigidBody* b) { b->setDamping(kNan, 0); }},
        {"NaN angular damping", [](btRigidBody* b) { b->setDamping(0, kNan); }},
        {"NaN linear factor", [](btRigidBody* b) { b->setLinearFactor(btVector3(1, kNan, 1)); }},
        {"Inf angular factor", [](btRigidBody* b) { b->setAngularFactor(btVector3(kInf, 1, 1)); }},
        {"NaN friction", [](btRigidBody* b) { b->setFriction(kNan); }},
        {"Inf restitution", [](btRigidBody* b) { b->setRestitution(kInf); }},
        {"NaN sleeping thresholds", [](btRigidBody* b) { b->setSleepingThresholds(kNan, 1); }},
        {"NaN mass", [](btRigidBody* b) { b->setMassProps(kNan, btVector3(1, 1, 1)); }},
        {"NaN inertia", [](btRigidBody* b) { b->setMassProps(1, btVector3(kNan, 1, 1)); }},
        {"box with NaN half extents", nullptr,
         [](Scene& s) { return s.boxShape(btVector3(0.5f, kNan, 0.5f)); }},
        {"sphere with NaN radius", nullptr, [](Scene& s) { return s.sphereShape(kNan); }},
        {"box with NaN margin", nullptr,
         [](Scene& s) {
             btBoxShape* box = s.boxShape(btVector3(0.5f, 0.5f, 0.5f));
             box->setMargin(kNan);
             return box;
         }},
        {"box with Inf scaling", nullptr,
         [](Scene& s) {
             btBoxShape* box = s.boxShape(btVector3(0.5f, 0.5f, 0.5f));
             box->setLocalScaling(btVector3(1, kInf, 1));
             return box;
         }},
        {"capsule with NaN radius", nullptr, [](Scene& s) { return s.ownShape(new btCapsuleShape(kNan, 1.0f)); }},
        {"capsule with negative height", nullptr, [](Scene& s) { return s.ownShape(new btCapsuleShape(0.3f, -1.0f)); }},
        {"cylinder with NaN half extents", nullptr,
         [](Scene& s) { return s.ownShape(new btCylinderShape(btVector3(0.5f, kNan, 0.5f))); }},
        {"cone with negative height", nullptr, [](Scene& s) { return s.ownShape(new btConeShape(0.5f, -1.0f)); }},
        // Bullet's hull computer crashes on a NaN point: the world must not run it.
        {"hull with a NaN point", nullptr,
         [](Scene& s) {
             return s.hullShape({{-.5f, -.5f, -.5f}, {.5f, -.5f, -.5f}, {-.5f, .5f, -.5f}, {.5f, .5f, -.5f},
                                 {-.5f, -.5f, .5f}, {.5f, -.5f, .5f}, {-.5f, .5f, .5f}, {kNan, .5f, .5f}});
         }},
    };
}

// Every bad case on one world kind: the test body is named, the neighbours stay finite and
// the far box falls exactly as on a clean stock world.
void expectNamedAndContained(const Config& config, bool gpuPath)
{
    for (const BadCase& c : badCases()) {
        SCOPED_TRACE(c.name);
        ScenePtr gpu = layout(WorldKind::Gpu, config, c.shape);
        ScenePtr clean = layout(WorldKind::Stock, Config::bulletMode(), nullptr);
        for (int i = 0; i < 3; ++i) {
            gpu->step();
            clean->step();
        }
        if (c.spoil) c.spoil(gpu->body(2));
        for (int i = 0; i < 30; ++i) {
            EXPECT_NO_THROW(gpu->step());
            clean->step();
            ASSERT_EQ(gpu->gpuWorld()->isGpuPath(), gpuPath) << gpu->report()->cpuPathReason;
        }
        const int index = gpu->worldIndex(gpu->body(2));
        EXPECT_TRUE(names(*gpu->report(), index)) << "body " << index << " not named";
        for (int good : {1, 3}) {
            EXPECT_FALSE(names(*gpu->report(), gpu->worldIndex(gpu->body(good)))) << "good body " << good << " named";
            EXPECT_TRUE(finiteBody(gpu->body(good))) << "good body " << good;
        }
        EXPECT_LT(std::fabs(gpu->body(1)->getWorldTransform().getOrigin().y() -
                            clean->body(1)->getWorldTransform().getOrigin().y()),
                  tol::kFreeFallPosition);
        // The neighbour rests on the ground, however the bad body ends.
        EXPECT_NEAR(gpu->body(3)->getWorldTransform().getOrigin().y(), 0.5, 0.05);
    }
}

}  // namespace

TEST(BadInput, NamedAndContainedOnTheGpuPath) { expectNamedAndContained(Config::bulletMode(), true); }

TEST(BadInput, NamedAndContainedOnTheCpuPath)
{
    Config config = Config::bulletMode();
    config.forceCpu = true;
    expectNamedAndContained(config, false);
}

TEST(BadInput, FixedBodyComesBack)
{
    for (bool cpu : {false, true}) {
        SCOPED_TRACE(cpu ? "CPU path" : "GPU path");
        Config config = Config::bulletMode();
        config.forceCpu = cpu;
        ScenePtr gpu = layout(WorldKind::Gpu, config, nullptr);
        btRigidBody* b = gpu->body(2);
        gpu->step();
        b->setFriction(kNan);
        for (int i = 0; i < 5; ++i) gpu->step();
        b->setFriction(0.5f);
        b->setLinearVelocity(btVector3(0, 5, 0));  // thrown up once it is well-formed again
        b->activate();
        for (int i = 0; i < 10; ++i) gpu->step();
        EXPECT_GT(b->getWorldTransform().getOrigin().y(), 0.8) << "the fixed body was not simulated again";
        EXPECT_EQ(b->getActivationState() == DISABLE_SIMULATION, false);
    }
}

TEST(BadInput, NanWorldGravityIsNamed)
{
    for (bool cpu : {false, true}) {
        SCOPED_TRACE(cpu ? "CPU path" : "GPU path");
        Config config = Config::bulletMode();
        config.forceCpu = cpu;
        ScenePtr gpu = layout(WorldKind::Gpu, config, nullptr);
        gpu->step();
        gpu->world().setGravity(btVector3(0, kNan, 0));
        for (int i = 0; i < 5; ++i) EXPECT_NO_THROW(gpu->step());
        bool named = false;
        for (const Issue& issue : gpu->report()->issues)
            named |= issue.kind == Issue::Kind::BadArgument && issue.message.find("gravity") != std::string::npos;
        EXPECT_TRUE(named);
        for (int i = 1; i <= 3; ++i) {
            EXPECT_TRUE(names(*gpu->report(), gpu->worldIndex(gpu->body(i)))) << "body " << i;
            EXPECT_TRUE(finiteBody(gpu->body(i))) << "body " << i;
        }
    }
}

// A box spinning at 1e22 rad/s: the rotation update overflows, and Bullet keeps the old basis.
TEST(BadInput, HugeSpinKeepsTheOrientationAsStock)
{
    SideBySide s([](WorldKind kind, const Config& config) {
        auto scene = std::make_unique<Scene>(kind, config);
        btRigidBody* b = scene->addBody(scene->boxShape(btVector3(0.5f, 0.5f, 0.5f)), 1, btVector3(0, 10, 0));
        b->setAngularVelocity(btVector3(1e22f, 0, 0));
        return scene;
    });
    s.step(3);
    ASSERT_TRUE(s.onGpu());
    for (const Issue& issue : s.gpu->report()->issues) EXPECT_NE(issue.kind, Issue::Kind::BadBody) << issue.message;
    const btMatrix3x3& g = s.gpu->body(0)->getWorldTransform().getBasis();
    const btMatrix3x3& k = s.stock->body(0)->getWorldTransform().getBasis();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(g[r][c], k[r][c]) << r << "," << c;
    EXPECT_LT(s.distance(0), tol::kFreeFallPosition);
}

// Sizes stock Bullet handles: a dynamic box of half extent 1e6 is taken out by stock (its AABB
// overflows the broadphase's bound) and must be here too, named; tiny and heavy boxes fall as
// stock's do.
TEST(BadInput, ExtremeSizesAsStock)
{
    struct Extreme {
        const char* name;
        btVector3 halfExtents;
        float mass;
        btVector3 at;
    };
    // The huge box starts far above the rest (overlapping nothing).
    for (const Extreme& e : {Extreme{"half extent 1e6", btVector3(1e6f, 1e6f, 1e6f), 1.0f, btVector3(0, 3e6f, 0)},
                             Extreme{"half extent 1e-6", btVector3(1e-6f, 1e-6f, 1e-6f), 1.0f, btVector3(20, 3, 0)},
                             Extreme{"mass 1e6", btVector3(0.5f, 0.5f, 0.5f), 1e6f, btVector3(20, 3, 0)}}) {
        SCOPED_TRACE(e.name);
        SideBySide s([&](WorldKind kind, const Config& config) {
            auto scene = std::make_unique<Scene>(kind, config);
            scene->addBody(scene->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
            scene->addBody(scene->boxShape(btVector3(0.5f, 0.5f, 0.5f)), 1, btVector3(-20, 3, 0));
            scene->addBody(scene->boxShape(e.halfExtents), e.mass, e.at);
            return scene;
        });
        for (int i = 0; i < 60; ++i) {
            s.step();
            ASSERT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        }
        for (int i = 1; i <= 2; ++i) {
            EXPECT_TRUE(finiteBody(s.gpu->body(i))) << "body " << i;
            EXPECT_EQ(s.gpu->body(i)->getActivationState() == DISABLE_SIMULATION,
                      s.stock->body(i)->getActivationState() == DISABLE_SIMULATION)
                << "body " << i;
        }
        const bool outOnStock = s.stock->body(2)->getActivationState() == DISABLE_SIMULATION;
        EXPECT_EQ(names(*s.gpu->report(), s.gpu->worldIndex(s.gpu->body(2))), outOnStock);
        EXPECT_LT(s.distance(1), tol::kRestHeight);
        // Where it rests (a box smaller than its margin rolls on a point: only the height is
        // comparable).
        if (!outOnStock) EXPECT_NEAR(s.gpuY(2), s.stockY(2), 0.01);
    }
}
