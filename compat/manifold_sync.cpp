// manifold_sync.cpp — the device's contact reports as the app's btPersistentManifolds: Bullet's
// body order (the algorithm's: a concave or plane side second, a sphere before a box, a
// compound's child first, else the pair cache's lower proxy id first), one manifold per compound
// child pair and per
// convex–mesh pair (its triangles' points reduced to four as addManifoldPoint does), combined
// friction and restitution as btManifoldResult, lifetimes followed across steps.
#include "manifold_sync.h"

#include "parallel_rows.h"
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

}  // namespace

void triangleOfFeature(const btCollisionShape* concave, unsigned key, int* partId, int* index)
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

namespace {

struct NewPoint {
    btManifoldPoint point;
    uint featureId;
    bool pending;  // its user data and coefficients came from the callbacks before the solve
};

}  // namespace

ManifoldSync::Side ManifoldSync::orient(const RowMap& rows, int bodyA, int bodyB, int indexA, int indexB,
                                       const std::unordered_set<const btCollisionObject*>& removed)
{
    Side out{};
    if (bodyA < 0 || bodyB < 0 || size_t(bodyA) >= rows.size() || size_t(bodyB) >= rows.size()) return out;
    const btCollisionObject* oA = rows.at(size_t(bodyA));
    const btCollisionObject* oB = rows.at(size_t(bodyB));
    if (!oA || !oB || (!removed.empty() && (removed.count(oA) || removed.count(oB)))) return out;
    const btCollisionShape* leafA = leafShape(oA, indexA);
    const btCollisionShape* leafB = leafShape(oB, indexB);
    const bool concA = leafA->isConcave(), concB = leafB->isConcave();
    const int tA = leafA->getShapeType(), tB = leafB->getShapeType();
    // The algorithm's order: convex–concave and convex–plane put the convex first, the
    // sphere–box algorithm the sphere, a compound's child algorithms the child; else the pair
    // cache's (the lower proxy id first).
    const bool compA = oA->getCollisionShape()->isCompound(), compB = oB->getCollisionShape()->isCompound();
    bool swap;
    if (concA != concB) swap = concA;
    else if ((tA == SPHERE_SHAPE_PROXYTYPE) != (tB == SPHERE_SHAPE_PROXYTYPE) &&
             (tA == BOX_SHAPE_PROXYTYPE || tB == BOX_SHAPE_PROXYTYPE))
        swap = tA == BOX_SHAPE_PROXYTYPE;
    else if (compA != compB) swap = compB;
    else swap = proxyId(oA) > proxyId(oB);
    out.valid = true;
    out.swap = swap;
    out.spheres = tA == SPHERE_SHAPE_PROXYTYPE && tB == SPHERE_SHAPE_PROXYTYPE;
    out.concaveA = concA ? leafA : nullptr;
    out.concaveB = concB ? leafB : nullptr;
    out.key = swap ? Key{oB, oA, sideKey(oB, leafB, indexB), sideKey(oA, leafA, indexA)}
                   : Key{oA, oB, sideKey(oA, leafA, indexA), sideKey(oB, leafB, indexB)};
    return out;
}

const btManifoldPoint* ManifoldSync::continued(const Side& side, unsigned featureId, int index0, int partId1,
                                               int index1, const btVector3& localA) const
{
    auto it = m_map.find(side.key);
    if (it == m_map.end() || side.spheres) return nullptr;  // stock clears a sphere pair's manifold each step
    const Entry& e = it->second;
    const btPersistentManifold* m = e.manifold;
    const btScalar thr2 = m->getContactBreakingThreshold() * m->getContactBreakingThreshold();
    int match = -1;
    for (int j = 0; j < m->getNumContacts() && match < 0; ++j) {
        const btManifoldPoint& o = m->getContactPoint(j);
        if (featureId != BTG_FEATURE_UNKNOWN && e.ids[j] == featureId && o.m_index1 == index1 && o.m_partId1 == partId1 &&
            o.m_index0 == index0 && (o.m_localPointA - localA).length2() < thr2)
            match = j;
    }
    if (match < 0) {
        btScalar best = thr2;
        for (int j = 0; j < m->getNumContacts(); ++j) {
            const btScalar d2 = (m->getContactPoint(j).m_localPointA - localA).length2();
            if (d2 < best) {
                best = d2;
                match = j;
            }
        }
    }
    return match >= 0 ? &m->getContactPoint(match) : nullptr;
}

