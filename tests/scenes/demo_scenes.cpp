// demo_scenes.cpp — the example-browser scenes of demo_scenes.h.
#include "demo_scenes.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletDynamics/Vehicle/btRaycastVehicle.h>

#include <cmath>
#include <map>
#include <memory>
#include <tuple>

#include "scenes/benchmark_specs.h"
#include "scenes/mesh_scenes.h"

namespace btgpu::scenes {

namespace {

btTransform pose(const float* rot, const float* pos)
{
    return btTransform(btQuaternion(rot[0], rot[1], rot[2], rot[3]), btVector3(pos[0], pos[1], pos[2]));
}

btTransform frame(const float* f)
{
    return btTransform(btQuaternion(f[3], f[4], f[5], f[6]), btVector3(f[0], f[1], f[2]));
}

// xorshift32, the same everywhere (std distributions differ between standard libraries).
struct Rng {
    std::uint32_t s;
    std::uint32_t next()
    {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        return s;
    }
};

void addSpecJoints(Scene& s, const spec::Scene& data, const std::vector<btRigidBody*>& bodies)
{
    for (const spec::JointSpec& j : data.joints) {
        btRigidBody& a = *bodies.at(size_t(j.a));
        btRigidBody& b = *bodies.at(size_t(j.b));
        if (j.kind == spec::JointSpec::Kind::Hinge) {
            auto* h = s.addJoint(new btHingeConstraint(a, b, frame(j.frameA), frame(j.frameB)), true);
            h->setLimit(j.limit[0], j.limit[1]);
        } else {
            auto* c = s.addJoint(new btConeTwistConstraint(a, b, frame(j.frameA), frame(j.frameB)), true);
            c->setLimit(j.limit[0], j.limit[1], j.limit[2]);
        }
    }
}

}  // namespace

ScenePtr fromSpec(WorldKind kind, const Config& config, const spec::Scene& data, const std::string& name)
{
    using spec::ShapeKind;
    auto s = std::make_unique<Scene>(kind, config, name);
    s->world().setGravity(btVector3(data.gravity[0], data.gravity[1], data.gravity[2]));
    s->world().getSolverInfo().m_numIterations = data.iterations;
    std::map<std::tuple<int, float, float, float>, btCollisionShape*> shared;
    std::vector<btRigidBody*> bodies;
    for (const spec::BodySpec& b : data.bodies) {
        auto key = b.shape == ShapeKind::Box      ? std::make_tuple(0, b.half[0], b.half[1], b.half[2])
                   : b.shape == ShapeKind::Sphere ? std::make_tuple(1, b.radius, 0.f, 0.f)
                   : b.shape == ShapeKind::Hull   ? std::make_tuple(2, float(b.hull), 0.f, 0.f)
                   : b.shape == ShapeKind::Mesh   ? std::make_tuple(4, 0.f, 0.f, 0.f)
                                                  : std::make_tuple(3, 0.f, 0.f, 0.f);
        btCollisionShape*& shape = shared[key];
        if (!shape) {
            if (b.shape == ShapeKind::Box) {
                shape = s->boxShape(btVector3(b.half[0], b.half[1], b.half[2]));
            } else if (b.shape == ShapeKind::Sphere) {
                shape = s->sphereShape(b.radius);
            } else if (b.shape == ShapeKind::Hull) {
                const spec::HullSpec& h = data.hulls.at(size_t(b.hull));
                auto* hull = s->ownShape(new btConvexHullShape(h.points.data(), int(h.points.size() / 3), 3 * sizeof(float)));
                if (h.polyhedral) hull->initializePolyhedralFeatures();
                hull->setMargin(h.margin);
                shape = hull;
            } else if (b.shape == ShapeKind::Mesh) {
                auto* vertices = s->ownData(new std::vector<float>(data.meshVertices));
                auto* indices = s->ownData(new std::vector<int>(data.meshIndices));
                auto* array = s->ownData(new btTriangleIndexVertexArray(int(indices->size() / 3), indices->data(),
                                                                        3 * int(sizeof(int)), int(vertices->size() / 3),
                                                                        vertices->data(), 3 * int(sizeof(float))));
                shape = s->ownShape(new btBvhTriangleMeshShape(array, true));
            } else {
                shape = s->ownShape(new btStaticPlaneShape(btVector3(0, 1, 0), 0));
            }
        }
        btRigidBody* body = s->addBody(shape, b.mass, pose(b.rot, b.pos), Material{b.friction, b.restitution});
        body->setDamping(b.linearDamping, b.angularDamping);
        bodies.push_back(body);
    }
    addSpecJoints(*s, data, bodies);
    return s;
}

ScenePtr benchPile(WorldKind kind, const Config& config, int layers)
{
    return fromSpec(kind, config, spec::makeBenchPile(layers), "bench_pile");
}

ScenePtr benchStacks(WorldKind kind, const Config& config)
{
    return fromSpec(kind, config, spec::makeBenchStacks(), "bench_stacks");
}

ScenePtr benchTower(WorldKind kind, const Config& config, int rings)
{
    return fromSpec(kind, config, spec::makeBenchTower(rings), "bench_tower");
}

ScenePtr benchHulls(WorldKind kind, const Config& config, int layers)
{
    return fromSpec(kind, config, spec::makeBenchHulls(layers), "bench_hulls");
}

ScenePtr voronoiPieces(WorldKind kind, const Config& config, int cells)
{
    return fromSpec(kind, config, spec::makeVoronoi(cells), "voronoi");
}

ScenePtr benchMixedShapes(WorldKind kind, const Config& config, int layers)
{
    auto s = std::make_unique<Scene>(kind, config, "bench_mixed");
    s->world().getSolverInfo().m_numIterations = 5;
    s->addBody(s->boxShape(btVector3(250, 50, 250)), 0, btVector3(0, -50, 0));
    btCollisionShape* shapes[9];
    for (int r = 0; r < 3; ++r) {
        const btScalar f = btScalar(0.5) * btScalar(r + 1);
        shapes[r] = s->boxShape(btVector3(1.5, 1.5, 1.5) * f);
        shapes[3 + r] = s->sphereShape(btScalar(1.5) * f);
        shapes[6 + r] = s->ownShape(new btCapsuleShape(f, 2 * f));
    }
    Rng rng{2024u};
    const int size = 10;
    const float cube = 1.5f;
    float spacing = 2.0f, offset = -float(size) * (cube * 2 + spacing) * 0.5f, y = 20;
    for (int k = 0; k < layers; ++k) {
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                const btVector3 p(offset + float(i) * (cube * 2 + spacing), y, offset + float(j) * (cube * 2 + spacing));
                const int idx = int(rng.next() % 9u);
                s->addBody(shapes[idx], btScalar(0.5) * btScalar(idx % 3 + 1),
                           btVector3(0, 25, 0) + btVector3(5, 1, 5) * p);
            }
        offset -= 0.05f * spacing * float(size - 1);
        spacing *= 1.1f;
        y += cube * 2 + spacing;
    }
    return s;
}

