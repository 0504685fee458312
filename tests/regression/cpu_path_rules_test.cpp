// cpu_path_rules_test.cpp — every Bullet setting the GPU path does not follow sends the world to
// the CPU path with a reason naming it and a Fallback issue, and set back the next step runs on
// the GPU again from where the CPU path left the bodies (agreeing with stock); settings left on
// the GPU path on purpose (they change nothing Bullet computes here) keep it.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btMinkowskiSumShape.h>
#include <BulletCollision/CollisionShapes/btTriangleMesh.h>

#include <BulletDynamics/ConstraintSolver/btNNCGConstraintSolver.h>
#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "side_by_side.h"

using namespace btgpu;
using namespace btgpu::test;

namespace {

std::map<const Scene*, btCollisionShape*>& savedShapes()
{
    static std::map<const Scene*, btCollisionShape*> saved;
    return saved;
}

struct Rule {
    std::string name;
    std::string expect;  // a piece of cpuPathReason
    std::function<void(Scene&)> set, reset;
};

void nearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info)
{
    btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}
bool added(btManifoldPoint&, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*, int, int)
{
    return true;
}
struct SubclassSolver : btSequentialImpulseConstraintSolver {};

btCollisionDispatcher& dispatcher(Scene& s) { return *static_cast<btCollisionDispatcher*>(s.world().getDispatcher()); }
btDefaultCollisionConfiguration& configuration(Scene& s)
{
    return *static_cast<btDefaultCollisionConfiguration*>(dispatcher(s).getCollisionConfiguration());
}

// A setting of the world's btContactSolverInfo, set and put back (per scene: SideBySide sets it
// on both worlds).
Rule solverInfo(const std::string& name, const std::string& expect, std::function<void(btContactSolverInfo&)> change)
{
    auto saved = std::make_shared<std::map<const Scene*, btContactSolverInfo>>();
    return {name, expect,
            [=](Scene& s) {
                (*saved)[&s] = s.world().getSolverInfo();
                change(s.world().getSolverInfo());
            },
            [=](Scene& s) { static_cast<btContactSolverInfoData&>(s.world().getSolverInfo()) = saved->at(&s); }};
}

// A global of Bullet's, set to `value` and put back to what it was when the rule was made.
template <typename T>
Rule global(const std::string& name, const std::string& expect, T& variable, T value)
{
    const T original = variable;
    return {name, expect, [=, &variable](Scene&) { variable = value; },
            [=, &variable](Scene&) { variable = original; }};
}

// A collision flag on body 1.
Rule flag(const std::string& name, const std::string& expect, int f)
{
    return {name, expect, [=](Scene& s) { s.body(1)->setCollisionFlags(s.body(1)->getCollisionFlags() | f); },
            [=](Scene& s) { s.body(1)->setCollisionFlags(s.body(1)->getCollisionFlags() & ~f); }};
}

