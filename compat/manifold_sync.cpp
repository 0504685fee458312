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
    // Built where it stays (emplace_back): a temporary copied in stalled the fill on its
    // stores (perf: most of refill's time at loads of the stack copy).
    NewPoint(const btVector3& localA, const btVector3& localB, const btVector3& normal, btScalar distance, uint feature)
        : point(localA, localB, normal, distance), featureId(feature)
    {
    }
    btManifoldPoint point;    // as it goes into the manifold: without its user data until placed
    void* userData = nullptr;  // what it holds once placed
    int lifeTime = 0;          // m_lifeTime once placed (the point's own holds its tag until then)
    uint featureId;
    bool pending = false;  // its user data and coefficients came from the callbacks before the solve
    bool moved = false;    // a callback changed its geometry (PointState::moved)
    int continues = -1;    // the old point it continues, -1 for none
};

// Until a fill has placed its points, each carries its source in m_lifeTime: old point j as
// kOldTag + j, new point i as kNewTag + i (Bullet's own calls move points between slots).
constexpr int kOldTag = 1 << 20;
constexpr int kNewTag = 1 << 21;

}  // namespace

namespace {

// Two compounds of which one has no dynamic AABB tree: btCompoundCompoundCollisionAlgorithm
// runs its base class, whose child algorithms are compound algorithms in turn (compound.h).
bool nestedCompounds(const btCollisionShape* a, const btCollisionShape* b)
{
    return a->isCompound() && b->isCompound() &&
           (!static_cast<const btCompoundShape*>(a)->getDynamicAabbTree() ||
            !static_cast<const btCompoundShape*>(b)->getDynamicAabbTree());
}

}  // namespace

int ManifoldSync::refreshesPerStep(const btCollisionObject* body0, const btCollisionObject* body1)
{
    // btCompoundCollisionAlgorithm and btCompoundCompoundCollisionAlgorithm::processCollision
    // (3.24): "we need to refresh all contact manifolds" of their child algorithms, then collide;
    // where a compound's child algorithm is itself a compound algorithm (nestedCompounds) that
    // refreshes them once more.
    const btCollisionShape *a = body0->getCollisionShape(), *b = body1->getCollisionShape();
    if (nestedCompounds(a, b)) return 3;
    return a->isCompound() || b->isCompound() ? 2 : 1;
}

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
    // The algorithm's order: convex–concave and convex–plane put the convex first, a compound's
    // child algorithms the child; else the pair cache's (the lower proxy id first). A sphere and
    // a box meet in the convex–convex algorithm, which keeps the order it is given (Bullet's
    // sphere–box algorithm, which puts the sphere first, is compiled out unless
    // USE_BUGGY_SPHERE_BOX_ALGORITHM).
    const bool compA = oA->getCollisionShape()->isCompound(), compB = oB->getCollisionShape()->isCompound();
    bool swap;
    if (concA != concB) swap = concA;
    else if (compA != compB) swap = compB;
    // Nested compound algorithms: the innermost child algorithm takes B's leaf, then A's.
    else if (nestedCompounds(oA->getCollisionShape(), oB->getCollisionShape())) swap = proxyId(oA) < proxyId(oB);
    else swap = proxyId(oA) > proxyId(oB);
    out.valid = true;
    out.swap = swap;
    out.spheres = tA == SPHERE_SHAPE_PROXYTYPE && tB == SPHERE_SHAPE_PROXYTYPE;
    out.concaveA = concA ? leafA : nullptr;
    out.concaveB = concB ? leafB : nullptr;
    out.refreshes = refreshesPerStep(oA, oB);
    out.key = swap ? Key{oB, oA, sideKey(oB, leafB, indexB), sideKey(oA, leafA, indexA)}
                   : Key{oA, oB, sideKey(oA, leafA, indexA), sideKey(oB, leafB, indexB)};
    return out;
}

