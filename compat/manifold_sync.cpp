// manifold_sync.cpp — the device's contact reports as the app's btPersistentManifolds: Bullet's
// body order (the algorithm's: a concave or plane side second, a sphere before a box, else the
// broadphase pair's lower proxy id first), one manifold per compound child pair and per
// convex–mesh pair (its triangles' points reduced to four as addManifoldPoint does), combined
// friction and restitution as btManifoldResult, lifetimes followed across steps.
#include "manifold_sync.h"

#include "shared/mesh.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <vector>

namespace btgpu {

namespace {

const btCollisionShape* leafShape(const btCollisionObject* o, int index)
{
    const btCollisionShape* s = o->getCollisionShape();
    if (s->isCompound()) {
        const auto* c = static_cast<const btCompoundShape*>(s);
        if (index >= 0 && index < c->getNumChildShapes()) return c->getChildShape(index);
    }
    return s;
}

int proxyId(const btCollisionObject* o) { return o->getBroadphaseHandle() ? o->getBroadphaseHandle()->m_uniqueId : 0; }

// The manifold's side key: a compound's child; the whole shape (-1) for a convex or concave side
// (stock keeps one manifold for all of a mesh's triangles).
int sideKey(const btCollisionObject* o, const btCollisionShape* leaf, int index)
{
    return o->getCollisionShape()->isCompound() && !leaf->isConcave() ? index : -1;
}

struct HeightfieldPeek : btHeightfieldTerrainShape {
    static constexpr int btHeightfieldTerrainShape::*kWidth = &HeightfieldPeek::m_heightStickWidth;
};

// A point on a concave side: its triangle's (part id, index) back from its feature id (the
// triangle's key, btgTriangleKey), as Bullet's per-point m_partId / m_index of that side.
void triangleOf(const btCollisionShape* concave, uint key, int* partId, int* index)
{
    if (key == BTG_FEATURE_UNKNOWN) return;
    if (concave->getShapeType() == TERRAIN_SHAPE_PROXYTYPE) {
        const int w = static_cast<const btHeightfieldTerrainShape*>(concave)->*HeightfieldPeek::kWidth;
        const uint perRow = uint(std::max(2 * (w - 1), 1));
        *index = int(key / perRow);
        *partId = int(key % perRow);
        return;
    }
    *partId = int((key & 0x7fffffffu) >> BTG_BVH_PART_SHIFT);
    *index = int(key & BTG_BVH_TRIANGLE_MASK);
}

struct NewPoint {
    btManifoldPoint point;
    uint featureId;
};

}  // namespace

void ManifoldSync::fill(btDispatcher* dispatcher, const RowMap& rows, const BodyReadback& rb,
                        const std::unordered_set<const btCollisionObject*>& removed)
{
    if (!dispatcher || !rb.contactsValid) return;
    ++m_stamp;
    // Reports in pair order; a key's points gathered in that order (a mesh pair's triangles).
    std::vector<Key> order;
    std::vector<std::vector<NewPoint>> points;
    std::unordered_map<Key, size_t, KeyHash> slot;
    std::vector<char> spheres;  // sphere–sphere: cleared and refilled each step, lifetime 0
    for (size_t i = 0; i < rb.numContacts; ++i) {
        const BtgContactReport& r = rb.contacts[i];
        if (r.bodyA < 0 || r.bodyB < 0 || size_t(r.bodyA) >= rows.size() || size_t(r.bodyB) >= rows.size()) continue;
        const btCollisionObject* oA = rows.at(size_t(r.bodyA));
        const btCollisionObject* oB = rows.at(size_t(r.bodyB));
        if (!oA || !oB || (!removed.empty() && (removed.count(oA) || removed.count(oB)))) continue;
        const btCollisionShape* leafA = leafShape(oA, r.indexA);
        const btCollisionShape* leafB = leafShape(oB, r.indexB);
        const bool concA = leafA->isConcave(), concB = leafB->isConcave();
        const int tA = leafA->getShapeType(), tB = leafB->getShapeType();
        // The algorithm's order: convex–concave and convex–plane put the convex first, the
        // sphere–box algorithm the sphere, a compound's child algorithms the child; else the
        // pair cache's (the lower proxy id first).
        const bool compA = oA->getCollisionShape()->isCompound(), compB = oB->getCollisionShape()->isCompound();
        bool swap;
        if (concA != concB) swap = concA;
        else if ((tA == SPHERE_SHAPE_PROXYTYPE) != (tB == SPHERE_SHAPE_PROXYTYPE) &&
                 (tA == BOX_SHAPE_PROXYTYPE || tB == BOX_SHAPE_PROXYTYPE))
            swap = tA == BOX_SHAPE_PROXYTYPE;
        else if (compA != compB) swap = compB;
        else swap = proxyId(oA) > proxyId(oB);
        Key key = swap ? Key{oB, oA, sideKey(oB, leafB, r.indexB), sideKey(oA, leafA, r.indexA)}
                       : Key{oA, oB, sideKey(oA, leafA, r.indexA), sideKey(oB, leafB, r.indexB)};
        auto [it, fresh] = slot.emplace(key, order.size());
        if (fresh) {
            order.push_back(key);
            points.emplace_back();
            spheres.push_back(tA == SPHERE_SHAPE_PROXYTYPE && tB == SPHERE_SHAPE_PROXYTYPE);
        }
        std::vector<NewPoint>& list = points[it->second];
        for (int k = 0; k < r.numPoints && k < BTG_MAX_POINTS; ++k) {
            const btVector3 n(r.normal[k].x, r.normal[k].y, r.normal[k].z);
            const btVector3 pB(r.pointB[k].x, r.pointB[k].y, r.pointB[k].z);
            const float d = r.pointB[k].w;
            const btVector3 pA = pB + n * d;
            const btVector3 lA(r.localA[k].x, r.localA[k].y, r.localA[k].z);
            const btVector3 lB(r.localB[k].x, r.localB[k].y, r.localB[k].z);
            const btVector3 d1(r.dir1[k].x, r.dir1[k].y, r.dir1[k].z);
            const btVector3 d2 = n.cross(d1);  // btgFrictionDir2
            // The impulses act on the report's A along +n, +d1, +d2; Bullet's on body0.
            int partA = r.partIdA, indexA = r.indexA, partB = r.partIdB, indexB = r.indexB;
            if (concA) triangleOf(leafA, r.featureId[k], &partA, &indexA);
            if (concB) triangleOf(leafB, r.featureId[k], &partB, &indexB);
            btManifoldPoint p = swap ? btManifoldPoint(lB, lA, -n, d) : btManifoldPoint(lA, lB, n, d);
            p.m_positionWorldOnA = swap ? pB : pA;
            p.m_positionWorldOnB = swap ? pA : pB;
            p.m_lateralFrictionDir1 = swap ? -d1 : d1;
            p.m_lateralFrictionDir2 = swap ? -d2 : d2;
            p.m_appliedImpulse = r.localA[k].w;
            p.m_appliedImpulseLateral1 = r.localB[k].w;
            p.m_appliedImpulseLateral2 = r.dir1[k].w;
            p.m_partId0 = swap ? partB : partA;
            p.m_index0 = swap ? indexB : indexA;
            p.m_partId1 = swap ? partA : partB;
            p.m_index1 = swap ? indexA : indexB;
            p.m_combinedFriction = btManifoldResult::calculateCombinedFriction(key.body0, key.body1);
            p.m_combinedRestitution = btManifoldResult::calculateCombinedRestitution(key.body0, key.body1);
            p.m_combinedRollingFriction = btManifoldResult::calculateCombinedRollingFriction(key.body0, key.body1);
            p.m_combinedSpinningFriction = btManifoldResult::calculateCombinedSpinningFriction(key.body0, key.body1);
            list.push_back({p, r.featureId[k]});
        }
    }

    for (size_t g = 0; g < order.size(); ++g) {
        const Key& key = order[g];
        auto it = m_map.find(key);
        if (it == m_map.end()) {
            btPersistentManifold* m = dispatcher->getNewManifold(key.body0, key.body1);
            it = m_map.emplace(key, Entry{m, 0, {}}).first;
        }
        Entry& e = it->second;
        btPersistentManifold* m = e.manifold;
        // Lifetimes: a point that continues an old one (same feature and sub-shape, else the
        // nearest in A's frame within the breaking threshold, as getCacheEntry) counts on; a
        // new one starts at 1, as stock's refreshContactPoints leaves a point added this step.
        const int oldCount = m->getNumContacts();
        btManifoldPoint old[MANIFOLD_CACHE_SIZE];
        for (int j = 0; j < oldCount; ++j) old[j] = m->getContactPoint(j);
        const btScalar thr2 = m->getContactBreakingThreshold() * m->getContactBreakingThreshold();
        unsigned claimed = 0;
        for (NewPoint& np : points[g]) {
            int match = -1;
            for (int j = 0; j < oldCount && match < 0; ++j)
                if (!((claimed >> j) & 1u) && np.featureId != BTG_FEATURE_UNKNOWN && e.ids[j] == np.featureId &&
                    old[j].m_index1 == np.point.m_index1 && old[j].m_partId1 == np.point.m_partId1 &&
                    old[j].m_index0 == np.point.m_index0 &&
                    (old[j].m_localPointA - np.point.m_localPointA).length2() < thr2)
                    match = j;
            if (match < 0) {
                btScalar best = thr2;
                for (int j = 0; j < oldCount; ++j) {
                    const btScalar d2 = (old[j].m_localPointA - np.point.m_localPointA).length2();
                    if (!((claimed >> j) & 1u) && d2 < best) {
                        best = d2;
                        match = j;
                    }
                }
            }
            if (match >= 0) claimed |= 1u << match;
            np.point.m_lifeTime = spheres[g] ? 0 : (match >= 0 ? old[match].m_lifeTime + 1 : 1);
        }
        m->clearManifold();
        for (const NewPoint& np : points[g]) {
            int at = m->addManifoldPoint(np.point);
            if (at >= 0 && at < MANIFOLD_CACHE_SIZE) e.ids[at] = np.featureId;
        }
        e.stamp = m_stamp;
    }

    // Pairs that stopped touching: released, as stock's algorithm empties and the pair goes;
    // a pair of two sleeping (or static) bodies is not collided by stock: kept as it was.
    for (auto it = m_map.begin(); it != m_map.end();) {
        const Entry& e = it->second;
        if (e.stamp == m_stamp || (!it->first.body0->isActive() && !it->first.body1->isActive())) {
            ++it;
            continue;
        }
        dispatcher->releaseManifold(e.manifold);
        it = m_map.erase(it);
    }
}

void ManifoldSync::releaseAll(btDispatcher* dispatcher)
{
    if (dispatcher)
        for (auto& [key, e] : m_map) dispatcher->releaseManifold(e.manifold);
    m_map.clear();
}

void ManifoldSync::removed(btDispatcher* dispatcher, const btCollisionObject* object)
{
    for (auto it = m_map.begin(); it != m_map.end();) {
        if (it->first.body0 != object && it->first.body1 != object) {
            ++it;
            continue;
        }
        if (dispatcher) dispatcher->releaseManifold(it->second.manifold);
        it = m_map.erase(it);
    }
}

}  // namespace btgpu
