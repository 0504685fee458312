// fuzz_world.cpp — builds a recipe's Bullet objects, applies its ops between steps and watches
// the bodies. Bad input is judged from what the body actually holds after the app's call (Bullet
// clamps damping, so setDamping(Inf) is not bad), which is what a world can check too.
#include "fuzz_world.h"

#include "btgpu/btGpuDynamicsWorld.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <type_traits>

namespace btgpu::fuzz {

namespace {

// Issue::Kind::BadArgument is being added; until then any issue other than BadBody that comes
// with a bad call counts as naming it.
template <class K, class = void>
struct HasBadArgument : std::false_type {};
template <class K>
struct HasBadArgument<K, std::void_t<decltype(K::BadArgument)>> : std::true_type {};
template <class K>
bool namesArgument(K kind)
{
    if constexpr (HasBadArgument<K>::value) return kind == K::BadArgument;
    else return kind != K::BadBody;
}

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
bool finite(const btTransform& t)
{
    const btMatrix3x3& b = t.getBasis();
    return finite(t.getOrigin()) && finite(b[0]) && finite(b[1]) && finite(b[2]);
}
// Bitwise, x y z only (a NaN left as it was is unchanged; the fourth lane is padding).
bool same(const btVector3& a, const btVector3& b) { return std::memcmp(&a, &b, 3 * sizeof(float)) == 0; }
bool same(const btTransform& a, const btTransform& b)
{
    return same(a.getOrigin(), b.getOrigin()) && same(a.getBasis()[0], b.getBasis()[0]) &&
           same(a.getBasis()[1], b.getBasis()[1]) && same(a.getBasis()[2], b.getBasis()[2]);
}

std::string shapeBad(const btCollisionShape* shape)
{
    switch (shape->getShapeType()) {
        case BOX_SHAPE_PROXYTYPE:
            if (!finite(static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin())) return "box half extents";
            break;
        case SPHERE_SHAPE_PROXYTYPE:
            if (!std::isfinite(static_cast<const btSphereShape*>(shape)->getRadius())) return "sphere radius";
            break;
        case CONVEX_HULL_SHAPE_PROXYTYPE: {
            auto* hull = static_cast<const btConvexHullShape*>(shape);
            if (hull->getNumPoints() == 0) return "hull without points";
            for (int i = 0; i < hull->getNumPoints(); ++i)
                if (!finite(hull->getUnscaledPoints()[i])) return "hull point";
            break;
        }
        case COMPOUND_SHAPE_PROXYTYPE: {
            auto* compound = static_cast<const btCompoundShape*>(shape);
            for (int i = 0; i < compound->getNumChildShapes(); ++i) {
                std::string why = shapeBad(compound->getChildShape(i));
                if (!why.empty()) return "compound child " + why;
            }
            break;
        }
        default: break;
    }
    if (!finite(shape->getLocalScaling())) return "shape scaling";
    if (!std::isfinite(shape->getMargin())) return "shape margin";
    if (shape->getShapeType() != STATIC_PLANE_PROXYTYPE) {
        btVector3 mn, mx;
        shape->getAabb(btTransform::getIdentity(), mn, mx);
        if (!finite(mn) || !finite(mx)) return "shape bounds";
    }
    return "";
}

// What a world can see of a body's input: "" when it is all finite and meaningful.
std::string badReason(const btRigidBody* b)
{
    if (!finite(b->getWorldTransform())) return "transform";
    std::string shape = shapeBad(b->getCollisionShape());
    if (!shape.empty()) return shape;
    if (!std::isfinite(b->getFriction()) || !std::isfinite(b->getRestitution())) return "friction or restitution";
    if (b->isKinematicObject()) {
        btTransform t;
        if (b->getMotionState()) b->getMotionState()->getWorldTransform(t);
        if (b->getMotionState() && !finite(t)) return "kinematic motion state";
        return "";
    }
    if (b->isStaticObject()) return "";
    if (!finite(b->getLinearVelocity()) || !finite(b->getAngularVelocity())) return "velocity";
    if (!finite(b->getTotalForce()) || !finite(b->getTotalTorque())) return "force or torque";
    if (!finite(b->getGravity())) return "gravity";
    if (!std::isfinite(b->getLinearDamping()) || !std::isfinite(b->getAngularDamping())) return "damping";
    if (!finite(b->getLinearFactor()) || !finite(b->getAngularFactor())) return "linear or angular factor";
    if (std::isnan(b->getLinearSleepingThreshold()) || std::isnan(b->getAngularSleepingThreshold()))
        return "sleeping thresholds";
    if (!std::isfinite(b->getInvMass()) || b->getInvMass() <= 0.0f) return "mass";
    btVector3 ii = b->getInvInertiaDiagLocal();
    if (!finite(ii) || ii.x() < 0 || ii.y() < 0 || ii.z() < 0) return "inertia";
    return "";
}

bool stateFinite(const btRigidBody* b)
{
    return finite(b->getWorldTransform()) && finite(b->getLinearVelocity()) && finite(b->getAngularVelocity());
}

class FuzzWorld {
public:
    FuzzWorld(const Recipe& r, Engine engine, const RunOptions& options) : m_r(r), m_engine(engine), m_options(options)
    {
        m_trace.bodies.resize(r.bodies.size());
        m_config = std::make_unique<btDefaultCollisionConfiguration>();
        m_dispatcher = std::make_unique<btCollisionDispatcher>(m_config.get());
        m_broadphase = std::make_unique<btDbvtBroadphase>();
        m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
        if (engine == Engine::Gpu) {
            btgpu::Config config = btgpu::Config::bulletMode();
            config.internalSubsteps = r.internalSubsteps;
            config.solver = r.jacobi ? btgpu::SolverKind::JacobiMassSplitting
                            : r.soft ? btgpu::SolverKind::Auto
                                     : btgpu::SolverKind::BatchedPgs;
            config.profile = r.profiling;
            config.syncBroadphaseAabbs = r.syncAabbs;
            m_gpu = new btGpuDynamicsWorld(m_dispatcher.get(), m_broadphase.get(), m_solver.get(), m_config.get(), config);
            m_world.reset(m_gpu);
        } else {
            m_world = std::make_unique<btDiscreteDynamicsWorld>(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
                                                                m_config.get());
        }
        m_world->setGravity(btVector3(0, -10, 0));
        m_shapes.resize(r.shapes.size());
        m_bodies.resize(r.bodies.size());
        m_inWorld.assign(r.bodies.size(), false);
        m_inputBad.assign(r.bodies.size(), false);
        if (r.groundPlane) {
            m_planeShape = std::make_unique<btStaticPlaneShape>(r.planeNormal, 0.0f);
            m_plane = std::make_unique<btRigidBody>(0.0f, nullptr, m_planeShape.get());
            guarded("add plane", [&] { m_world->addRigidBody(m_plane.get()); });
        }
        for (size_t i = 0; i < r.bodies.size(); ++i) {
            const BodySpec& spec = r.bodies[i];
            if (engine == Engine::Stock && !spec.stockSafe && !options.stockEverything) continue;
            m_bodies[i] = makeBody(spec);
            m_trace.bodies[i].built = true;
            judgeInput(int(i), "");
            if (spec.atStart) add(int(i));
        }
    }

