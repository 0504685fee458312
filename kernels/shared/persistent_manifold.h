/* persistent_manifold.h — Bullet's btPersistentManifold for the GJK pair kinds: each substep
 * adds the one point its algorithm found (btManifoldResult::addContactPoint: replace the
 * cached point nearest in A's frame within the breaking threshold, keeping its identity, else
 * append, or when 4 are held replace the one sortCachedPoints picks: keep the deepest and the
 * largest area), then refreshes every point (refreshContactPoints: points kept in both bodies'
 * frames move with them; a point farther apart than the threshold along its normal, or drifted
 * sideways by more than it, is removed, the last point taking its place). Identities (0..7)
 * carry the warm start: a replaced point keeps its impulses as in Bullet, a new one starts
 * cold; a friction anchor (CF_HAS_FRICTION_ANCHOR) inside its friction cone is not replaced at
 * all (replaceContactPoint), so it drifts with the bodies until the refresh drops it. */
#ifndef BTG_PERSISTENT_MANIFOLD_H
#define BTG_PERSISTENT_MANIFOLD_H
#include "narrowphase_common.h"

static inline BtgPersistentManifold btgEmptyPersistent(int bodyA, int bodyB, int kind)
{
    BtgPersistentManifold m;
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        m.localA[k] = btgZero4();
        m.localB[k] = btgZero4();
        m.normal[k] = btgMake4(0.0f, 1.0f, 0.0f, 0.0f);
        m.id[k] = 0u;
        m.subShape[k] = BTG_FEATURE_UNKNOWN;
    }
    m.bodyA = bodyA;
    m.bodyB = bodyB;
    m.numPoints = 0;
    m.kind = kind;
    m.added = -1;
    m.addedMask = 0u;
    m.anchorMask = 0u;
    m.addedPoints = 0u;
    return m;
}

/* calcArea4Points with gContactCalcArea3Points (Bullet's default): |(p0 - p1) x (p3 - p2)|^2. */
static inline float btgArea3(BtgFloat4 p0, BtgFloat4 p1, BtgFloat4 p2, BtgFloat4 p3)
{
    BtgFloat4 c = btgCross3(p0 - p1, p3 - p2);
    return btgDot3(c, c);
}

/* btPersistentManifold::sortCachedPoints: the slot the new point (A-frame point pa, distance
 * d) replaces in a full manifold. */
