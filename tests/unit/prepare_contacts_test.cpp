// prepare_contacts_test.cpp — the prepare stage: rows within tolerance of the reference on a
// mixed scene, and Bullet 3.24's targets on hand-made cases: erp2 bias below the split
// threshold, split push rows past it, speculative approach for separated points, the
// restitution curve (2:1 masses) and the effective mass; and the rows against the ones
// Bullet's own convertContact builds (relaxation, cfm, soft contacts, rolling rows).
#include "contact_fixture.h"
#include "shared/persistent_manifold.h"
#include "stages/contact_cache.h"
#include "stages/prepare_contacts.h"
#include "test_device.h"
#include "tolerances.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include <cmath>
#include <gtest/gtest.h>
#include <memory>

using namespace btgpu;

namespace {

std::vector<BtgContact> runDevice(const ref::ContactBodies& b, const std::vector<BtgManifold>& ms, const BtgStepParams& p,
                                  std::vector<BtgEdge>* edges = nullptr)
{
    DeviceWorld w(test::context());
    test::uploadWorld(w, b, ms, uint(ms.size()), {}, ms.size() + 4);
    buildContacts(w, p);
    prepareContacts(w, p);
    if (edges) {
        size_t n = w.counters.download(w.ctx, kNumCounters)[kEdgeCount];
        *edges = w.edges.download(w.ctx, n);
    }
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
    std::vector<BtgEdge> expectEdges = ref::prepareContacts(expect, s.bodies, p);
    std::vector<BtgEdge> gotEdges;
    std::vector<BtgContact> got = runDevice(s.bodies, s.manifolds, p, &gotEdges);
    ASSERT_EQ(got.size(), expect.size());
    // Every contact is an edge of the constraint graph, in contact order.
    ASSERT_EQ(gotEdges.size(), expectEdges.size());
    for (size_t i = 0; i < gotEdges.size(); ++i) {
        EXPECT_EQ(gotEdges[i].bodyA, expectEdges[i].bodyA) << i;
        EXPECT_EQ(gotEdges[i].bodyB, expectEdges[i].bodyB) << i;
        EXPECT_EQ(gotEdges[i].bodyA, got[i].bodyA) << i;
    }
    int split = 0, speculative = 0;
    for (size_t i = 0; i < got.size(); ++i) {
        const BtgContact &g = got[i], &e = expect[i];
        for (int c = 0; c < 4; ++c) {
            expectNearRel(btgLane(g.normal, c), btgLane(e.normal, c), "normal", int(i));
            expectNearRel(btgLane(g.tangent1, c), btgLane(e.tangent1, c), "tangent1", int(i));
            expectNearRel(btgLane(g.tangent2, c), btgLane(e.tangent2, c), "tangent2", int(i));
            expectNearRel(btgLane(g.frictionCos, c), btgLane(e.frictionCos, c), "frictionCos", int(i));
            expectNearRel(btgLane(g.frictionSin, c), btgLane(e.frictionSin, c), "frictionSin", int(i));
            expectNearRel(btgLane(g.normalMass, c), btgLane(e.normalMass, c), "normalMass", int(i));
            expectNearRel(btgLane(g.friction1Mass, c), btgLane(e.friction1Mass, c), "friction1Mass", int(i));
            expectNearRel(btgLane(g.friction2Mass, c), btgLane(e.friction2Mass, c), "friction2Mass", int(i));
            expectNearRel(btgLane(g.normalTarget, c), btgLane(e.normalTarget, c), "target", int(i));
            expectNearRel(btgLane(g.pushTarget, c), btgLane(e.pushTarget, c), "push target", int(i));
            EXPECT_EQ(btgLane(g.separation, c), btgLane(built[i].separation, c)) << "separation " << i;
            split += btgLane(e.pushTarget, c) != 0.0f;
            speculative += btgLane(built[i].separation, c) > 0.0f;
        }
        expectNearRel(g.friction, e.friction, "friction", int(i));
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
        EXPECT_NEAR(btgLane(c[0].normalTarget, k), 0.01f * p.erp2 * invDt, 1e-5f);
        EXPECT_EQ(btgLane(c[0].pushTarget, k), 0.0f);
        // Past the split threshold: the bias moves to the push row, the velocity row keeps 0.
        EXPECT_NEAR(btgLane(c[1].normalTarget, k), 0.0f, 1e-6f);
        EXPECT_NEAR(btgLane(c[1].pushTarget, k), 0.05f * p.erp2 * invDt, 1e-5f);
        // Separated: approach at most distance / dt.
        EXPECT_NEAR(btgLane(c[2].normalTarget, k), -0.01f * invDt, 1e-5f);
        // Two infinite masses: no rows at all.
        EXPECT_EQ(btgLane(c[3].normalMass, k), 0.0f);
    }
    EXPECT_FLOAT_EQ(c[0].friction, 0.25f);  // 0.5 * 0.5
    // Corner point of a unit box (inertia 1/6): 1 / (1 + 6 |r x n|^2) with r x n = (0.5, 0, -0.5) up to sign.
    EXPECT_NEAR(c[0].normalMass.x, 1.0f / (1.0f + 6.0f * 0.5f), 1e-5f);
    // Friction directions: orthonormal, perpendicular to the normal.
    EXPECT_NEAR(btgDot3(c[0].tangent1, c[0].normal), 0.0f, 1e-6f);
    EXPECT_NEAR(btgDot3(c[0].tangent2, c[0].normal), 0.0f, 1e-6f);
    EXPECT_NEAR(btgDot3(c[0].tangent1, c[0].tangent2), 0.0f, 1e-6f);
}

// Bullet's convertContact gives each point its own friction direction: along that point's slip
// velocity taken after this substep's forces (getVelocityInLocalPointNoDelta), btPlaneSpace1's p
// when it slips less than sqrt(SIMD_EPSILON). A box spinning about the normal slips a different
// way at each corner; before the forces it was at rest (so the pre-force velocity would give p).
TEST(PrepareContacts, FrictionDirectionPerPointAlongItsSlip)
{
    ref::ContactBodies b;
    int ground = test::addBody(b, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.5f);
    int box = test::addBody(b, btgMake4(0, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC, 0.5f);
    int still = test::addBody(b, btgMake4(3, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC, 0.5f);
    b.linVel0[box] = btgZero4();
    b.angVel0[box] = btgZero4();
    b.angVel[box] = btgMake4(0, 2, 0, 0);
    b.linVel[box] = btgMake4(0, -0.1f, 0, 0);  // gravity's impulse: along the normal, no slip
    BtgStepParams p = test::defaultParams(3);
    std::vector<BtgManifold> ms = {test::boxOnPlane(box, ground, b.pos[box], 0.5f, -0.01f),
                                   test::boxOnPlane(still, ground, b.pos[still], 0.5f, -0.01f)};
    std::vector<BtgContact> c = runDevice(b, ms, p);
    ASSERT_EQ(c.size(), 2u);
    for (int k = 0; k < 4; ++k) {
        const BtgFloat4 rA = btgXyz(c[0].rA[k]);
        const BtgFloat4 slip = btgNormalize3(btgCross3(b.angVel[box], rA));
        const BtgFloat4 d1 = btgFrictionDir1(&c[0], k), d2 = btgFrictionDir2(&c[0], k);
        EXPECT_NEAR(btgDot3(d1, slip), 1.0f, 1e-5f) << "point " << k;
        EXPECT_NEAR(btgDot3(d2, slip), 0.0f, 1e-5f) << "point " << k;
        EXPECT_NEAR(btgDot3(d2, c[0].normal), 0.0f, 1e-6f) << "point " << k;
        EXPECT_NEAR(btgDot3(d2, d2), 1.0f, 1e-5f) << "point " << k;
        // No slip: btPlaneSpace1's p, for every point.
        EXPECT_NEAR(btgDot3(btgFrictionDir1(&c[1], k), c[1].tangent1), 1.0f, 1e-6f) << "point " << k;
    }
    // The corners slip four different ways.
    EXPECT_LT(btgDot3(btgFrictionDir1(&c[0], 0), btgFrictionDir1(&c[0], 2)), -0.99f);
}

// SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION: btPlaneSpace1's p at every point
// whatever its slip (the same spinning box), on the device and in the reference.
TEST(PrepareContacts, VelocityIndependentFrictionAlongPlaneSpace)
{
    ref::ContactBodies b;
    int ground = test::addBody(b, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.5f);
    int box = test::addBody(b, btgMake4(0, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC, 0.5f);
    b.angVel[box] = btgMake4(0, 2, 0, 0);
    b.linVel[box] = btgMake4(1, -0.1f, 0.5f, 0);
    BtgStepParams p = test::defaultParams(2);
    p.solverFlags |= BTG_SOLVER_VELOCITY_INDEPENDENT_FRICTION;
    p.twoFrictionDirections = 1;
    std::vector<BtgManifold> ms = {test::boxOnPlane(box, ground, b.pos[box], 0.5f, -0.01f)};
    std::vector<BtgContact> c = runDevice(b, ms, p);
    std::vector<BtgContact> expect = ref::buildContacts(ms, 1, b, {}, p);
    ref::prepareContacts(expect, b, p);
    ASSERT_EQ(c.size(), 1u);
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(btgLane(c[0].frictionCos, k), 1.0f) << "point " << k;
        EXPECT_EQ(btgLane(c[0].frictionSin, k), 0.0f) << "point " << k;
        EXPECT_EQ(btgLane(expect[0].frictionCos, k), 1.0f) << "point " << k;
        expectNearRel(btgLane(c[0].friction1Mass, k), btgLane(expect[0].friction1Mass, k), "friction1Mass", k);
        expectNearRel(btgLane(c[0].friction2Mass, k), btgLane(expect[0].friction2Mass, k), "friction2Mass", k);
        EXPECT_GT(btgLane(c[0].friction2Mass, k), 0.0f);
    }
    // btPlaneSpace1 of (0, 1, 0): p = (-1, 0, 0), q = (0, 0, 1)
    EXPECT_EQ(c[0].tangent1.x, -1.0f);
    EXPECT_EQ(c[0].tangent2.z, 1.0f);
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
    EXPECT_NEAR(c[0].normalTarget.x, 1.5f, 1e-5f);  // -e * rel_vel with e = 1 * 0.5, rel_vel = -3 m/s
    EXPECT_NEAR(c[0].normalMass.x, 1.0f / 1.5f, 1e-6f);       // central: 1 / (1/2 + 1/1)
    b.linVel0[upper] = b.linVel[upper] = btgMake4(0, -0.05f, 0, 0);
    b.linVel0[lower] = b.linVel[lower] = btgMake4(0, 0.05f, 0, 0);
    c = runDevice(b, {slow}, p);
    EXPECT_EQ(c[0].normalTarget.x, 0.0f);
}

// A NaN friction must never pose as a legal one (fmin/fmax would turn it into -10).
TEST(PrepareContacts, NanFrictionStaysNan)
{
    EXPECT_TRUE(std::isnan(btgCombinedFriction(std::nanf(""), 0.5f)));
    EXPECT_EQ(btgCombinedFriction(20.0f, 1.0f), 10.0f);
    EXPECT_EQ(btgCombinedFriction(-20.0f, 1.0f), -10.0f);
    EXPECT_EQ(btgCombinedFriction(0.5f, 0.5f), 0.25f);
}

namespace {

// btSequentialImpulseConstraintSolver's own rows for one manifold (convertContact), read from
// its pools: normal rows, friction rows, rolling rows in the order it adds them.
struct PeekSolver : btSequentialImpulseConstraintSolver {
    void convert(btPersistentManifold* m, const btContactSolverInfo& info)
    {
        m_tmpSolverBodyPool.resize(0);
        m_tmpSolverContactConstraintPool.resize(0);
        m_tmpSolverContactFrictionConstraintPool.resize(0);
        m_tmpSolverContactRollingFrictionConstraintPool.resize(0);
        m_fixedBodyId = -1;
        convertContact(m, info);
    }
    const btSolverConstraint& normalRow(int k) const { return m_tmpSolverContactConstraintPool[k]; }
    const btSolverConstraint& frictionRow(int k) const { return m_tmpSolverContactFrictionConstraintPool[k]; }
    int rollingRows() const { return m_tmpSolverContactRollingFrictionConstraintPool.size(); }
    const btSolverConstraint& rollingRow(int k) const { return m_tmpSolverContactRollingFrictionConstraintPool[k]; }
};

struct BulletPair {
    btBoxShape boxShape{btVector3(btScalar(0.5), btScalar(0.3), btScalar(0.2))};
    btBoxShape groundShape{btVector3(10, 10, 10)};
    std::unique_ptr<btRigidBody> box, ground;
    BulletPair(const btTransform& boxXf, const btVector3& linVel, const btVector3& angVel)
    {
        btVector3 inertia;
        boxShape.calculateLocalInertia(2, inertia);
        box = std::make_unique<btRigidBody>(2, nullptr, &boxShape, inertia);
        box->setWorldTransform(boxXf);
        box->setCenterOfMassTransform(boxXf);
        box->setLinearVelocity(linVel);
        box->setAngularVelocity(angVel);
        ground = std::make_unique<btRigidBody>(0, nullptr, &groundShape, btVector3(0, 0, 0));
        ground->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -10, 0)));
    }
};

BtgFloat4 f4(const btVector3& v) { return btgMake4(v.x(), v.y(), v.z(), 0); }

void expectVecNear(BtgFloat4 got, const btVector3& want, float tol, const char* what)
{
    EXPECT_NEAR(got.x, want.x(), tol) << what;
    EXPECT_NEAR(got.y, want.y(), tol) << what;
    EXPECT_NEAR(got.z, want.z(), tol) << what;
}

}  // namespace