std::vector<Rule> rules()
{
    static SubclassSolver subclassSolver;
    static btNNCGConstraintSolver nncg;
    static btDantzigSolver dantzig;
    static btMLCPSolver mlcp(&dantzig);
    static btCapsuleShape capsule(.5, 1);
    // A compound holding a shape the GPU path does not take (a Minkowski sum).
    static btSphereShape ball(.2f);
    static btMinkowskiSumShape sum(&capsule, &ball);
    static btCompoundShape compound;
    if (compound.getNumChildShapes() == 0) compound.addChildShape(btTransform::getIdentity(), &sum);
    // A compound of one box: its manifolds' body order is the compound algorithm's (a child first).
    static btBoxShape boxChild(btVector3(.5, .5, .5));
    static btCompoundShape boxCompound;
    if (boxCompound.getNumChildShapes() == 0) boxCompound.addChildShape(btTransform::getIdentity(), &boxChild);
    // A convex triangle mesh the app gave polyhedral features: stock then clips it against
    // featured hulls, which the GPU path does not.
    static btTriangleMesh featuredMesh;
    static btConvexTriangleMeshShape featured(&featuredMesh);
    if (featuredMesh.getNumTriangles() == 0) {
        const btVector3 v[4] = {{0, -.5f, 0}, {.5f, .3f, 0}, {-.4f, .3f, .4f}, {-.3f, .3f, -.5f}};
        featuredMesh.addTriangle(v[0], v[1], v[2]);
        featuredMesh.addTriangle(v[0], v[2], v[3]);
        featuredMesh.addTriangle(v[0], v[3], v[1]);
        featuredMesh.addTriangle(v[1], v[3], v[2]);
        featured.recalcLocalAabb();
        featured.initializePolyhedralFeatures();
    }
    auto solver = [](const std::string& name, btConstraintSolver* other) {
        auto saved = std::make_shared<std::map<const Scene*, btConstraintSolver*>>();
        return Rule{name, "constraint solver",
                    [=](Scene& s) {
                        (*saved)[&s] = s.world().getConstraintSolver();
                        s.world().setConstraintSolver(other);
                    },
                    [=](Scene& s) { s.world().setConstraintSolver(saved->at(&s)); }};
    };
    return {
        solver("solver subclass", &subclassSolver),
        solver("NNCG solver", &nncg),
        solver("MLCP solver", &mlcp),
        {"near callback", "near callback", [](Scene& s) { dispatcher(s).setNearCallback(nearCallback); },
         [](Scene& s) { dispatcher(s).setNearCallback(btCollisionDispatcher::defaultNearCallback); }},
        // An overlap filter callback is served (callbacks_test.cpp).
        // The contact events are served (callbacks_test.cpp), but for the cases it tests.
        // The combiners are served (callbacks_test.cpp), but for the cases it tests.
        // gContactBreakingThreshold is followed (contact_threshold_test.cpp).
        solverInfo("m_linearSlop", "m_linearSlop", [](btContactSolverInfo& i) { i.m_linearSlop = btScalar(0.01); }),
        solverInfo("m_leastSquaresResidualThreshold", "m_leastSquaresResidualThreshold",
                   [](btContactSolverInfo& i) { i.m_leastSquaresResidualThreshold = btScalar(1e-6); }),
        solverInfo("no iterations", "m_numIterations", [](btContactSolverInfo& i) { i.m_numIterations = 0; }),
        // SOLVER_RANDMIZE_ORDER is served by the PGS solver's own order (solver_features_test.cpp).
        // SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS is served by the PGS solver's
        // interleaved sweep (solver_features_test.cpp).
        {"SAT for featured hulls", "m_enableSatConvex",
         [](Scene& s) { s.world().getDispatchInfo().m_enableSatConvex = true; },
         [](Scene& s) { s.world().getDispatchInfo().m_enableSatConvex = false; }},
        {"continuous dispatch", "m_dispatchFunc",
         [](Scene& s) { s.world().getDispatchInfo().m_dispatchFunc = btDispatcherInfo::DISPATCH_CONTINUOUS; },
         [](Scene& s) { s.world().getDispatchInfo().m_dispatchFunc = btDispatcherInfo::DISPATCH_DISCRETE; }},
        {"box-box algorithm replaced", "collision algorithm for box-box",
         [](Scene& s) {
             dispatcher(s).registerCollisionCreateFunc(
                 BOX_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE,
                 configuration(s).getCollisionAlgorithmCreateFunc(BOX_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE));
         },
         [](Scene& s) {
             dispatcher(s).registerCollisionCreateFunc(
                 BOX_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE,
                 configuration(s).getCollisionAlgorithmCreateFunc(BOX_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE));
         }},
        // Friction anchors are served where the pairs keep persistent manifolds
        // (solver_features_test.cpp); a sphere's pairs with boxes keep none on the device.
        {"friction anchor beside a sphere", "friction anchors (CF_HAS_FRICTION_ANCHOR) on a box beside a sphere",
         [](Scene& s) {
             static btSphereShape ball(btScalar(0.5));
             s.body(1)->setCollisionFlags(s.body(1)->getCollisionFlags() | btCollisionObject::CF_HAS_FRICTION_ANCHOR);
             s.body(2)->setCollisionShape(&ball);
         },
         [](Scene& s) {
             s.body(1)->setCollisionFlags(s.body(1)->getCollisionFlags() & ~btCollisionObject::CF_HAS_FRICTION_ANCHOR);
             s.body(2)->setCollisionShape(s.body(1)->getCollisionShape());
         }},
        // Two anisotropic bodies are served (solver_features_test.cpp) unless one is a compound or
        // concave, whose manifolds' body order is its algorithm's (here body 2 made a compound).
        {"anisotropic rolling friction on two bodies, one a compound", "anisotropic rolling friction on more than one body",
         [](Scene& s) {
             s.body(1)->setRollingFriction(btScalar(0.1));
             for (int b : {1, 2})
                 s.body(b)->setAnisotropicFriction(btVector3(1, btScalar(0.5), 1),
                                                   btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION);
             savedShapes()[&s] = s.body(2)->getCollisionShape();
             s.body(2)->setCollisionShape(&boxCompound);
             s.world().updateSingleAabb(s.body(2));
         },
         [](Scene& s) {
             s.body(1)->setRollingFriction(0);
             for (int b : {1, 2}) s.body(b)->setAnisotropicFriction(btVector3(1, 1, 1));
             s.body(2)->setCollisionShape(savedShapes().at(&s));
             s.world().updateSingleAabb(s.body(2));
         }},
        {"anisotropic friction on two bodies, one a compound", "anisotropic friction on more than one body",
         [](Scene& s) {
             for (int b : {1, 2}) s.body(b)->setAnisotropicFriction(btVector3(1, btScalar(0.5), 1));
             savedShapes()[&s] = s.body(2)->getCollisionShape();
             s.body(2)->setCollisionShape(&boxCompound);
             s.world().updateSingleAabb(s.body(2));
         },
         [](Scene& s) {
             for (int b : {1, 2}) s.body(b)->setAnisotropicFriction(btVector3(1, 1, 1));
             s.body(2)->setCollisionShape(savedShapes().at(&s));
             s.world().updateSingleAabb(s.body(2));
         }},
        {"anisotropic friction with cached directions", "anisotropic friction with friction direction caching",
         [](Scene& s) {
             s.body(1)->setAnisotropicFriction(btVector3(1, btScalar(0.5), 1));
             s.world().getSolverInfo().m_solverMode |= SOLVER_ENABLE_FRICTION_DIRECTION_CACHING |
                                                       SOLVER_USE_2_FRICTION_DIRECTIONS |
                                                       SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION;
         },
         [](Scene& s) {
             s.body(1)->setAnisotropicFriction(btVector3(1, 1, 1));
             s.world().getSolverInfo().m_solverMode &= ~(SOLVER_ENABLE_FRICTION_DIRECTION_CACHING |
                                                         SOLVER_USE_2_FRICTION_DIRECTIONS |
                                                         SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION);
         }},
        // A contact processing threshold is served by the PGS solver (solver_features_test.cpp);
        // the Jacobi and soft solvers fall back (JacobiSolverFallsBackForRowsItLacks).
        // CCD is served step by step (ccd_test.cpp); beside an overlap filter a step it acts in
        // would ask the filter again.
        {"CCD beside an overlap filter", "continuous collision detection (setCcdMotionThreshold) beside",
         [](Scene& s) {
             static struct AcceptAll : btOverlapFilterCallback {
                 bool needBroadphaseCollision(btBroadphaseProxy*, btBroadphaseProxy*) const override { return true; }
             } acceptAll;
             s.body(3)->setCcdMotionThreshold(btScalar(0.01));
             s.body(3)->setCcdSweptSphereRadius(btScalar(0.2));
             s.world().getPairCache()->setOverlapFilterCallback(&acceptAll);
         },
         [](Scene& s) {
             s.body(3)->setCcdMotionThreshold(0);
             s.body(3)->setCcdSweptSphereRadius(0);
             s.world().getPairCache()->setOverlapFilterCallback(nullptr);
         }},
        {"shape swapped for a convex mesh with polyhedral features", "polyhedral features",
         [](Scene& s) { s.body(2)->setCollisionShape(&featured); },
         [](Scene& s) { s.body(2)->setCollisionShape(s.body(1)->getCollisionShape()); }},
        {"shape swapped for a compound of an unserved shape", "unsupported shape",
         [](Scene& s) { s.body(2)->setCollisionShape(&compound); },
         [](Scene& s) { s.body(2)->setCollisionShape(s.body(1)->getCollisionShape()); }},
        // stock's solver moves a kinematic body that kept its mass by that mass (the bullet mode's)
        {"a body made kinematic by its flag alone", "a kinematic body with mass",
         [](Scene& s) { s.body(2)->setCollisionFlags(s.body(2)->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT); },
         [](Scene& s) { s.body(2)->setCollisionFlags(s.body(2)->getCollisionFlags() & ~btCollisionObject::CF_KINEMATIC_OBJECT); }},
    };
}

