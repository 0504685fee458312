// stability.cpp — the stability harness: stepping, measures, judging, and the results table
// (see stability.h).
#include "stability/stability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

namespace btgpu::stability {

bool fullMode()
{
    const char* v = std::getenv("BTGPU_STABILITY_FULL");
    return v && *v && std::string(v) != "0";
}

namespace {

bool isDynamic(const btRigidBody* b) { return b->getInvMass() > 0; }

// Lowest point of a body (boxes by their corners, spheres by their radius, else the AABB).
double lowestPoint(const btRigidBody* b)
{
    const btTransform& t = b->getWorldTransform();
    const btCollisionShape* shape = b->getCollisionShape();
    if (shape->getShapeType() == BOX_SHAPE_PROXYTYPE) {
        const btVector3 h = static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin();
        double lowest = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 8; ++i) {
            const btVector3 c((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
            lowest = std::min(lowest, double((t * c).y()));
        }
        return lowest;
    }
    if (shape->getShapeType() == SPHERE_SHAPE_PROXYTYPE)
        return t.getOrigin().y() - static_cast<const btSphereShape*>(shape)->getRadius();
    btVector3 lo, hi;
    shape->getAabb(t, lo, hi);
    return lo.y();
}

struct DeepestContact : btCollisionWorld::ContactResultCallback {
    double deepest = 0;  // most negative distance, 0 when none
    btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override
    {
        deepest = std::min(deepest, double(cp.getDistance()));
        return 0;
    }
};

double speedBoundFor(const Scene& scene)
{
    // No body can go faster than it would falling from the highest point of the scene to the
    // ground (energy), plus its starting speed, plus 1 m/s of slack for contact pushes.
    double top = 0, start = 0;
    for (const btRigidBody* b : scene.bodies()) {
        if (!isDynamic(b)) continue;
        btVector3 lo, hi;
        b->getCollisionShape()->getAabb(b->getWorldTransform(), lo, hi);
        top = std::max(top, double(hi.y()));
        start = std::max(start, double(b->getLinearVelocity().length()));
    }
    return std::sqrt(2 * 10 * std::max(top, 0.0)) + start + 1;
}

void appendRow(const std::string& row)
{
    const char* path = std::getenv("BTGPU_STABILITY_TABLE");
    if (!path || !*path) return;
    bool fresh;
    {
        std::ifstream in(path);
        fresh = !in.good() || in.peek() == std::ifstream::traits_type::eof();
    }
    std::ofstream out(path, std::ios::app);
    if (fresh) out << "| case | engine | result | measured |\n| --- | --- | --- | --- |\n";
    out << row << "\n";
}

std::string mm(double metres)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g mm", metres * 1000);
    return buf;
}

}  // namespace

double penetration(Scene& scene, double groundY)
{
    double deepest = 0;
    const auto& bodies = scene.bodies();
    std::vector<btVector3> lo(bodies.size()), hi(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        bodies[i]->getCollisionShape()->getAabb(bodies[i]->getWorldTransform(), lo[i], hi[i]);
        // Only bodies over the ground's footprint (the wall scene has no ground).
        if (isDynamic(bodies[i]) && bodies.size() > 1 && !isDynamic(bodies[0]) &&
            bodies[0]->getCollisionShape()->getShapeType() == BOX_SHAPE_PROXYTYPE && scene.name() != "bullet_vs_wall")
            deepest = std::max(deepest, groundY - lowestPoint(bodies[i]));
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (!isDynamic(bodies[i])) continue;
        for (std::size_t j = i + 1; j < bodies.size(); ++j) {
            if (!isDynamic(bodies[j])) continue;
            if (!TestAabbAgainstAabb2(lo[i], hi[i], lo[j], hi[j])) continue;
            DeepestContact cb;
            scene.world().contactPairTest(bodies[i], bodies[j], cb);
            deepest = std::max(deepest, -cb.deepest);
        }
    }
    return deepest;
}

double kePerMass(const Scene& scene)
{
    double ke = 0, mass = 0;
    for (const btRigidBody* b : scene.bodies()) {
        if (!isDynamic(b)) continue;
        const double m = 1.0 / b->getInvMass();
        const btVector3 w = b->getAngularVelocity();
        const btVector3 lw = b->getInvInertiaTensorWorld().inverse() * w;
        ke += 0.5 * m * b->getLinearVelocity().length2() + 0.5 * double(w.dot(lw));
        mass += m;
    }
    return mass > 0 ? ke / mass : 0;
}

double totalEnergy(const Scene& scene)
{
    double e = 0;
    for (const btRigidBody* b : scene.bodies()) {
        if (!isDynamic(b)) continue;
        const double m = 1.0 / b->getInvMass();
        const btVector3 w = b->getAngularVelocity();
        const btVector3 lw = b->getInvInertiaTensorWorld().inverse() * w;
        e += 0.5 * m * b->getLinearVelocity().length2() + 0.5 * double(w.dot(lw)) +
             m * 10 * double(b->getWorldTransform().getOrigin().y());
    }
    return e;
}

Outcome run(Scene& scene, const Criteria& c)
{
    Outcome o;
    o.kind = scene.kind();
    o.speedBound = c.speed >= 0 ? c.speed : speedBoundFor(scene);
    if (c.noSleep)
        for (btRigidBody* b : scene.bodies())
            if (isDynamic(b)) b->setActivationState(DISABLE_DEACTIVATION);
    const btVector3 driftStart =
        c.driftBody >= 0 ? scene.body(c.driftBody)->getWorldTransform().getOrigin() : btVector3(0, 0, 0);
    const double e0 = totalEnergy(scene);
    std::vector<btVector3> starts;
    for (const btRigidBody* b : scene.bodies()) starts.push_back(b->getWorldTransform().getOrigin());
    auto farthest = [&] {
        double d = 0;
        for (std::size_t i = 0; i < scene.bodies().size(); ++i)
            if (isDynamic(scene.bodies()[i]))
                d = std::max(d, double((scene.bodies()[i]->getWorldTransform().getOrigin() - starts[i]).length()));
        return d;
    };
    o.gpuEveryStep = scene.report() != nullptr;
    const int steps = int(std::lround(c.seconds / double(c.timeStep)));
    const double measureFrom = c.measureFrom >= 0 ? c.measureFrom : c.settleBy >= 0 ? c.settleBy : c.seconds;
    const int measureEvery = std::max(1, int(std::lround(0.5 / double(c.timeStep))));  // every 0.5 s
    const auto t0 = std::chrono::steady_clock::now();
    bool settled = true;
    for (int s = 1; s <= steps; ++s) {
        scene.step(c.timeStep, 1, c.timeStep);
        const double t = s * double(c.timeStep);
        if (!scenes::allFinite(scene)) {
            o.finite = false;
            break;
        }
        if (const Report* r = scene.report()) o.gpuEveryStep = o.gpuEveryStep && r->gpuPath;
        for (const btRigidBody* b : scene.bodies())
            if (isDynamic(b)) o.maxSpeed = std::max(o.maxSpeed, double(b->getLinearVelocity().length()));
        if (c.move >= 0 && (s % measureEvery == 0 || s == steps)) o.maxMove = std::max(o.maxMove, farthest());
        const double ke = kePerMass(scene);
        if (ke > tol::kSettledKePerMass) o.settleTime = t;
        if (c.settleBy >= 0 && t >= c.settleBy && ke > tol::kSettledKePerMass) settled = false;
        if (c.energyNeverGrows) o.energyRise = std::max(o.energyRise, totalEnergy(scene) - e0);
        if (c.penetration >= 0 && t + 1e-9 >= measureFrom && (s % measureEvery == 0 || s == steps))
            o.penetration = std::max(o.penetration, penetration(scene));
    }
    o.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    o.finalKePerMass = kePerMass(scene);
    if (c.driftBody >= 0) {
        // Sideways only: sinking is what the penetration bound judges, and a body released
        // above its resting place falls by design.
        btVector3 d = scene.body(c.driftBody)->getWorldTransform().getOrigin() - driftStart;
        o.drop = -double(d.y());
        d.setY(0);
        o.drift = d.length();
    }
    if (const Report* r = scene.report()) {
        o.gpuPath = r->gpuPath;
        o.stages = r->stages;
        o.issues = int(r->issues.size());
        if (!r->issues.empty()) o.firstIssue = r->issues.front().message;
    }
    std::ostringstream why;
    if (!o.finite) why << "NaN/inf; ";
    if (o.finite && o.maxSpeed > o.speedBound) why << "speed " << o.maxSpeed << " > " << o.speedBound << " m/s; ";
    if (o.finite && c.settleBy >= 0 && !settled) why << "not settled by " << c.settleBy << " s; ";
    if (o.finite && c.penetration >= 0 && o.penetration > c.penetration)
        why << "penetration " << mm(o.penetration) << " > " << mm(c.penetration) << "; ";
    if (o.finite && c.driftBody >= 0 && o.drift > c.drift) why << "drift " << mm(o.drift) << " > " << mm(c.drift) << "; ";
    if (o.finite && c.drop >= 0 && o.drop > c.drop) why << "top fell " << mm(o.drop) << " > " << mm(c.drop) << "; ";
    if (o.finite && c.move >= 0 && o.maxMove > c.move) why << "a body moved " << mm(o.maxMove) << " > " << mm(c.move) << "; ";
    if (o.finite && c.energyNeverGrows && o.energyRise > tol::kEnergyRise)
        why << "energy rose " << o.energyRise << " J; ";
    o.why = why.str();
    o.pass = o.why.empty();
    return o;
}

Outcome run(const Builder& make, WorldKind kind, const Criteria& criteria, const Config& config)
{
    ScenePtr scene = make(kind, config);
    return run(*scene, criteria);
}

std::string figure(const Outcome& o)
{
    std::ostringstream f;
    f.precision(3);
    if (!o.finite) f << "NaN; ";
    f << "pen " << mm(o.penetration) << ", drift " << mm(o.drift) << ", top drop " << mm(o.drop);
    if (o.maxMove > 0) f << ", farthest move " << mm(o.maxMove);
    f << ", vmax " << o.maxSpeed << " m/s, KE/M "
      << o.finalKePerMass << " J/kg, settled at " << o.settleTime << " s";
    if (o.energyRise > 0) f << ", energy rise " << o.energyRise << " J";
    if (o.kind == WorldKind::Gpu) f << (o.gpuPath ? ", gpu path" : ", CPU fallback");
    if (o.issues) f << ", " << o.issues << " issue(s): " << o.firstIssue;
    f << ", " << o.wallSeconds << " s wall";
    return f.str();
}

void record(const std::string& caseName, const Outcome& o, const std::string& figureText)
{
    recordAs(caseName, scenes::toString(o.kind), o, figureText);
}

void recordAs(const std::string& caseName, const std::string& engine, const Outcome& o, const std::string& figureText)
{
    std::string result = o.pass ? "pass" : "FAIL";
    if (!o.pass) result += " (" + o.why.substr(0, o.why.size() >= 2 ? o.why.size() - 2 : 0) + ")";
    ::testing::Test::RecordProperty(engine + "_result", result);
    ::testing::Test::RecordProperty(engine + "_figure", figureText);
    appendRow("| " + caseName + " | " + engine + " | " + result + " | " + figureText + " |");
    std::printf("[ %-5s ] %-28s %-5s %s%s\n", engine.c_str(), caseName.c_str(), o.pass ? "pass" : "FAIL",
                figureText.c_str(), o.pass ? "" : ("  <- " + o.why).c_str());
}

void appendRowNotRun(const std::string& caseName, const std::string& engine, const std::string& why)
{
    ::testing::Test::RecordProperty(engine + "_result", "not run");
    appendRow("| " + caseName + " | " + engine + " | not run | " + why + " |");
    std::printf("[ %-5s ] %-28s not run: %s\n", engine.c_str(), caseName.c_str(), why.c_str());
}

void judge(const std::string& caseName, const Outcome& stock, const Outcome& gpu, bool requireGpuPath)
{
    record(caseName, stock, figure(stock));
    record(caseName, gpu, figure(gpu));
    if (stock.pass) {
        EXPECT_TRUE(gpu.pass) << caseName << ": stock Bullet passes, btgpu fails: " << gpu.why;
    } else if (!gpu.pass) {
        std::printf("[ both  ] %s: stock Bullet fails too (%s); recorded, not failed\n", caseName.c_str(),
                    stock.why.c_str());
    }
    if (requireGpuPath) EXPECT_TRUE(gpu.gpuPath) << caseName << ": btgpu fell back to the CPU path";
}

void judgeAs(const std::string& caseName, const std::string& engine, const Outcome& stock, const Outcome& gpu)
{
    recordAs(caseName, engine, gpu, figure(gpu));
    if (stock.pass) EXPECT_TRUE(gpu.pass) << caseName << ": stock Bullet passes, " << engine << " fails: " << gpu.why;
    EXPECT_TRUE(gpu.gpuPath) << caseName << ": " << engine << " fell back to the CPU path";
}

void runEngines(const std::string& caseName, const Builder& make, const Criteria& criteria)
{
    const Outcome stock = run(make, WorldKind::Stock, criteria);
    const Outcome gpu = run(make, WorldKind::Gpu, criteria);
    judge(caseName, stock, gpu);
    judgeAs(caseName, "btgpu default", stock, run(make, WorldKind::Gpu, criteria, Config()));
}

void runEarned(const std::string& caseName, const Builder& make, const Criteria& criteria, int internalSubsteps)
{
    Config config = Config::bulletMode();
    config.internalSubsteps = internalSubsteps;
    const Outcome gpu = run(make, WorldKind::Gpu, criteria, config);
    recordAs(caseName, "btgpu, " + std::to_string(internalSubsteps) + " internal substeps", gpu, figure(gpu));
    EXPECT_TRUE(gpu.pass) << caseName << " with " << internalSubsteps << " internal substeps: " << gpu.why;
}

}  // namespace btgpu::stability
