// prepare_contacts_test.cpp — the prepare stage: rows within tolerance of the reference on a
// mixed scene, and Bullet 3.24's targets on hand-made cases: erp2 bias below the split
// threshold, split push rows past it, speculative approach for separated points, the
// restitution curve (2:1 masses) and the effective mass.
#include "contact_fixture.h"
#include "stages/contact_cache.h"
#include "stages/prepare_contacts.h"
#include "test_device.h"
#include "tolerances.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace btgpu;

namespace {

std::vector<BtgContact> runDevice(const ref::ContactBodies& b, const std::vector<BtgManifold>& ms, const BtgStepParams& p)
{
    DeviceWorld w(test::context());
    test::uploadWorld(w, b, ms, uint(ms.size()), {}, ms.size() + 4);
    buildContacts(w, p);
    prepareContacts(w, p);
    return test::downloadContacts(w);
}

void expectNearRel(float got, float want, const char* what, int i)
{
    EXPECT_NEAR(got, want, tol::kStageAbs + tol::kStageRel * std::fabs(want)) << what << " contact " << i;
}

}  // namespace

TEST(PrepareContacts, MatchesReference)
{
    test::StackScene s = test::stackScene(5, 3, 3);
    BtgStepParams p = test::defaultParams(int(s.bodies.props.size()));
    const std::vector<BtgContact> built = ref::buildContacts(s.manifolds, int(s.manifolds.size()), s.bodies, {}, p);
    std::vector<BtgContact> expect = built;
    ref::prepareContacts(expect, s.bodies, p);
    std::vector<BtgContact> got = runDevice(s.bodies, s.manifolds, p);
    ASSERT_EQ(got.size(), expect.size());
    int split = 0, speculative = 0;
    for (size_t i = 0; i < got.size(); ++i) {
        const BtgContact &g = got[i], &e = expect[i];
        for (int c = 0; c < 4; ++c) {
            expectNearRel(btgLane(g.normal, c), btgLane(e.normal, c), "normal/friction", int(i));
            expectNearRel(btgLane(g.t1, c), btgLane(e.t1, c), "t1/restitution", int(i));
            expectNearRel(btgLane(g.t2, c), btgLane(e.t2, c), "t2", int(i));
            expectNearRel(btgLane(g.normalMass, c), btgLane(e.normalMass, c), "normalMass", int(i));
            expectNearRel(btgLane(g.friction1Mass, c), btgLane(e.friction1Mass, c), "friction1Mass", int(i));
            expectNearRel(btgLane(g.friction2Mass, c), btgLane(e.friction2Mass, c), "friction2Mass", int(i));
            expectNearRel(g.rA[c].w, e.rA[c].w, "target", int(i));
            expectNearRel(g.rB[c].w, e.rB[c].w, "push target", int(i));
            split += e.rB[c].w != 0.0f;
            speculative += built[i].rA[c].w > 0.0f;  // the signed distance, before prepare
        }
    }
    EXPECT_GT(split, 0);  // the scene covers every kind of row
    EXPECT_GT(speculative, 0);
}