Rule processingThreshold(const char* expect)
{
    return {"contact processing threshold", expect, [](Scene& s) { s.body(1)->setContactProcessingThreshold(0); },
            [](Scene& s) { s.body(1)->setContactProcessingThreshold(BT_LARGE_FLOAT); }};
}

bool hasFallbackIssue(const Report& r, const std::string& reason)
{
    for (const Issue& issue : r.issues)
        if (issue.kind == Issue::Kind::Fallback && issue.message == reason) return true;
    return false;
}

}  // namespace

TEST(CpuPathRules, EachRuleFallsBackAndComesBack)
{
    ScenePtr scene = scenes::dropRow(WorldKind::Gpu);
    scene->step();
    const Report& r = *scene->report();
    ASSERT_TRUE(r.gpuPath) << r.cpuPathReason;
    for (const Rule& rule : rules()) {
        SCOPED_TRACE(rule.name);
        // EXPECT only between set and reset: a global must be put back whatever happens.
        rule.set(*scene);
        scene->step();
        EXPECT_FALSE(r.gpuPath);
        EXPECT_NE(r.cpuPathReason.find(rule.expect), std::string::npos) << r.cpuPathReason;
        EXPECT_TRUE(hasFallbackIssue(r, r.cpuPathReason)) << r.cpuPathReason;
        rule.reset(*scene);
        scene->step();
        EXPECT_TRUE(r.gpuPath) << r.cpuPathReason;
        EXPECT_TRUE(r.cpuPathReason.empty()) << r.cpuPathReason;
    }
    EXPECT_TRUE(scenes::allFinite(*scene));
}

// A drop-row scene with Config::solver = `kind`, after a first step on the GPU path.
ScenePtr dropRowStepped(SolverKind kind)
{
    Config config = Config::bulletMode();
    config.solver = kind;
    ScenePtr scene = scenes::dropRow(WorldKind::Gpu, config);
    scene->step();
    EXPECT_TRUE(scene->report()->gpuPath) << scene->report()->cpuPathReason;
    return scene;
}

