// scenes.h — the scene library: every test, benchmark and demo scene, defined once. A Scene
// owns everything Bullet needs (configuration, dispatcher, broadphase, solver, shapes, motion
// states, bodies) and builds the same bodies on stock btDiscreteDynamicsWorld or on
// btGpuDynamicsWorld, so the two can be stepped side by side and compared body by body.
#pragma once
#include <btBulletDynamicsCommon.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "btgpu/Config.h"
#include "btgpu/Report.h"

class btGpuDynamicsWorld;

namespace btgpu::scenes {

enum class WorldKind { Stock, Gpu };
const char* toString(WorldKind kind);
// What Report::solver names, for the tools' output ("soft step", "bullet mode (batched PGS)", ...).
const char* solverName(SolverKind kind);

// Bullet's defaults (btRigidBodyConstructionInfo); Bullet multiplies the two bodies' values,
// so a scene that needs a value sets it on both bodies of the contact.
struct Material {
    btScalar friction = btScalar(0.5);
    btScalar restitution = btScalar(0);
};

class Scene {
public:
    explicit Scene(WorldKind kind, const Config& config = Config::bulletMode(), std::string name = "");
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    const std::string& name() const { return m_name; }
    WorldKind kind() const { return m_kind; }
    btDiscreteDynamicsWorld& world() { return *m_world; }
    const btDiscreteDynamicsWorld& world() const { return *m_world; }
    btGpuDynamicsWorld* gpuWorld() { return m_gpuWorld; }  // nullptr on Stock
    const Report* report() const;                          // nullptr on Stock

    // Shapes, owned by the scene (keep them alive as long as any body uses them).
    btBoxShape* boxShape(const btVector3& halfExtents);
    btSphereShape* sphereShape(btScalar radius);
    btConvexHullShape* hullShape(const std::vector<btVector3>& points);
    // Any other shape, which the scene then owns.
    template <class S>
    S* ownShape(S* shape)
    {
        m_shapes.emplace_back(shape);
        return shape;
    }
    // Anything a shape points into (a mesh's vertex arrays), kept until the shapes are gone.
    template <class T>
    T* ownData(T* data)
    {
        m_data.emplace_back(std::shared_ptr<T>(data));
        return data;
    }

    // Adds a body to the world; the scene owns it and its btDefaultMotionState. Mass 0 makes
    // it static (as in Bullet).
    btRigidBody* addBody(btCollisionShape* shape, btScalar mass, const btTransform& transform,
                         const Material& material = Material());
    btRigidBody* addBody(btCollisionShape* shape, btScalar mass, const btVector3& origin,
                         const Material& material = Material());
    // A body made from the app's own construction info (settings only it carries, such as
    // m_additionalDamping); the scene gives it a btDefaultMotionState at `transform`.
    btRigidBody* addBody(btRigidBody::btRigidBodyConstructionInfo info, const btTransform& transform);
    // A kinematic body (CF_KINEMATIC_OBJECT, DISABLE_DEACTIVATION), moved through its motion state.
    btRigidBody* addKinematic(btCollisionShape* shape, const btTransform& transform,
                              const Material& material = Material());
    // Removes the body from the world and deletes it (and its motion state).
    void removeBody(btRigidBody* body);
    // Adds a joint to the world (addConstraint); the scene owns it and removes it before the
    // bodies go.
    template <class C>
    C* addJoint(C* joint, bool disableCollisionsBetweenLinkedBodies = false)
    {
        m_joints.emplace_back(joint);
        m_world->addConstraint(joint, disableCollisionsBetweenLinkedBodies);
        return joint;
    }
    // Joints in the order the scene added them.
    btTypedConstraint* joint(int i) const { return m_joints.at(static_cast<std::size_t>(i)).get(); }
    int numJoints() const { return static_cast<int>(m_joints.size()); }

    // Bodies in the order the scene created them (removed ones left out): index i of two scenes
    // built by the same builder is the same body, whatever order the world keeps them in.
    const std::vector<btRigidBody*>& bodies() const { return m_bodies; }
    btRigidBody* body(int i) const { return m_bodies.at(static_cast<std::size_t>(i)); }
    // Index of a body in world().getCollisionObjectArray() (what Issue::bodyIndex names), -1 if absent.
    int worldIndex(const btRigidBody* body) const;

