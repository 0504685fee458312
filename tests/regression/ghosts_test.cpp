// ghosts_test.cpp — ghost objects on the GPU path against stock: a trigger volume's overlapping
// objects and its pair cache each step while boxes fall through it (and after the app moves
// it), an app's ghost subclass getting stock's add/remove calls, Bullet's kinematic character
// walking into a step and a wall, and a character's ghost beside dynamic bodies falling back.
#include <gtest/gtest.h>

#include "scenes/ghost_scenes.h"
#include "side_by_side.h"

#include <algorithm>
#include <functional>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace btgpu;
using namespace btgpu::test;
using scenes::GhostScene;

namespace {

int indexOf(const btCollisionWorld& world, const btCollisionObject* o)
{
    return world.getCollisionObjectArray().findLinearSearch(const_cast<btCollisionObject*>(o));
}

// The world indices of the objects a ghost overlaps, in its list's order.
std::vector<int> overlapping(const GhostScene& g)
{
    std::vector<int> out;
    for (int i = 0; i < g.ghost()->getNumOverlappingObjects(); ++i)
        out.push_back(indexOf(g.scene->world(), g.ghost()->getOverlappingObject(i)));
    return out;
}

// A btPairCachingGhostObject's pairs as (smaller, larger) world indices, sorted.
std::vector<std::pair<int, int>> cachedPairs(const GhostScene& g)
{
    auto* ghost = static_cast<btPairCachingGhostObject*>(g.ghost());
    const btBroadphasePairArray& pairs = ghost->getOverlappingPairCache()->getOverlappingPairArray();
    std::vector<std::pair<int, int>> out;
    for (int i = 0; i < pairs.size(); ++i) {
        int a = indexOf(g.scene->world(), static_cast<btCollisionObject*>(pairs[i].m_pProxy0->m_clientObject));
        int b = indexOf(g.scene->world(), static_cast<btCollisionObject*>(pairs[i].m_pProxy1->m_clientObject));
        out.emplace_back(std::min(a, b), std::max(a, b));
    }
    std::sort(out.begin(), out.end());
    return out;
}

// An app's own ghost: logs every add and remove call ((+/-) world index of the other object).
struct LoggingGhost : btGhostObject {
    std::vector<int>* log = nullptr;
    btCollisionWorld* world = nullptr;
    void addOverlappingObjectInternal(btBroadphaseProxy* other, btBroadphaseProxy* self) override
    {
        log->push_back(1 + indexOf(*world, static_cast<btCollisionObject*>(other->m_clientObject)));
        btGhostObject::addOverlappingObjectInternal(other, self);
    }
    void removeOverlappingObjectInternal(btBroadphaseProxy* other, btDispatcher* d, btBroadphaseProxy* self) override
    {
        log->push_back(-1 - indexOf(*world, static_cast<btCollisionObject*>(other->m_clientObject)));
        btGhostObject::removeOverlappingObjectInternal(other, d, self);
    }
};

// One step of the trigger scene on both worlds: at step 100 the app moves the trigger 23 m down,
// into the path of the boxes still falling; the GPU world must stay on the GPU path.
void stepTriggerFall(GhostScene& stock, GhostScene& gpu, int i)
{
    if (i == 100) {
        stock.moveGhost(0, btVector3(0, -20, 0));
        gpu.moveGhost(0, btVector3(0, -20, 0));
    }
    stock.scene->step();
    gpu.scene->step();
    ASSERT_TRUE(gpu.scene->gpuWorld()->isGpuPath()) << "step " << i << ": " << gpu.scene->report()->cpuPathReason;
}

}  // namespace

