// update_aabbs_test.cpp — device world AABBs equal the CPU reference (same shared function),
// and the reference itself gives the boxes Bullet would: rotated boxes by |R| h, spheres by
// their radius, planes and excluded rows an inverted box that overlaps nothing.
#include "broadphase_scene.h"
#include "reference/update_aabbs.h"
#include "shared/aabb.h"
#include "stages/update_aabbs.h"
#include "test_device.h"
#include "tolerances.h"

#include <gtest/gtest.h>

using namespace btgpu;

namespace {
void expectNear4(BtgFloat4 a, BtgFloat4 b, const char* what, size_t i)
{
    float tx = tol::kStageAbs + tol::kStageRel * std::fabs(b.x);
    float ty = tol::kStageAbs + tol::kStageRel * std::fabs(b.y);
    float tz = tol::kStageAbs + tol::kStageRel * std::fabs(b.z);
    EXPECT_NEAR(a.x, b.x, tx) << what << " row " << i;
    EXPECT_NEAR(a.y, b.y, ty) << what << " row " << i;
    EXPECT_NEAR(a.z, b.z, tz) << what << " row " << i;
}
}  // namespace

TEST(UpdateAabbs, MatchesReference)
{
    test::BroadphaseScene s = test::makeBroadphaseScene(3000, 20.0f, 11);
    DeviceWorld w(test::context());
    s.upload(w);
    const float threshold = 0.02f;
    updateAabbs(w, threshold);
    std::vector<BtgFloat4> gotMin = w.aabbMin.download(w.ctx, s.pos.size());
    std::vector<BtgFloat4> gotMax = w.aabbMax.download(w.ctx, s.pos.size());
    std::vector<BtgFloat4> refMin, refMax;
    ref::updateAabbs(s.pos, s.rot, s.props, s.shapes, threshold, refMin, refMax);
    size_t exact = 0;
    for (size_t i = 0; i < s.pos.size(); ++i) {
        expectNear4(gotMin[i], refMin[i], "min", i);
        expectNear4(gotMax[i], refMax[i], "max", i);
        exact += gotMin[i].x == refMin[i].x && gotMin[i].y == refMin[i].y && gotMin[i].z == refMin[i].z &&
                 gotMax[i].x == refMax[i].x && gotMax[i].y == refMax[i].y && gotMax[i].z == refMax[i].z;
    }
    // Only products, sums and fabs: with contraction off the device rounds like the host.
    EXPECT_EQ(exact, s.pos.size());
}

TEST(UpdateAabbs, ReferenceShapes)
{
    BtgShape box = test::makeBoxShape(1.0f, 2.0f, 0.5f);
    BtgFloat4 at = btgMake4(1, 2, 3, 0);
    BtgAabb a = btgBodyAabb(at, btgMake4(0, 0, 0, 1), box, BTG_BODY_DYNAMIC, 0.1f);
    EXPECT_FLOAT_EQ(a.lo.x, 1 - 1.1f);
    EXPECT_FLOAT_EQ(a.hi.y, 2 + 2.1f);
    EXPECT_FLOAT_EQ(a.lo.z, 3 - 0.6f);
    // 90 degrees about z swaps the x and y extents.
    float s = std::sqrt(0.5f);
    a = btgBodyAabb(at, btgMake4(0, 0, s, s), box, BTG_BODY_DYNAMIC, 0.0f);
    EXPECT_NEAR(a.hi.x - a.lo.x, 4.0f, 1e-5f);
    EXPECT_NEAR(a.hi.y - a.lo.y, 2.0f, 1e-5f);
    // 45 degrees about z: x and y extents both (1 + 2) / sqrt 2.
    float c = std::cos(0.3926991f), sn = std::sin(0.3926991f);
    a = btgBodyAabb(at, btgMake4(0, 0, sn, c), box, BTG_BODY_DYNAMIC, 0.0f);
    EXPECT_NEAR(a.hi.x - at.x, 3.0f * s, 1e-5f);
    EXPECT_NEAR(a.hi.y - at.y, 3.0f * s, 1e-5f);
    EXPECT_NEAR(a.hi.z - at.z, 0.5f, 1e-6f);

    BtgShape sphere{};
    sphere.type = BTG_SHAPE_SPHERE;
    sphere.param = btgMake4(0.7f, 0, 0, 0);
    a = btgBodyAabb(at, btgMake4(0, 0, sn, c), sphere, BTG_BODY_DYNAMIC, 0.05f);
    EXPECT_FLOAT_EQ(a.hi.x, 1 + 0.7f + 0.05f);
    EXPECT_FLOAT_EQ(a.lo.z, 3 - 0.7f - 0.05f);

    BtgShape plane{};
    plane.type = BTG_SHAPE_PLANE;
    a = btgBodyAabb(at, btgMake4(0, 0, 0, 1), plane, BTG_BODY_STATIC, 0.05f);
    EXPECT_GT(a.lo.x, a.hi.x);
    a = btgBodyAabb(at, btgMake4(0, 0, 0, 1), box, BTG_BODY_EXCLUDED, 0.05f);
    EXPECT_GT(a.lo.y, a.hi.y);
}