    ~FuzzWorld()
    {
        for (size_t i = 0; i < m_bodies.size(); ++i)
            if (m_inWorld[i]) m_world->removeRigidBody(m_bodies[i].get());
        if (m_plane) m_world->removeRigidBody(m_plane.get());
        if (m_lateProbe) m_world->removeRigidBody(m_lateProbe.get());
        m_world.reset();
    }

    Trace run()
    {
        float localTime = 0.0f;
        for (size_t k = 0; k < m_r.ops.size(); ++k) {
            const Op& op = m_r.ops[k];
            if (op.kind == OpKind::Step) {
                step(op, int(k), &localTime);
                continue;
            }
            if (m_engine == Engine::Stock && !op.stockSafe && !m_options.stockEverything) continue;
            if (op.body >= 0 && !m_bodies[size_t(op.body)]) continue;
            std::vector<int> touched = affected(op);
            std::vector<std::string> before;
            for (int i : touched) before.push_back(badReason(m_bodies[size_t(i)].get()));
            guarded(toString(op.kind), [&] { apply(op); });
            for (size_t j = 0; j < touched.size(); ++j) judgeInput(touched[j], before[j]);
        }
        closingCheck(&localTime);
        m_trace.issues = m_gpu ? int(m_gpu->report().issues.size()) : 0;
        return m_trace;
    }

private:
    template <class F>
    void guarded(const std::string& what, F&& f)
    {
        try {
            f();
        } catch (const std::exception& e) {
            m_trace.exceptions.push_back(what + ": " + e.what());
        } catch (...) {
            m_trace.exceptions.push_back(what + ": unknown exception");
        }
    }