// Each step the trigger holds the bodies stock's holds, in stock's order, and its pair cache
// stock's pairs; the most it held at once and the steps it held any say the boxes went through.
// After 100 steps the app moves it 23 m down, into the path of the boxes still falling.
TEST(Ghosts, TriggerCountsTheBodiesInsideAsStock)
{
    auto stock = scenes::triggerFall(WorldKind::Stock);
    auto gpu = scenes::triggerFall(WorldKind::Gpu);
    int most = 0, stepsWithAny = 0;
    std::set<int> seen;
    std::set<int> seenAfterMove;
    for (int i = 0; i < 180; ++i) {
        ASSERT_NO_FATAL_FAILURE(stepTriggerFall(*stock, *gpu, i));
        const std::vector<int> s = overlapping(*stock), g = overlapping(*gpu);
        ASSERT_EQ(g, s) << "step " << i;
        ASSERT_EQ(cachedPairs(*gpu), cachedPairs(*stock)) << "step " << i;
        most = std::max(most, int(s.size()));
        stepsWithAny += !s.empty();
        seen.insert(s.begin(), s.end());
        if (i >= 100) seenAfterMove.insert(s.begin(), s.end());
    }
    std::printf("trigger: up to %d bodies at once, %d steps with any, %zu bodies seen (%zu after the move); host "
                "broadphase %.3f ms a call\n",
                most, stepsWithAny, seen.size(), seenAfterMove.size(), gpu->scene->report()->ghostBroadphaseMs);
    EXPECT_EQ(seen.size(), 8u);     // eight boxes went through
    EXPECT_EQ(seen.count(10), 0u);  // not the box falling beside it (scene body 9; the ghost is world index 1)
    EXPECT_GE(most, 2);
    EXPECT_EQ(seenAfterMove.size(), 8u);  // and through it again where the app moved it
    EXPECT_FALSE(gpu->scene->report()->stages.empty());
    for (int b = 1; b <= 9; ++b)
        EXPECT_LT((stock->scene->body(b)->getWorldTransform().getOrigin() - gpu->scene->body(b)->getWorldTransform().getOrigin()).length(),
                  tol::kRestHeight) << "body " << b;
}

namespace {

// When each body entered and last was in the trigger's list (the two passes through it apart), on
// stock and on a btgpu world run with `config`; `each` sees both sorted lists every step.
struct TriggerTimes {
    std::map<int, int> enteredS, enteredG, leftS, leftG;
    int differ = 0;  // steps whose lists differ
};
TriggerTimes triggerTimes(const Config& config,
                          const std::function<void(int, const std::vector<int>&, const std::vector<int>&, GhostScene&)>& each)
{
    auto stock = scenes::triggerFall(WorldKind::Stock);
    auto gpu = scenes::triggerFall(WorldKind::Gpu, config);
    TriggerTimes t;
    for (int i = 0; i < 180; ++i) {
        stepTriggerFall(*stock, *gpu, i);
        if (::testing::Test::HasFatalFailure()) return t;
        std::vector<int> s = overlapping(*stock), g = overlapping(*gpu);
        std::sort(s.begin(), s.end());
        std::sort(g.begin(), g.end());
        t.differ += s != g;
        each(i, s, g, *gpu);
        const int pass = i < 100 ? 0 : 1000;
        for (int b : s) {
            t.enteredS.emplace(pass + b, i);
            t.leftS[pass + b] = i;
        }
        for (int b : g) {
            t.enteredG.emplace(pass + b, i);
            t.leftG[pass + b] = i;
        }
    }
    std::printf("trigger (%s): %d of 180 steps differ from stock's list; host broadphase %.3f ms a call\n",
                config.ghostPairsFromDevice ? "from the device" : "from the tree", t.differ,
                gpu->scene->report()->ghostBroadphaseMs);
    EXPECT_EQ(t.enteredG.size(), t.enteredS.size());
    EXPECT_EQ(t.enteredG.size(), 16u);  // eight boxes, twice
    for (const auto& [b, step] : t.enteredS) EXPECT_EQ(t.enteredG[b], step) << "body " << b;
    return t;
}

}  // namespace