// The rows prepare builds against the btSolverConstraint rows Bullet 3.24's convertContact
// builds for the same manifold (a turned, moving box on the ground, two points): effective
// masses, cfm and friction directions of the normal and friction rows, and the rolling rows'
// axes, masses and coefficients, with m_sor, m_globalCfm and soft contacts off and on.
TEST(PrepareContacts, MatchesBulletConvertContact)
{
    struct Case {
        const char* name;
        btScalar sor, globalCfm;
        bool soft;
        bool anisotropic = false;  // with two friction directions
    };
    for (const Case& cs : {Case{"defaults", 1, 0, false}, Case{"sor and cfm", btScalar(0.7), btScalar(0.02), false},
                           Case{"stiffness and damping", 1, 0, true},
                           Case{"anisotropic friction, two directions", 1, 0, false, true}}) {
        SCOPED_TRACE(cs.name);
        const btTransform xf(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.4)), btVector3(0, btScalar(0.3), 0));
        const btVector3 v(btScalar(0.8), btScalar(-0.2), btScalar(0.3)), w(btScalar(0.5), btScalar(1.5), btScalar(-0.7));
        BulletPair bp(xf, v, w);
        bp.box->setFriction(btScalar(0.6));
        bp.box->setRollingFriction(btScalar(0.1));
        bp.box->setSpinningFriction(btScalar(0.05));
        bp.ground->setFriction(btScalar(0.5));
        bp.ground->setRollingFriction(btScalar(0.02));
        if (cs.soft) bp.box->setContactStiffnessAndDamping(btScalar(3000), btScalar(40));
        const btVector3 scale(1, btScalar(0.5), btScalar(0.2));
        if (cs.anisotropic) bp.box->setAnisotropicFriction(scale);
        btContactSolverInfo info;
        info.m_timeStep = btScalar(1) / btScalar(60);
        info.m_sor = cs.sor;
        info.m_globalCfm = cs.globalCfm;
        info.m_solverMode &= ~SOLVER_USE_WARMSTARTING;
        if (cs.anisotropic) info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
        // Two points on the ground (y = 0), the box's side a little into it.
        btPersistentManifold manifold(bp.box.get(), bp.ground.get(), 0, btScalar(0.02), btScalar(0.02));
        const btVector3 n(0, 1, 0);
        const btVector3 onB[2] = {btVector3(btScalar(0.3), 0, btScalar(0.1)), btVector3(btScalar(-0.25), 0, btScalar(-0.05))};
        const btScalar depth[2] = {btScalar(-0.01), btScalar(-0.004)};
        for (int k = 0; k < 2; ++k) {
            const btVector3 onA = onB[k] + n * depth[k];
            btManifoldPoint p(bp.box->getWorldTransform().invXform(onA), bp.ground->getWorldTransform().invXform(onB[k]), n,
                              depth[k]);
            p.m_positionWorldOnA = onA;
            p.m_positionWorldOnB = onB[k];
            p.m_combinedFriction = btManifoldResult::calculateCombinedFriction(bp.box.get(), bp.ground.get());
            p.m_combinedRollingFriction = btManifoldResult::calculateCombinedRollingFriction(bp.box.get(), bp.ground.get());
            p.m_combinedSpinningFriction = btManifoldResult::calculateCombinedSpinningFriction(bp.box.get(), bp.ground.get());
            if (cs.soft) {
                p.m_combinedContactDamping1 = btManifoldResult::calculateCombinedContactDamping(bp.box.get(), bp.ground.get());
                p.m_combinedContactStiffness1 =
                    btManifoldResult::calculateCombinedContactStiffness(bp.box.get(), bp.ground.get());
                p.m_contactPointFlags |= BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
            }
            manifold.addManifoldPoint(p);
        }
        PeekSolver solver;
        solver.convert(&manifold, info);
        ASSERT_EQ(solver.rollingRows(), 6);

        // The same on btgpu's side.
        ref::ContactBodies b;
        const btQuaternion q = xf.getRotation();
        const BtgFloat4 rot = btgMake4(q.x(), q.y(), q.z(), q.w());
        const BtgFloat4 invI = f4(bp.box->getInvInertiaDiagLocal());
        int box = test::addBody(b, f4(xf.getOrigin()), 0.5f, invI, BTG_BODY_DYNAMIC, 0.6f);
        int ground = test::addBody(b, btgMake4(0, -10, 0, 0), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.5f);
        b.rot[box] = rot;
        const BtgMat3 iw = btgInvInertiaWorld(rot, invI);
        b.invInertiaWorld[3 * box] = iw.r0;
        b.invInertiaWorld[3 * box + 1] = iw.r1;
        b.invInertiaWorld[3 * box + 2] = iw.r2;
        b.linVel[box] = b.linVel0[box] = f4(v);
        b.angVel[box] = b.angVel0[box] = f4(w);
        b.props[box].rollingFriction = 0.1f;
        b.props[box].spinningFriction = 0.05f;
        b.props[ground].rollingFriction = 0.02f;
        if (cs.anisotropic) {
            b.props[box].flags |= BTG_BODY_ANISOTROPIC;
            b.props[box].anisotropicFriction = f4(scale);
        }
        if (cs.soft) {
            b.props[box].flags |= BTG_BODY_STIFFNESS_DAMPING;
            b.props[box].contactStiffness = 3000.0f;
            b.props[box].contactDamping = 40.0f;
        }
        BtgManifold m = btgEmptyManifold(box, ground);
        m.breakingThreshold = 0.02f;
        for (int k = 0; k < 2; ++k) btgAddPoint(&m, f4(n), f4(onB[k]), depth[k], BTG_FEATURE_VERTEX | uint(k));
        BtgStepParams p = test::defaultParams(2);
        p.warmstartFactor = 0.0f;
        p.sor = float(cs.sor);
        p.globalCfm = float(cs.globalCfm);
        p.solverFlags = BTG_SOLVER_ROLLING_FRICTION | (cs.soft ? BTG_SOLVER_SOFT_CONTACTS : 0u) |
                        (cs.anisotropic ? BTG_SOLVER_ANISOTROPIC_FRICTION : 0u);
        p.twoFrictionDirections = cs.anisotropic ? 1 : 0;
        std::vector<BtgContact> c = ref::buildContacts({m}, 1, b, {}, p);
        std::vector<BtgRollingContact> rolling;
        std::vector<BtgFrictionDirs> dirs;
        ref::prepareContacts(c, b, p, &rolling, &dirs);
        ASSERT_EQ(dirs.size(), cs.anisotropic ? 1u : 0u);
        ASSERT_EQ(c.size(), 1u);
        ASSERT_EQ(rolling.size(), 1u);
        const float rel = 2e-5f;
        for (int k = 0; k < 2; ++k) {
            SCOPED_TRACE(k);
            const btSolverConstraint& nr = solver.normalRow(k);
            const btSolverConstraint& fr = solver.frictionRow(cs.anisotropic ? 2 * k : k);
            EXPECT_NEAR(btgLane(c[0].normalMass, k), nr.m_jacDiagABInv, rel * nr.m_jacDiagABInv);
            EXPECT_NEAR(btgLane(c[0].normalCfm, k), nr.m_cfm, rel * std::fabs(nr.m_cfm) + 1e-9f);
            EXPECT_NEAR(btgLane(c[0].friction1Mass, k), fr.m_jacDiagABInv, rel * fr.m_jacDiagABInv);
            expectVecNear(btgFrictionDir1Of(&c[0], dirs.empty() ? nullptr : &dirs[0], k), fr.m_contactNormal1, 1e-5f,
                          "friction direction");
            if (cs.anisotropic) {
                const btSolverConstraint& fr2 = solver.frictionRow(2 * k + 1);
                expectVecNear(dirs[0].dir2[k], fr2.m_contactNormal1, 1e-5f, "friction direction 2");
                EXPECT_NEAR(btgLane(c[0].friction2Mass, k), fr2.m_jacDiagABInv, rel * fr2.m_jacDiagABInv);
                // scaled: neither unit nor in the tangent plane
                EXPECT_LT(btgLength3(dirs[0].dir1[k]), 0.99f);
                EXPECT_GT(std::fabs(dirs[0].dir1[k].y), 1e-3f);
            }
            EXPECT_NEAR(c[0].friction, fr.m_friction, 1e-7f);
            // Bullet's rhs = (target - J v) * mass at setup; the row's target is prepare's.
            const BtgFloat4 rA = c[0].rA[k];
            const BtgFloat4 vA = f4(v) + btgCross3(f4(w), rA);
            const float jv = btgDot3(f4(n), vA);
            EXPECT_NEAR((btgLane(c[0].normalTarget, k) - jv) * btgLane(c[0].normalMass, k), nr.m_rhs,
                        1e-4f * std::fabs(nr.m_rhs) + 1e-6f);
            // Rolling rows: torsional about the normal, then the two rolling axes.
            const btSolverConstraint& spin = solver.rollingRow(3 * k);
            const btSolverConstraint& r1 = solver.rollingRow(3 * k + 1);
            const btSolverConstraint& r2 = solver.rollingRow(3 * k + 2);
            EXPECT_NEAR(rolling[0].spinMass, spin.m_jacDiagABInv, rel * spin.m_jacDiagABInv);
            EXPECT_NEAR(rolling[0].roll1Mass, r1.m_jacDiagABInv, rel * r1.m_jacDiagABInv);
            EXPECT_NEAR(rolling[0].roll2Mass, r2.m_jacDiagABInv, rel * r2.m_jacDiagABInv);
            expectVecNear(rolling[0].rollAxis1, r1.m_relpos2CrossNormal, 1e-6f, "rolling axis 1");
            expectVecNear(rolling[0].rollAxis2, r2.m_relpos2CrossNormal, 1e-6f, "rolling axis 2");
            EXPECT_NEAR(rolling[0].spinningFriction, spin.m_friction, 1e-7f);
            EXPECT_NEAR(rolling[0].rollingFriction, r1.m_friction, 1e-7f);
        }
    }
}

