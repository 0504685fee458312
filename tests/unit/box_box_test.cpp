// box_box_test.cpp — shared/box_box.h against stock: the points btBoxBoxDetector reports for two
// btBoxShapes (count, order, normal, points, depths) over boxes resting, tilted, edge on edge and
// at random, and the persistent step's rules (no new point while apart, a kept point goes on
// within the breaking threshold, several added at once).
#include "shared/box_box.h"

#include <btBulletCollisionCommon.h>
#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>

#include <cstdio>
#include <random>
#include <vector>
#include <gtest/gtest.h>

namespace {

struct StockPoints {
    std::vector<btVector3> normal, point;
    std::vector<btScalar> depth;
};

// What the detector hands its result, call by call.
struct Capture : btDiscreteCollisionDetectorInterface::Result {
    StockPoints* out;
    void setShapeIdentifiersA(int, int) override {}
    void setShapeIdentifiersB(int, int) override {}
    void addContactPoint(const btVector3& n, const btVector3& p, btScalar d) override
    {
        out->normal.push_back(n);
        out->point.push_back(p);
        out->depth.push_back(d);
    }
};

StockPoints stock(const btBoxShape& a, const btTransform& ta, const btBoxShape& b, const btTransform& tb)
{
    StockPoints s;
    Capture c;
    c.out = &s;
    btDiscreteCollisionDetectorInterface::ClosestPointInput in;
    in.m_transformA = ta;
    in.m_transformB = tb;
    btBoxBoxDetector detector(&a, &b);
    detector.getClosestPoints(in, c, nullptr);
    return s;
}

BtgCollider collider(const btBoxShape& box, const btTransform& t, int body)
{
    BtgCollider c{};
    const btVector3 h = box.getHalfExtentsWithMargin(), o = t.getOrigin();
    const btQuaternion q = t.getRotation();
    c.shape.type = BTG_SHAPE_BOX;
    c.shape.param = btgMake4(h.x(), h.y(), h.z(), box.getMargin());
    c.pose.pos = btgMake4(o.x(), o.y(), o.z(), 0);
    c.pose.rot = btgQuatToMat3(btgMake4(q.x(), q.y(), q.z(), q.w()));
    c.body = body;
    return c;
}

btTransform pose(btVector3 origin, btQuaternion q = btQuaternion::getIdentity())
{
    return btTransform(q, origin);
}

// Compares one case; returns false (and says why) when btgpu's points are not stock's.
bool same(const btBoxShape& a, const btTransform& ta, const btBoxShape& b, const btTransform& tb, std::string* why)
{
    const StockPoints s = stock(a, ta, b, tb);
    const BtgBoxBoxPoints g = btgBoxBoxPoints(collider(a, ta, 0), collider(b, tb, 1));
    char buf[256];
    if (int(s.point.size()) != g.count) {
        std::snprintf(buf, sizeof buf, "count %d, stock %d", g.count, int(s.point.size()));
        *why = buf;
        return false;
    }
    for (int k = 0; k < g.count; ++k) {
        const btVector3 n(g.normal.x, g.normal.y, g.normal.z), p(g.pointB[k].x, g.pointB[k].y, g.pointB[k].z);
        const double dn = n.dot(s.normal[size_t(k)]), dp = (p - s.point[size_t(k)]).length();
        const double dd = std::fabs(double(g.distance[k]) - double(s.depth[size_t(k)]));
        if (dn < 0.99999 || dp > 1e-4 || dd > 1e-4) {
            std::snprintf(buf, sizeof buf, "point %d: normal dot %.6f, point off %.2e m, depth off %.2e m", k, dn, dp, dd);
            *why = buf;
            return false;
        }
    }
    return true;
}

}  // namespace

// The pile's cases: a box landing on another offset by half its width (one corner over the
// other's corner), slightly tilted either way; a box on a wide ground; a box turned on its edge.
TEST(BoxBox, DetectorPointsAsStockOnStructuredCases)
{
    btBoxShape unit(btVector3(1, 1, 1)), ground(btVector3(400, 1, 400)), small(btVector3(0.1f, 0.1f, 0.1f)),
        plank(btVector3(2, 0.1f, 0.5f));
    struct Case {
        const btBoxShape *a, *b;
        btTransform ta, tb;
    };
    std::vector<Case> cases;
    for (int s = 0; s < 9; ++s) {
        const btScalar tilt = btScalar(s - 4) * btScalar(0.002);
        cases.push_back({&unit, &unit, pose(btVector3(0, 5, 0)),
                         pose(btVector3(1, 6.97f, 1), btQuaternion(btVector3(1, 0, 1).normalized(), tilt))});
        cases.push_back({&ground, &unit, pose(btVector3(0, -1, 0)),
                         pose(btVector3(0.3f, 0.99f, -2), btQuaternion(btVector3(0, 0, 1), tilt))});
        cases.push_back({&unit, &small, pose(btVector3(0, 0, 0), btQuaternion(btVector3(0, 1, 0), 0.3f)),
                         pose(btVector3(0.2f, 1.09f, 0.1f), btQuaternion(btVector3(1, 0, 0), 0.01f + tilt))});
        cases.push_back({&unit, &unit, pose(btVector3(0, 0, 0)),
                         pose(btVector3(0, 2.37f, 0), btQuaternion(btVector3(1, 0, 1).normalized(), btScalar(0.785) + tilt))});
        cases.push_back({&plank, &unit, pose(btVector3(0, 0, 0), btQuaternion(btVector3(0, 0, 1), 0.2f)),
                         pose(btVector3(1.5f, 1.35f, 0.2f), btQuaternion(btVector3(0, 0, 1), 0.2f + tilt))});
    }
    int pointsSeen = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        std::string why;
        EXPECT_TRUE(same(*cases[i].a, cases[i].ta, *cases[i].b, cases[i].tb, &why)) << "case " << i << ": " << why;
        const int n = int(stock(*cases[i].a, cases[i].ta, *cases[i].b, cases[i].tb).point.size());
        pointsSeen += n;
    }
    EXPECT_GT(pointsSeen, 60);  // the cases touch: the comparison is not of empty answers
}

