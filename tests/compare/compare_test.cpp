// compare_test.cpp — btgpu::saveWorld and btgpu_compare on scenes this test builds and saves:
// bodies come back from a file as they were saved; a pile and a stack stay within stock's chaos
// on the GPU path (exit 0); a jointed scene runs on the CPU path (exit 3); missing, empty,
// garbage, truncated and corrupted files are bad input (exit 2) named with a message, and never
// crash the loader; one child run of the executable checks its exit code and output files.
#include <BulletDynamics/ConstraintSolver/btGearConstraint.h>
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "btgpu/SaveWorld.h"
#include "btgpu/btGpuDynamicsWorld.h"
#include "compare/bullet_file_check.h"
#include "compare/compare_run.h"
#include "compare/compare_report.h"
#include "compare/imported_world.h"
#include "scenes/scenes.h"

using namespace btgpu;
using namespace btgpu::compare;
using scenes::WorldKind;

namespace {

std::string tempDir()
{
    static const std::string dir = [] {
        std::string d = (std::filesystem::temp_directory_path() / ("btgpu_compare_test_" + std::to_string(::getpid()))).string();
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

std::string savedScene(const std::string& name, scenes::Scene& scene)
{
    const std::string path = tempDir() + "/" + name + ".bullet";
    const SaveResult r = saveWorld(&scene.world(), path);
    EXPECT_TRUE(r.ok) << r.error;
    return path;
}

std::vector<char> readAll(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

void writeAll(const std::string& path, const std::vector<char>& bytes)
{
    std::ofstream f(path, std::ios::binary);
    f.write(bytes.data(), std::streamsize(bytes.size()));
}

// The stages a box scene on the GPU path must have run: pairs, box-box contacts, the solve.
void expectBoxStages(const CompareResult& r)
{
    for (const char* stage : {"find_pairs", "narrowphase_sat", "prepare_contacts", "solve_constraints", "integrate_transforms"})
        EXPECT_NE(std::find(r.gpuStages.begin(), r.gpuStages.end(), stage), r.gpuStages.end()) << stage;
}

CompareResult compareFile(const std::string& path, int steps)
{
    CompareOptions o;
    o.path = path;
    o.steps = steps;
    return runCompare(o);
}

// A body the scene library does not make: every field the importer drops set away from its default.
struct OddBodies {
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    std::unique_ptr<btCollisionShape> box{new btBoxShape(btVector3(0.3f, 0.2f, 0.4f))};
    explicit OddBodies(btDiscreteDynamicsWorld& world)
    {
        for (int i = 0; i < 3; ++i) {
            btRigidBody::btRigidBodyConstructionInfo info(btScalar(2.7 + i), nullptr, box.get(), btVector3(0.11f, 0.23f, 0.37f));
            info.m_startWorldTransform.setOrigin(btVector3(btScalar(3 * i), 1.5f, -4));
            info.m_startWorldTransform.setRotation(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.3 * i)));
            bodies.emplace_back(new btRigidBody(info));
            btRigidBody* b = bodies.back().get();
            b->setLinearVelocity(btVector3(1.25f, 2.5f, -0.75f));
            b->setAngularVelocity(btVector3(0.5f, -1.5f, 2.f));
            b->setDamping(0.125f, 0.375f);
            b->setSleepingThresholds(0.25f, 0.5f);
            b->setLinearFactor(btVector3(1, 1, 0));
            b->setAngularFactor(btVector3(0, 1, 1));
            b->setFriction(0.9f);
            b->setRestitution(0.3f);
            b->setRollingFriction(0.05f);
            b->setContactProcessingThreshold(0.5f);
            b->setCcdMotionThreshold(0.1f);
            b->setCcdSweptSphereRadius(0.05f);
            b->setAnisotropicFriction(btVector3(1, 0.5f, 1));
            world.addRigidBody(b, short(1 << (i + 1)), short(btBroadphaseProxy::AllFilter ^ (1 << (i + 1))));
            b->setGravity(btVector3(0, -3, 1));
            b->setActivationState(DISABLE_DEACTIVATION);
        }
        bodies[2]->setCollisionFlags(bodies[2]->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
        bodies[1]->setContactStiffnessAndDamping(3e4f, 0.25f);
        bodies[1]->setHitFraction(0.5f);
        bodies[0]->applyCentralForce(btVector3(4, 5, 6));  // pending until the next step
        bodies[0]->applyTorque(btVector3(-1, 2, -3));
        bodies[0]->setInterpolationLinearVelocity(btVector3(0.5f, 0.25f, 0.125f));
        bodies[0]->setInterpolationAngularVelocity(btVector3(-0.5f, 0.75f, 1));
    }
};

void expectSameBody(const btRigidBody& a, const btRigidBody& b, int i)
{
    SCOPED_TRACE("body " + std::to_string(i));
    EXPECT_EQ(a.getWorldTransform().getOrigin(), b.getWorldTransform().getOrigin());
    for (int r = 0; r < 3; ++r) EXPECT_EQ(a.getWorldTransform().getBasis()[r], b.getWorldTransform().getBasis()[r]);
    EXPECT_EQ(a.getInterpolationWorldTransform().getOrigin(), b.getInterpolationWorldTransform().getOrigin());
    EXPECT_EQ(a.getInvMass(), b.getInvMass());
    EXPECT_EQ(a.getInvInertiaDiagLocal(), b.getInvInertiaDiagLocal());
    EXPECT_EQ(a.getLinearVelocity(), b.getLinearVelocity());
    EXPECT_EQ(a.getAngularVelocity(), b.getAngularVelocity());
    EXPECT_EQ(a.getLinearDamping(), b.getLinearDamping());
    EXPECT_EQ(a.getAngularDamping(), b.getAngularDamping());
    EXPECT_EQ(a.getLinearSleepingThreshold(), b.getLinearSleepingThreshold());
    EXPECT_EQ(a.getAngularSleepingThreshold(), b.getAngularSleepingThreshold());
    EXPECT_EQ(a.getLinearFactor(), b.getLinearFactor());
    EXPECT_EQ(a.getAngularFactor(), b.getAngularFactor());
    EXPECT_EQ(a.getGravity(), b.getGravity());
    EXPECT_EQ(a.getFriction(), b.getFriction());
    EXPECT_EQ(a.getRestitution(), b.getRestitution());
    EXPECT_EQ(a.getRollingFriction(), b.getRollingFriction());
    EXPECT_EQ(a.getAnisotropicFriction(), b.getAnisotropicFriction());
    EXPECT_EQ(a.hasAnisotropicFriction(), b.hasAnisotropicFriction());
    EXPECT_EQ(a.getContactProcessingThreshold(), b.getContactProcessingThreshold());
    EXPECT_EQ(a.getCcdMotionThreshold(), b.getCcdMotionThreshold());
    EXPECT_EQ(a.getCcdSweptSphereRadius(), b.getCcdSweptSphereRadius());
    EXPECT_EQ(a.getContactStiffness(), b.getContactStiffness());
    EXPECT_EQ(a.getContactDamping(), b.getContactDamping());
    EXPECT_EQ(a.getHitFraction(), b.getHitFraction());
    EXPECT_EQ(a.getInterpolationLinearVelocity(), b.getInterpolationLinearVelocity());
    EXPECT_EQ(a.getInterpolationAngularVelocity(), b.getInterpolationAngularVelocity());
    EXPECT_EQ(a.getTotalForce(), b.getTotalForce());
    EXPECT_EQ(a.getTotalTorque(), b.getTotalTorque());
    EXPECT_EQ(a.getCollisionFlags(), b.getCollisionFlags());
    EXPECT_EQ(a.getActivationState(), b.getActivationState());
    EXPECT_EQ(a.getDeactivationTime(), b.getDeactivationTime());
    ASSERT_TRUE(a.getBroadphaseHandle() && b.getBroadphaseHandle());
    EXPECT_EQ(a.getBroadphaseHandle()->m_collisionFilterGroup, b.getBroadphaseHandle()->m_collisionFilterGroup);
    EXPECT_EQ(a.getBroadphaseHandle()->m_collisionFilterMask, b.getBroadphaseHandle()->m_collisionFilterMask);
    EXPECT_EQ(a.getCollisionShape()->getShapeType(), b.getCollisionShape()->getShapeType());
}

}  // namespace

TEST(SaveWorld, NamesWhatFails)
{
    EXPECT_FALSE(saveWorld(nullptr, tempDir() + "/x.bullet").ok);
    scenes::ScenePtr scene = scenes::restingBox(WorldKind::Stock);
    const SaveResult r = saveWorld(&scene->world(), "/nonexistent-dir/scene.bullet");
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find("/nonexistent-dir/scene.bullet"), std::string::npos) << r.error;
    EXPECT_FALSE(std::filesystem::exists("/nonexistent-dir/scene.bullet.partial"));
}

// Every field the importer drops comes back bitwise, on stock and on the btgpu world, and the
// restored stock world then steps exactly as the world that was saved.
TEST(SaveWorld, BodiesComeBackAsSaved)
{
    scenes::ScenePtr scene = scenes::basicDemo(WorldKind::Stock);
    for (int i = 0; i < 30; ++i) scene->step();  // mid-fall: velocities, interpolation, contacts
    OddBodies odd(scene->world());
    const std::string path = savedScene("odd_bodies", *scene);
    const FileCheck file = checkBulletFile(path);
    ASSERT_TRUE(file.ok) << file.error;
    EXPECT_FALSE(file.doublePrecision);
    EXPECT_EQ(file.version, 324);
    ASSERT_EQ(probeImport(file), "");

    btCollisionObjectArray& saved = scene->world().getCollisionObjectArray();
    for (Engine e : {Engine::Stock, Engine::Gpu}) {
        std::string error;
        std::unique_ptr<ImportedWorld> w = ImportedWorld::load(file, e, Config::bulletMode(), error);
        ASSERT_TRUE(w) << error;
        ASSERT_EQ(int(w->bodies().size()), saved.size());
        for (int i = 0; i < saved.size(); ++i) expectSameBody(*btRigidBody::upcast(saved[i]), *w->bodies()[size_t(i)], i);
        const Restoration& r = w->restoration();
        EXPECT_EQ(r.restored.count("linear and angular velocity"), 1u);
        EXPECT_EQ(r.restored.count("collision filter group and mask"), 1u);
        EXPECT_EQ(r.restored.at("per-body gravity"), 3);
        EXPECT_EQ(w->world().getGravity(), scene->world().getGravity());
    }

    // Same bodies, same order, same settings: the loaded stock world steps as the saved one,
    // which keeps its motion states and contact manifolds (a cold start is all that differs,
    // so the comparison starts where neither had contacts: the odd bodies are in the air).
    scenes::ScenePtr fresh = scenes::basicDemo(WorldKind::Stock);
    OddBodies odd2(fresh->world());
    const std::string path2 = savedScene("fresh", *fresh);
    std::string error;
    std::unique_ptr<ImportedWorld> w = ImportedWorld::load(checkBulletFile(path2), Engine::Stock, Config::bulletMode(), error);
    ASSERT_TRUE(w) << error;
    for (int s = 0; s < 120; ++s) {
        fresh->world().stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
        w->world().stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
    }
    btCollisionObjectArray& original = fresh->world().getCollisionObjectArray();
    for (int i = 0; i < original.size(); ++i)
        ASSERT_EQ(original[i]->getWorldTransform().getOrigin(), w->bodies()[size_t(i)]->getWorldTransform().getOrigin()) << "body " << i;
}

TEST(Compare, BadInputIsNamed)
{
    scenes::ScenePtr scene = scenes::restingBox(WorldKind::Stock);
    const std::string good = savedScene("good", *scene);
    const std::vector<char> bytes = readAll(good);
    ASSERT_GT(bytes.size(), 200u);
    auto expectBad = [&](const std::string& path, const std::string& words) {
        const CompareResult r = compareFile(path, 10);
        EXPECT_EQ(r.exitCode, kBadInput) << path;
        EXPECT_NE(r.error.find(path), std::string::npos) << r.error;
        EXPECT_NE(r.error.find(words), std::string::npos) << r.error;
    };
    expectBad(tempDir() + "/missing.bullet", "no such file");
    writeAll(tempDir() + "/empty.bullet", {});
    expectBad(tempDir() + "/empty.bullet", "empty file");
    std::vector<char> garbage(4096);
    std::mt19937 rng(7);
    for (char& c : garbage) c = char(rng());
    writeAll(tempDir() + "/garbage.bullet", garbage);
    expectBad(tempDir() + "/garbage.bullet", "not a .bullet file");
    writeAll(tempDir() + "/header.bullet", std::vector<char>(bytes.begin(), bytes.begin() + 12));
    expectBad(tempDir() + "/header.bullet", "truncated");
    // Cut anywhere: the DNA chunk Bullet writes last is gone or cut.
    for (size_t cut : {size_t(13), size_t(40), bytes.size() / 3, bytes.size() / 2, bytes.size() - 300, bytes.size() - 1}) {
        writeAll(tempDir() + "/cut.bullet", std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut)));
        expectBad(tempDir() + "/cut.bullet", "truncated");
    }
    // Garbage over the DNA's tables.
    std::vector<char> dna = bytes;
    const size_t at = size_t(std::search(dna.begin(), dna.end(), "SDNANAME", "SDNANAME" + 8) - dna.begin());
    ASSERT_LT(at, dna.size());
    for (size_t i = at + 8; i < at + 16; ++i) dna[i] = char(0x7f);
    writeAll(tempDir() + "/dna.bullet", dna);
    expectBad(tempDir() + "/dna.bullet", "corrupt DNA");
    // A chunk's length made huge.
    std::vector<char> len = bytes;
    len[12 + 4 + 3] = char(0x40);
    writeAll(tempDir() + "/len.bullet", len);
    expectBad(tempDir() + "/len.bullet", "truncated");
}

