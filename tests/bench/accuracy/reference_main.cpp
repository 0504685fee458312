// reference_main.cpp — btgpu_accuracy_reference: the converged reference for the chaotic pile.
// Stock Bullet's double-precision build (Debian's -float64 libraries), 16 substeps per 1/60 s
// frame and 100 solver iterations; writes the pile statistics over time for btgpu_accuracy.
// Its own executable: the double and float Bullet libraries share most symbol names.
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "pile_stats.h"
#include "scenes/accuracy_scenes.h"

static_assert(sizeof(btScalar) == 8, "the reference links the double-precision Bullet (bullet-float64)");

namespace {

const char* kUsage =
    "usage: btgpu_accuracy_reference [--quick] [--dims NX NY NZ] [--seconds S] [--substeps N]\n"
    "                                [--iterations N] --out FILE\n"
    "  defaults: 10x10x10 boxes, 4 s, 16 substeps per 1/60 s frame, 100 iterations;\n"
    "  --quick: 5x4x5 boxes, 2 s (the ctest run).\n";

[[noreturn]] void usage(const std::string& why)
{
    std::fprintf(stderr, "btgpu_accuracy_reference: %s\n%s", why.c_str(), kUsage);
    std::exit(2);
}

}  // namespace

int main(int argc, char** argv)
{
    int dims[3] = {10, 10, 10}, substeps = 16, iterations = 100;
    double seconds = 4;
    std::string out;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> const char* {
            if (i + 1 >= argc) usage("missing value after " + a);
            return argv[++i];
        };
        if (a == "--quick") {
            dims[0] = 5, dims[1] = 4, dims[2] = 5;
            seconds = 2;
        } else if (a == "--dims") {
            for (int& d : dims) d = std::atoi(next());
        } else if (a == "--seconds") seconds = std::atof(next());
        else if (a == "--substeps") substeps = std::atoi(next());
        else if (a == "--iterations") iterations = std::atoi(next());
        else if (a == "--out") out = next();
        else if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else usage("unknown argument " + a);
    }
    if (out.empty()) usage("--out FILE is required");
    if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || substeps < 1 || iterations < 1 || seconds <= 0)
        usage("counts must be positive");

    // The same world as tests/scenes' Scene builds, in double precision.
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
    world.setGravity(btVector3(0, -10, 0));
    world.getSolverInfo().m_numIterations = iterations;

    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    std::vector<std::unique_ptr<btDefaultMotionState>> states;
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    auto add = [&](btCollisionShape* shape, btScalar mass, const btTransform& t) {
        btVector3 inertia(0, 0, 0);
        if (mass > 0) shape->calculateLocalInertia(mass, inertia);
        states.push_back(std::make_unique<btDefaultMotionState>(t));
        btRigidBody::btRigidBodyConstructionInfo info(mass, states.back().get(), shape, inertia);
        info.m_friction = btgpu::scenes::kPileFriction;
        info.m_restitution = 0;
        bodies.push_back(std::make_unique<btRigidBody>(info));
        if (mass > 0) bodies.back()->setActivationState(DISABLE_DEACTIVATION);
        world.addRigidBody(bodies.back().get());
    };
    const double g = btgpu::scenes::kPileGroundHalfExtent;
    shapes.push_back(std::make_unique<btBoxShape>(btVector3(g, g, g)));
    add(shapes.back().get(), 0, btTransform(btQuaternion::getIdentity(), btVector3(0, -g, 0)));
    shapes.push_back(std::make_unique<btBoxShape>(btVector3(.5, .5, .5)));
    for (const auto& p : btgpu::scenes::pileLayout(dims[0], dims[1], dims[2]))
        add(shapes.back().get(), 1,
            btTransform(btQuaternion(p.rotation[0], p.rotation[1], p.rotation[2], p.rotation[3]),
                        btVector3(p.position[0], p.position[1], p.position[2])));

    std::vector<btRigidBody*> raw;
    for (auto& b : bodies) raw.push_back(b.get());
    std::ofstream file(out);
    file << "# btgpu_accuracy_reference: stock Bullet, double precision\n"
         << "# dims " << dims[0] << ' ' << dims[1] << ' ' << dims[2] << "\n# seconds " << seconds
         << "\n# settings substeps=" << substeps << " iterations=" << iterations << "\n"
         << "t_s,mean_height_m,penetration_m,kinetic_energy_J\n";
    const int frames = int(seconds * 60 + 0.5);
    const int every = int(btgpu::accuracy::kPileSampleSeconds * 60 + 0.5);
    const auto t0 = std::chrono::steady_clock::now();
    char line[160];
    for (int f = 0; f <= frames; ++f) {
        if (f > 0) world.stepSimulation(1.0 / 60, substeps, 1.0 / (60.0 * substeps));
        if (f % every) continue;
        const auto s = btgpu::accuracy::pileStats<btRigidBody, btBoxShape>(raw);
        std::snprintf(line, sizeof line, "%.4f,%.9g,%.9g,%.9g\n", f / 60.0, s.meanHeight, s.penetration,
                      s.kineticEnergy);
        file << line;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "btgpu_accuracy_reference: %d boxes, %.1f s simulated in %.1f s -> %s\n",
                 dims[0] * dims[1] * dims[2], seconds, wall, out.c_str());
    return file ? 0 : 1;
}
