// actions_test.cpp — actions (btActionInterface) on the GPU path: Bullet's raycast vehicle on a
// box ground and on a heightfield against stock, an app's own action that keeps a body awake
// (the deactivation sees what the action did, as Bullet's updateActivationState does), what an
// action sees inside a call of several internal steps, and actions that remove and add bodies.
#include <gtest/gtest.h>

#include "scenes/vehicle_scenes.h"
#include "side_by_side.h"

#include <BulletCollision/CollisionDispatch/btGhostObject.h>
#include <BulletCollision/CollisionShapes/btMinkowskiSumShape.h>

#include <cmath>
#include <functional>

using namespace btgpu;
using namespace btgpu::test;

namespace {

// An app's own action: runs `what` in every updateAction.
struct LambdaAction : btActionInterface {
    std::function<void(btCollisionWorld*, btScalar)> what;
    explicit LambdaAction(std::function<void(btCollisionWorld*, btScalar)> f) : what(std::move(f)) {}
    void updateAction(btCollisionWorld* world, btScalar dt) override { what(world, dt); }
    void debugDraw(btIDebugDraw*) override {}
};

void driveStraight(scenes::VehicleGround ground, const Config& config = Config::bulletMode(), double heightTol = 0.02)
{
    auto stock = scenes::raycastVehicle(scenes::WorldKind::Stock, Config::bulletMode(), ground);
    auto gpu = scenes::raycastVehicle(scenes::WorldKind::Gpu, config, ground);
    const btVector3 start = stock->chassis->getWorldTransform().getOrigin();
    for (int i = 0; i < 300; ++i) {  // 5 s: 1 s settling, then 4 s at full engine force
        const btScalar force = i < 60 ? 0 : 1000;
        stock->drive(force);
        gpu->drive(force);
        stock->scene->step();
        gpu->scene->step();
        ASSERT_TRUE(gpu->scene->gpuWorld()->isGpuPath()) << "step " << i << ": " << gpu->scene->report()->cpuPathReason;
    }
    const double stockRun = (stock->chassis->getWorldTransform().getOrigin() - start).z();
    const double gpuRun = (gpu->chassis->getWorldTransform().getOrigin() - start).z();
    const double stockY = stock->chassis->getWorldTransform().getOrigin().y();
    const double gpuY = gpu->chassis->getWorldTransform().getOrigin().y();
    std::printf("vehicle: stock %.3f m, btgpu %.3f m along z; chassis height %.4f / %.4f m; wheel 0 contact %d/%d\n",
                stockRun, gpuRun, stockY, gpuY, int(stock->vehicle->getWheelInfo(0).m_raycastInfo.m_isInContact),
                int(gpu->vehicle->getWheelInfo(0).m_raycastInfo.m_isInContact));
    EXPECT_GT(stockRun, 5.0);  // it drove
    EXPECT_NEAR(gpuRun, stockRun, 0.05 * stockRun);
    EXPECT_NEAR(gpuY, stockY, heightTol);
    const btVector3 sideways = gpu->chassis->getWorldTransform().getOrigin() - start;
    EXPECT_LT(std::fabs(sideways.x()), 0.05 * gpuRun);  // straight
    for (int w = 0; w < 4; ++w) EXPECT_TRUE(gpu->vehicle->getWheelInfo(w).m_raycastInfo.m_isInContact) << "wheel " << w;
}

}  // namespace

TEST(Actions, RaycastVehicleDrivesAsStockOnABox) { driveStraight(scenes::VehicleGround::Box); }

TEST(Actions, RaycastVehicleDrivesAsStockOnAHeightfield) { driveStraight(scenes::VehicleGround::Heightfield); }

// The library's default solver (Auto: the soft step): the same run, the chassis 1.6 cm higher
// (0.7927 m against stock's 0.7763 on PoCL): its substeps integrate gravity within the step,
// where the vehicle's suspension pushes once a step (the action's impulse), so the two balance
// at another height.
TEST(Actions, RaycastVehicleDrivesAsStockOnTheDefaultSolver)
{
    driveStraight(scenes::VehicleGround::Box, Config(), 0.03);
}