// Random damage anywhere in a real file: the check or the probe names it, or it loads; the
// process never crashes (Bullet's loader only ever sees damage in a forked child).
// BTGPU_COMPARE_DAMAGE_TRIALS=N runs more.
TEST(Compare, DamagedFilesNeverCrash)
{
    scenes::ScenePtr scene = scenes::hullLanding(WorldKind::Stock);
    const std::vector<char> bytes = readAll(savedScene("hull", *scene));
    std::mt19937 rng(11);
    const char* env = std::getenv("BTGPU_COMPARE_DAMAGE_TRIALS");
    const int trials = env ? std::atoi(env) : 60;
    int rejected = 0, probed = 0, loaded = 0;
    for (int trial = 0; trial < trials; ++trial) {
        std::vector<char> b = bytes;
        const int flips = 1 + int(rng() % 8);
        for (int f = 0; f < flips; ++f) b[12 + rng() % (b.size() - 12)] = char(rng());
        const FileCheck c = checkBulletBytes(b, "damaged");
        if (!c.ok) {
            ++rejected;
            continue;
        }
        const std::string probe = probeImport(c);
        if (!probe.empty()) {
            if (probed++ < 3) std::printf("probe: %s\n", probe.c_str());
            continue;
        }
        std::string error;
        std::unique_ptr<ImportedWorld> w = ImportedWorld::load(c, Engine::Stock, Config::bulletMode(), error);
        loaded += w ? 1 : 0;
    }
    std::printf("damaged files: %d rejected by the check, %d by the importer in the probe, %d loaded\n", rejected, probed, loaded);
    EXPECT_GT(rejected, 0);
}