// The same trigger as a big world would run it (Config::ghostPairsExactUpTo 0): only the ghost's
// pairs updated, from Bullet's own tree. Each body enters the trigger's list at stock's step
// (the same leaves), and leaves it at most 10 steps before stock's (whose lazy cleanup keeps a
// pair that stopped overlapping up to ~10 steps); the list never holds a body stock's does not.
TEST(Ghosts, TriggerInABigWorldFromTheTree)
{
    Config big = Config::bulletMode();
    big.ghostPairsExactUpTo = 0;
    big.ghostPairsFromDevice = false;
    const TriggerTimes t = triggerTimes(big, [](int i, const std::vector<int>& s, const std::vector<int>& g, GhostScene&) {
        for (int b : g) EXPECT_TRUE(std::binary_search(s.begin(), s.end(), b)) << "step " << i << " body " << b;
    });
    for (const auto& [b, step] : t.leftS) {
        EXPECT_LE(t.leftG.at(b), step) << "body " << b;
        EXPECT_GE(t.leftG.at(b), step - 10) << "body " << b;
    }
}

// The same trigger with its pairs from the device (Config::ghostPairsFromDevice, the default past
// ghostPairsExactUpTo): stock's Dbvt leaves kept by stage broadphase_leaves, stock's pair cache
// followed on the host with its lazy cleanup, the ghost pairs put into Bullet's pair cache (whose
// ghost callback fills the list); no broadphase work on the host. Each body enters the trigger's
// list at stock's step and leaves it within 10 steps of stock's (the followed cache's order is not
// stock's, so its round-robin cleanup reaches a pair at another step); the app's move of the
// trigger is followed; the pair cache of a btPairCachingGhostObject holds the list's pairs.
TEST(Ghosts, TriggerInABigWorldFromTheDevice)
{
    Config big = Config::bulletMode();
    big.ghostPairsExactUpTo = 0;
    double hostMs = 0.0;
    const TriggerTimes t = triggerTimes(big, [&hostMs](int i, const std::vector<int>&, const std::vector<int>& g, GhostScene& gpu) {
        const std::vector<std::string>& stages = gpu.scene->report()->stages;
        EXPECT_NE(std::find(stages.begin(), stages.end(), "broadphase_leaves"), stages.end()) << "step " << i;
        EXPECT_EQ(cachedPairs(gpu).size(), g.size()) << "step " << i;
        hostMs += gpu.scene->report()->ghostBroadphaseMs;
    });
    for (const auto& [b, step] : t.leftS) EXPECT_NEAR(t.leftG.at(b), step, 10) << "body " << b;
    EXPECT_EQ(hostMs, 0.0);  // nothing of Bullet's broadphase ran
}

// An app's ghost subclass with its own addOverlappingObjectInternal and
// removeOverlappingObjectInternal gets stock's calls, in stock's order, at the same steps.
TEST(Ghosts, GhostSubclassGetsStockCalls)
{
    std::vector<int> stockLog, gpuLog;
    auto maker = [](std::vector<int>* log) {
        return [log]() {
            auto* g = new LoggingGhost();
            g->log = log;
            return static_cast<btGhostObject*>(g);
        };
    };
    auto stock = scenes::triggerFall(WorldKind::Stock, Config::bulletMode(), maker(&stockLog));
    auto gpu = scenes::triggerFall(WorldKind::Gpu, Config::bulletMode(), maker(&gpuLog));
    static_cast<LoggingGhost*>(stock->ghost())->world = &stock->scene->world();
    static_cast<LoggingGhost*>(gpu->ghost())->world = &gpu->scene->world();
    for (int i = 0; i < 180; ++i) {
        stock->scene->step();
        gpu->scene->step();
        ASSERT_TRUE(gpu->scene->gpuWorld()->isGpuPath()) << "step " << i << ": " << gpu->scene->report()->cpuPathReason;
        ASSERT_EQ(gpuLog, stockLog) << "step " << i;
    }
    const size_t removes = size_t(std::count_if(stockLog.begin(), stockLog.end(), [](int v) { return v < 0; }));
    std::printf("ghost subclass: %zu calls, %zu of them removes\n", stockLog.size(), removes);
    EXPECT_GE(stockLog.size(), 16u);  // eight boxes in and out
    EXPECT_GE(removes, 8u);
}