    // The bodies an op can give bad input: its target, every user of a shape it changes, and
    // for world gravity every body (Bullet sets it on each active one).
    std::vector<int> affected(const Op& op)
    {
        std::vector<int> out;
        for (size_t i = 0; i < m_bodies.size(); ++i) {
            if (!m_bodies[i]) continue;
            bool hit = op.kind == OpKind::WorldGravity || int(i) == op.body;
            if ((op.kind == OpKind::Scaling || op.kind == OpKind::Margin) && m_r.bodies[i].shape == m_r.bodies[size_t(op.body)].shape)
                hit = true;
            if (hit) out.push_back(int(i));
        }
        return out;
    }

    // Bad input is what an app call leaves in a body that was fine before it; a body that went
    // non-finite in a step is the world's doing, not the app's, and is judged as such.
    void judgeInput(int i, const std::string& before)
    {
        std::string after = badReason(m_bodies[size_t(i)].get());
        if (after.empty()) {
            m_inputBad[size_t(i)] = false;
            return;
        }
        if (!before.empty()) return;
        m_inputBad[size_t(i)] = true;
        BodyTrace& t = m_trace.bodies[size_t(i)];
        if (t.badWhy.empty()) t.badWhy = after, t.badAtCall = int(m_trace.calls.size());
    }

    btCollisionShape* shape(int index)
    {
        std::unique_ptr<btCollisionShape>& s = m_shapes[size_t(index)];
        if (s) return s.get();
        const ShapeSpec& spec = m_r.shapes[size_t(index)];
        const btVector3& z = spec.size;
        switch (spec.kind) {
            case ShapeKind::Box: s = std::make_unique<btBoxShape>(z); break;
            case ShapeKind::Sphere: s = std::make_unique<btSphereShape>(z.x()); break;
            case ShapeKind::Hull:
                s = std::make_unique<btConvexHullShape>(spec.points.empty() ? nullptr : &spec.points[0].x(),
                                                        int(spec.points.size()), int(sizeof(btVector3)));
                break;
            case ShapeKind::Plane: s = std::make_unique<btStaticPlaneShape>(spec.normal, spec.constant); break;
            case ShapeKind::Capsule: s = std::make_unique<btCapsuleShape>(z.x(), z.y()); break;
            case ShapeKind::Cylinder: s = std::make_unique<btCylinderShape>(z); break;
            case ShapeKind::Cone: s = std::make_unique<btConeShape>(z.x(), z.y()); break;
            case ShapeKind::Compound: {
                m_children.push_back(std::make_unique<btBoxShape>(z * 0.5f));
                auto compound = std::make_unique<btCompoundShape>();
                btTransform t = btTransform::getIdentity();
                t.setOrigin(btVector3(z.x(), 0, 0));
                compound->addChildShape(t, m_children.back().get());
                t.setOrigin(btVector3(-z.x(), 0, 0));
                compound->addChildShape(t, m_children.back().get());
                s = std::move(compound);
                break;
            }
        }
        return s.get();
    }

    std::unique_ptr<btRigidBody> makeBody(const BodySpec& spec)
    {
        btCollisionShape* sh = shape(spec.shape);
        float mass = spec.motion == Motion::Dynamic ? spec.mass : 0.0f;
        btVector3 inertia(0, 0, 0);
        if (mass != 0.0f) sh->calculateLocalInertia(mass, inertia);
        m_motionStates.push_back(std::make_unique<btDefaultMotionState>(spec.start));
        btRigidBody::btRigidBodyConstructionInfo info(mass, m_motionStates.back().get(), sh, inertia);
        info.m_friction = spec.friction;
        info.m_restitution = spec.restitution;
        auto body = std::make_unique<btRigidBody>(info);
        if (spec.motion == Motion::Kinematic) {
            body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
            body->setActivationState(DISABLE_DEACTIVATION);
        }
        if (spec.motion == Motion::Dynamic) {
            body->setLinearVelocity(spec.linVel);
            body->setAngularVelocity(spec.angVel);
        }
        if (spec.ownGravity) {
            body->setFlags(body->getFlags() | BT_DISABLE_WORLD_GRAVITY);
            body->setGravity(btVector3(0, -10, 0));
            body->setActivationState(DISABLE_DEACTIVATION);
        }
        m_ids[body.get()] = int(&spec - &m_r.bodies[0]);
        return body;
    }