// A file whose structure is sound but whose hull claims 2^28 points: Bullet's importer reads
// far past the record and dies; the probe (a forked child) names it, this process never sees it.
// (2^24 points: a larger count spends seconds allocating before the read faults.)
TEST(Compare, ImporterCrashIsBadInput)
{
    scenes::ScenePtr scene = scenes::hullLanding(WorldKind::Stock);
    const std::string good = savedScene("hull_good", *scene);
    std::vector<char> b = readAll(good);
    const int hullPoints = int(scene->body(1)->getCollisionShape()->getShapeType() == CONVEX_HULL_SHAPE_PROXYTYPE
                                   ? static_cast<btConvexHullShape*>(scene->body(1)->getCollisionShape())->getNumPoints()
                                   : -1);
    ASSERT_GT(hullPoints, 0);
    // Chunks after the 12-byte header: {code, len, 8-byte pointer, dna_nr, nr} then len bytes;
    // a hull record ends with its point count and 4 bytes of padding.
    bool found = false;
    for (size_t at = 12; at + 24 <= b.size() && !found;) {
        int code, len;
        std::memcpy(&code, &b[at], 4);
        std::memcpy(&len, &b[at + 4], 4);
        const size_t data = at + 24;
        int count = 0;
        if (code == BT_SHAPE_CODE && size_t(len) == sizeof(btConvexHullShapeData)) {
            std::memcpy(&count, &b[data + size_t(len) - 8], 4);
            if (count == hullPoints) {
                const int huge = 1 << 24;
                std::memcpy(&b[data + size_t(len) - 8], &huge, 4);
                found = true;
            }
        }
        at = data + size_t(len);
    }
    ASSERT_TRUE(found);
    const std::string path = tempDir() + "/hull_points.bullet";
    writeAll(path, b);
    ASSERT_TRUE(checkBulletFile(path).ok);  // the structure is sound
    const CompareResult r = compareFile(path, 10);
    EXPECT_EQ(r.exitCode, kBadInput);
    // A segmentation fault; under AddressSanitizer the child stops at the first bad read instead.
    EXPECT_NE(r.error.find("corrupt: Bullet's importer"), std::string::npos) << r.error;
}