// setContactProcessingThreshold: a manifold's points farther apart than the smaller of its
// bodies' thresholds get no rows (convertContacts skips them) and keep the impulses their
// btManifoldPoint had, unscaled by the warm start; the nearer ones are prepared as always.
// Device and reference alike, bit for bit; without BTG_SOLVER_PROCESSING_THRESHOLD every point
// has rows.
TEST(PrepareContacts, ProcessingThresholdLeavesFartherPointsUnsolved)
{
    ref::ContactBodies b;
    int ground = test::addBody(b, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.5f);
    int box = test::addBody(b, btgMake4(0, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0), BTG_BODY_DYNAMIC, 0.5f);
    b.props[box].contactProcessingThreshold = 0.0f;
    BtgStepParams p = test::defaultParams(2);
    p.warmstartFactor = 0.85f;
    p.solverFlags |= BTG_SOLVER_PROCESSING_THRESHOLD;
    BtgManifold m = test::boxOnPlane(box, ground, b.pos[box], 0.5f, 0.0f);
    const float d[4] = {-0.01f, -0.002f, 0.003f, 0.01f};
    for (int k = 0; k < 4; ++k) {
        m.points[k].distance = d[k];
        m.points[k].py = b.pos[box].y - 0.5f - d[k];
    }
    const std::vector<BtgManifold> ms = {m};
    std::vector<BtgContact> prev = ref::buildContacts(ms, 1, b, {}, p);
    prev[0].normalImpulse = btgMake4(1.0f, 2.0f, 3.0f, 4.0f);
    for (bool flag : {true, false}) {
        SCOPED_TRACE(flag);
        BtgStepParams q = p;
        if (!flag) q.solverFlags &= ~BTG_SOLVER_PROCESSING_THRESHOLD;
        std::vector<BtgContact> expect = ref::buildContacts(ms, 1, b, prev, q);
        ref::prepareContacts(expect, b, q);
        DeviceWorld w(test::context());
        test::uploadWorld(w, b, ms, 1, prev, 5);
        buildContacts(w, q);
        prepareContacts(w, q);
        std::vector<BtgContact> got = test::downloadContacts(w);
        ASSERT_EQ(got.size(), 1u);
        for (int k = 0; k < 4; ++k) {
            const bool solved = !flag || d[k] <= 0.0f;
            EXPECT_EQ(btgLane(got[0].normalMass, k) != 0.0f, solved) << k;
            EXPECT_EQ(btgLane(got[0].friction1Mass, k) != 0.0f, solved) << k;
            const float old = btgLane(prev[0].normalImpulse, k);
            EXPECT_EQ(btgLane(got[0].normalImpulse, k), solved ? old * q.warmstartFactor : old) << k;
            EXPECT_EQ(btgLane(got[0].normalImpulse, k), btgLane(expect[0].normalImpulse, k)) << k;
            EXPECT_EQ(btgLane(got[0].normalMass, k), btgLane(expect[0].normalMass, k)) << k;
            EXPECT_EQ(btgLane(got[0].normalTarget, k), btgLane(expect[0].normalTarget, k)) << k;
            if (!solved) {
                EXPECT_EQ(btgLane(got[0].normalTarget, k), 0.0f) << k;
                EXPECT_EQ(btgLane(got[0].pushTarget, k), 0.0f) << k;
            }
        }
    }
}