    void add(int i)
    {
        if (m_inWorld[size_t(i)]) return;
        guarded("addRigidBody", [&] { m_world->addRigidBody(m_bodies[size_t(i)].get()); });
        m_inWorld[size_t(i)] = true;
    }

    void apply(const Op& op)
    {
        btRigidBody* b = op.body >= 0 ? m_bodies[size_t(op.body)].get() : nullptr;
        switch (op.kind) {
            case OpKind::Step: break;
            case OpKind::LinVel: b->setLinearVelocity(op.v); break;
            case OpKind::AngVel: b->setAngularVelocity(op.v); break;
            case OpKind::Teleport: {
                btTransform t = btTransform::getIdentity();
                if (op.a != 1.0f) t.getBasis().setValue(op.a, 0, 0, 0, 1, 0, 0, 0, 1);
                t.setOrigin(op.v);
                b->setWorldTransform(t);
                if (b->getMotionState()) b->getMotionState()->setWorldTransform(t);
                break;
            }
            case OpKind::Force: b->applyCentralForce(op.v); break;
            case OpKind::Torque: b->applyTorque(op.v); break;
            case OpKind::BodyGravity: b->setGravity(op.v); break;
            case OpKind::Damping: b->setDamping(op.a, op.b); break;
            case OpKind::Friction: b->setFriction(op.a); break;
            case OpKind::Restitution: b->setRestitution(op.a); break;
            case OpKind::LinFactor: b->setLinearFactor(op.v); break;
            case OpKind::AngFactor: b->setAngularFactor(op.v); break;
            case OpKind::Sleeping: b->setSleepingThresholds(op.a, op.b); break;
            case OpKind::MassProps: {
                // Only on dynamic bodies: a static body given mass in place is an app bug Bullet
                // itself does not survive in every case (it stays in the static lists).
                if (b->isStaticOrKinematicObject()) break;
                btVector3 inertia = op.v;
                if (op.n) b->getCollisionShape()->calculateLocalInertia(op.a, inertia);
                b->setMassProps(op.a, inertia);
                b->updateInertiaTensor();
                break;
            }
            case OpKind::Scaling: b->getCollisionShape()->setLocalScaling(op.v); break;
            case OpKind::Margin: b->getCollisionShape()->setMargin(op.a); break;
            case OpKind::MoveKinematic: {
                if (!b->isKinematicObject() || !b->getMotionState()) break;
                btTransform t = b->getWorldTransform();
                t.setOrigin(op.v);
                b->getMotionState()->setWorldTransform(t);
                break;
            }
            case OpKind::WorldGravity: m_world->setGravity(op.v); break;
            case OpKind::Remove:
                if (!m_inWorld[size_t(op.body)]) break;
                m_world->removeRigidBody(b);
                m_inWorld[size_t(op.body)] = false;
                break;
            case OpKind::Add: add(op.body); break;
        }
    }

    struct Saved {
        btTransform xf, graphics;
        btVector3 lin, ang;
    };

    std::vector<Saved> save()
    {
        std::vector<Saved> out(m_bodies.size());
        for (size_t i = 0; i < m_bodies.size(); ++i) {
            if (!m_bodies[i]) continue;
            btRigidBody* b = m_bodies[i].get();
            out[i].xf = b->getWorldTransform();
            if (b->getMotionState()) b->getMotionState()->getWorldTransform(out[i].graphics);
            out[i].lin = b->getLinearVelocity();
            out[i].ang = b->getAngularVelocity();
        }
        return out;
    }

    bool changedSince(const std::vector<Saved>& before)
    {
        std::vector<Saved> now = save();
        for (size_t i = 0; i < now.size(); ++i) {
            if (!m_bodies[i]) continue;
            if (!same(now[i].xf, before[i].xf) || !same(now[i].graphics, before[i].graphics) ||
                !same(now[i].lin, before[i].lin) || !same(now[i].ang, before[i].ang))
                return true;
        }
        return false;
    }