// A box pushed against a wall by an action (touching it from the start): after the solve it is
// still, after the action it moves at 1 m/s (above Bullet's 0.8 m/s sleeping threshold). Bullet's deactivation runs after
// the actions, so the box never sleeps; a deactivation that saw the velocity before the action
// would put it to sleep after 2 s.
TEST(Actions, DeactivationSeesWhatTheActionDid)
{
    auto make = [](WorldKind kind, const Config& config) {
        auto s = std::make_unique<Scene>(kind, config, "pushed_box");
        s->addBody(s->boxShape(btVector3(50, 1, 50)), 0, btVector3(0, -1, 0));
        s->addBody(s->boxShape(btVector3(btScalar(.5), 2, 2)), 0, btVector3(btScalar(1.5), 2, 0));  // the wall
        s->addBody(s->boxShape(btVector3(btScalar(.5), btScalar(.5), btScalar(.5))), 1, btVector3(btScalar(.5), btScalar(.5), 0));
        return s;
    };
    SideBySide s(make);
    LambdaAction stockPush([&](btCollisionWorld*, btScalar) {
        s.stock->body(2)->setLinearVelocity(btVector3(1, s.stock->body(2)->getLinearVelocity().y(), 0));
    });
    LambdaAction gpuPush([&](btCollisionWorld*, btScalar) {
        s.gpu->body(2)->setLinearVelocity(btVector3(1, s.gpu->body(2)->getLinearVelocity().y(), 0));
    });
    s.stock->world().addAction(&stockPush);
    s.gpu->world().addAction(&gpuPush);
    for (int i = 0; i < 240; ++i) {  // 4 s
        s.step();
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
        ASSERT_EQ(s.gpu->body(2)->getActivationState(), s.stock->body(2)->getActivationState()) << "step " << i;
        ASSERT_LT(s.distance(2), tol::kRestHeight) << "step " << i;
    }
    EXPECT_TRUE(s.gpu->body(2)->isActive());
    EXPECT_NEAR(s.gpu->body(2)->getWorldTransform().getOrigin().x(), 0.5, 0.01);  // against the wall
    s.stock->world().removeAction(&stockPush);
    s.gpu->world().removeAction(&gpuPush);
}

// With two internal steps a call, an action runs twice a call and sees the body where that
// internal step put it (not interpolated, not the previous call's).
TEST(Actions, ActionSeesEachInternalStep)
{
    SideBySide s(scenes::freeFall);
    std::vector<double> seenStock, seenGpu;
    LambdaAction stockWatch([&](btCollisionWorld*, btScalar) { seenStock.push_back(s.stock->body(1)->getWorldTransform().getOrigin().y()); });
    LambdaAction gpuWatch([&](btCollisionWorld*, btScalar) { seenGpu.push_back(s.gpu->body(1)->getWorldTransform().getOrigin().y()); });
    s.stock->world().addAction(&stockWatch);
    s.gpu->world().addAction(&gpuWatch);
    for (int i = 0; i < 20; ++i) {
        s.step(1, btScalar(1) / 30, 4, kStep);
        ASSERT_TRUE(s.onGpu()) << "step " << i;
        ASSERT_EQ(seenGpu.size(), seenStock.size()) << "call " << i;
    }
    ASSERT_EQ(seenStock.size(), 40u);
    for (size_t k = 0; k < seenStock.size(); ++k) EXPECT_NEAR(seenGpu[k], seenStock[k], tol::kFreeFallPosition) << k;
    EXPECT_LT(seenStock.back(), seenStock.front() - 1.0);  // it fell
    s.stock->world().removeAction(&stockWatch);
    s.gpu->world().removeAction(&gpuWatch);
}

