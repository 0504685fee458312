// soft_step_motion_test.cpp — a body's own motion in the soft step (SolverKind::SoftStep), no
// contacts: a box tumbling near its intermediate axis (btgpu_accuracy's tumbling_box, Bullet's
// implicit gyroscopic term) turns as in the bullet mode and as on stock. The soft step applies
// the forces' angular change whole at the step's start, as Bullet does; shared out over its
// substeps, the box's energy drifted twice stock's, and more with more substeps. Both btgpu
// worlds asserted on the GPU path at every step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "scenes/accuracy_scenes.h"
#include "tolerances.h"

using namespace btgpu;
using namespace btgpu::scenes;

namespace {

// Rotational energy of copy c's box (from its basis and local inertia, as btgpu_accuracy's
// tumbling_box measures it).
double rotationalEnergy(const AccuracyScene& a, int c)
{
    const btRigidBody* b = a.scene->bodies()[size_t(a.firstBody + c * a.bodiesPerCopy)];
    const btMatrix3x3& r = b->getWorldTransform().getBasis();
    const btVector3 w = b->getAngularVelocity();
    const btVector3 l = r * (b->getLocalInertia() * (w * r));
    return 0.5 * double(w.dot(l));
}

// Its relative energy drift since e0, averaged over the copies.
double drift(const AccuracyScene& a, const std::vector<double>& e0)
{
    double d = 0;
    for (int c = 0; c < a.copies; ++c) d += rotationalEnergy(a, c) / e0[size_t(c)] - 1;
    return d / a.copies;
}

}  // namespace

TEST(SoftStepMotion, TumblingBoxTurnsAsTheBulletMode)
{
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    // Four copies, 12 m apart: the world has pairs to look for, so the soft step runs its
    // substeps (a world with one body integrates as the bullet mode does).
    const int copies = 4;
    AccuracyScene stock = accuracyTumblingBox(WorldKind::Stock, Config::bulletMode(), copies);
    AccuracyScene bullet = accuracyTumblingBox(WorldKind::Gpu, Config::bulletMode(), copies);
    AccuracyScene gpuSoft = accuracyTumblingBox(WorldKind::Gpu, soft, copies);
    std::vector<double> e0;
    for (int c = 0; c < copies; ++c) e0.push_back(rotationalEnergy(stock, c));
    for (int i = 0; i < 120; ++i) {  // 2 s, btgpu_accuracy --quick's run
        stock.scene->step();
        bullet.scene->step();
        gpuSoft.scene->step();
        ASSERT_TRUE(bullet.scene->report()->gpuPath) << "step " << i << ": " << bullet.scene->report()->cpuPathReason;
        ASSERT_TRUE(gpuSoft.scene->report()->gpuPath) << "step " << i << ": " << gpuSoft.scene->report()->cpuPathReason;
        ASSERT_EQ(SolverKind::SoftStep, gpuSoft.scene->report()->solver);
    }
    const std::vector<std::string>& stages = gpuSoft.scene->report()->stages;
    ASSERT_NE(std::find(stages.begin(), stages.end(), "solve_soft"), stages.end()) << "the soft step did not run";
    const double driftStock = drift(stock, e0), driftBullet = drift(bullet, e0), driftSoft = drift(gpuSoft, e0);
    RecordProperty("energy_drift_stock", std::to_string(driftStock));
    RecordProperty("energy_drift_bullet", std::to_string(driftBullet));
    RecordProperty("energy_drift_soft", std::to_string(driftSoft));
    EXPECT_NEAR(driftSoft, driftBullet, tol::kSoftFreeTurnEnergy) << "stock " << driftStock;
    EXPECT_NEAR(driftSoft, driftStock, tol::kSoftFreeTurnEnergy);
    const btVector3 ws = gpuSoft.scene->bodies()[size_t(gpuSoft.firstBody)]->getAngularVelocity();
    const btVector3 wb = bullet.scene->bodies()[size_t(bullet.firstBody)]->getAngularVelocity();
    EXPECT_LT((ws - wb).length(), tol::kSoftFreeTurnEnergy * wb.length()) << "the spin axes parted";
}