// The Jacobi solver (Config::solver = JacobiMassSplitting) has plain contact rows only: the
// rows the PGS solver adds for these settings send such a world to the CPU path, naming them.
TEST(CpuPathRules, JacobiSolverFallsBackForRowsItLacks)
{
    ScenePtr scene = dropRowStepped(SolverKind::JacobiMassSplitting);
    const Report& r = *scene->report();
    const std::vector<Rule> jacobiRules = {
        {"rolling friction", "rolling or spinning friction with Config::solver = JacobiMassSplitting",
         [](Scene& s) { s.body(2)->setRollingFriction(btScalar(0.1)); }, [](Scene& s) { s.body(2)->setRollingFriction(0); }},
        {"spinning friction", "rolling or spinning friction with Config::solver = JacobiMassSplitting",
         [](Scene& s) { s.body(1)->setSpinningFriction(btScalar(0.1)); },
         [](Scene& s) { s.body(1)->setSpinningFriction(0); }},
        solverInfo("m_sor", "m_sor changed from 1 with Config::solver = JacobiMassSplitting",
                   [](btContactSolverInfo& i) { i.m_sor = btScalar(0.9); }),
        solverInfo("m_globalCfm", "m_globalCfm changed from 0 with Config::solver = JacobiMassSplitting",
                   [](btContactSolverInfo& i) { i.m_globalCfm = btScalar(1e-4); }),
        flag("contact stiffness and damping", "CF_HAS_CONTACT_STIFFNESS_DAMPING) with Config::solver = JacobiMassSplitting",
             btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING),
        {"anisotropic friction", "anisotropic friction (setAnisotropicFriction) with Config::solver = JacobiMassSplitting",
         [](Scene& s) { s.body(1)->setAnisotropicFriction(btVector3(1, btScalar(0.5), 1)); },
         [](Scene& s) { s.body(1)->setAnisotropicFriction(btVector3(1, 1, 1)); }},
        processingThreshold("setContactProcessingThreshold) with Config::solver = JacobiMassSplitting"),
        flag("friction anchors", "CF_HAS_FRICTION_ANCHOR) with Config::solver = JacobiMassSplitting",
             btCollisionObject::CF_HAS_FRICTION_ANCHOR),
        solverInfo("randomised order", "SOLVER_RANDMIZE_ORDER with Config::solver = JacobiMassSplitting",
                   [](btContactSolverInfo& i) { i.m_solverMode |= SOLVER_RANDMIZE_ORDER; }),
        solverInfo("interleaving", "SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS with Config::solver = JacobiMassSplitting",
                   [](btContactSolverInfo& i) { i.m_solverMode |= SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS; }),
    };
    for (const Rule& rule : jacobiRules) {
        SCOPED_TRACE(rule.name);
        rule.set(*scene);
        scene->step();
        EXPECT_FALSE(r.gpuPath);
        EXPECT_NE(r.cpuPathReason.find(rule.expect), std::string::npos) << r.cpuPathReason;
        rule.reset(*scene);
        scene->step();
        EXPECT_TRUE(r.gpuPath) << r.cpuPathReason;
    }
}

// The Bullet settings the soft step's rows do not follow (its contacts are its own springs),
// each with the words that name it; set on body 1 or the solver info. (Anisotropic friction it
// serves: SolverFeatures.SoftStepAnisotropicFrictionAsStock.)
std::vector<Rule> softStepLacks()
{
    return {flag("friction anchors", "CF_HAS_FRICTION_ANCHOR) with Config::solver = SoftStep",
                 btCollisionObject::CF_HAS_FRICTION_ANCHOR),
            solverInfo("SOR", "m_sor changed with Config::solver = SoftStep",
                       [](btContactSolverInfo& i) { i.m_sor = btScalar(0.5); })};
}

// A SoftStep world that meets one of them goes to the CPU path, naming the mode.
TEST(CpuPathRules, SoftStepFallsBackForRowsItLacks)
{
    ScenePtr scene = dropRowStepped(SolverKind::SoftStep);
    const Report& r = *scene->report();
    for (const Rule& rule : softStepLacks()) {
        SCOPED_TRACE(rule.name);
        rule.set(*scene);
        scene->step();
        EXPECT_FALSE(r.gpuPath);
        EXPECT_NE(r.cpuPathReason.find(rule.expect), std::string::npos) << r.cpuPathReason;
        rule.reset(*scene);
        scene->step();
        EXPECT_TRUE(r.gpuPath) << r.cpuPathReason;
    }
}

// A drop-row scene with Config::solver = Auto after its first step, which ran the soft step on
// the GPU path.
ScenePtr autoSolverScene()
{
    ScenePtr scene = dropRowStepped(SolverKind::Auto);
    const Report& r = *scene->report();
    EXPECT_EQ(SolverKind::SoftStep, r.solver);
    EXPECT_EQ("", r.solverReason);
    EXPECT_EQ(10, r.softSubsteps);
    return scene;
}

// Config::solver = Auto stays on the GPU path through each of them: the batched PGS while the
// world uses it (Report::solverReason naming it), the soft step before and after.
TEST(CpuPathRules, AutoSolverTakesTheBatchedPgsForRowsTheSoftStepLacks)
{
    ScenePtr scene = autoSolverScene();
    const Report& r = *scene->report();
    for (const Rule& rule : softStepLacks()) {
        SCOPED_TRACE(rule.name);
        rule.set(*scene);
        for (int i = 0; i < 3; ++i) {
            scene->step();
            EXPECT_TRUE(r.gpuPath) << r.cpuPathReason;
            EXPECT_EQ(SolverKind::BatchedPgs, r.solver);
            EXPECT_NE(r.solverReason.find(rule.expect), std::string::npos) << r.solverReason;
        }
        rule.reset(*scene);
        scene->step();
        EXPECT_TRUE(r.gpuPath) << r.cpuPathReason;
        EXPECT_EQ(SolverKind::SoftStep, r.solver);
        EXPECT_EQ("", r.solverReason);
    }
}