TEST(PrepareContacts, BulletTargets)
{
    ref::ContactBodies b;
    int ground = test::addBody(b, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.5f);
    int box = test::addBody(b, btgMake4(0, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC, 0.5f);
    int wall = test::addBody(b, btgMake4(5, 0, 0, 0), 0.0f, btgZero4(), BTG_BODY_STATIC);
    BtgStepParams p = test::defaultParams(3);
    std::vector<BtgManifold> ms = {test::boxOnPlane(box, ground, b.pos[box], 0.5f, -0.01f),
                                   test::boxOnPlane(box, ground, b.pos[box], 0.5f, -0.05f),
                                   test::boxOnPlane(box, ground, b.pos[box], 0.5f, 0.01f),
                                   test::boxOnPlane(wall, ground, b.pos[wall], 0.5f, -0.01f)};
    std::vector<BtgContact> c = runDevice(b, ms, p);
    ASSERT_EQ(c.size(), 4u);
    const float invDt = 60.0f;
    for (int k = 0; k < 4; ++k) {
        // Shallow: erp2 * depth / dt joins the velocity row.
        EXPECT_NEAR(c[0].rA[k].w, 0.01f * p.erp2 * invDt, 1e-5f);
        EXPECT_EQ(c[0].rB[k].w, 0.0f);
        // Past the split threshold: the bias moves to the push row, the velocity row keeps 0.
        EXPECT_NEAR(c[1].rA[k].w, 0.0f, 1e-6f);
        EXPECT_NEAR(c[1].rB[k].w, 0.05f * p.erp2 * invDt, 1e-5f);
        // Separated: approach at most distance / dt.
        EXPECT_NEAR(c[2].rA[k].w, -0.01f * invDt, 1e-5f);
        // Two infinite masses: no rows at all.
        EXPECT_EQ(btgLane(c[3].normalMass, k), 0.0f);
    }
    EXPECT_FLOAT_EQ(c[0].normal.w, 0.25f);  // friction 0.5 * 0.5
    // Corner point of a unit box (inertia 1/6): 1 / (1 + 6 |r x n|^2) with r x n = (0.5, 0, -0.5) up to sign.
    EXPECT_NEAR(c[0].normalMass.x, 1.0f / (1.0f + 6.0f * 0.5f), 1e-5f);
    // Friction directions: orthonormal, perpendicular to the normal.
    EXPECT_NEAR(btgDot3(c[0].t1, c[0].normal), 0.0f, 1e-6f);
    EXPECT_NEAR(btgDot3(c[0].t2, c[0].normal), 0.0f, 1e-6f);
    EXPECT_NEAR(btgDot3(c[0].t1, c[0].t2), 0.0f, 1e-6f);
}

TEST(PrepareContacts, RestitutionTwoToOne)
{
    // Sphere A (2 kg) falls at 2 m/s onto sphere B (1 kg) rising at 1 m/s; e = 1 * 0.5.
    ref::ContactBodies b;
    int lower = test::addBody(b, btgZero4(), 1.0f, btgMake4(2.5f, 2.5f, 2.5f, 0), BTG_BODY_DYNAMIC, 0.5f, 0.5f);
    int upper = test::addBody(b, btgMake4(0, 1, 0, 0), 0.5f, btgMake4(1.25f, 1.25f, 1.25f, 0), BTG_BODY_DYNAMIC, 0.5f, 1.0f);
    b.linVel0[upper] = b.linVel[upper] = btgMake4(0, -2, 0, 0);
    b.linVel0[lower] = b.linVel[lower] = btgMake4(0, 1, 0, 0);
    BtgManifold m = test::onePointManifold(upper, lower, btgMake4(0, 1, 0, 0), btgMake4(0, 0.5f, 0, 0), 0.0f);
    BtgManifold slow = m;  // same geometry, approach under the restitution threshold
    BtgStepParams p = test::defaultParams(2);
    std::vector<BtgContact> c = runDevice(b, {m}, p);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_NEAR(c[0].t1.w, 0.5f, 1e-7f);
    EXPECT_NEAR(c[0].rA[0].w, 1.5f, 1e-5f);                   // -e * rel_vel, rel_vel = -3 m/s
    EXPECT_NEAR(c[0].normalMass.x, 1.0f / 1.5f, 1e-6f);       // central: 1 / (1/2 + 1/1)
    b.linVel0[upper] = b.linVel[upper] = btgMake4(0, -0.05f, 0, 0);
    b.linVel0[lower] = b.linVel[lower] = btgMake4(0, 0.05f, 0, 0);
    c = runDevice(b, {slow}, p);
    EXPECT_EQ(c[0].rA[0].w, 0.0f);
}

// A NaN friction must never pose as a legal one (fmin/fmax would turn it into -10).
TEST(PrepareContacts, NanFrictionStaysNan)
{
    EXPECT_TRUE(std::isnan(btgCombinedFriction(std::nanf(""), 0.5f)));
    EXPECT_EQ(btgCombinedFriction(20.0f, 1.0f), 10.0f);
    EXPECT_EQ(btgCombinedFriction(-20.0f, 1.0f), -10.0f);
    EXPECT_EQ(btgCombinedFriction(0.5f, 0.5f), 0.25f);
}