    // One stepSimulation call, with what a verdict needs before and after it.
    void step(const Op& op, int opIndex, float* localTime)
    {
        CallTrace call;
        call.op = opIndex;
        call.dt = op.a, call.maxSubSteps = op.n, call.fixedStep = op.b;
        call.cls = classify(op.a, op.n, op.b, *localTime);
        const int callIndex = int(m_trace.calls.size());
        if (m_engine == Engine::Stock && call.cls == ArgClass::Bad && !m_options.stockEverything) {
            m_trace.calls.push_back(call);
            return;
        }
        std::vector<int> badNow;
        // Still bad now: the world's own setGravity (the closing check) fixes per-body gravity.
        for (size_t i = 0; i < m_bodies.size(); ++i)
            if (m_bodies[i] && m_inWorld[i] && m_inputBad[i] && !badReason(m_bodies[i].get()).empty())
                badNow.push_back(int(i));
        std::vector<Saved> before;
        if (call.cls != ArgClass::Normal) before = save();
        const size_t issuesBefore = m_gpu ? m_gpu->report().issues.size() : 0;
        call.ran = true;
        guarded("stepSimulation", [&] { call.returned = m_world->stepSimulation(op.a, op.n, op.b); });
        if (call.cls != ArgClass::Bad) {
            int simulated = 0;
            bulletSubsteps(op.a, op.n, op.b, localTime, &simulated);
        }
        if (call.cls != ArgClass::Normal) call.changedBodies = changedSince(before);
        if (m_gpu) {
            call.gpuPath = m_gpu->isGpuPath() ? "gpu" : "cpu";
            if (!m_gpu->isGpuPath()) m_trace.cpuReason = m_gpu->report().cpuPathReason;
            collectIssues(issuesBefore, &call);
        }
        // A call that simulated must have seen every bad body in the world.
        int clamped = op.n == 0 ? call.returned : std::min(call.returned, op.n);
        if (call.cls == ArgClass::Normal && clamped > 0)
            for (int i : badNow) {
                BodyTrace& t = m_trace.bodies[size_t(i)];
                if (!t.mustBeNamed) t.mustBeNamed = true, t.mustPath = m_gpu ? call.gpuPath : "stock";
            }
        // A call may clear bad input (stepSimulation clears forces even when it simulates
        // nothing): a body whose input is fine now need not be named for it later.
        for (size_t i = 0; i < m_bodies.size(); ++i)
            if (m_bodies[i] && m_inputBad[i] && badReason(m_bodies[i].get()).empty()) m_inputBad[i] = false;
        observe(callIndex);
        call.stateHash = hashState();
        m_trace.calls.push_back(call);
    }

    void collectIssues(size_t from, CallTrace* call)
    {
        const std::vector<Issue>& issues = m_gpu->report().issues;
        const btCollisionObjectArray& objs = m_world->getCollisionObjectArray();
        for (size_t k = from; k < issues.size(); ++k) {
            const Issue& issue = issues[k];
            if (namesArgument(issue.kind) && call->cls != ArgClass::Normal) call->reported = true;
            if (issue.kind != Issue::Kind::BadBody) continue;
            if (issue.bodyIndex < 0 || issue.bodyIndex >= objs.size()) {
                m_trace.badIndex.push_back("bodyIndex " + std::to_string(issue.bodyIndex) + " of " +
                                           std::to_string(objs.size()) + ": " + issue.message);
                continue;
            }
            auto it = m_ids.find(objs[issue.bodyIndex]);
            if (it == m_ids.end()) {
                m_trace.namedOthers.push_back(issue.message);
                continue;
            }
            BodyTrace& t = m_trace.bodies[size_t(it->second)];
            if (!t.named) t.named = true, t.namedBy = issue.message, t.namedAtCall = int(m_trace.calls.size());
        }
    }

