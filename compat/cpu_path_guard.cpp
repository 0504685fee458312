// cpu_path_guard.cpp — holding bad bodies out of a CPU-path step: what hold() changes on each
// (activation DISABLE_SIMULATION, filter group and mask 0 with its pairs removed, a non-finite
// transform of a static body swapped for a finite one so the broadphase tree stays sane) and
// release() restores.
#include "cpu_path_guard.h"

#include <btBulletDynamicsCommon.h>

#include "body_rows.h"
#include "shape_checks.h"

#include <cmath>

namespace btgpu {

std::string CpuPathGuard::badKinematicMotionState(const btCollisionObject* o)
{
    // Bullet reads a kinematic body's motion state inside the step (saveKinematicState): a
    // non-finite transform there would only show after it, so it is looked at here, as the GPU
    // path sees it before its substeps.
    const btRigidBody* rb = btRigidBody::upcast(o);
    if (!rb || !o->isKinematicObject() || !rb->getMotionState()) return "";
    btTransform t;
    rb->getMotionState()->getWorldTransform(t);
    const btMatrix3x3& b = t.getBasis();
    const bool finite = std::isfinite(t.getOrigin().length2()) && std::isfinite(b[0].length2()) &&
                        std::isfinite(b[1].length2()) && std::isfinite(b[2].length2());
    return finite ? "" : "non-finite transform from its motion state (kinematic body)";
}

std::string CpuPathGuard::badShape(const btCollisionShape* shape, int depth)
{
    auto it = m_shapeVerdicts.find(shape);
    if (it != m_shapeVerdicts.end()) return it->second;
    std::string why = badShapeInput(shape);
    if (why.empty() && shape->isCompound() && depth < 8) {
        auto* compound = static_cast<const btCompoundShape*>(shape);
        for (int i = 0; i < compound->getNumChildShapes() && why.empty(); ++i)
            why = badShape(compound->getChildShape(i), depth + 1);
    }
    m_shapeVerdicts.emplace(shape, why);
    return why;
}

void CpuPathGuard::hold(btDiscreteDynamicsWorld& world, const std::function<void(Issue)>& report)
{
    m_shapeVerdicts.clear();
    const btCollisionObjectArray& objs = world.getCollisionObjectArray();
    std::unordered_set<const btCollisionObject*> badNow;
    for (int i = 0; i < objs.size(); ++i) {
        btCollisionObject* o = objs[i];
        std::string why = badInput(o);
        if (why.empty()) {
            std::string shape = badShape(o->getCollisionShape(), 0);
            if (!shape.empty()) why = "shape: " + shape;
        }
        if (why.empty()) why = badKinematicMotionState(o);
        if (why.empty()) {
            // Good again after being held: a new proxy finds its pairs again (the broadphase
            // would not look for them while the body stands still).
            if (m_bad.count(o) && o->getBroadphaseHandle()) world.refreshBroadphaseProxy(o);
            continue;
        }
        badNow.insert(o);
        if (!m_bad.count(o))
            report({Issue::Kind::BadBody,
                    "body " + std::to_string(i) + " (user index " + std::to_string(o->getUserIndex()) + ", shape " +
                        o->getCollisionShape()->getName() + "): " + why +
                        "; kept out of the simulation until fixed (CPU path)",
                    i, o->getUserIndex(), o->getCollisionShape()->getShapeType()});
        Held h{o, o->getActivationState(), 0, 0, false, btTransform::getIdentity()};
        if (btBroadphaseProxy* proxy = o->getBroadphaseHandle()) {
            h.group = proxy->m_collisionFilterGroup;
            h.mask = proxy->m_collisionFilterMask;
            proxy->m_collisionFilterGroup = 0;
            proxy->m_collisionFilterMask = 0;
            world.getPairCache()->removeOverlappingPairsContainingProxy(proxy, world.getDispatcher());
        }
        o->forceActivationState(DISABLE_SIMULATION);
        const btTransform& t = o->getWorldTransform();
        btVector3 r0 = t.getBasis()[0], r1 = t.getBasis()[1], r2 = t.getBasis()[2];
        bool finiteTransform = std::isfinite(t.getOrigin().length2()) && std::isfinite(r0.length2()) &&
                               std::isfinite(r1.length2()) && std::isfinite(r2.length2());
        if (!finiteTransform && o->isStaticObject()) {
            // Bullet sets a static body's AABB every step, disabled or not: a NaN one would
            // poison the broadphase tree for everyone.
            h.appTransform = t;
            o->setWorldTransform(btTransform::getIdentity());
            h.transformSwapped = true;
        }
        m_held.push_back(h);
    }
    m_bad = std::move(badNow);
}

void CpuPathGuard::release()
{
    for (const Held& h : m_held) {
        h.body->forceActivationState(h.activationState);
        if (btBroadphaseProxy* proxy = h.body->getBroadphaseHandle()) {
            proxy->m_collisionFilterGroup = h.group;
            proxy->m_collisionFilterMask = h.mask;
        }
        if (h.transformSwapped) h.body->setWorldTransform(h.appTransform);
    }
    m_held.clear();
}

}  // namespace btgpu
