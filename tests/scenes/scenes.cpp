// scenes.cpp — Scene (owning every Bullet object, building stock or GPU worlds alike), the
// scene builders, the catalog by name, and the measures the tests and demos compare.
#include "scenes/scenes.h"
#include "scenes/compound_scenes.h"
#include "scenes/convex_scenes.h"
#include "scenes/mesh_scenes.h"
#include "scenes/joint_scenes.h"
#include "scenes/scene_specs.h"

#include <map>
#include <tuple>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "btgpu/btGpuDynamicsWorld.h"

namespace btgpu::scenes {

const char* toString(WorldKind kind)
{
    return kind == WorldKind::Stock ? "stock" : "btgpu";
}

const char* solverName(SolverKind kind)
{
    switch (kind) {
    case SolverKind::SoftStep: return "soft step";
    case SolverKind::JacobiMassSplitting: return "Jacobi with mass splitting";
    case SolverKind::Auto: return "auto";
    case SolverKind::BatchedPgs: break;
    }
    return "bullet mode (batched PGS)";
}

Scene::Scene(WorldKind kind, const Config& config, std::string name)
    : m_name(std::move(name)), m_kind(kind)
{
    m_collisionConfiguration = std::make_unique<btDefaultCollisionConfiguration>();
    m_dispatcher = std::make_unique<btCollisionDispatcher>(m_collisionConfiguration.get());
    m_broadphase = std::make_unique<btDbvtBroadphase>();
    m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    if (kind == WorldKind::Gpu) {
        auto* gpu = new btGpuDynamicsWorld(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
                                           m_collisionConfiguration.get(), config);
        m_gpuWorld = gpu;
        m_world.reset(gpu);
    } else {
        m_world = std::make_unique<btDiscreteDynamicsWorld>(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
                                                            m_collisionConfiguration.get());
    }
    // Bullet's default already, said here so every scene states its gravity.
    m_world->setGravity(btVector3(0, -10, 0));
}

Scene::~Scene()
{
    // Bodies leave the world before anything they point at is deleted; the world goes before
    // the solver, broadphase, dispatcher and configuration it was built on (member order).
    // Joints leave first: they point at the bodies.
    for (auto it = m_joints.rbegin(); it != m_joints.rend(); ++it) m_world->removeConstraint(it->get());
    m_joints.clear();
    for (auto it = m_bodies.rbegin(); it != m_bodies.rend(); ++it) {
        m_world->removeRigidBody(*it);
        delete (*it)->getMotionState();
        delete *it;
    }
    m_bodies.clear();
    m_world.reset();
}

const Report* Scene::report() const
{
    return m_gpuWorld ? &m_gpuWorld->report() : nullptr;
}

btBoxShape* Scene::boxShape(const btVector3& halfExtents)
{
    auto* shape = new btBoxShape(halfExtents);
    m_shapes.emplace_back(shape);
    return shape;
}

btSphereShape* Scene::sphereShape(btScalar radius)
{
    auto* shape = new btSphereShape(radius);
    m_shapes.emplace_back(shape);
    return shape;
}

btConvexHullShape* Scene::hullShape(const std::vector<btVector3>& points)
{
    auto* shape = new btConvexHullShape(points.empty() ? nullptr : &points[0].x(), static_cast<int>(points.size()),
                                        sizeof(btVector3));
    m_shapes.emplace_back(shape);
    return shape;
}

btRigidBody* Scene::addBody(btCollisionShape* shape, btScalar mass, const btTransform& transform,
                            const Material& material)
{
    btVector3 inertia(0, 0, 0);
    if (mass != btScalar(0)) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_friction = material.friction;
    info.m_restitution = material.restitution;
    return addBody(info, transform);
}

btRigidBody* Scene::addBody(btRigidBody::btRigidBodyConstructionInfo info, const btTransform& transform)
{
    info.m_motionState = new btDefaultMotionState(transform);
    auto* body = new btRigidBody(info);
    body->setUserIndex(static_cast<int>(m_bodies.size()));
    m_bodies.push_back(body);
    m_world->addRigidBody(body);
    return body;
}

btRigidBody* Scene::addBody(btCollisionShape* shape, btScalar mass, const btVector3& origin,
                            const Material& material)
{
    btTransform t;
    t.setIdentity();
    t.setOrigin(origin);
    return addBody(shape, mass, t, material);
}

btRigidBody* Scene::addKinematic(btCollisionShape* shape, const btTransform& transform, const Material& material)
{
    btVector3 inertia(0, 0, 0);
    auto* motionState = new btDefaultMotionState(transform);
    btRigidBody::btRigidBodyConstructionInfo info(0, motionState, shape, inertia);
    info.m_friction = material.friction;
    info.m_restitution = material.restitution;
    auto* body = new btRigidBody(info);
    // Flags before addRigidBody: the world picks the broadphase filter group from them.
    body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    body->setActivationState(DISABLE_DEACTIVATION);
    body->setUserIndex(static_cast<int>(m_bodies.size()));
    m_bodies.push_back(body);
    m_world->addRigidBody(body);
    return body;
}

void Scene::removeBody(btRigidBody* body)
{
    auto it = std::find(m_bodies.begin(), m_bodies.end(), body);
    if (it == m_bodies.end()) return;
    m_world->removeRigidBody(body);
    m_bodies.erase(it);
    delete body->getMotionState();
    delete body;
}

int Scene::worldIndex(const btRigidBody* body) const
{
    const btCollisionObjectArray& objects = m_world->getCollisionObjectArray();
    for (int i = 0; i < objects.size(); ++i)
        if (objects[i] == body) return i;
    return -1;
}

int Scene::step(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
    if (beforeStep) beforeStep(*this, m_time + timeStep);
    int substeps = m_world->stepSimulation(timeStep, maxSubSteps, fixedTimeStep);
    m_time += timeStep;
    ++m_steps;
    return substeps;
}

// --- builders --------------------------------------------------------------------------------

namespace {

// The 50 m ground box of Bullet's examples (top face at y = 0).
btRigidBody* addGround(Scene& scene, btScalar halfExtent = 50, const Material& material = Material())
{
    return scene.addBody(scene.boxShape(btVector3(halfExtent, halfExtent, halfExtent)), 0,
                         btVector3(0, -halfExtent, 0), material);
}

// The lattice from the shared plain-data spec (scene_specs.h), so tests, demos and the
// benchmark's three backends simulate the very same bodies.
ScenePtr makeLattice(WorldKind kind, int nx, int ny, int nz, const Config& config, bool boxes)
{
    auto scene = std::make_unique<Scene>(kind, config, boxes ? "cubes" : "spheres");
    const spec::Scene data = spec::makeStack(nx, ny, nz, boxes ? spec::ShapeKind::Box : spec::ShapeKind::Sphere);
    std::map<std::tuple<int, float, float, float>, btCollisionShape*> shapes;  // shared by equal bodies
    for (const spec::BodySpec& b : data.bodies) {
        const bool box = b.shape == spec::ShapeKind::Box;
        auto key = std::make_tuple(box ? 0 : 1, box ? b.half[0] : b.radius, box ? b.half[1] : 0.0f, box ? b.half[2] : 0.0f);
        btCollisionShape*& shape = shapes[key];
        if (!shape)
            shape = box ? static_cast<btCollisionShape*>(scene->boxShape(btVector3(b.half[0], b.half[1], b.half[2])))
                        : static_cast<btCollisionShape*>(scene->sphereShape(b.radius));
        scene->addBody(shape, b.mass, btVector3(b.pos[0], b.pos[1], b.pos[2]), Material{b.friction, b.restitution});
    }
    return scene;
}

}  // namespace

ScenePtr basicDemo(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "basic_demo");
    addGround(*scene, 50);
    btBoxShape* box = scene->boxShape(btVector3(btScalar(.1), btScalar(.1), btScalar(.1)));
    // Loop order and positions as in Bullet's examples/BasicDemo/BasicExample.cpp.
    for (int k = 0; k < 5; k++)
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 5; j++)
                scene->addBody(box, 1, btVector3(btScalar(0.2 * i), btScalar(2 + .2 * k), btScalar(0.2 * j)));
    return scene;
}