// A tick callback that starts friction anchors within a call of several internal steps: Auto
// does not switch solvers inside the call (its rest runs on the CPU path, saying so); the next
// call runs the batched PGS on the GPU path.
TEST(CpuPathRules, AutoSolverSwitchesBetweenCalls)
{
    ScenePtr scene = autoSolverScene();
    const Report& r = *scene->report();
    scene->world().setInternalTickCallback(
        [](btDynamicsWorld* world, btScalar) {
            btCollisionObject* o = world->getCollisionObjectArray()[1];
            o->setCollisionFlags(o->getCollisionFlags() | btCollisionObject::CF_HAS_FRICTION_ANCHOR);
        },
        nullptr, false);
    scene->step(btScalar(3) / 60, 3, btScalar(1) / 60);
    EXPECT_FALSE(r.gpuPath);
    EXPECT_NE(r.cpuPathReason.find("Config::solver = Auto would switch solvers"), std::string::npos) << r.cpuPathReason;
    scene->world().setInternalTickCallback(nullptr);
    scene->step();
    EXPECT_TRUE(r.gpuPath) << r.cpuPathReason;
    EXPECT_EQ(SolverKind::BatchedPgs, r.solver);
}

// What Auto runs is the chosen solver's step, bit for bit: a plain scene as SoftStep, one with
// friction anchors as BatchedPgs.
TEST(CpuPathRules, AutoSolverRunsTheChosenSolverBitwise)
{
    auto run = [](SolverKind kind, bool anchors) {
        Config config = Config::bulletMode();
        config.solver = kind;
        ScenePtr scene = scenes::dropRow(WorldKind::Gpu, config);
        if (anchors)
            scene->body(1)->setCollisionFlags(scene->body(1)->getCollisionFlags() | btCollisionObject::CF_HAS_FRICTION_ANCHOR);
        for (int i = 0; i < 30; ++i) {
            scene->step();
            EXPECT_TRUE(scene->report()->gpuPath) << scene->report()->cpuPathReason;
        }
        return scene->gpuWorld()->stateHash();
    };
    EXPECT_EQ(run(SolverKind::SoftStep, false), run(SolverKind::Auto, false));
    EXPECT_EQ(run(SolverKind::BatchedPgs, true), run(SolverKind::Auto, true));
    EXPECT_NE(run(SolverKind::BatchedPgs, false), run(SolverKind::Auto, false));
}

// The library's default is Auto (issue 13: the default holds stiff scenes up): a world made
// with Config's defaults, as the one-line swap makes it, runs the soft step bit for bit, and the
// bullet mode takes over on the GPU path where the world uses what only it serves (m_sor here).
// Config::bulletMode() is the defaults with the batched PGS.
TEST(CpuPathRules, TheDefaultIsAutoAndRunsTheSoftStep)
{
    EXPECT_EQ(SolverKind::Auto, Config().solver);
    EXPECT_EQ(SolverKind::BatchedPgs, Config::bulletMode().solver);
    auto run = [](const Config& config, btScalar sor) {
        ScenePtr scene = scenes::dropRow(WorldKind::Gpu, config);
        scene->world().getSolverInfo().m_sor = sor;
        for (int i = 0; i < 30; ++i) {
            scene->step();
            EXPECT_TRUE(scene->report()->gpuPath) << scene->report()->cpuPathReason;
        }
        const bool soft = config.solver != SolverKind::BatchedPgs && sor == btScalar(1);
        EXPECT_EQ(soft ? SolverKind::SoftStep : SolverKind::BatchedPgs, scene->report()->solver);
        return scene->gpuWorld()->stateHash();
    };
    Config soft = Config::bulletMode();
    soft.solver = SolverKind::SoftStep;
    EXPECT_EQ(run(soft, 1), run(Config(), 1));
    EXPECT_EQ(run(Config::bulletMode(), btScalar(0.9)), run(Config(), btScalar(0.9)));
    EXPECT_NE(run(Config::bulletMode(), 1), run(Config(), 1));
}

TEST(CpuPathRules, ComingBackAgreesWithStock)
{
    // Set while the boxes fall: they land on the CPU path; set back, the GPU path must go on from
    // where the CPU path left every row (not from its own last upload) and stay with stock.
    std::vector<Rule> all = rules();
    for (const char* name : {"m_linearSlop", "near callback", "m_leastSquaresResidualThreshold"}) {
        SCOPED_TRACE(name);
        const Rule& rule = *std::find_if(all.begin(), all.end(), [&](const Rule& r) { return r.name == name; });
        SideBySide s(scenes::dropRow);
        s.step(5);
        ASSERT_TRUE(s.onGpu());
        s.both(rule.set);
        s.step(60);
        EXPECT_FALSE(s.onGpu());
        s.both(rule.reset);
        s.step(60);
        EXPECT_TRUE(s.onGpu()) << s.gpu->report()->cpuPathReason;
        for (int b = 1; b <= 3; ++b) {
            EXPECT_NEAR(s.gpuY(b), 0.5, tol::kRestHeight + 0.01) << "box " << b << " is not resting on the ground";
            EXPECT_LT(s.distance(b), tol::kRestHeight) << "box " << b;
        }
    }
}