ScenePtr capsuleRagdolls(WorldKind kind, const Config& config, int count)
{
    auto s = std::make_unique<Scene>(kind, config, "ragdoll");
    const spec::Scene data = spec::makeRagdolls(count);
    std::map<std::pair<float, float>, btCollisionShape*> shared;
    std::vector<btRigidBody*> bodies;
    for (const spec::BodySpec& b : data.bodies) {
        btCollisionShape* shape = nullptr;
        if (b.mass == 0) {
            shape = s->boxShape(btVector3(b.half[0], b.half[1], b.half[2]));
        } else {
            // makeRagdolls' box of a capsule: half[0] its radius, half[1] half its height plus it.
            btCollisionShape*& c = shared[{b.half[0], b.half[1]}];
            if (!c) c = s->ownShape(new btCapsuleShape(b.half[0], 2 * (b.half[1] - b.half[0])));
            shape = c;
        }
        btRigidBody* body = s->addBody(shape, b.mass, pose(b.rot, b.pos), Material{b.friction, b.restitution});
        body->setDamping(b.linearDamping, b.angularDamping);
        bodies.push_back(body);
    }
    addSpecJoints(*s, data, bodies);
    return s;
}

ScenePtr benchRagdolls(WorldKind kind, const Config& config, int rows)
{
    auto s = std::make_unique<Scene>(kind, config, "bench_ragdolls");
    s->world().getSolverInfo().m_numIterations = 5;
    s->addBody(s->boxShape(btVector3(250, 50, 250)), 0, btVector3(0, -50, 0));
    const spec::Scene one = spec::makeRagdolls(1);  // ground, then one ragdoll's 11 parts at the origin
    const btScalar scale = 3.5f;
    std::vector<btCollisionShape*> shapes;
    for (size_t i = 1; i < one.bodies.size(); ++i) {
        const spec::BodySpec& b = one.bodies[i];
        shapes.push_back(s->ownShape(new btCapsuleShape(scale * b.half[0], scale * 2 * (b.half[1] - b.half[0]))));
    }
    btVector3 pos(0, 1, 0);
    for (int size = rows; size > 0; --size) {
        const float offset = -float(size) * 6.0f * 0.5f;
        for (int i = 0; i < size; ++i) {
            pos.setX(offset + float(i) * 6.0f);
            std::vector<btRigidBody*> parts(1, nullptr);  // index 0: the spec's ground, not used
            for (size_t k = 1; k < one.bodies.size(); ++k) {
                const spec::BodySpec& b = one.bodies[k];
                btTransform t = pose(b.rot, b.pos);
                t.setOrigin(pos + scale * t.getOrigin());
                btRigidBody* body = s->addBody(shapes[k - 1], b.mass, t, Material{b.friction, b.restitution});
                body->setDamping(b.linearDamping, b.angularDamping);
                parts.push_back(body);
            }
            for (const spec::JointSpec& j : one.joints) {
                btTransform fa = frame(j.frameA), fb = frame(j.frameB);
                fa.setOrigin(scale * fa.getOrigin()), fb.setOrigin(scale * fb.getOrigin());
                btRigidBody& a = *parts.at(size_t(j.a));
                btRigidBody& b = *parts.at(size_t(j.b));
                if (j.kind == spec::JointSpec::Kind::Hinge) {
                    s->addJoint(new btHingeConstraint(a, b, fa, fb), true)->setLimit(j.limit[0], j.limit[1]);
                } else {
                    s->addJoint(new btConeTwistConstraint(a, b, fa, fb), true)->setLimit(j.limit[0], j.limit[1], j.limit[2]);
                }
            }
        }
        pos.setY(pos.y() + 7.0f);
        pos.setZ(pos.z() - 2.0f);
    }
    return s;
}