static inline int btgSortCachedPoints(const BtgPersistentManifold* m, const float* dist, BtgFloat4 pa, float d)
{
    int deepest = -1;
    float maxPen = d;
    for (int i = 0; i < 4; ++i)
        if (dist[i] < maxPen) {
            deepest = i;
            maxPen = dist[i];
        }
    float res[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (deepest != 0) res[0] = btgArea3(pa, m->localA[1], m->localA[3], m->localA[2]);
    if (deepest != 1) res[1] = btgArea3(pa, m->localA[0], m->localA[3], m->localA[2]);
    if (deepest != 2) res[2] = btgArea3(pa, m->localA[0], m->localA[3], m->localA[1]);
    if (deepest != 3) res[3] = btgArea3(pa, m->localA[0], m->localA[2], m->localA[1]);
    /* btVector4::closestAxis4: the largest absolute value, the first on a tie */
    int best = 0;
    for (int i = 1; i < 4; ++i)
        if (btgAbs(res[i]) > btgAbs(res[best])) best = i;
    return best;
}

/* A fresh identity: none the manifold held before this step, nor one a point added in this step
 * took (so a new point never inherits the warm start of one it does not continue). With at most
 * 4 points before and 4 after, one of the 8 is always free. */
static inline uint btgFreshId(const BtgPersistentManifold* prev, const BtgPersistentManifold* now)
{
    for (uint id = 0u; id < 8u; ++id) {
        int used = 0;
        for (int k = 0; k < prev->numPoints; ++k) used |= prev->id[k] == id;
        for (int k = 0; k < now->numPoints; ++k) used |= now->id[k] == id;
        if (!used) return id;
    }
    return 7u;
}

static inline void btgRemovePersistentPoint(BtgPersistentManifold* m, float* dist, int i)
{
    const int last = m->numPoints - 1;
    if (i != last) {
        m->localA[i] = m->localA[last];
        m->localB[i] = m->localB[last];
        m->normal[i] = m->normal[last];
        m->id[i] = m->id[last];
        m->subShape[i] = m->subShape[last];
        dist[i] = dist[last];
    }
    m->numPoints = last;
}

/* The cached points' distances from the last refresh (Bullet's m_distance1, what
 * sortCachedPoints compares), into dist. */
static inline void btgPersistentBegin(const BtgPersistentManifold* m, float* dist)
{
    for (int k = 0; k < BTG_MAX_POINTS; ++k) dist[k] = 0.0f;
    for (int k = 0; k < m->numPoints; ++k) dist[k] = m->normal[k].w;
}

/* btManifoldResult::addContactPoint: one point (normal from B towards A, the point on B, its
 * signed distance, its sub-shape key: a triangle's for a concave pair, else BTG_FEATURE_UNKNOWN)
 * into the manifold, prev being the manifold as the step began. */
static inline void btgPersistentAdd(BtgPersistentManifold* m, float* dist, const BtgPersistentManifold* prev,
                                    BtgFloat4 normal, BtgFloat4 pointB, float distance, BtgPose pa, BtgPose pb,
                                    float threshold, uint subShape)
{
    if (distance > threshold) return;
    BtgFloat4 worldA = pointB + normal * distance;
    BtgFloat4 la = btgPoseApplyInv(pa, worldA), lb = btgPoseApplyInv(pb, pointB);
    int slot = -1;
    float shortest = threshold * threshold;
    for (int k = 0; k < m->numPoints; ++k) {
        BtgFloat4 d = m->localA[k] - la;
        float d2 = btgDot3(d, d);
        if (d2 < shortest) {
            shortest = d2;
            slot = k;
        }
    }
    uint id;
    if (slot >= 0) {
        id = m->id[slot]; /* replaceContactPoint keeps the impulses and the lifetime */
        /* ... and a friction anchor whose lateral impulse lay inside its friction cone keeps
         * the old point itself (its body-frame points, normal and distance); the callbacks still
         * see it as the point this collision gave */
        if ((prev->anchorMask >> id) & 1u) {
            m->added = (int)id;
            m->addedMask |= 1u << id;
            return;
        }
    } else if (m->numPoints < BTG_MAX_POINTS) {
        id = btgFreshId(prev, m);
        slot = m->numPoints++;
    } else {
        slot = btgSortCachedPoints(m, dist, la, distance);
        id = btgFreshId(prev, m);
    }
    m->localA[slot] = la;
    m->localB[slot] = lb;
    m->normal[slot] = btgXyz(normal);
    m->id[slot] = id;
    m->subShape[slot] = subShape;
    m->added = (int)id;
    m->addedMask |= 1u << id;
    dist[slot] = distance;
}

/* refreshContactPoints: every point from its two body-frame points, removed back to front;
 * each kept point's refreshed distance left in dist and in its normal's w. */
static inline void btgPersistentRefresh(BtgPersistentManifold* m, float* dist, BtgPose pa, BtgPose pb, float threshold)
{
    for (int k = m->numPoints - 1; k >= 0; --k) {
        BtgFloat4 wa = btgPoseApply(pa, m->localA[k]), wb = btgPoseApply(pb, m->localB[k]);
        dist[k] = btgDot3(wa - wb, m->normal[k]);
    }
    for (int k = m->numPoints - 1; k >= 0; --k) {
        BtgFloat4 wa = btgPoseApply(pa, m->localA[k]), wb = btgPoseApply(pb, m->localB[k]);
        if (dist[k] > threshold) {
            btgRemovePersistentPoint(m, dist, k);
            continue;
        }
        BtgFloat4 drift = wb - (wa - m->normal[k] * dist[k]);
        if (btgDot3(drift, drift) > threshold * threshold) btgRemovePersistentPoint(m, dist, k);
    }
    for (int k = 0; k < m->numPoints; ++k) m->normal[k].w = dist[k];
}

/* btCompoundCollisionAlgorithm's refresh of its child algorithms' manifolds before the children
 * collide: the points kept last substep refreshed at the poses now (a compound child's pair
 * starts its substep from this; then its own algorithm adds and refreshes again). */
static inline BtgPersistentManifold btgChildPreRefresh(BtgPersistentManifold m, BtgPose pa, BtgPose pb, float threshold)
{
    float dist[BTG_MAX_POINTS];
    btgPersistentBegin(&m, dist);
    btgPersistentRefresh(&m, dist, pa, pb, threshold);
    return m;
}

/* One substep of the pair's manifold: prev (empty for a new pair), the point found now (if
 * valid), the poses now. dist receives each kept point's refreshed distance. */
static inline BtgPersistentManifold btgPersistentStep(BtgPersistentManifold prev, BtgConvexPoint p, BtgPose pa,
                                                      BtgPose pb, float threshold, float* dist)
{
    BtgPersistentManifold m = prev;
    m.added = -1;
    m.addedMask = 0u;
    btgPersistentBegin(&m, dist);
    if (p.valid) btgPersistentAdd(&m, dist, &prev, p.normal, p.pointB, p.distance, pa, pb, threshold, BTG_FEATURE_UNKNOWN);
    btgPersistentRefresh(&m, dist, pa, pb, threshold);
    return m;
}

/* The manifold the contact stages read: each point on B's surface now, with its own normal and
 * refreshed distance, identity BTG_FEATURE_SINGLE | id. */
static inline BtgManifold btgManifoldFromPersistent(BtgPersistentManifold pm, const float* dist, BtgPose pb)
{
    BtgManifold m = btgEmptyManifold(pm.bodyA, pm.bodyB);
    for (int k = 0; k < pm.numPoints; ++k)
        btgAddPoint(&m, btgXyz(pm.normal[k]), btgPoseApply(pb, pm.localB[k]), dist[k], BTG_FEATURE_SINGLE | pm.id[k]);
    return m;
}

#endif