// Landed on the GPU path, then a rule sends the world to the CPU path: Bullet's own step must
// find the boxes' pairs with the ground, which its broadphase did not test while the GPU path
// moved them (its AABBs were kept current, its pair tests deferred). Resting boxes no longer
// leave their fat broadphase volumes, so only a full pair update finds those pairs at once.
TEST(CpuPathRules, GoingToTheCpuPathAfterLandingFindsTheGroundPairs)
{
    std::vector<Rule> all = rules();
    const Rule& rule =
        *std::find_if(all.begin(), all.end(), [](const Rule& r) { return r.name == std::string("m_linearSlop"); });
    // Released 4 m up: no broadphase pair with the ground when they are added.
    auto make = [](WorldKind kind, const Config& config) {
        auto scene = std::make_unique<Scene>(kind, config, "high_drop");
        scene->addBody(scene->boxShape(btVector3(20, 1, 20)), 0, btVector3(0, -1, 0));
        for (int b = 0; b < 3; ++b)
            scene->addBody(scene->boxShape(btVector3(btScalar(.5), btScalar(.5), btScalar(.5))), 1,
                           btVector3(btScalar(2 * b - 2), 4, 0));
        return scene;
    };
    SideBySide s(make);
    s.step(150);
    ASSERT_TRUE(s.onGpu());
    for (int b = 1; b <= 3; ++b) ASSERT_NEAR(s.gpuY(b), 0.5, 0.01) << "box " << b << " has not landed";
    s.both(rule.set);
    s.step(1);
    EXPECT_FALSE(s.onGpu());
    // Bullet's broadphase holds stock's pairs at once (left alone, its own stage migration would
    // find them a few steps later, the boxes unsupported meanwhile).
    EXPECT_EQ(s.gpu->world().getPairCache()->getNumOverlappingPairs(),
              s.stock->world().getPairCache()->getNumOverlappingPairs());
    EXPECT_EQ(s.gpu->world().getPairCache()->getNumOverlappingPairs(), 3);
    s.step(59);
    EXPECT_FALSE(s.onGpu());
    for (int b = 1; b <= 3; ++b) {
        EXPECT_NEAR(s.gpuY(b), 0.5, tol::kRestHeight + 0.01) << "box " << b << " is not resting on the ground";
        // Landed on the GPU path: as far from stock as the landing left them.
        EXPECT_LT(s.distance(b), 0.005) << "box " << b;
    }
}

TEST(CpuPathRules, StructureRulesFallBackAndComeBack)
{
    // A box with polyhedral features beside plain boxes (stock collides the two kinds apart);
    // removing it brings the GPU path back.
    ScenePtr scene = scenes::dropRow(WorldKind::Gpu);
    scene->step();
    btBoxShape* featured = scene->boxShape(btVector3(.5, .5, .5));
    featured->initializePolyhedralFeatures();
    btRigidBody* body = scene->addBody(featured, 1, btVector3(6, 3, 0));
    scene->step();
    const Report& r = *scene->report();
    EXPECT_FALSE(r.gpuPath);
    EXPECT_NE(r.cpuPathReason.find("polyhedral features"), std::string::npos) << r.cpuPathReason;
    scene->removeBody(body);
    scene->step();
    EXPECT_TRUE(r.gpuPath) << r.cpuPathReason;
}

TEST(CpuPathRules, ForeignDispatcherBroadphaseOrPairCacheFallBack)
{
    // Set at construction, so only the fallback is checked. (btCollisionDispatcherMt is such a
    // subclass; Debian's build crashes constructing one outside a BT_THREADSAFE build.)
    struct SubclassDispatcher : btCollisionDispatcher {
        using btCollisionDispatcher::btCollisionDispatcher;
    };
    struct SubclassBroadphase : btDbvtBroadphase {};
    struct SubclassPairCache : btHashedOverlappingPairCache {};
    btDefaultCollisionConfiguration configuration;
    btSequentialImpulseConstraintSolver solver;
    btBoxShape box(btVector3(.5, .5, .5));
    auto run = [&](btDispatcher* d, btBroadphaseInterface* bp, const std::string& expect) {
        SCOPED_TRACE(expect);
        btGpuDynamicsWorld world(d, bp, &solver, &configuration);
        btRigidBody body(1, nullptr, &box, btVector3(1, 1, 1));
        world.addRigidBody(&body);
        world.stepSimulation(kStep);
        EXPECT_FALSE(world.report().gpuPath);
        EXPECT_NE(world.report().cpuPathReason.find(expect), std::string::npos) << world.report().cpuPathReason;
        world.removeRigidBody(&body);
    };
    btCollisionDispatcher plain(&configuration);
    btDbvtBroadphase dbvt;
    SubclassDispatcher subclass(&configuration);
    run(&subclass, &dbvt, "collision dispatcher");
    SubclassBroadphase broadphase;
    run(&plain, &broadphase, "broadphase");
    SubclassPairCache cache;  // outlives the broadphase, which does not own it
    btDbvtBroadphase withCache(&cache);
    run(&plain, &withCache, "overlapping pair cache");
}

