// seed_contacts.cpp — stock's manifolds taken from the dispatcher, and each made into the
// device's warm-start entry (keys: the points on A in A's frame, stock's accumulated normal
// impulses; friction starts cold, its directions being the device's own) and persistent
// manifold (both bodies' local points, the normal from B towards A with its distance, the slot
// as the identity).
#include "seed_contacts.h"

namespace btgpu {

namespace {
bool convexLeaf(const btCollisionObject* o)
{
    const btCollisionShape* s = o->getCollisionShape();
    return s && !s->isCompound() && !s->isConcave() && !s->isSoftBody();
}
BtgFloat4 f4(const btVector3& v, float w = 0.0f) { return btgMake4(float(v.x()), float(v.y()), float(v.z()), w); }
}  // namespace

std::vector<StockContact> takeStockContacts(btDispatcher* dispatcher)
{
    std::vector<StockContact> out;
    if (!dispatcher) return out;
    for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
        const btPersistentManifold* m = dispatcher->getManifoldByIndexInternal(i);
        if (m->getNumContacts() <= 0 || !convexLeaf(m->getBody0()) || !convexLeaf(m->getBody1())) continue;
        StockContact c;
        c.body0 = m->getBody0();
        c.body1 = m->getBody1();
        c.numPoints = std::min(m->getNumContacts(), int(BTG_MAX_POINTS));
        for (int k = 0; k < c.numPoints; ++k) c.points[k] = m->getContactPoint(k);
        out.push_back(c);
    }
    return out;
}

BtgCachedContact seededEntry(const StockContact& c, bool swap, int rowA, int rowB)
{
    BtgCachedContact e{};
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        e.point[k] = btgZero4();
        e.featureId[k] = BTG_FEATURE_UNKNOWN;
    }
    for (int k = 0; k < c.numPoints; ++k) {
        const btManifoldPoint& p = c.points[k];
        e.point[k] = f4(swap ? p.m_localPointB : p.m_localPointA, float(p.m_appliedImpulse));
        e.featureId[k] = BTG_FEATURE_SINGLE | uint(k);  // the seeded manifold's identities
    }
    e.partIdA = e.indexA = e.partIdB = e.indexB = BTG_NO_SUB_SHAPE;
    e.bodyA = rowA;
    e.bodyB = rowB;
    e.numPoints = c.numPoints;
    return e;
}

BtgPersistentManifold seededManifold(const StockContact& c, bool swap, int rowA, int rowB, int kind)
{
    BtgPersistentManifold m{};
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        m.localA[k] = btgZero4();
        m.localB[k] = btgZero4();
        m.normal[k] = btgMake4(0.0f, 1.0f, 0.0f, 0.0f);
        m.id[k] = 0u;
    }
    for (int k = 0; k < c.numPoints; ++k) {
        const btManifoldPoint& p = c.points[k];
        m.localA[k] = f4(swap ? p.m_localPointB : p.m_localPointA);
        m.localB[k] = f4(swap ? p.m_localPointA : p.m_localPointB);
        // m_normalWorldOnB points from stock's body 1 towards body 0: from the device's B to A
        // unless the two are swapped.
        m.normal[k] = f4(swap ? -p.m_normalWorldOnB : p.m_normalWorldOnB, float(p.getDistance()));
        m.id[k] = uint(k);
        // A friction anchor inside its cone is kept by the next refresh (replaceContactPoint's test).
        const btScalar lateral = p.m_appliedImpulseLateral1 * p.m_appliedImpulseLateral1 +
                                 p.m_appliedImpulseLateral2 * p.m_appliedImpulseLateral2;
        const btScalar cone = p.m_combinedFriction * p.m_appliedImpulse;
        if ((p.m_contactPointFlags & BT_CONTACT_FLAG_FRICTION_ANCHOR) && !(lateral > cone * cone))
            m.anchorMask |= 1u << uint(k);
    }
    m.bodyA = rowA;
    m.bodyB = rowB;
    m.numPoints = c.numPoints;
    m.kind = kind;
    m.added = -1;
    m.addedMask = 0u;
    return m;
}

}  // namespace btgpu