ScenePtr freeFall(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "free_fall");
    addGround(*scene);
    scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(0, 30, 0));
    return scene;
}

ScenePtr dropRow(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "drop_row");
    addGround(*scene);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    for (int i = -1; i <= 1; ++i) scene->addBody(box, 1, btVector3(btScalar(2 * i), 3, 0));
    return scene;
}

ScenePtr restingBox(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "resting_box");
    addGround(*scene);
    scene->addBody(scene->boxShape(btVector3(.5, .5, .5)), 1, btVector3(0, .5, 0));
    return scene;
}

ScenePtr sphereLanding(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "sphere_landing");
    addGround(*scene);
    scene->addBody(scene->sphereShape(.5), 1, btVector3(0, 2, 0));
    return scene;
}

ScenePtr hullLanding(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "hull_landing");
    addGround(*scene);
    // A box-like hull with a flat bottom (so it comes to rest on a face, not an edge) and two
    // extra vertices that make it irregular: centre of mass and inertia are not a box's.
    std::vector<btVector3> points = {
        {-.5, -.3, -.4}, {.5, -.3, -.4}, {.5, -.3, .4}, {-.5, -.3, .4},
        {-.4, .3, -.3},  {.4, .3, -.3},  {.4, .3, .3},  {-.4, .3, .3},
        {0, .5, 0},      {.6, 0, 0},
    };
    scene->addBody(scene->hullShape(points), 1, btVector3(0, 2, 0));
    return scene;
}