void ManifoldSync::refill(Group& g, const BtgContactReport* reports)
{
    NewPoint points[4 * BTG_MAX_POINTS];  // a convex–mesh pair's triangles: reduced as they come
    std::vector<NewPoint> many;
    int count = 0;
    auto push = [&](const NewPoint& np) {
        if (count < int(sizeof(points) / sizeof(points[0]))) points[count++] = np;
        else many.push_back(np);
    };
    const Key& key = g.entry->first;
    for (size_t i = g.first; i < g.last; ++i) {
        const BtgContactReport& r = reports[i];
        const Side& side = m_sides[i];
        if (!side.valid) continue;
        const bool swap = side.swap;
        for (int k = 0; k < r.numPoints && k < BTG_MAX_POINTS; ++k) {
            const btVector3 n(r.normal[k].x, r.normal[k].y, r.normal[k].z);
            const btVector3 pB(r.pointB[k].x, r.pointB[k].y, r.pointB[k].z);
            const float d = r.pointB[k].w;
            const btVector3 pA = pB + n * d;
            const btVector3 lA(r.localA[k].x, r.localA[k].y, r.localA[k].z);
            const btVector3 lB(r.localB[k].x, r.localB[k].y, r.localB[k].z);
            const btVector3 d1(r.dir1[k].x, r.dir1[k].y, r.dir1[k].z);
            const btVector3 d2 = n.cross(d1);  // btgFrictionDir2
            int partA = r.partIdA, indexA = r.indexA, partB = r.partIdB, indexB = r.indexB;
            if (side.concaveA) triangleOfFeature(side.concaveA, r.featureId[k], &partA, &indexA);
            if (side.concaveB) triangleOfFeature(side.concaveB, r.featureId[k], &partB, &indexB);
            // The impulses act on the report's A along +n, +d1, +d2; Bullet's on body0.
            NewPoint np{swap ? btManifoldPoint(lB, lA, -n, d) : btManifoldPoint(lA, lB, n, d), r.featureId[k], false};
            btManifoldPoint& p = np.point;
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
            if (!m_pending.empty()) {
                auto it = m_pending.find(PointKey{r.bodyA, r.bodyB, r.indexA, r.indexB, r.featureId[k], k});
                if (it != m_pending.end()) {
                    p.m_userPersistentData = it->second.userData;
                    p.m_combinedFriction = it->second.friction;
                    p.m_combinedRestitution = it->second.restitution;
                    np.pending = true;
                }
            }
            push(np);
        }
    }
    Entry& e = g.entry->second;
    btPersistentManifold* m = e.manifold;
    // Lifetimes: a point that continues an old one (same feature and sub-shape, else the
    // nearest in A's frame within the breaking threshold, as getCacheEntry) counts on; a new one
    // starts at 1, as stock's refreshContactPoints leaves a point added this step.
    const int oldCount = m->getNumContacts();
    btManifoldPoint old[MANIFOLD_CACHE_SIZE];
    for (int j = 0; j < oldCount; ++j) old[j] = m->getContactPoint(j);
    const btScalar thr2 = m->getContactBreakingThreshold() * m->getContactBreakingThreshold();
    unsigned claimed = 0;
    const int total = count + int(many.size());
    auto at = [&](int i) -> NewPoint& { return i < count ? points[i] : many[size_t(i - count)]; };
    for (int i = 0; i < total; ++i) {
        NewPoint& np = at(i);
        int match = -1;
        for (int j = 0; j < oldCount && match < 0; ++j)
            if (!((claimed >> j) & 1u) && np.featureId != BTG_FEATURE_UNKNOWN && e.ids[j] == np.featureId &&
                old[j].m_index1 == np.point.m_index1 && old[j].m_partId1 == np.point.m_partId1 &&
                old[j].m_index0 == np.point.m_index0 && (old[j].m_localPointA - np.point.m_localPointA).length2() < thr2)
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
        np.point.m_lifeTime = g.spheres ? 0 : (match >= 0 ? old[match].m_lifeTime + 1 : 1);
        // A point that continues one keeps its user data (replaceContactPoint); stock clears a
        // sphere pair's manifold every step, which drops it.
        if (!np.pending) np.point.m_userPersistentData = match >= 0 && !g.spheres ? old[match].m_userPersistentData : nullptr;
    }
    // Emptied without Bullet's clearManifold, which would end the contact and destroy the
    // points' user data (the callbacks for both are the fill's, serially: contactEvents); the
    // points go in without their user data, so that a point the reduction drops takes none with
    // it, and get it once placed.
    g.before = oldCount;
    for (int j = 0; j < oldCount; ++j) m->getContactPoint(j).m_userPersistentData = nullptr;
    m->setNumContacts(0);
    int owner[MANIFOLD_CACHE_SIZE] = {-1, -1, -1, -1};
    for (int i = 0; i < total; ++i) {
        btManifoldPoint pt = at(i).point;
        pt.m_userPersistentData = nullptr;
        const int slot = m->addManifoldPoint(pt);
        if (slot >= 0 && slot < MANIFOLD_CACHE_SIZE) {
            e.ids[slot] = at(i).featureId;
            owner[slot] = i;
        }
    }
    for (int s = 0; s < m->getNumContacts(); ++s)
        if (owner[s] >= 0) m->getContactPoint(s).m_userPersistentData = at(owner[s]).point.m_userPersistentData;
    // User data no point holds any more: destroyed, as stock's point removal does.
    g.dropped.clear();
    auto held = [&](void* p) {
        for (int s = 0; s < m->getNumContacts(); ++s)
            if (m->getContactPoint(s).m_userPersistentData == p) return true;
        return false;
    };
    for (int j = 0; j < oldCount; ++j)
        if (old[j].m_userPersistentData && !held(old[j].m_userPersistentData)) g.dropped.push_back(old[j].m_userPersistentData);
    for (int i = 0; i < total; ++i) {
        void* p = at(i).point.m_userPersistentData;
        if (p && !held(p) && std::find(g.dropped.begin(), g.dropped.end(), p) == g.dropped.end()) g.dropped.push_back(p);
    }
}