const btManifoldPoint* ManifoldSync::continued(const Side& side, unsigned featureId, int index0, int partId1,
                                               int index1, const btVector3& localA, bool* moved, bool identities) const
{
    if (moved) *moved = false;
    const Node* node = m_map.find(side.key);
    // none, or its body left; stock clears a sphere pair's manifold each step
    if (!node || !node->second.manifold || side.spheres) return nullptr;
    const Entry& e = node->second;
    const btPersistentManifold* m = e.manifold;
    const btScalar thr2 = m->getContactBreakingThreshold() * m->getContactBreakingThreshold();
    // By identity the first with the feature id; else (a triangle's key may name several points)
    // the nearest of those within the threshold.
    int match = -1;
    btScalar nearest = thr2;
    for (int j = 0; j < m->getNumContacts() && !(identities && match >= 0); ++j) {
        const btManifoldPoint& o = m->getContactPoint(j);
        const btScalar d2 = (o.m_localPointA - localA).length2();
        if (featureId != BTG_FEATURE_UNKNOWN && e.ids[j] == featureId && o.m_index1 == index1 && o.m_partId1 == partId1 &&
            o.m_index0 == index0 && (identities || d2 < nearest)) {
            match = j;
            nearest = d2;
        }
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
    if (match >= 0 && moved) *moved = e.moved[match];
    return match >= 0 ? &m->getContactPoint(match) : nullptr;
}

void ManifoldSync::refill(Group& g, const BtgContactReport* reports)
{
    // Reused by each thread (a convex–mesh pair's triangles bring more than four: reduced as they
    // go in): no point is built or copied more than its one way into the manifold needs.
    static thread_local std::vector<NewPoint> points;
    points.clear();
    points.reserve(4 * BTG_MAX_POINTS);
    const Key& key = g.entry->first;
    // One pair of bodies: their combined coefficients once (btManifoldResult's, per point on stock).
    const btScalar friction = btManifoldResult::calculateCombinedFriction(key.body0, key.body1);
    const btScalar restitution = btManifoldResult::calculateCombinedRestitution(key.body0, key.body1);
    const btScalar rolling = btManifoldResult::calculateCombinedRollingFriction(key.body0, key.body1);
    const btScalar spinning = btManifoldResult::calculateCombinedSpinningFriction(key.body0, key.body1);
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
            NewPoint& np = swap ? points.emplace_back(lB, lA, -n, d, r.featureId[k]) : points.emplace_back(lA, lB, n, d, r.featureId[k]);
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
            p.m_combinedFriction = friction;
            p.m_combinedRestitution = restitution;
            p.m_combinedRollingFriction = rolling;
            p.m_combinedSpinningFriction = spinning;
            if (!m_pending.empty()) {
                auto it = m_pending.find(PointKey{r.bodyA, r.bodyB, r.indexA, r.indexB, r.featureId[k], k});
                if (it != m_pending.end()) {
                    np.userData = it->second.userData;
                    p.m_combinedFriction = it->second.friction;
                    p.m_combinedRestitution = it->second.restitution;
                    np.pending = true;
                    np.moved = it->second.moved;
                }
            }
        }
    }
    Entry& e = g.entry->second;
    btPersistentManifold* m = e.manifold;
    // Lifetimes: a point that continues an old one (same feature and sub-shape, else the
    // nearest in A's frame within the breaking threshold, as getCacheEntry) counts on; a new one
    // starts at 1, as stock's refreshContactPoints leaves a point added this step.
    const int oldCount = m->getNumContacts();
    const int ages = refreshesPerStep(key.body0, key.body1);
    // What the matching and the lifetimes need of the old points (not whole copies: the old
    // points a refill keeps stay where they are in the manifold).
    struct Old {
        btVector3 m_localPointA;
        int m_index0, m_index1, m_partId1, m_lifeTime;
        void* m_userPersistentData;
    } old[MANIFOLD_CACHE_SIZE];
    for (int j = 0; j < oldCount; ++j) {
        const btManifoldPoint& p = m->getContactPoint(j);
        old[j] = Old{p.m_localPointA, p.m_index0, p.m_index1, p.m_partId1, p.m_lifeTime, p.m_userPersistentData};
    }
    const btScalar thr2 = m->getContactBreakingThreshold() * m->getContactBreakingThreshold();
    unsigned claimed = 0;
    const int total = int(points.size());
    for (NewPoint& np : points) {
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
        np.continues = match;
        np.lifeTime = g.spheres ? 0 : (match >= 0 ? old[match].m_lifeTime + ages : 1);
        // A point that continues one keeps its user data (replaceContactPoint); stock clears a
        // sphere pair's manifold every step, which drops it.
        if (!np.pending) np.userData = match >= 0 && !g.spheres ? old[match].m_userPersistentData : nullptr;
    }
    // Emptied without Bullet's clearManifold, which would end the contact and destroy the
    // points' user data (the callbacks for both are the fill's, serially: contactEvents); the
    // points go in without their user data, so that a point the reduction drops takes none with
    // it, and get it once placed.
    g.before = oldCount;
    for (int j = 0; j < oldCount; ++j) m->getContactPoint(j).m_userPersistentData = nullptr;
    unsigned oldIds[MANIFOLD_CACHE_SIZE];
    bool oldMoved[MANIFOLD_CACHE_SIZE];
    for (int j = 0; j < MANIFOLD_CACHE_SIZE; ++j) {
        oldIds[j] = e.ids[j];
        oldMoved[j] = e.moved[j];
    }
    // Stock's order inside the pair's collision: the detector's points go into the manifold as
    // it holds them (a continued point replaces its old one in place, a new one is added,
    // replacing by Bullet's reduction when four are held), then refreshContactPoints keeps the
    // old points nothing replaced while they stay within the breaking threshold at the
    // transforms the pair was collided at (a box tipping onto an edge of another still shows
    // four points on stock). Such a point was not in the device's solve: its impulses are 0.
    // A GJK, box or (bullet mode) convex–concave pair's manifold is the device's persistent one,
    // refreshed there as stock's (a concave pair's normal groups, consecutive reports, together): its
    // points are the whole manifold (keeping old ones here would double the refresh).
    const bool persistent = reports[g.first].persistent != 0;
    e.persistent = persistent;
    const bool retain = !persistent && m_collidedAtValid && !g.spheres && total > 0 && g.row0 >= 0 && g.row1 >= 0 &&
                        size_t(std::max(g.row0, g.row1)) < m_collidedAt.size();
    // Kept: the old points stay in their slots, in order (as addManifoldPoint would put each
    // back), without their user data (taken above), tagged; else the manifold starts empty.
    m->setNumContacts(retain ? oldCount : 0);
    if (retain)
        for (int j = 0; j < oldCount; ++j) m->getContactPoint(j).m_lifeTime = kOldTag + j;
    for (int i = 0; i < total; ++i) {
        btManifoldPoint& pt = points[size_t(i)].point;  // no user data yet (NewPoint::userData)
        pt.m_lifeTime = kNewTag + i;
        const int continues = points[size_t(i)].continues;
        int slot = -1;
        for (int s = 0; retain && continues >= 0 && s < m->getNumContacts() && slot < 0; ++s)
            if (m->getContactPoint(s).m_lifeTime == kOldTag + continues) slot = s;
        if (slot >= 0) m->getContactPoint(slot) = pt;
        else m->addManifoldPoint(pt);
    }
    if (retain) {
        const btTransform& t0 = m_collidedAt[size_t(g.row0)];
        const btTransform& t1 = m_collidedAt[size_t(g.row1)];
        const btScalar breaking = m->getContactBreakingThreshold();
        for (int s = m->getNumContacts() - 1; s >= 0; --s) {
            btManifoldPoint& p = m->getContactPoint(s);
            if (p.m_lifeTime >= kNewTag) continue;
            p.m_positionWorldOnA = t0(p.m_localPointA);
            p.m_positionWorldOnB = t1(p.m_localPointB);
            p.m_distance1 = (p.m_positionWorldOnA - p.m_positionWorldOnB).dot(p.m_normalWorldOnB);
            const btVector3 drift = p.m_positionWorldOnB - (p.m_positionWorldOnA - p.m_normalWorldOnB * p.m_distance1);
            if (p.m_distance1 > breaking || drift.length2() > thr2) m->removeContactPoint(s);  // a new point stays: never emptied
        }
    }
    int owner[MANIFOLD_CACHE_SIZE] = {-1, -1, -1, -1};
    for (int s = 0; s < m->getNumContacts(); ++s) {
        btManifoldPoint& p = m->getContactPoint(s);
        if (p.m_lifeTime >= kNewTag) {
            const int i = p.m_lifeTime - kNewTag;
            owner[s] = i;
            e.ids[s] = points[size_t(i)].featureId;
            e.moved[s] = points[size_t(i)].moved;
            p.m_lifeTime = points[size_t(i)].lifeTime;
        } else {
            const int j = p.m_lifeTime - kOldTag;
            e.ids[s] = oldIds[j];
            e.moved[s] = oldMoved[j];
            p.m_lifeTime = old[j].m_lifeTime + ages;
            p.m_appliedImpulse = p.m_appliedImpulseLateral1 = p.m_appliedImpulseLateral2 = 0;
            p.m_userPersistentData = old[j].m_userPersistentData;
        }
    }
    for (int s = 0; s < m->getNumContacts(); ++s)
        if (owner[s] >= 0) m->getContactPoint(s).m_userPersistentData = points[size_t(owner[s])].userData;
    // User data no point holds any more: destroyed, as stock's point removal does.
    g.dropped.clear();
    auto held = [&](void* p) {
        for (int s = 0; s < m->getNumContacts(); ++s)
            if (m->getContactPoint(s).m_userPersistentData == p) return true;
        return false;
    };
    for (int j = 0; j < oldCount; ++j)
        if (old[j].m_userPersistentData && !held(old[j].m_userPersistentData)) g.dropped.push_back(old[j].m_userPersistentData);
    for (const NewPoint& np : points) {
        void* p = np.userData;
        if (p && !held(p) && std::find(g.dropped.begin(), g.dropped.end(), p) == g.dropped.end()) g.dropped.push_back(p);
    }
}

