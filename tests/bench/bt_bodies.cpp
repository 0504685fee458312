// bt_bodies.cpp — Bullet bodies for a bench Scene (see bt_bodies.h).
#include "bt_bodies.h"

#include <map>
#include <tuple>

namespace btgpu::bench {

BtBodies::~BtBodies()
{
    if (!m_world) return;
    for (auto it = m_joints.rbegin(); it != m_joints.rend(); ++it) m_world->removeConstraint(it->get());
    for (auto it = m_bodies.rbegin(); it != m_bodies.rend(); ++it) m_world->removeRigidBody(it->get());
}

void BtBodies::leaveWithWorld()
{
    if (!m_world) return;
    for (auto it = m_joints.rbegin(); it != m_joints.rend(); ++it) m_world->removeConstraint(it->get());
    // Stock's removeRigidBody finds the body by a linear search of the world's arrays (and
    // the world's destructor cleans each proxy's pairs by walking every pair): at 1,000,000
    // bodies the teardown took minutes. The bench is the app here: its bodies leave with the
    // world, their proxies freed with the broadphase after it.
    for (auto& b : m_bodies) b->setBroadphaseHandle(nullptr);
    m_world = nullptr;
}

void BtBodies::build(const Scene& scene, const Options& options, btDiscreteDynamicsWorld* world)
{
    if (options.absoluteThresholds)
        if (auto* d = dynamic_cast<btCollisionDispatcher*>(world->getDispatcher()))
            d->setDispatcherFlags(d->getDispatcherFlags() & ~btCollisionDispatcher::CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD);
    m_world = world;
    world->setGravity(btVector3(scene.gravity[0], scene.gravity[1], scene.gravity[2]));
    world->getSolverInfo().m_numIterations = scene.iterations;
    // One shape per distinct size, as an app would share them (and as btgpu's shape tables
    // and Bullet3's collidables expect).
    std::map<std::tuple<int, float, float, float>, btCollisionShape*> shared;
    m_bodies.reserve(scene.bodies.size());
    for (const BodySpec& b : scene.bodies) {
        auto key = b.shape == ShapeKind::Box      ? std::make_tuple(0, b.half[0], b.half[1], b.half[2])
                   : b.shape == ShapeKind::Sphere ? std::make_tuple(1, b.radius, 0.f, 0.f)
                   : b.shape == ShapeKind::Hull   ? std::make_tuple(2, float(b.hull), 0.f, 0.f)
                   : b.shape == ShapeKind::Mesh   ? std::make_tuple(4, 0.f, 0.f, 0.f)
                   : b.shape == ShapeKind::Capsule ? std::make_tuple(6, b.radius, b.half[1], 0.f)
                   : b.shape == ShapeKind::Compound ? std::make_tuple(5, float(b.compound), 0.f, 0.f)
                                                  : std::make_tuple(3, 0.f, 0.f, 0.f);
        btCollisionShape*& shape = shared[key];
        if (!shape) {
            if (b.shape == ShapeKind::Mesh) {
                // The scene's own arrays, read in place (BenchmarkDemo's way), 32-bit indices.
                m_mesh = std::make_unique<btTriangleIndexVertexArray>(
                    int(scene.meshIndices.size() / 3), const_cast<int*>(scene.meshIndices.data()), 3 * int(sizeof(int)),
                    int(scene.meshVertices.size() / 3), const_cast<float*>(scene.meshVertices.data()),
                    3 * int(sizeof(float)));
                m_shapes.emplace_back(new btBvhTriangleMeshShape(m_mesh.get(), true));
            } else if (b.shape == ShapeKind::Compound) {
                auto* compound = new btCompoundShape();
                for (const scenes::spec::ChildSpec& c : scene.compounds.at(size_t(b.compound)).children) {
                    if (c.shape == ShapeKind::Sphere) m_shapes.emplace_back(new btSphereShape(c.radius));
                    else m_shapes.emplace_back(new btBoxShape(btVector3(c.half[0], c.half[1], c.half[2])));
                    compound->addChildShape(btTransform(btQuaternion(c.rot[0], c.rot[1], c.rot[2], c.rot[3]),
                                                        btVector3(c.pos[0], c.pos[1], c.pos[2])),
                                            m_shapes.back().get());
                }
                m_shapes.emplace_back(compound);
            } else if (b.shape == ShapeKind::Box) {
                m_shapes.emplace_back(new btBoxShape(btVector3(b.half[0], b.half[1], b.half[2])));
            } else if (b.shape == ShapeKind::Sphere) {
                m_shapes.emplace_back(new btSphereShape(b.radius));
            } else if (b.shape == ShapeKind::Capsule) {
                m_shapes.emplace_back(new btCapsuleShape(b.radius, 2 * b.half[1]));
            } else if (b.shape == ShapeKind::Hull) {
                const HullSpec& h = scene.hulls.at(size_t(b.hull));
                auto* hull = new btConvexHullShape(h.points.data(), int(h.points.size() / 3), 3 * sizeof(float));
                if (h.polyhedral) hull->initializePolyhedralFeatures();
                hull->setMargin(h.margin);
                m_shapes.emplace_back(hull);
            } else {
                m_shapes.emplace_back(new btStaticPlaneShape(btVector3(0, 1, 0), 0));
            }
            shape = m_shapes.back().get();
        }
        btVector3 inertia(0, 0, 0);
        if (b.mass > 0) shape->calculateLocalInertia(b.mass, inertia);
        btTransform xf(btQuaternion(b.rot[0], b.rot[1], b.rot[2], b.rot[3]), btVector3(b.pos[0], b.pos[1], b.pos[2]));
        btMotionState* ms = nullptr;
        if (b.mass > 0) {
            m_motionStates.emplace_back(new btDefaultMotionState(xf));
            ms = m_motionStates.back().get();
        }
        btRigidBody::btRigidBodyConstructionInfo ci(b.mass, ms, shape, inertia);
        ci.m_startWorldTransform = xf;
        ci.m_friction = b.friction;
        ci.m_restitution = b.restitution;
        ci.m_linearDamping = b.linearDamping;
        ci.m_angularDamping = b.angularDamping;
        m_bodies.emplace_back(new btRigidBody(ci));
        if (options.noSleep && b.mass > 0) m_bodies.back()->setActivationState(DISABLE_DEACTIVATION);
        world->addRigidBody(m_bodies.back().get());
    }
    auto frame = [](const float* f) {
        return btTransform(btQuaternion(f[3], f[4], f[5], f[6]), btVector3(f[0], f[1], f[2]));
    };
    for (const scenes::spec::JointSpec& j : scene.joints) {
        btRigidBody& a = *m_bodies[size_t(j.a)];
        btRigidBody& b = *m_bodies[size_t(j.b)];
        if (j.kind == scenes::spec::JointSpec::Kind::Hinge) {
            auto* h = new btHingeConstraint(a, b, frame(j.frameA), frame(j.frameB));
            h->setLimit(j.limit[0], j.limit[1]);
            m_joints.emplace_back(h);
        } else {
            auto* c = new btConeTwistConstraint(a, b, frame(j.frameA), frame(j.frameB));
            c->setLimit(j.limit[0], j.limit[1], j.limit[2]);
            m_joints.emplace_back(c);
        }
        world->addConstraint(m_joints.back().get(), true);
    }
}

void BtBodies::poses(std::vector<Pose>& out) const
{
    out.resize(m_bodies.size());
    for (size_t i = 0; i < m_bodies.size(); ++i) {
        // The body's own transform: what the simulation computed, not the interpolated
        // motion state.
        const btTransform& t = m_bodies[i]->getWorldTransform();
        btQuaternion q = t.getRotation();
        out[i] = {{t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z()}, {q.x(), q.y(), q.z(), q.w()}};
    }
}

void BtBodies::contacts(btDiscreteDynamicsWorld* world, FrameInfo& out, bool points)
{
    out.pairs = world->getBroadphase()->getOverlappingPairCache()->getNumOverlappingPairs();
    if (!points) return;
    btDispatcher* d = world->getDispatcher();
    long manifolds = 0, pts = 0;
    for (int i = 0; i < d->getNumManifolds(); ++i) {
        int n = d->getManifoldByIndexInternal(i)->getNumContacts();
        manifolds += n > 0;
        pts += n;
    }
    out.manifolds = manifolds;
    out.points = pts;
}

}  // namespace btgpu::bench