void ManifoldSync::contactEvents()
{
    // Stock's order within a manifold's step: a sphere pair's manifold is cleared first (its
    // contact ends), points are added (the contact starts with the first of an empty manifold),
    // then the refresh removes the points that went (their user data destroyed).
    for (Group& g : m_groups) {
        btPersistentManifold* m = g.entry->second.manifold;
        const bool restarted = g.spheres && g.before > 0 && !g.fresh;
        if (restarted && gContactEndedCallback) gContactEndedCallback(m);
        if ((g.fresh || restarted) && m->getNumContacts() > 0 && gContactStartedCallback) gContactStartedCallback(m);
        if (gContactDestroyedCallback)
            for (void* p : g.dropped) gContactDestroyedCallback(p);
        g.dropped.clear();
    }
}

void ManifoldSync::fill(btDispatcher* dispatcher, const RowMap& rows, const BodyReadback& rb,
                        const std::unordered_set<const btCollisionObject*>& removed)
{
    if (!dispatcher || !rb.contactsValid) return;
    ++m_stamp;
    // Each report's Bullet identity, in parallel (reads only).
    const size_t n = rb.numContacts;
    m_sides.resize(n);
    forEachChunk(n, 2048, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) {
            const BtgContactReport& r = rb.contacts[i];
            m_sides[i] = orient(rows, r.bodyA, r.bodyB, r.indexA, r.indexB, removed);
        }
    });
    // Reports are in pair order: a manifold's (a mesh pair's triangles, one compound child pair)
    // are consecutive. Serially: the dispatcher's pool (getNewManifold is not thread-safe).
    m_groups.clear();
    bool duplicate = false;
    for (size_t i = 0; i < n; ++i) {
        const Side& side = m_sides[i];
        if (!side.valid) continue;
        if (!m_groups.empty() && m_groups.back().entry->first == side.key && m_groups.back().last == i) {
            m_groups.back().last = i + 1;
            continue;
        }
        auto it = m_map.find(side.key);
        const bool fresh = it == m_map.end();
        if (fresh)
            it = m_map.emplace(side.key, Entry{dispatcher->getNewManifold(side.key.body0, side.key.body1), 0, {}}).first;
        duplicate |= it->second.stamp == m_stamp;  // the same manifold again, not adjacent
        it->second.stamp = m_stamp;
        m_groups.push_back({&*it, i, i + 1, side.spheres, fresh, 0, {}});
    }
    if (duplicate) {
        // Not seen in pair order, but kept right: one group per manifold, in report order.
        std::unordered_map<const void*, size_t> firstOf;
        std::vector<Group> merged;
        std::vector<std::vector<size_t>> members;
        for (const Group& g : m_groups) {
            auto [it, first] = firstOf.emplace(g.entry->second.manifold, merged.size());
            if (first) {
                merged.push_back(g);
                members.emplace_back();
            } else {
                merged[it->second].fresh |= g.fresh;
            }
            for (size_t i = g.first; i < g.last; ++i) members[it->second].push_back(i);
        }
        // Reorder the reports' sides so that each manifold's are consecutive.
        std::vector<Side> sides;
        std::vector<BtgContactReport> reports;
        for (size_t k = 0; k < merged.size(); ++k) {
            merged[k].first = sides.size();
            for (size_t i : members[k]) {
                sides.push_back(m_sides[i]);
                reports.push_back(rb.contacts[i]);
            }
            merged[k].last = sides.size();
        }
        m_sides.swap(sides);
        m_scratch.swap(reports);
        m_groups.swap(merged);
        for (Group& g : m_groups) refill(g, m_scratch.data());
    } else {
        forEachChunk(m_groups.size(), 512, [&](size_t begin, size_t end, int) {
            for (size_t k = begin; k < end; ++k) refill(m_groups[k], rb.contacts.data());
        });
    }
    m_pending.clear();
    contactEvents();

    // Pairs that stopped touching: released, as stock's algorithm empties and the pair goes;
    // a pair of two sleeping (or static) bodies is not collided by stock: kept as it was.
    // Released from the dispatcher's last index down, so its array order does not depend on
    // the map's (address-hashed) order.
    std::vector<std::pair<int, Key>> stale;
    for (const auto& [key, e] : m_map)
        if (e.stamp != m_stamp && (key.body0->isActive() || key.body1->isActive()))
            stale.push_back({e.manifold->m_index1a, key});
    std::sort(stale.begin(), stale.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    for (const auto& [index, key] : stale) {
        auto it = m_map.find(key);
        dispatcher->releaseManifold(it->second.manifold);
        m_map.erase(it);
    }
}

void ManifoldSync::releaseAll(btDispatcher* dispatcher)
{
    if (dispatcher)
        for (auto& [key, e] : m_map) {
            btPersistentManifold* m = e.manifold;
            for (int j = 0; j < m->getNumContacts(); ++j) {
                btManifoldPoint& p = m->getContactPoint(j);
                if (p.m_userPersistentData && gContactDestroyedCallback) gContactDestroyedCallback(p.m_userPersistentData);
                p.m_userPersistentData = nullptr;
            }
            m->setNumContacts(0);
            dispatcher->releaseManifold(m);
        }
    m_map.clear();
    m_pending.clear();
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