TEST(CpuPathRules, MultipointIterationsOnlyWhereTheyAct)
{
    // The convex-convex algorithm serves hull-box pairs; box-box pairs have their own, so a
    // boxes-only world keeps the GPU path with the same change.
    ScenePtr hull = scenes::hullLanding(WorldKind::Gpu);
    ScenePtr boxes = scenes::dropRow(WorldKind::Gpu);
    hull->step();
    boxes->step();
    configuration(*hull).setConvexConvexMultipointIterations(3, 3);
    configuration(*boxes).setConvexConvexMultipointIterations(3, 3);
    hull->step();
    boxes->step();
    EXPECT_FALSE(hull->report()->gpuPath);
    EXPECT_NE(hull->report()->cpuPathReason.find("collision algorithm"), std::string::npos)
        << hull->report()->cpuPathReason;
    EXPECT_TRUE(boxes->report()->gpuPath) << boxes->report()->cpuPathReason;
    configuration(*hull).setConvexConvexMultipointIterations(0, 3);  // Bullet's defaults
    hull->step();
    EXPECT_TRUE(hull->report()->gpuPath) << hull->report()->cpuPathReason;

    // Plane-convex pairs: a box over a static plane.
    btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
    Scene onPlane(WorldKind::Gpu);
    onPlane.addBody(&plane, 0, btVector3(0, 0, 0));
    onPlane.addBody(onPlane.boxShape(btVector3(.5, .5, .5)), 1, btVector3(0, 2, 0));
    onPlane.step();
    ASSERT_TRUE(onPlane.report()->gpuPath) << onPlane.report()->cpuPathReason;
    configuration(onPlane).setPlaneConvexMultipointIterations(3, 3);
    onPlane.step();
    EXPECT_FALSE(onPlane.report()->gpuPath);
    configuration(onPlane).setPlaneConvexMultipointIterations(1, 0);  // Bullet's defaults
    onPlane.step();
    EXPECT_TRUE(onPlane.report()->gpuPath) << onPlane.report()->cpuPathReason;
}

TEST(CpuPathRules, BreakingThresholdKeptAlikeInConfigStaysOnGpu)
{
    const btScalar saved = gContactBreakingThreshold;
    gContactBreakingThreshold = btScalar(0.03);
    Config config = Config::bulletMode();
    config.contactThreshold = 0.03f;
    ScenePtr scene = scenes::restingBox(WorldKind::Gpu, config);
    scene->step();
    EXPECT_TRUE(scene->report()->gpuPath) << scene->report()->cpuPathReason;
    gContactBreakingThreshold = saved;
}

TEST(CpuPathRules, SettingsThatChangeNothingHereStayOnGpu)
{
    // Each is unread by Bullet 3.24 for rigid bodies without joints, acts only together with a
    // setting that falls back by itself, or is followed by the GPU path (cpu_path_rules.cpp).
    ScenePtr scene = scenes::dropRow(WorldKind::Gpu);
    btDiscreteDynamicsWorld& w = scene->world();
    btContactSolverInfo& info = w.getSolverInfo();
    const btContactSolverInfo saved = info;
    info.m_tau = 0.3f;
    info.m_damping = 0.5f;
    info.m_friction = 0.7f;
    info.m_restitution = 0.4f;
    info.m_maxErrorReduction = 5;
    info.m_frictionERP = 0.5f;
    info.m_frictionCFM = 0.1f;
    info.m_restingContactRestitutionThreshold = 7;
    info.m_minimumSolverBatchSize = 1;
    info.m_maxGyroscopicForce = 5;
    info.m_singleAxisRollingFrictionThreshold = 1;
    info.m_deformable_erp = 0.5f;
    info.m_articulatedWarmstartingFactor = 0.5f;
    info.m_numNonContactInnerIterations = 3;
    info.m_solverMode = (info.m_solverMode & ~SOLVER_SIMD) | SOLVER_CACHE_FRIENDLY | SOLVER_FRICTION_SEPARATE;
    w.getDispatchInfo().m_deterministicOverlappingPairs = true;
    w.getDispatchInfo().m_allowedCcdPenetration = 0.1f;
    dispatcher(*scene).setDispatcherFlags(btCollisionDispatcher::CD_STATIC_STATIC_REPORTED);
    w.setApplySpeculativeContactRestitution(true);
    w.setSynchronizeAllMotionStates(true);
    w.setLatencyMotionStateInterpolation(false);
    gContactAddedCallback = added;  // no body asks for it (CF_CUSTOM_MATERIAL_CALLBACK)
    btRigidBody* b = scene->body(1);
    btRigidBody* c = scene->body(2);
    c->setCollisionFlags(c->getCollisionFlags() | btCollisionObject::CF_DISABLE_SPU_COLLISION_PROCESSING |
                         btCollisionObject::CF_DISABLE_VISUALIZE_OBJECT);
    b->setContactProcessingThreshold(BT_LARGE_FLOAT);
    b->setAnisotropicFriction(btVector3(1, 2, 1), btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION);
    b->setCcdMotionThreshold(0.1f);  // with m_useContinuous off below
    w.getDispatchInfo().m_useContinuous = false;
    b->setFlags(b->getFlags() | BT_DISABLE_WORLD_GRAVITY);
    scene->step();
    EXPECT_TRUE(scene->report()->gpuPath) << scene->report()->cpuPathReason;
    gContactAddedCallback = nullptr;
    static_cast<btContactSolverInfoData&>(info) = saved;
}

namespace {
struct NoDeactivationDrawer : btIDebugDraw {
    void drawLine(const btVector3&, const btVector3&, const btVector3&) override {}
    void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override {}
    void reportErrorWarning(const char*) override {}
    void draw3dText(const btVector3&, const char*) override {}
    void setDebugMode(int) override {}
    int getDebugMode() const override { return DBG_NoDeactivation; }
};
}  // namespace