// An action that removes and deletes a body, and one that adds a body, inside a call of several
// internal steps: the rows follow at the next internal step and nothing reads the deleted body.
TEST(Actions, ActionRemovesAndAddsBodies)
{
    SideBySide s(scenes::dropRow);
    auto changer = [](Scene* scene, int* calls) {
        return [scene, calls](btCollisionWorld*, btScalar) {
            ++*calls;
            if (*calls == 15) scene->removeBody(scene->body(2));
            if (*calls == 25) scene->addBody(scene->sphereShape(btScalar(.5)), 1, btVector3(0, 3, 0));
        };
    };
    int stockCalls = 0, gpuCalls = 0;
    LambdaAction stockChange(changer(s.stock.get(), &stockCalls)), gpuChange(changer(s.gpu.get(), &gpuCalls));
    s.stock->world().addAction(&stockChange);
    s.gpu->world().addAction(&gpuChange);
    for (int i = 0; i < 75; ++i) {
        s.step(1, btScalar(1) / 30, 4, kStep);
        ASSERT_TRUE(s.onGpu()) << "step " << i << ": " << s.gpu->report()->cpuPathReason;
    }
    ASSERT_EQ(gpuCalls, stockCalls);
    ASSERT_EQ(s.gpu->bodies().size(), s.stock->bodies().size());
    for (size_t b = 1; b < s.gpu->bodies().size(); ++b) EXPECT_LT(s.distance(int(b)), tol::kRestHeight) << "body " << b;
    s.stock->world().removeAction(&stockChange);
    s.gpu->world().removeAction(&gpuChange);
}

// An action that adds what the GPU path does not serve (a ghost object of a btMinkowskiSumShape)
// in the first of a call's
// four internal steps: the other three run on Bullet's own internal steps, the report says why,
// and the bodies stay where stock puts them. With the ghost gone the GPU path returns.
TEST(Actions, UnservedObjectAddedByAnActionMovesTheRestOfTheCallToTheCpuPath)
{
    SideBySide s(scenes::dropRow);
    btGhostObject stockGhost, gpuGhost;
    btSphereShape ball(btScalar(0.5));
    btMinkowskiSumShape ghostShape(&ball, &ball);
    stockGhost.setCollisionShape(&ghostShape);
    gpuGhost.setCollisionShape(&ghostShape);
    int stockCalls = 0, gpuCalls = 0;
    auto adder = [](btCollisionWorld* world, btGhostObject* ghost, int* calls) {
        if (++*calls == 9) world->addCollisionObject(ghost, btBroadphaseProxy::SensorTrigger, btBroadphaseProxy::AllFilter);
    };
    LambdaAction stockAdd([&](btCollisionWorld* w, btScalar) { adder(w, &stockGhost, &stockCalls); });
    LambdaAction gpuAdd([&](btCollisionWorld* w, btScalar) { adder(w, &gpuGhost, &gpuCalls); });
    s.stock->world().addAction(&stockAdd);
    s.gpu->world().addAction(&gpuAdd);
    s.step(2, btScalar(4) / 60, 4, kStep);  // 8 internal steps on the GPU path
    ASSERT_TRUE(s.onGpu());
    s.step(1, btScalar(4) / 60, 4, kStep);  // the ghost comes in the first internal step
    EXPECT_FALSE(s.onGpu());
    EXPECT_NE(s.gpu->report()->cpuPathReason.find("from internal step 2 of 4"), std::string::npos)
        << s.gpu->report()->cpuPathReason;
    EXPECT_EQ(gpuCalls, stockCalls);
    for (int b = 1; b <= 3; ++b) EXPECT_LT(s.distance(b), tol::kRestHeight) << "body " << b;
    // The GPU path's manifolds went back to the pool: the dispatcher holds Bullet's own, as stock's.
    EXPECT_EQ(s.gpu->world().getDispatcher()->getNumManifolds(), s.stock->world().getDispatcher()->getNumManifolds());
    s.step(5, btScalar(4) / 60, 4, kStep);
    EXPECT_FALSE(s.onGpu());
    s.stock->world().removeCollisionObject(&stockGhost);
    s.gpu->world().removeCollisionObject(&gpuGhost);
    s.step(20, btScalar(4) / 60, 4, kStep);
    EXPECT_TRUE(s.onGpu());
    EXPECT_EQ(gpuCalls, stockCalls);
    for (int b = 1; b <= 3; ++b) EXPECT_LT(s.distance(b), tol::kRestHeight) << "body " << b;
    s.stock->world().removeAction(&stockAdd);
    s.gpu->world().removeAction(&gpuAdd);
}