TEST(Compare, PileStaysWithinStocksChaos)
{
    scenes::ScenePtr scene = scenes::basicDemo(WorldKind::Stock);
    const CompareResult r = compareFile(savedScene("pile", *scene), 240);
    std::fputs(summary(r).c_str(), stdout);
    ASSERT_NE(r.exitCode, kBadInput) << r.error;
    EXPECT_TRUE(r.gpuPathEveryStep) << r.cpuPathReason;
    EXPECT_EQ(r.exitCode, kWithinChaos);
    EXPECT_EQ(r.dynamicBodies, 125);
    expectBoxStages(r);
    const std::string out = tempDir() + "/pile_out";
    ASSERT_EQ(writeOutputs(r, out), "");
    for (const char* f : {"compare.md", "timeline.csv", "bodies.csv", "divergence.svg"})
        EXPECT_GT(std::filesystem::file_size(out + "/" + f), 100u) << f;
}

TEST(Compare, StackStaysWithinStocksChaos)
{
    scenes::ScenePtr scene = scenes::boxStack(WorldKind::Stock, Config::bulletMode(), 6);
    const CompareResult r = compareFile(savedScene("stack", *scene), 180);
    std::fputs(summary(r).c_str(), stdout);
    EXPECT_TRUE(r.gpuPathEveryStep) << r.cpuPathReason;
    EXPECT_EQ(r.exitCode, kWithinChaos);
    EXPECT_EQ(r.bodiesOutside, 0);
    expectBoxStages(r);
}