ScenePtr compoundPile(WorldKind kind, const Config& config, int count)
{
    auto s = std::make_unique<Scene>(kind, config, "compound");
    s->addBody(s->boxShape(btVector3(50, 50, 50)), 0, btVector3(0, -50, 0));
    auto child = [](btCompoundShape* c, btCollisionShape* shape, const btVector3& at) {
        c->addChildShape(btTransform(btQuaternion::getIdentity(), at), shape);
    };
    auto* table = s->ownShape(new btCompoundShape());
    child(table, s->boxShape(btVector3(0.6f, 0.05f, 0.4f)), btVector3(0, 0.3f, 0));
    for (float x : {-0.5f, 0.5f})
        for (float z : {-0.3f, 0.3f}) child(table, s->boxShape(btVector3(0.05f, 0.25f, 0.05f)), btVector3(x, 0, z));
    auto* ell = s->ownShape(new btCompoundShape());
    child(ell, s->boxShape(btVector3(0.5f, 0.1f, 0.1f)), btVector3(0.2f, 0, 0));
    child(ell, s->boxShape(btVector3(0.1f, 0.4f, 0.1f)), btVector3(-0.2f, 0.3f, 0));
    auto* dumbbell = s->ownShape(new btCompoundShape());
    child(dumbbell, s->sphereShape(0.25f), btVector3(-0.5f, 0, 0));
    child(dumbbell, s->sphereShape(0.25f), btVector3(0.5f, 0, 0));
    child(dumbbell, s->boxShape(btVector3(0.5f, 0.06f, 0.06f)), btVector3(0, 0, 0));
    btCompoundShape* kinds[3] = {table, ell, dumbbell};
    for (int i = 0; i < count; ++i) {
        const float a = 0.7f * float(i);
        btTransform t(btQuaternion(btVector3(0, 1, 0), a), btVector3(0.8f * std::cos(a), 1.0f + 0.7f * float(i), 0.8f * std::sin(a)));
        s->addBody(kinds[i % 3], 1, t);
    }
    return s;
}