// Bullet's character walks 3 s along +z: up the 0.3 m step, across it, down, into the wall. It
// is where stock's is within 1 cm each step, on the ground when stock's is, and it did step up
// and stop at the wall. Its ghost is moved by the character inside each step (setWorldTransform).
void walkIntoAStepAndAWall(const Config& config)
{
    auto stock = scenes::characterWalk(WorldKind::Stock);
    auto gpu = scenes::characterWalk(WorldKind::Gpu, config);
    double onStep = 0, onGroundAfter = 0, zAt150 = 0;
    for (int i = 0; i < 180; ++i) {
        stock->character->setWalkDirection(btVector3(0, 0, btScalar(0.05)));
        gpu->character->setWalkDirection(btVector3(0, 0, btScalar(0.05)));
        stock->scene->step();
        gpu->scene->step();
        ASSERT_TRUE(gpu->scene->gpuWorld()->isGpuPath()) << "step " << i << ": " << gpu->scene->report()->cpuPathReason;
        const btVector3 s = stock->ghost()->getWorldTransform().getOrigin(), g = gpu->ghost()->getWorldTransform().getOrigin();
        ASSERT_LT((s - g).length(), 0.01) << "step " << i;
        ASSERT_EQ(gpu->character->onGround(), stock->character->onGround()) << "step " << i;
        ASSERT_EQ(gpu->character->canJump(), stock->character->canJump()) << "step " << i;
        if (i == 60) onStep = g.y();         // z 3: on the step
        if (i == 130) onGroundAfter = g.y();  // z 6.5: down again
        if (i == 150) zAt150 = g.z();
    }
    const btVector3 end = stock->ghost()->getWorldTransform().getOrigin(), gEnd = gpu->ghost()->getWorldTransform().getOrigin();
    std::printf("character: stock ends at z %.4f y %.4f, btgpu at z %.4f y %.4f; on the step %.3f m, after it %.3f m\n",
                end.z(), end.y(), gEnd.z(), gEnd.y(), onStep, onGroundAfter);
    EXPECT_NEAR(onStep - onGroundAfter, 0.3, 0.02);  // it stepped up the 0.3 m step, and down
    EXPECT_LT(gEnd.z(), 7.75);                        // the wall's face
    EXPECT_NEAR(gEnd.z(), zAt150, 1e-4);              // stopped there: 1.5 m of walking into it
    EXPECT_TRUE(gpu->character->onGround());
    EXPECT_LT((end - gEnd).length(), 0.01);
}

TEST(Ghosts, CharacterWalksIntoAStepAndAWallAsStock) { walkIntoAStepAndAWall(Config::bulletMode()); }

// The same as a big world runs it: the character's ghost pairs from Bullet's tree only.
TEST(Ghosts, CharacterInABigWorldWalksAsStock)
{
    Config big = Config::bulletMode();
    big.ghostPairsExactUpTo = 0;
    big.ghostPairsFromDevice = false;
    walkIntoAStepAndAWall(big);
}

// A character's ghost (contact response) keeps the tree even where triggers' pairs come from the
// device: its action's setAabb calls move stock's leaf within the step, which the device's leaves
// do not follow (it lands 12 cm late off the step without the tree).
TEST(Ghosts, CharacterInABigWorldKeepsTheTree)
{
    Config big = Config::bulletMode();
    big.ghostPairsExactUpTo = 0;
    walkIntoAStepAndAWall(big);
    auto gpu = scenes::characterWalk(WorldKind::Gpu, big);
    gpu->scene->step();
    const std::vector<std::string>& stages = gpu->scene->report()->stages;
    EXPECT_EQ(std::find(stages.begin(), stages.end(), "broadphase_leaves"), stages.end());
    EXPECT_GT(gpu->scene->report()->ghostBroadphaseMs, 0.0);
}