void ManifoldSync::contactEvents()
{
    // Stock's order within a manifold's step: a sphere pair's manifold is cleared first (its
    // contact ends), points are added (the contact starts with the first of an empty manifold),
    // then the refresh removes the points that went (their user data destroyed).
    if (!gContactEndedCallback && !gContactStartedCallback && !gContactDestroyedCallback) return;  // (a walk of every manifold)
    for (Group& g : m_groups) {
        btPersistentManifold* m = g.entry->second.manifold;
        const bool restarted = g.spheres && g.before > 0 && !g.fresh;
        if (restarted && gContactEndedCallback) gContactEndedCallback(m);
        // A manifold's first point starts its contact (btManifoldResult::addContactPoint), whether
        // the manifold is new or was held empty (Config::stockEmptyManifolds).
        if ((g.before == 0 || restarted) && m->getNumContacts() > 0 && gContactStartedCallback) gContactStartedCallback(m);
        if (gContactDestroyedCallback)
            for (void* p : g.dropped) gContactDestroyedCallback(p);
        g.dropped.clear();
    }
}

void ManifoldSync::fill(btDispatcher* dispatcher, const RowMap& rows, const BodyReadback& rb,
                        const std::unordered_set<const btCollisionObject*>& removed,
                        const std::function<void()>& beforeEvents)
{
    if (!dispatcher || !rb.contactsValid) return;
    ++m_stamp;
    // Each report's Bullet identity and its map entry, in parallel: the lookups are the costly
    // part (a random access each; 100,000+ manifolds at 32,768 cubes), and nothing inserts
    // while they run.
    const size_t n = rb.numContacts;
    m_sides.resize(n);
    // Each lookup's two misses (its slot, its node) are fetched ahead, kAhead reports apart.
    constexpr size_t kAhead = 8;
    std::vector<size_t>& hashes = m_hashes;
    hashes.resize(n);
    forEachChunk(n, 2048, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end + 2 * kAhead; ++i) {
            if (i < end) {
                Side& side = m_sides[i];
                const BtgContactReport& r = rb.reports[i];
                side = orient(rows, r.bodyA, r.bodyB, r.indexA, r.indexB, removed);
                side.node = nullptr;
                hashes[i] = KeyHash()(side.key);
                if (side.valid) m_map.prefetchSlot(hashes[i]);
            }
            if (i >= begin + kAhead && i - kAhead < end && m_sides[i - kAhead].valid) m_map.prefetchNode(hashes[i - kAhead]);
            if (i >= begin + 2 * kAhead) {
                Side& side = m_sides[i - 2 * kAhead];
                if (side.valid) side.node = m_map.find(side.key, hashes[i - 2 * kAhead]);
                side.held = side.node && side.node->second.manifold;
            }
        }
    });
    // Reports are in pair order: a manifold's (a mesh pair's triangles, one compound child pair)
    // are consecutive. The groups in parallel: a valid report starts one unless the report just
    // before it is of the same manifold. Then, serially in group order, the groups whose key held
    // no manifold (new pairs, few a step): their node, and a new manifold from the dispatcher's
    // pool (getNewManifold is not thread-safe).
    std::vector<std::vector<size_t>>& startsIn = m_startsIn;  // per chunk, kept with their capacity
    startsIn.resize(size_t(chunkCount(n, 4096)));
    for (std::vector<size_t>& starts : startsIn) starts.clear();
    forEachChunk(n, 4096, [&](size_t begin, size_t end, int chunk) {
        for (size_t i = begin; i < end; ++i) {
            const Side& side = m_sides[i];
            if (side.valid && !(i > 0 && m_sides[i - 1].valid && m_sides[i - 1].key == side.key))
                startsIn[size_t(chunk)].push_back(i);
        }
    });
    m_starts.clear();
    for (const std::vector<size_t>& starts : startsIn) m_starts.insert(m_starts.end(), starts.begin(), starts.end());
    m_groups.resize(m_starts.size());
    std::vector<std::vector<size_t>>& unheldIn = m_unheldIn;
    unheldIn.resize(size_t(chunkCount(m_starts.size(), 2048)));
    for (std::vector<size_t>& unheld : unheldIn) unheld.clear();
    forEachChunk(m_starts.size(), 2048, [&](size_t begin, size_t end, int chunk) {
        for (size_t k = begin; k < end; ++k) {
            const size_t i = m_starts[k];
            const Side& side = m_sides[i];
            size_t last = i + 1;
            while (last < n && m_sides[last].valid && m_sides[last].key == side.key) ++last;
            const BtgContactReport& r = rb.reports[i];
            Group& g = m_groups[k];
            g.entry = side.node;
            g.first = i;
            g.last = last;
            g.row0 = side.swap ? r.bodyB : r.bodyA;
            g.row1 = side.swap ? r.bodyA : r.bodyB;
            g.spheres = side.spheres;
            g.fresh = false;
            g.before = 0;
            if (!side.held) unheldIn[size_t(chunk)].push_back(k);
        }
    });
    for (const std::vector<size_t>& unheld : unheldIn)
        for (size_t k : unheld) {
            Group& g = m_groups[k];
            const Side& side = m_sides[g.first];
            Node* node = side.node ? side.node : m_map.insert(side.key);  // new, or a new key of an earlier group
            g.entry = node;
            g.fresh = !node->second.manifold;
            if (g.fresh) {
                // New, or revived after its body left (a new body at the freed address).
                m_dead.erase(node);
                node->second = Entry{dispatcher->getNewManifold(side.key.body0, side.key.body1), 0, {}, {}};
                m_byObject[side.key.body0].push_back(node);
                if (side.key.body1 != side.key.body0) m_byObject[side.key.body1].push_back(node);
            }
        }
    // Stamps in parallel; a manifold named by two groups (not adjacent: not seen in pair order)
    // shows as a stamp already this fill's.
    const size_t numGroups = m_groups.size();
    std::vector<unsigned char> duplicateIn(size_t(chunkCount(numGroups, 2048)), 0);
    forEachChunk(numGroups, 2048, [&](size_t begin, size_t end, int chunk) {
        for (size_t k = begin; k < end; ++k)
            if (__atomic_exchange_n(&m_groups[k].entry->second.stamp, m_stamp, __ATOMIC_RELAXED) == m_stamp)
                duplicateIn[size_t(chunk)] = 1;
    });
    const bool duplicate = std::find(duplicateIn.begin(), duplicateIn.end(), 1) != duplicateIn.end();
    m_nextLive.clear();
    if (duplicate) {
        // Kept right anyway: one group per manifold, in report order.
        std::unordered_map<const void*, size_t> firstOf;
        std::vector<Group> merged;
        std::vector<std::vector<size_t>> members;
        for (const Group& g : m_groups) {
            auto [it, first] = firstOf.emplace(g.entry, merged.size());
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
                reports.push_back(rb.reports[i]);
            }
            merged[k].last = sides.size();
        }
        m_sides.swap(sides);
        m_scratch.swap(reports);
        m_groups.swap(merged);
        for (Group& g : m_groups) {
            refill(g, m_scratch.data());
            m_nextLive.push_back(g.entry);
        }
    } else {
        forEachChunk(numGroups, 512, [&](size_t begin, size_t end, int) {
            for (size_t k = begin; k < end; ++k) {
                // The manifolds lie scattered over the dispatcher's pool: the one two groups
                // ahead is fetched (for writing) while this one is refilled, its node four ahead.
                if (k + 4 < end) __builtin_prefetch(m_groups[k + 4].entry);
                if (k + 2 < end) prefetchObject(m_groups[k + 2].entry->second.manifold, sizeof(btPersistentManifold), true);
                refill(m_groups[k], rb.reports);
            }
        });
        for (const Group& g : m_groups) m_nextLive.push_back(g.entry);
    }
    if (beforeEvents) beforeEvents();
    m_pending.clear();
    contactEvents();

    // Pairs that stopped touching: released, as stock's algorithm empties and the pair goes;
    // a pair of two sleeping (or static) bodies is not collided by stock: kept as it was. Only
    // the last fill's entries can be stale; they are judged in parallel (random accesses).
    m_staleFlag.assign(m_live.size(), 0);
    forEachChunk(m_live.size(), 4096, [&](size_t begin, size_t end, int) {
        for (size_t i = begin; i < end; ++i) {
            if (i + 8 < end) __builtin_prefetch(m_live[i + 8]);
            Node* node = m_live[i];
            // A null manifold: its body left (m_dead).
            if (!node->second.manifold || node->second.stamp == m_stamp) continue;
            const bool awake = node->first.body0->isActive() || node->first.body1->isActive();
            // An empty manifold of a pair stock still holds stays as it is: what the serial pass
            // below would do with it (no points to refresh or remove), decided here in parallel
            // (with the device's empty manifolds most stale entries are these).
            const bool heldEmpty = m_wantedValid && node->second.manifold->getNumContacts() == 0 && stockHolds(node->first);
            m_staleFlag[i] = awake && !heldEmpty ? 1 : 2;
        }
    });
    // Released from the dispatcher's last index down, so its array order does not depend on
    // the map's (address-hashed) order.
    std::vector<std::pair<int, Node*>> stale;
    for (size_t i = 0; i < m_live.size(); ++i) {
        if (m_staleFlag[i] == 2) m_nextLive.push_back(m_live[i]);
        if (m_staleFlag[i] == 1) stale.push_back({m_live[i]->second.manifold->m_index1a, m_live[i]});
    }
    std::sort(stale.begin(), stale.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    for (const auto& [index, node] : stale) {
        // With stock's pairs noted (Config::stockEmptyManifolds) a manifold lives as long as its
        // pair's algorithm: given back when the pair left, kept (emptied if its points went)
        // while it stays.
        const bool held = m_wantedValid && stockHolds(node->first);
        if ((!m_wantedValid || held) && keepsOldPoints(node, rows)) {
            m_nextLive.push_back(node);
            continue;
        }
        if (held) {
            btPersistentManifold* m = node->second.manifold;
            for (int s = m->getNumContacts() - 1; s >= 0; --s) m->removeContactPoint(s);  // destroyed, then ended
            m_nextLive.push_back(node);
            continue;
        }
        dispatcher->releaseManifold(node->second.manifold);
        forget(node);
    }
    // Nodes of bodies that left and were not found again: gone for good.
    for (Node* node : m_dead) m_map.erase(node);
    m_dead.clear();
    if (m_wantedValid) holdStockPairs(dispatcher, removed);
    m_wantedValid = false;  // each internal step notes its own pairs
    m_live.swap(m_nextLive);
}