ScenePtr bouncingSphere(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "bouncing_sphere");
    // Bullet multiplies the two restitutions: ground 1 x sphere 0.5 bounces with 0.5.
    addGround(*scene, 50, Material{btScalar(0.5), btScalar(1)});
    scene->addBody(scene->sphereShape(.5), 1, btVector3(0, 5, 0), Material{btScalar(0.5), btScalar(0.5)});
    return scene;
}

ScenePtr boxStack(WorldKind kind, const Config& config, int count)
{
    auto scene = std::make_unique<Scene>(kind, config, "box_stack");
    addGround(*scene);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    for (int i = 0; i < count; ++i) scene->addBody(box, 1, btVector3(0, btScalar(.5 + i), 0));
    return scene;
}

ScenePtr kinematicPush(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "kinematic_push");
    addGround(*scene);
    btBoxShape* box = scene->boxShape(btVector3(.5, .5, .5));
    for (int i = 0; i < 3; ++i) scene->addBody(box, 1, btVector3(btScalar(1.1 * i), .5, 0));
    // Lifted 1 cm: a kinematic body does not collide with the static ground anyway, but this keeps
    // the pusher's face clear of any ground contact an implementation might still generate.
    const btVector3 start(-2, btScalar(.51), 0);
    btTransform t;
    t.setIdentity();
    t.setOrigin(start);
    btRigidBody* pusher = scene->addKinematic(scene->boxShape(btVector3(.5, .5, 1.5)), t);
    // The app sets the pose the body must have at the end of the step; Bullet derives the
    // kinematic velocity from it (btRigidBody::saveKinematicState).
    scene->beforeStep = [pusher, start](Scene&, double endTime) {
        btTransform pose;
        pose.setIdentity();
        const double travelled = kPusherSpeed * std::min(endTime, kPusherSeconds);
        pose.setOrigin(start + btVector3(btScalar(travelled), 0, 0));
        pusher->getMotionState()->setWorldTransform(pose);
    };
    return scene;
}

ScenePtr cubes(WorldKind kind, int nx, int ny, int nz, const Config& config)
{
    return makeLattice(kind, nx, ny, nz, config, true);
}

ScenePtr spheres(WorldKind kind, int nx, int ny, int nz, const Config& config)
{
    return makeLattice(kind, nx, ny, nz, config, false);
}

ScenePtr dispersingSpheres(WorldKind kind, const Config& config)
{
    auto scene = std::make_unique<Scene>(kind, config, "dispersing_spheres");
    scene->world().setGravity(btVector3(0, 0, 0));
    btSphereShape* ball = scene->sphereShape(btScalar(0.5));
    const btScalar pitch = btScalar(1.06);
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
            for (int k = 0; k < 5; ++k) {
                const btVector3 offset(btScalar(i - 2) * pitch, btScalar(j - 2) * pitch, btScalar(k - 2) * pitch);
                btRigidBody* body = scene->addBody(ball, 1, offset + btVector3(0, 10, 0));
                body->setLinearVelocity(offset);
            }
    return scene;
}

// --- catalog -----------------------------------------------------------------------------------