TEST(Compare, UnservedSettingRunsOnTheCpuPath)
{
    // Joints with a setting the GPU path does not take (the Jacobi solver solves no joint rows)
    // send the world there from the first step, and the verdict says so.
    scenes::ScenePtr scene = scenes::dropRow(WorldKind::Stock);
    btPoint2PointConstraint joint(*scene->body(1), *scene->body(2), btVector3(1, 0, 0), btVector3(-1, 0, 0));
    scene->world().addConstraint(&joint);
    CompareOptions o;
    o.path = savedScene("jointed", *scene);
    scene->world().removeConstraint(&joint);
    o.steps = 30;
    o.config.solver = SolverKind::JacobiMassSplitting;
    const CompareResult r = runCompare(o);
    std::fputs(summary(r).c_str(), stdout);
    EXPECT_EQ(r.constraints, 1);
    EXPECT_FALSE(r.gpuPathEveryStep);
    EXPECT_EQ(r.firstCpuPathStep, 1);
    EXPECT_NE(r.cpuPathReason.find("JacobiMassSplitting"), std::string::npos) << r.cpuPathReason;
    EXPECT_EQ(r.exitCode, kCpuPath);
}

TEST(Compare, JointedSceneRunsOnTheGpuPath)
{
    // A point-to-point joint and a gear (Bullet's importer brings back both) between two boxes.
    scenes::ScenePtr scene = scenes::dropRow(WorldKind::Stock);
    btPoint2PointConstraint joint(*scene->body(1), *scene->body(2), btVector3(1, 0, 0), btVector3(-1, 0, 0));
    btGearConstraint gear(*scene->body(1), *scene->body(2), btVector3(0, 1, 0), btVector3(0, 1, 0), 2.0f);
    scene->world().addConstraint(&joint);
    scene->world().addConstraint(&gear);
    const std::string path = savedScene("p2p", *scene);
    scene->world().removeConstraint(&gear);
    scene->world().removeConstraint(&joint);
    const CompareResult r = compareFile(path, 30);
    std::fputs(summary(r).c_str(), stdout);
    EXPECT_EQ(r.constraints, 2);
    EXPECT_TRUE(r.gpuPathEveryStep) << r.cpuPathReason;
    EXPECT_EQ(r.exitCode, kWithinChaos);
}