// Random boxes near contact (fixed seed): the same points as stock in at least 99.5% of the
// cases (a near tie between two axes may fall the other way on rounding), and never a point where
// stock finds the boxes apart.
TEST(BoxBox, DetectorPointsAsStockAtRandom)
{
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> u(-1, 1), ext(0.05f, 2.0f);
    int cases = 0, matched = 0, touching = 0;
    for (int i = 0; i < 4000; ++i) {
        btBoxShape a(btVector3(ext(rng), ext(rng), ext(rng))), b(btVector3(ext(rng), ext(rng), ext(rng)));
        const btQuaternion qa(btVector3(u(rng), u(rng), u(rng)).normalized(), 3.14159f * u(rng));
        const btQuaternion qb(btVector3(u(rng), u(rng), u(rng)).normalized(), 3.14159f * u(rng));
        const btVector3 ha = a.getHalfExtentsWithMargin(), hb = b.getHalfExtentsWithMargin();
        const btScalar reach = ha.length() + hb.length();
        const btVector3 d = btVector3(u(rng), u(rng), u(rng)).normalized() * (reach * (0.35f + 0.5f * std::fabs(u(rng))));
        const btTransform ta(qa, btVector3(0, 0, 0)), tb(qb, d);
        std::string why;
        ++cases;
        const StockPoints s = stock(a, ta, b, tb);
        touching += !s.point.empty();
        if (same(a, ta, b, tb, &why)) ++matched;
        else if (s.point.empty()) ADD_FAILURE() << "case " << i << ": a point where stock finds none: " << why;
    }
    std::printf("box-box at random: %d of %d as stock (%d touching)\n", matched, cases, touching);
    EXPECT_GT(touching, 1000);
    EXPECT_GE(matched, cases - cases / 200);
}

// The persistent step: nothing new while the boxes are apart (even within the breaking
// threshold), a kept point goes on while within it, and a new overlap adds the detector's points.
TEST(BoxBox, PersistentStepKeepsAndAddsAsStock)
{
    btBoxShape unit(btVector3(1, 1, 1));
    const float threshold = 0.035f;
    float dist[BTG_MAX_POINTS];
    // 1 cm apart: stock's detector reports nothing, so a new pair holds nothing.
    BtgPersistentManifold m = btgBoxBoxStep(btgEmptyPersistent(0, 1, BTG_PAIR_BOX_BOX), collider(unit, pose(btVector3(0, 0, 0)), 0),
                                            collider(unit, pose(btVector3(0.5f, 2.01f, 0.5f)), 1), threshold, dist);
    EXPECT_EQ(m.numPoints, 0);
    // 2 mm deep: the four corners of the overlap, all added at once.
    m = btgBoxBoxStep(m, collider(unit, pose(btVector3(0, 0, 0)), 0), collider(unit, pose(btVector3(0.5f, 1.998f, 0.5f)), 1),
                      threshold, dist);
    ASSERT_EQ(m.numPoints, 4);
    EXPECT_EQ(m.added, -2);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(dist[k], -0.002f, 1e-5f);
    // Lifted 1 cm apart: the detector adds nothing, the refresh keeps the four (within 3.5 cm).
    BtgPersistentManifold kept = btgBoxBoxStep(m, collider(unit, pose(btVector3(0, 0, 0)), 0),
                                               collider(unit, pose(btVector3(0.5f, 2.008f, 0.5f)), 1), threshold, dist);
    ASSERT_EQ(kept.numPoints, 4);
    EXPECT_EQ(kept.added, -1);
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(kept.id[k], m.id[k]);
        EXPECT_NEAR(dist[k], 0.008f, 1e-5f);
    }
    // 5 cm apart: beyond the threshold, the refresh drops them.
    kept = btgBoxBoxStep(m, collider(unit, pose(btVector3(0, 0, 0)), 0), collider(unit, pose(btVector3(0.5f, 2.05f, 0.5f)), 1),
                         threshold, dist);
    EXPECT_EQ(kept.numPoints, 0);
}