bool ManifoldSync::keepsOldPoints(Node* node, const RowMap& rows)
{
    // Stock's algorithm for a pair its detector found nothing for this step still refreshes the
    // manifold: the old points stay while within the breaking threshold at the transforms the
    // pair was collided at, aged a step; the contact ends when the last goes (Bullet's
    // removeContactPoint calls the app's destroyed and ended callbacks). A sphere pair's
    // manifold is cleared every step instead.
    // A persistent manifold's refresh is the device's own: a pair it left without points has
    // none on stock either.
    if (!m_collidedAtValid || node->second.persistent) return false;
    const Key& k = node->first;
    if (leafShape(k.body0, k.sub0)->getShapeType() == SPHERE_SHAPE_PROXYTYPE &&
        leafShape(k.body1, k.sub1)->getShapeType() == SPHERE_SHAPE_PROXYTYPE)
        return false;
    const int r0 = rows.rowOf(k.body0), r1 = rows.rowOf(k.body1);
    if (r0 < 0 || r1 < 0 || size_t(std::max(r0, r1)) >= m_collidedAt.size()) return false;
    btPersistentManifold* m = node->second.manifold;
    Entry& e = node->second;
    const btTransform& t0 = m_collidedAt[size_t(r0)];
    const btTransform& t1 = m_collidedAt[size_t(r1)];
    const btScalar breaking = m->getContactBreakingThreshold();
    // Only while stock's broadphase would still hold the pair: the AABBs as its world expands
    // them (the contact threshold) and as its Dbvt leaves are fattened (0.05 m): a moving body's,
    // and a static one's too where the world updates every AABB each step (Bullet's default:
    // its first update, with the contact threshold, fattens the leaf it was inserted with, and
    // the leaf stays; a ball falling out of a static trigger keeps its point a step longer).
    // Stock's lazy removal of pairs that stopped overlapping is not followed.
    btVector3 min0, max0, min1, max1;
    k.body0->getCollisionShape()->getAabb(t0, min0, max0);
    k.body1->getCollisionShape()->getAabb(t1, min1, max1);
    const btScalar pad0 = breaking + (k.body0->isStaticObject() && !m_staticLeavesFattened ? 0 : btScalar(0.05));
    const btScalar pad1 = breaking + (k.body1->isStaticObject() && !m_staticLeavesFattened ? 0 : btScalar(0.05));
    if (!TestAabbAgainstAabb2(min0 - btVector3(pad0, pad0, pad0), max0 + btVector3(pad0, pad0, pad0),
                              min1 - btVector3(pad1, pad1, pad1), max1 + btVector3(pad1, pad1, pad1)))
        return false;
    for (int s = m->getNumContacts() - 1; s >= 0; --s) {
        btManifoldPoint& p = m->getContactPoint(s);
        p.m_positionWorldOnA = t0(p.m_localPointA);
        p.m_positionWorldOnB = t1(p.m_localPointB);
        p.m_distance1 = (p.m_positionWorldOnA - p.m_positionWorldOnB).dot(p.m_normalWorldOnB);
        p.m_lifeTime += refreshesPerStep(k.body0, k.body1);
        p.m_appliedImpulse = p.m_appliedImpulseLateral1 = p.m_appliedImpulseLateral2 = 0;
        const btVector3 drift = p.m_positionWorldOnB - (p.m_positionWorldOnA - p.m_normalWorldOnB * p.m_distance1);
        if (p.m_distance1 > breaking || drift.length2() > breaking * breaking) {
            const int last = m->getNumContacts() - 1;
            if (s != last && last < MANIFOLD_CACHE_SIZE) {  // the last point moves into s
                e.ids[s] = e.ids[last];
                e.moved[s] = e.moved[last];
            }
            m->removeContactPoint(s);
        }
    }
    return m->getNumContacts() > 0;
}