// A character standing 3 s with a box against its capsule and one far off: stock unites the box
// and the ghost (never deactivated) into one island over their broadphase pair, so the box never
// sleeps; the far one does. Then it walks 1 s into the box, which its ghost pushes (a fixed body
// in stock's solver). Both worlds alike every step.
TEST(Ghosts, BodyAgainstACharacterStaysAwakeAsStock)
{
    auto stock = scenes::characterWalk(WorldKind::Stock, Config::bulletMode(), true);
    auto gpu = scenes::characterWalk(WorldKind::Gpu, Config::bulletMode(), true);
    bool farSlept = false;
    double worstPushed = 0;
    for (int i = 0; i < 240; ++i) {
        const btVector3 walk = i < 180 ? btVector3(0, 0, 0) : btVector3(btScalar(0.02), 0, 0);
        stock->character->setWalkDirection(walk);
        gpu->character->setWalkDirection(walk);
        stock->scene->step();
        gpu->scene->step();
        ASSERT_TRUE(gpu->scene->gpuWorld()->isGpuPath()) << "step " << i << ": " << gpu->scene->report()->cpuPathReason;
        ASSERT_TRUE(stock->scene->body(3)->isActive()) << "step " << i;
        ASSERT_TRUE(gpu->scene->body(3)->isActive()) << "step " << i;
        const btVector3 s = stock->ghost()->getWorldTransform().getOrigin(), g = gpu->ghost()->getWorldTransform().getOrigin();
        ASSERT_LT((s - g).length(), 0.01) << "step " << i;
        // At rest to the millimetre; pushed, as boxes a kinematic body pushes.
        for (int b = 3; b <= 4; ++b) {
            const double d = (stock->scene->body(b)->getWorldTransform().getOrigin() - gpu->scene->body(b)->getWorldTransform().getOrigin()).length();
            ASSERT_LT(d, i < 180 ? tol::kRestHeight : tol::kPushedPosition) << "step " << i << " body " << b;
            if (i >= 180) worstPushed = std::max(worstPushed, d);
        }
        farSlept |= !gpu->scene->body(4)->isActive();
    }
    const double pushed = gpu->scene->body(3)->getWorldTransform().getOrigin().x() - 0.7;
    std::printf("character and boxes: the box against it pushed %.3f m (stock %.3f m, at most %.4f m apart); far box "
                "asleep %d/%d\n",
                pushed, stock->scene->body(3)->getWorldTransform().getOrigin().x() - 0.7, worstPushed,
                int(!stock->scene->body(4)->isActive()), int(!gpu->scene->body(4)->isActive()));
    EXPECT_TRUE(farSlept);
    EXPECT_FALSE(stock->scene->body(4)->isActive());
    EXPECT_GT(pushed, 0.1);
}

// A ghost as btCollisionObject starts (CF_STATIC_OBJECT, contact response) is a static collider in
// stock: a box dropped onto it lands, rests and sleeps where and when stock's does, and the
// ghost lists the box from the step stock's does.
TEST(Ghosts, StaticGhostIsAColliderAsStock)
{
    auto stock = scenes::ghostPlatform(WorldKind::Stock);
    auto gpu = scenes::ghostPlatform(WorldKind::Gpu);
    int firstListed = -1;
    for (int i = 0; i < 180; ++i) {
        stock->scene->step();
        gpu->scene->step();
        ASSERT_TRUE(gpu->scene->gpuWorld()->isGpuPath()) << "step " << i << ": " << gpu->scene->report()->cpuPathReason;
        ASSERT_LT((stock->scene->body(0)->getWorldTransform().getOrigin() - gpu->scene->body(0)->getWorldTransform().getOrigin()).length(),
                  tol::kRestHeight) << "step " << i;
        ASSERT_EQ(gpu->ghost()->getNumOverlappingObjects(), stock->ghost()->getNumOverlappingObjects()) << "step " << i;
        if (firstListed < 0 && stock->ghost()->getNumOverlappingObjects() > 0) firstListed = i;
    }
    const double y = gpu->scene->body(0)->getWorldTransform().getOrigin().y();
    std::printf("static ghost platform: box rests at y %.4f (stock %.4f), listed from step %d, asleep %d/%d\n", y,
                stock->scene->body(0)->getWorldTransform().getOrigin().y(), firstListed, int(!stock->scene->body(0)->isActive()),
                int(!gpu->scene->body(0)->isActive()));
    EXPECT_NEAR(y, 0.4, 0.02);  // on the platform, not through it
    EXPECT_GE(firstListed, 0);
    EXPECT_FALSE(stock->scene->body(0)->isActive());
    EXPECT_EQ(gpu->scene->body(0)->isActive(), stock->scene->body(0)->isActive());
}