// Friction anchors (BTG_SOLVER_FRICTION_ANCHORS, a body with BTG_BODY_FRICTION_ANCHOR): the
// contact's points on A come from the pair's persistent manifold (here each kept 3 mm along +x
// from where the point on B and the distance put it), and each friction row's target is
// setupFrictionConstraint's -(pA - pB).dir m_frictionERP / dt. Without the body flag the rows are
// as always: lever arms from the manifold, no targets.
TEST(PrepareContacts, FrictionAnchorTargetsPullTheDriftBack)
{
    for (bool anchored : {true, false}) {
        SCOPED_TRACE(anchored);
        ref::ContactBodies b;
        int ground = test::addBody(b, btgZero4(), 0.0f, btgZero4(), BTG_BODY_STATIC, 0.5f);
        int box = test::addBody(b, btgMake4(0, 0.5f, 0, 0), 1.0f, btgMake4(6, 6, 6, 0),
                                BTG_BODY_DYNAMIC | (anchored ? BTG_BODY_FRICTION_ANCHOR : 0u), 0.5f);
        BtgStepParams p = test::defaultParams(2);
        p.solverFlags |= BTG_SOLVER_FRICTION_ANCHORS | BTG_SOLVER_VELOCITY_INDEPENDENT_FRICTION;
        p.twoFrictionDirections = 1;
        p.frictionErp = 0.2f;
        const BtgManifold m = test::boxOnPlane(box, ground, b.pos[box], 0.5f, -0.001f);
        BtgPersistentManifold pm = btgEmptyPersistent(box, ground, BTG_PAIR_PLANE_BOX);
        pm.numPoints = m.numPoints;
        const float drift = 0.003f;
        for (int k = 0; k < m.numPoints; ++k) {
            const BtgManifoldPoint& q = m.points[k];
            const BtgFloat4 onA = btgMake4(q.px, q.py + q.distance, q.pz, 0);  // normal +y
            pm.localA[k] = onA - btgXyz(b.pos[box]) + btgMake4(drift, 0, 0, 0);
            pm.localB[k] = btgMake4(q.px, q.py, q.pz, 0);
            pm.id[k] = uint(k);
        }
        DeviceWorld w(test::context());
        test::uploadWorld(w, b, {m}, 1, {}, 5);
        w.gjkPairState.upload(w.ctx, std::vector<BtgPersistentManifold>{pm});
        buildContacts(w, p);
        prepareContacts(w, p);
        const std::vector<BtgContact> got = test::downloadContacts(w);
        const std::vector<BtgFrictionAnchor> anchors = w.frictionAnchors.download(w.ctx, 1);
        ASSERT_EQ(got.size(), 1u);
        const BtgContact& c = got[0];
        for (int k = 0; k < 4; ++k) {
            const BtgManifoldPoint& q = m.points[k];
            const float rx = q.px - b.pos[box].x + (anchored ? drift : 0.0f);
            EXPECT_NEAR(c.rA[k].x, rx, 1e-6f) << k;
            const float rate = p.frictionErp / p.dt;
            const float want1 = anchored ? -drift * c.tangent1.x * rate : 0.0f;
            const float want2 = anchored ? -drift * c.tangent2.x * rate : 0.0f;
            EXPECT_NEAR(btgLane(anchors[0].target1, k), want1, 1e-5f) << k;
            EXPECT_NEAR(btgLane(anchors[0].target2, k), want2, 1e-5f) << k;
        }
        if (anchored) EXPECT_GT(std::fabs(btgLane(anchors[0].target1, 0)) + std::fabs(btgLane(anchors[0].target2, 0)), 0.03f);
    }
}