TEST(CpuPathRules, GpuPathTakesWhatStepSimulationSets)
{
    // stepSimulation takes gDisableDeactivation from a debug drawer's DBG_NoDeactivation (only
    // the GPU world steps here, so the global is its own doing); internalSingleStepSimulation
    // sets the solver info's and dispatch info's time step.
    NoDeactivationDrawer drawer;
    gDisableDeactivation = false;
    ScenePtr awake = scenes::restingBox(WorldKind::Gpu);
    ScenePtr asleep = scenes::restingBox(WorldKind::Gpu);
    awake->world().setDebugDrawer(&drawer);
    awake->world().getSolverInfo().m_timeStep = 1;
    awake->world().getDispatchInfo().m_timeStep = 1;
    for (int i = 0; i < 200; ++i) {  // past gDeactivationTime (2 s)
        gDisableDeactivation = false;
        asleep->step();
        awake->step();
    }
    EXPECT_TRUE(awake->report()->gpuPath) << awake->report()->cpuPathReason;
    EXPECT_TRUE(gDisableDeactivation);
    EXPECT_TRUE(awake->body(1)->isActive()) << "the GPU path put the box to sleep under DBG_NoDeactivation";
    EXPECT_FALSE(asleep->body(1)->isActive()) << "the box never sleeps: the scene is wrong";
    EXPECT_EQ(awake->world().getSolverInfo().m_timeStep, kStep);
    EXPECT_EQ(awake->world().getDispatchInfo().m_timeStep, kStep);
    awake->world().setDebugDrawer(nullptr);
    gDisableDeactivation = false;
}

TEST(CpuPathRules, LatencyInterpolationOffAsStock)
{
    SideBySide s(scenes::freeFall);
    s.both([](Scene& scene) {
        scene.world().setLatencyMotionStateInterpolation(false);
        scene.body(1)->setAngularVelocity(btVector3(0, 2, 1));
    });
    for (int i = 0; i < 60; ++i) {
        s.stock->step(btScalar(1) / 100, 10, kStep);
        s.gpu->step(btScalar(1) / 100, 10, kStep);
        ASSERT_TRUE(s.onGpu());
        btTransform a, b;
        s.stock->body(1)->getMotionState()->getWorldTransform(a);
        s.gpu->body(1)->getMotionState()->getWorldTransform(b);
        ASSERT_LT((a.getOrigin() - b.getOrigin()).length(), tol::kInterpolatedTransform) << "call " << i;
    }
}

namespace {

// An app's own world classes: one overrides a step hook the GPU path never calls, one only
// adds what the GPU path honours.
struct OwnIntegration : btGpuDynamicsWorld {
    using btGpuDynamicsWorld::btGpuDynamicsWorld;
    int calls = 0;
    void integrateTransforms(btScalar dt) override
    {
        ++calls;
        btGpuDynamicsWorld::integrateTransforms(dt);
    }
};
struct OwnKinematics : btGpuDynamicsWorld {
    using btGpuDynamicsWorld::btGpuDynamicsWorld;
    int calls = 0;
    void saveKinematicState(btScalar dt) override
    {
        ++calls;
        btGpuDynamicsWorld::saveKinematicState(dt);
    }
};

template <class World>
void stepOwnWorld(bool expectGpu)
{
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    World world(&dispatcher, &broadphase, &solver, &config);
    btBoxShape box(btVector3(0.5f, 0.5f, 0.5f));
    btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, &box, btVector3(1, 1, 1));
    btRigidBody body(info);
    world.addRigidBody(&body);
    for (int i = 0; i < 3; ++i) world.stepSimulation(btScalar(1) / 60);
    EXPECT_EQ(world.isGpuPath(), expectGpu) << world.report().cpuPathReason;
    EXPECT_EQ(world.calls, 3) << "the app's hook was not called on every step";
    world.removeRigidBody(&body);
}

}  // namespace

// A hook the GPU path bypasses sends the world to the CPU path, where Bullet calls it; one it
// calls (saveKinematicState) keeps the GPU path.
TEST(CpuPathRules, OwnWorldClassesKeepTheirHooks)
{
    stepOwnWorld<OwnIntegration>(false);
    stepOwnWorld<OwnKinematics>(true);
}

TEST(CpuPathRules, FeaturedBoxesBesidePlainBoxesFallBack)
{
    // Stock clips two boxes whatever their features, but a featured box against a featured hull
    // too: the GPU path serves featured boxes as featured hulls, so the mix falls back.
    ScenePtr scene = scenes::dropRow(WorldKind::Gpu);
    scene->step();
    ASSERT_TRUE(scene->report()->gpuPath) << scene->report()->cpuPathReason;
    btBoxShape* featured = scene->boxShape(btVector3(.5, .5, .5));
    featured->initializePolyhedralFeatures();
    btRigidBody* b = scene->addBody(featured, 1, btVector3(6, 3, 0));
    scene->step();
    EXPECT_FALSE(scene->report()->gpuPath);
    EXPECT_NE(scene->report()->cpuPathReason.find("polyhedral features"), std::string::npos)
        << scene->report()->cpuPathReason;
    scene->removeBody(b);
    scene->step();
    EXPECT_TRUE(scene->report()->gpuPath) << scene->report()->cpuPathReason;
}