const std::vector<SceneEntry>& catalog()
{
    static const std::vector<SceneEntry> entries = {
        {"basic_demo", "Bullet's BasicDemo: 125 small boxes on a ground box", basicDemo},
        {"free_fall", "one box falling for 2 s", freeFall},
        {"drop_row", "three boxes dropped side by side from 3 m", dropRow},
        {"resting_box", "a unit box at rest on the ground", restingBox},
        {"sphere_landing", "a sphere dropped from 2 m", sphereLanding},
        {"hull_landing", "a 10-point convex hull dropped from 2 m", hullLanding},
        {"bouncing_sphere", "a sphere with restitution 0.5 dropped from 5 m", bouncingSphere},
        {"box_stack", "8 unit boxes stacked", [](WorldKind k, const Config& c) { return boxStack(k, c, 8); }},
        {"kinematic_push", "a kinematic box pushing three boxes", kinematicPush},
        {"convex_pile", "12 capsules, cylinders, cones, spheres, a multi-sphere, a convex mesh and scaled boxes",
         [](WorldKind k, const Config& c) { return convexPile(k, c); }},
        {"cylinder_ramp", "a cylinder rolling down a 15 degree box ramp", [](WorldKind k, const Config& c) { return cylinderRamp(k, c); }},
        {"cubes", "4x4x4 lattice of boxes (cubes:NXxNYxNZ for other sizes)",
         [](WorldKind k, const Config& c) { return cubes(k, 4, 4, 4, c); }},
        {"spheres", "4x4x4 lattice of spheres (spheres:NXxNYxNZ for other sizes)",
         [](WorldKind k, const Config& c) { return spheres(k, 4, 4, 4, c); }},
        {"rest_on_mesh", "a box and a sphere at rest on a flat two-part triangle mesh", restOnMesh},
        {"drop_on_mesh", "100 boxes and spheres dropped apart onto a flat triangle mesh", dropOnMesh},
        {"landscape", "bench 5: boxes, spheres and hulls on a rolling triangle-mesh landscape (1,000)",
         [](WorldKind k, const Config& c) { return landscape(k, c, 1000); }},
        {"landscape_1m", "1,000 bodies on a 1,000,000-triangle landscape",
         [](WorldKind k, const Config& c) { return landscape(k, c, 1000, 708); }},
        {"ragdolls", "4 ragdolls (boxes, hinges and cone-twists) dropping onto the ground",
         [](WorldKind k, const Config& c) { return ragdolls(k, c, 4); }},
        {"chain", "a chain of 20 point-to-point links hanging from a static anchor",
         [](WorldKind k, const Config& c) { return chain(k, c, 20); }},
        {"compounds", "100 compound tables and dumbbells dropped onto a box ground",
         [](WorldKind k, const Config& c) { return compoundDrop(k, c, 100); }},
        {"table_stack", "3 compound tables (a top on four legs) stacked on a box ground",
         [](WorldKind k, const Config& c) { return tableStack(k, c, 3); }},
    };
    return entries;
}

ScenePtr makeScene(const std::string& name, WorldKind kind, const Config& config)
{
    const std::size_t colon = name.find(':');
    if (colon != std::string::npos) {
        const std::string base = name.substr(0, colon);
        int nx = 0, ny = 0, nz = 0;
        char tail = 0;
        if (std::sscanf(name.c_str() + colon + 1, "%dx%dx%d%c", &nx, &ny, &nz, &tail) != 3 || nx <= 0 || ny <= 0 ||
            nz <= 0)
            return nullptr;
        if (base == "cubes") return cubes(kind, nx, ny, nz, config);
        if (base == "spheres") return spheres(kind, nx, ny, nz, config);
        return nullptr;
    }
    for (const SceneEntry& e : catalog())
        if (e.name == name) return e.make(kind, config);
    return nullptr;
}

// --- measures ----------------------------------------------------------------------------------

namespace {
bool isDynamic(const btRigidBody* b)
{
    return !b->isStaticOrKinematicObject() && b->getInvMass() > 0;
}
}  // namespace

StateDifference positionDifference(const Scene& a, const Scene& b)
{
    StateDifference d;
    const std::size_t n = std::min(a.bodies().size(), b.bodies().size());
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const btRigidBody* ba = a.bodies()[i];
        const btRigidBody* bb = b.bodies()[i];
        if (!isDynamic(ba) || !isDynamic(bb)) continue;
        const double dist = (ba->getWorldTransform().getOrigin() - bb->getWorldTransform().getOrigin()).length();
        d.maxPosition = std::max(d.maxPosition, dist);
        sum += dist;
        ++d.bodies;
    }
    d.meanPosition = d.bodies ? sum / d.bodies : 0.0;
    return d;
}

double meanHeight(const Scene& scene)
{
    double sum = 0.0;
    int n = 0;
    for (const btRigidBody* b : scene.bodies())
        if (isDynamic(b)) {
            sum += b->getWorldTransform().getOrigin().y();
            ++n;
        }
    return n ? sum / n : 0.0;
}

double lowestHeight(const Scene& scene)
{
    double lowest = std::numeric_limits<double>::infinity();
    for (const btRigidBody* b : scene.bodies())
        if (isDynamic(b)) lowest = std::min(lowest, double(b->getWorldTransform().getOrigin().y()));
    return lowest;
}

bool allFinite(const Scene& scene)
{
    for (const btRigidBody* b : scene.bodies()) {
        const btTransform& t = b->getWorldTransform();
        const btVector3& p = t.getOrigin();
        const btQuaternion q = t.getRotation();
        const btVector3& v = b->getLinearVelocity();
        const btVector3& w = b->getAngularVelocity();
        for (btScalar s : {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z()})
            if (!std::isfinite(s)) return false;
    }
    return true;
}

}  // namespace btgpu::scenes