    unsigned long long hashState() const
    {
        unsigned long long h = 1469598103934665603ull;
        auto mix = [&](const void* p, size_t n) {
            const unsigned char* c = static_cast<const unsigned char*>(p);
            for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
        };
        for (const std::unique_ptr<btRigidBody>& b : m_bodies) {
            if (!b) continue;
            const btTransform& t = b->getWorldTransform();
            mix(&t.getOrigin(), 3 * sizeof(float));
            for (int r = 0; r < 3; ++r) mix(&t.getBasis()[r], 3 * sizeof(float));
            mix(&b->getLinearVelocity(), 3 * sizeof(float));
            mix(&b->getAngularVelocity(), 3 * sizeof(float));
        }
        return h;
    }

    void observe(int callIndex)
    {
        for (size_t i = 0; i < m_bodies.size(); ++i) {
            if (!m_bodies[i]) continue;
            const btRigidBody* b = m_bodies[i].get();
            BodyTrace& t = m_trace.bodies[i];
            if (!stateFinite(b)) {
                if (t.nonFiniteAtCall < 0) t.nonFiniteAtCall = callIndex;
                continue;
            }
            float speed = b->getLinearVelocity().length();
            if (speed > t.maxSpeed) t.maxSpeed = speed, t.maxSpeedAtCall = callIndex;
        }
    }

    // The world still steps: gravity back to normal, a fresh sphere far from everything, three
    // variable steps (maxSubSteps 0: one step each, whatever the local time holds).
    void closingCheck(float* localTime)
    {
        guarded("setGravity", [&] { m_world->setGravity(btVector3(0, -10, 0)); });
        btRigidBody* probe = m_bodies[size_t(m_r.probe)].get();
        m_trace.probePos = probe->getWorldTransform().getOrigin();
        m_lateShape = std::make_unique<btSphereShape>(0.5f);
        btVector3 inertia;
        m_lateShape->calculateLocalInertia(1.0f, inertia);
        btTransform at = btTransform::getIdentity();
        at.setOrigin(btVector3(m_r.farX, 1000, 0));
        m_motionStates.push_back(std::make_unique<btDefaultMotionState>(at));
        m_lateProbe = std::make_unique<btRigidBody>(1.0f, m_motionStates.back().get(), m_lateShape.get(), inertia);
        m_lateProbe->setActivationState(DISABLE_DEACTIVATION);
        guarded("add probe", [&] { m_world->addRigidBody(m_lateProbe.get()); });
        const float v0 = probe->getLinearVelocity().y(), late0 = m_lateProbe->getLinearVelocity().y();
        Op closing;
        closing.a = 1.0f / 60.0f, closing.n = 0, closing.b = 1.0f / 60.0f;
        for (int i = 0; i < 3; ++i) step(closing, -1, localTime);
        m_trace.probeDv = probe->getLinearVelocity().y() - v0;
        m_trace.lateProbeDv = m_lateProbe->getLinearVelocity().y() - late0;
        m_trace.probeFinite = stateFinite(probe);
        m_trace.lateProbeFinite = stateFinite(m_lateProbe.get());
    }

    const Recipe& m_r;
    Engine m_engine;
    RunOptions m_options;
    Trace m_trace;
    std::unique_ptr<btDefaultCollisionConfiguration> m_config;
    std::unique_ptr<btCollisionDispatcher> m_dispatcher;
    std::unique_ptr<btBroadphaseInterface> m_broadphase;
    std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
    // Declared after what the world points at, before the bodies: destroyed first.
    std::vector<std::unique_ptr<btCollisionShape>> m_shapes, m_children;
    std::unique_ptr<btStaticPlaneShape> m_planeShape;
    std::unique_ptr<btSphereShape> m_lateShape;
    std::vector<std::unique_ptr<btDefaultMotionState>> m_motionStates;
    std::vector<std::unique_ptr<btRigidBody>> m_bodies;
    std::unique_ptr<btRigidBody> m_plane, m_lateProbe;
    std::unique_ptr<btDiscreteDynamicsWorld> m_world;
    btGpuDynamicsWorld* m_gpu = nullptr;
    std::vector<bool> m_inWorld;
    std::vector<bool> m_inputBad;  // holds bad input from the app now
    std::map<const btCollisionObject*, int> m_ids;
};

}  // namespace

Trace run(const Recipe& recipe, Engine engine, const RunOptions& options)
{
    FuzzWorld world(recipe, engine, options);
    return world.run();
}

}  // namespace btgpu::fuzz