// The executable itself, once: its exit code is the verdict's, and --out gets the four files.
TEST(Compare, ToolExitCodes)
{
    scenes::ScenePtr scene = scenes::boxStack(WorldKind::Stock, Config::bulletMode(), 3);
    const std::string path = savedScene("tool_stack", *scene);
    const std::string out = tempDir() + "/tool_out";
    auto run = [](const std::string& args) {
        const int status = std::system((std::string(BTGPU_COMPARE_EXE) + " " + args + " > /dev/null 2>&1").c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    EXPECT_EQ(run(path + " --steps 60 --quiet --out " + out), kWithinChaos);
    for (const char* f : {"compare.md", "timeline.csv", "bodies.csv", "divergence.svg"})
        EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
    EXPECT_EQ(run(tempDir() + "/missing.bullet"), kBadInput);
    EXPECT_EQ(run(path + " --steps 0"), kBadInput);
    EXPECT_EQ(run(""), kBadInput);
}

// The verdict can fail: btgpu with 8 device substeps per step eats most of a bounce that stock
// keeps (speculative contacts, README "Error against run time"); a bouncing sphere is not
// chaotic, so its band is the floor and the difference is caught, on the GPU path.
TEST(Compare, DifferentPhysicsIsCaught)
{
    scenes::ScenePtr scene = scenes::bouncingSphere(WorldKind::Stock);
    CompareOptions o;
    o.path = savedScene("bounce", *scene);
    o.steps = 90;  // 1.5 s: dropped from 5 m, landed at 1 s, near its apex of 1.25 m on stock
    o.config.internalSubsteps = 8;
    const CompareResult r = runCompare(o);
    std::fputs(summary(r).c_str(), stdout);
    EXPECT_TRUE(r.gpuPathEveryStep) << r.cpuPathReason;
    EXPECT_EQ(r.exitCode, kOutsideChaos);
    EXPECT_NE(std::find(r.gpuStages.begin(), r.gpuStages.end(), "solve_constraints"), r.gpuStages.end());
    EXPECT_FALSE(r.aggregatesWithin);
    EXPECT_EQ(r.bodiesOutside, 1);
}

// A triangle-mesh ground (Bullet serializes the mesh and its BVH): today meshes send the world to
// the CPU path (exit 3); once the GPU path serves them the same file must stay within chaos.
TEST(Compare, MeshGroundFollowsItsPath)
{
    btTriangleMesh mesh;
    mesh.addTriangle(btVector3(-20, 0, -20), btVector3(20, 0, -20), btVector3(-20, 0, 20));
    mesh.addTriangle(btVector3(20, 0, -20), btVector3(20, 0, 20), btVector3(-20, 0, 20));
    scenes::Scene scene(WorldKind::Stock);
    scene.addBody(scene.ownShape(new btBvhTriangleMeshShape(&mesh, true)), 0, btVector3(0, 0, 0));
    btBoxShape* box = scene.boxShape(btVector3(0.5f, 0.5f, 0.5f));
    for (int i = 0; i < 3; ++i) scene.addBody(box, 1, btVector3(btScalar(1.5 * i), btScalar(1 + i), 0));
    const CompareResult r = compareFile(savedScene("mesh_ground", scene), 120);
    std::fputs(summary(r).c_str(), stdout);
    ASSERT_NE(r.exitCode, kBadInput) << r.error;
    EXPECT_EQ(r.bodies, 4);
    if (r.gpuPathEveryStep) {
        EXPECT_EQ(r.exitCode, kWithinChaos);
    } else {
        EXPECT_EQ(r.exitCode, kCpuPath);
        EXPECT_FALSE(r.cpuPathReason.empty());
    }
    // The boxes landed on the mesh on stock (it was imported, not dropped): centres at 0.5.
    for (const BodyResult& b : r.finalBodies)
        if (b.dynamic) EXPECT_NEAR(b.stock.y(), 0.5, 0.05) << "body " << b.index;
}

#ifdef BTGPU_DOUBLE_WRITER
#include "double_scene.h"

// A file from Bullet's double build: its double records restored into the float worlds.
TEST(Compare, DoublePrecisionFileLoads)
{
    namespace ds = btgpu::double_scene;
    const std::string path = tempDir() + "/double.bullet";
    ASSERT_EQ(std::system((std::string(BTGPU_DOUBLE_WRITER) + " " + path).c_str()), 0);
    const FileCheck file = checkBulletFile(path);
    ASSERT_TRUE(file.ok) << file.error;
    EXPECT_TRUE(file.doublePrecision);
    std::string error;
    std::unique_ptr<ImportedWorld> w = ImportedWorld::load(file, Engine::Stock, Config::bulletMode(), error);
    ASSERT_TRUE(w) << error;
    ASSERT_EQ(int(w->bodies().size()), ds::kBoxes + 1);
    for (int i = 0; i < ds::kBoxes; ++i) {
        const btRigidBody& b = *w->bodies()[size_t(i + 1)];
        EXPECT_EQ(b.getLinearVelocity(), btVector3(btScalar(ds::kVelocityX), 0, btScalar(ds::kVelocityZPerBody * i)));
        EXPECT_EQ(b.getLinearDamping(), btScalar(ds::kLinearDamping));
        EXPECT_EQ(b.getAngularDamping(), btScalar(ds::kAngularDamping));
        EXPECT_EQ(b.getLinearSleepingThreshold(), btScalar(ds::kLinearSleep));
        EXPECT_EQ(b.getAngularSleepingThreshold(), btScalar(ds::kAngularSleep));
        EXPECT_FLOAT_EQ(1 / b.getInvMass(), btScalar(ds::kMass));
    }
    const CompareResult r = compareFile(path, 60);
    std::fputs(summary(r).c_str(), stdout);
    EXPECT_TRUE(r.gpuPathEveryStep) << r.cpuPathReason;
    EXPECT_EQ(r.exitCode, kWithinChaos);
    expectBoxStages(r);
}
#endif

// The app's own use: a btgpu world saved mid-run, its bodies back as the GPU path left them; a
// btgpu world saved at its start and loaded steps bitwise as the one that was saved.
TEST(SaveWorld, GpuWorldSavesAndReloads)
{
    scenes::ScenePtr running = scenes::basicDemo(WorldKind::Gpu);
    for (int i = 0; i < 45; ++i) running->step();  // landing: contacts, velocities
    ASSERT_TRUE(running->gpuWorld()->isGpuPath()) << running->report()->cpuPathReason;
    std::string error;
    std::unique_ptr<ImportedWorld> w =
        ImportedWorld::load(checkBulletFile(savedScene("gpu_running", *running)), Engine::Gpu, Config::bulletMode(), error);
    ASSERT_TRUE(w) << error;
    btCollisionObjectArray& saved = running->world().getCollisionObjectArray();
    ASSERT_EQ(int(w->bodies().size()), saved.size());
    for (int i = 0; i < saved.size(); ++i) expectSameBody(*btRigidBody::upcast(saved[i]), *w->bodies()[size_t(i)], i);

    scenes::ScenePtr fresh = scenes::basicDemo(WorldKind::Gpu);
    std::unique_ptr<ImportedWorld> g =
        ImportedWorld::load(checkBulletFile(savedScene("gpu_fresh", *fresh)), Engine::Gpu, Config::bulletMode(), error);
    ASSERT_TRUE(g) << error;
    for (int s = 0; s < 120; ++s) {
        fresh->step();
        g->world().stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
        ASSERT_TRUE(g->gpuWorld()->isGpuPath()) << g->gpuWorld()->report().cpuPathReason;
    }
    EXPECT_EQ(fresh->gpuWorld()->stateHash(), g->gpuWorld()->stateHash());
}