ScenePtr raycastVehicle(WorldKind kind, const Config& config, btRaycastVehicle** vehicleOut)
{
    auto s = std::make_unique<Scene>(kind, config, "vehicle");
    // A 129 x 129 heightfield 1 m apart; Bullet centres it on its bounds, so the body sits at
    // the middle height.
    const int n = 129;
    auto* heights = s->ownData(new std::vector<float>(size_t(n) * n));
    float lo = 1e30f, hi = -1e30f;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x = float(i) - 0.5f * float(n - 1), z = float(j) - 0.5f * float(n - 1);
            const float h = 0.6f * landscapeHeight(x, z);
            (*heights)[size_t(j) * n + size_t(i)] = h;
            lo = std::min(lo, h), hi = std::max(hi, h);
        }
    auto* terrain = s->ownShape(new btHeightfieldTerrainShape(n, n, heights->data(), 1, lo, hi, 1, PHY_FLOAT, false));
    s->addBody(terrain, 0, btVector3(0, 0.5f * (lo + hi), 0), Material{btScalar(0.8), 0});

    const float startY = 0.6f * landscapeHeight(0, 0) + 1.5f;
    btRigidBody* chassis = s->addBody(s->boxShape(btVector3(1, 0.5f, 2)), 800, btVector3(0, startY, 0));
    chassis->setActivationState(DISABLE_DEACTIVATION);
    auto* raycaster = s->ownData(new btDefaultVehicleRaycaster(&s->world()));
    btRaycastVehicle::btVehicleTuning tuning;
    auto* vehicle = s->ownData(new btRaycastVehicle(tuning, chassis, raycaster));
    vehicle->setCoordinateSystem(0, 1, 2);
    s->world().addAction(vehicle);
    const btScalar radius = 0.5f, rest = 0.6f;
    const btVector3 down(0, -1, 0), axle(-1, 0, 0);
    for (int w = 0; w < 4; ++w) {
        const bool front = w < 2;
        const btVector3 at(w % 2 ? -0.85f : 0.85f, 0, front ? 1.6f : -1.6f);
        btWheelInfo& info = vehicle->addWheel(at, down, axle, rest, radius, tuning, front);
        info.m_suspensionStiffness = 20;
        info.m_wheelsDampingRelaxation = 2.3f;
        info.m_wheelsDampingCompression = 4.4f;
        info.m_frictionSlip = 1000;
        info.m_rollInfluence = 0.1f;
    }
    // A few boxes in the car's way.
    btBoxShape* crate = s->boxShape(btVector3(0.4f, 0.4f, 0.4f));
    for (int i = 0; i < 8; ++i) {
        const float x = -2.0f + float(i % 4) * 1.2f, z = 9.0f + float(i / 4) * 1.2f;
        s->addBody(crate, 20, btVector3(x, 0.6f * landscapeHeight(x, z) + 1.0f, z));
    }
    s->beforeStep = [vehicle](Scene&, double endTime) {
        vehicle->applyEngineForce(1500, 2);
        vehicle->applyEngineForce(1500, 3);
        const btScalar steer = btScalar(0.25 * std::sin(0.5 * endTime));
        vehicle->setSteeringValue(steer, 0);
        vehicle->setSteeringValue(steer, 1);
    };
    if (vehicleOut) *vehicleOut = vehicle;
    return s;
}

void RayFan::move(double dt)
{
    const btScalar dx = btScalar(10 * dt * sweep);
    for (size_t i = 0; i < from.size(); ++i) from[i].setX(from[i].x() + dx), to[i].setX(to[i].x() + dx);
    if (!from.empty() && from[0].x() < -20) sweep = 1;
    if (!from.empty() && from[0].x() > 20) sweep = -1;
}

RayFan benchmarkRays(int count, double length)
{
    RayFan fan;
    for (int i = 0; i < count; ++i) {
        const btScalar a = btScalar(2 * SIMD_PI * i / count);
        const btVector3 from(0, 50, 0);
        btVector3 to = from + quatRotate(btQuaternion(btVector3(0, 1, 0), a), btVector3(btScalar(length), 0, 0));
        to.setY(-50);
        fan.from.push_back(from);
        fan.to.push_back(to);
    }
    return fan;
}

std::vector<double> castRays(const btCollisionWorld& world, const RayFan& rays)
{
    std::vector<double> fractions(rays.from.size(), 1.0);
    for (size_t i = 0; i < rays.from.size(); ++i) {
        btCollisionWorld::ClosestRayResultCallback cb(rays.from[i], rays.to[i]);
        world.rayTest(rays.from[i], rays.to[i], cb);
        if (cb.hasHit()) fractions[i] = cb.m_closestHitFraction;
    }
    return fractions;
}

}  // namespace btgpu::scenes