void ManifoldSync::noteCollidedAt(const RowMap& rows, bool staticLeavesFattened)
{
    m_staticLeavesFattened = staticLeavesFattened;
    m_collidedAt.resize(rows.size());
    forEachChunk(rows.size(), 4096, [&](size_t begin, size_t end, int) {
        for (size_t r = begin; r < end; ++r) {
            const btCollisionObject* o = rows.at(r);
            m_collidedAt[r] = o ? o->getWorldTransform() : btTransform::getIdentity();
        }
    });
    m_collidedAtValid = true;
}

void ManifoldSync::forget(Node* node)
{
    for (const btCollisionObject* o : {node->first.body0, node->first.body1}) {
        auto it = m_byObject.find(o);
        if (it == m_byObject.end()) continue;
        auto& list = it->second;
        list.erase(std::remove(list.begin(), list.end(), node), list.end());
        if (list.empty()) m_byObject.erase(it);
    }
    m_map.erase(node);
}

void ManifoldSync::releaseAll(btDispatcher* dispatcher)
{
    if (dispatcher)
        m_map.forEach([&](Node* node) {
            btPersistentManifold* m = node->second.manifold;
            if (!m) return;  // its body left: released then
            for (int j = 0; j < m->getNumContacts(); ++j) {
                btManifoldPoint& p = m->getContactPoint(j);
                if (p.m_userPersistentData && gContactDestroyedCallback) gContactDestroyedCallback(p.m_userPersistentData);
                p.m_userPersistentData = nullptr;
            }
            m->setNumContacts(0);
            dispatcher->releaseManifold(m);
        });
    m_map.clear();
    m_byObject.clear();
    m_live.clear();
    m_dead.clear();
    m_pending.clear();
    m_stockPairs.clear();
    m_uncollided.clear();
    m_compoundPairs.clear();
    m_wanted.clear();
    m_wantedSet.clear();
    m_wantedValid = false;
}

void ManifoldSync::removed(btDispatcher* dispatcher, const btCollisionObject* object)
{
    // Released at once (the app may delete the object next); the nodes wait for the next fill.
    auto it = m_byObject.find(object);
    if (it == m_byObject.end()) return;
    std::vector<Node*> nodes = std::move(it->second);
    m_byObject.erase(it);
    for (Node* node : nodes) {
        const btCollisionObject* other = node->first.body0 == object ? node->first.body1 : node->first.body0;
        auto o = m_byObject.find(other);
        if (o != m_byObject.end()) {
            o->second.erase(std::remove(o->second.begin(), o->second.end(), node), o->second.end());
            if (o->second.empty()) m_byObject.erase(o);
        }
        if (dispatcher && node->second.manifold) dispatcher->releaseManifold(node->second.manifold);
        node->second.manifold = nullptr;
        m_dead.insert(node);
    }
}

}  // namespace btgpu