    // One stepSimulation call; first runs beforeStep (with the scene time the step ends at),
    // which is how a scene drives kinematic bodies.
    int step(btScalar timeStep = btScalar(1) / btScalar(60), int maxSubSteps = 1,
             btScalar fixedTimeStep = btScalar(1) / btScalar(60));
    double time() const { return m_time; }
    int steps() const { return m_steps; }
    std::function<void(Scene&, double endTime)> beforeStep;

private:
    std::string m_name;
    WorldKind m_kind;
    std::unique_ptr<btDefaultCollisionConfiguration> m_collisionConfiguration;
    std::unique_ptr<btCollisionDispatcher> m_dispatcher;
    std::unique_ptr<btBroadphaseInterface> m_broadphase;
    std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
    std::vector<std::shared_ptr<void>> m_data;  // destroyed after the shapes that use it
    std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
    std::unique_ptr<btDiscreteDynamicsWorld> m_world;
    btGpuDynamicsWorld* m_gpuWorld = nullptr;  // m_world, when it is a btGpuDynamicsWorld
    std::vector<btRigidBody*> m_bodies;        // owned, with their motion states
    std::vector<std::unique_ptr<btTypedConstraint>> m_joints;
    double m_time = 0.0;
    int m_steps = 0;
};

using ScenePtr = std::unique_ptr<Scene>;

// --- the scenes. Static ground boxes have their top face at y = 0; gravity is (0, -10, 0). ---

// Bullet's examples/BasicDemo: 5x5x5 boxes of half extent 0.1, mass 1, at
// (0.2 i, 2 + 0.2 k, 0.2 j), over a ground box of half extent 50 centred at y = -50.
ScenePtr basicDemo(WorldKind kind, const Config& config = Config::bulletMode());
// One box (half extent 0.5, mass 1) released at y = 30: 2 s of free fall before it lands.
ScenePtr freeFall(WorldKind kind, const Config& config = Config::bulletMode());
// Three unit boxes released at y = 3, at x = -2, 0, 2 (bodies 1, 2, 3): apart, so a test can
// change one without disturbing the others.
ScenePtr dropRow(WorldKind kind, const Config& config = Config::bulletMode());
// A unit box (half extent 0.5) placed exactly on the ground (centre y = 0.5).
ScenePtr restingBox(WorldKind kind, const Config& config = Config::bulletMode());
// A sphere (radius 0.5) released at y = 2; it lands and rolls nowhere (flat ground, no spin).
ScenePtr sphereLanding(WorldKind kind, const Config& config = Config::bulletMode());
// A 10-point convex hull with a flat bottom face, released at y = 2.
ScenePtr hullLanding(WorldKind kind, const Config& config = Config::bulletMode());
// A sphere (radius 0.5) released at y = 5; restitution 0.5 (sphere) x 1 (ground) = 0.5.
ScenePtr bouncingSphere(WorldKind kind, const Config& config = Config::bulletMode());
// `count` unit boxes stacked exactly touching (centres 0.5, 1.5, ...).
ScenePtr boxStack(WorldKind kind, const Config& config = Config::bulletMode(), int count = 8);
// Three unit boxes in a row along x; a kinematic box (half extents 0.5, 0.5, 1.5) starts at
// x = -2 and moves at kPusherSpeed along +x for kPusherSeconds, pushing them.
ScenePtr kinematicPush(WorldKind kind, const Config& config = Config::bulletMode());
constexpr double kPusherSpeed = 1.0;    // m/s
constexpr double kPusherSeconds = 4.0;  // s, then it stops
// nx*ny*nz boxes of half extent 1, mass 1, friction 1, restitution 0; pitch 2.2 in x, y, z;
// odd layers shifted +1 in x and z; bottom layer 0.2 above a ground box of half extent 400.
ScenePtr cubes(WorldKind kind, int nx, int ny, int nz, const Config& config = Config::bulletMode());
// The same lattice of spheres of radius 1.
ScenePtr spheres(WorldKind kind, int nx, int ny, int nz, const Config& config = Config::bulletMode());
// 5x5x5 spheres of radius 0.5, 6 cm apart, without gravity, flying apart from the centre one
// (velocity = 1/s x offset): no contacts ever, only broadphase pairs that come apart (stock's
// empty manifolds and its lazy pair removal).
ScenePtr dispersingSpheres(WorldKind kind, const Config& config = Config::bulletMode());

// --- by name, for the benchmark, demos and tests that run every scene. ---
struct SceneEntry {
    std::string name;
    std::string description;
    std::function<ScenePtr(WorldKind, const Config&)> make;
};
// Every scene, with small defaults for cubes and spheres (4x4x4).
const std::vector<SceneEntry>& catalog();
// A catalog name, or "cubes:NXxNYxNZ" / "spheres:NXxNYxNZ"; nullptr when the name is unknown.
ScenePtr makeScene(const std::string& name, WorldKind kind, const Config& config = Config::bulletMode());

// --- measures over the dynamic bodies (inverse mass > 0), paired by scene index. ---
struct StateDifference {
    double maxPosition = 0.0;   // m
    double meanPosition = 0.0;  // m
    int bodies = 0;
};
StateDifference positionDifference(const Scene& a, const Scene& b);
double meanHeight(const Scene& scene);    // m, mean centre y
double lowestHeight(const Scene& scene);  // m, lowest centre y
bool allFinite(const Scene& scene);

}  // namespace btgpu::scenes
