/* concave_manifold.h — a convex–concave pair's manifold as stock's btConvexConcaveCollisionAlgorithm
 * keeps it: one btPersistentManifold for the pair, into which each triangle the walk meets adds
 * the one point its algorithm finds (SphereTriangleDetector for a sphere, GJK/EPA against a
 * btTriangleShape with the concave shape's margin for every other convex), in the walk's order,
 * through addContactPoint (persistent_manifold.h: replace the nearest within the threshold, else
 * append, else sortCachedPoints), then one refreshContactPoints for the pair. The manifold is kept
 * with the convex as A (stock's body0), so the matching and the reduction read the convex's
 * points as stock's do. Each point carries its triangle's key (btgTriangleKey).
 * The solver's contact rows carry one normal, stock's points one each: the points are split into
 * groups whose normals lie within BTG_MESH_MERGE_COS of the group's first, each group one device
 * manifold (a box across a crease keeps both faces' normals). */
#ifndef BTG_CONCAVE_MANIFOLD_H
#define BTG_CONCAVE_MANIFOLD_H
#include "contact_rows.h"
#include "compound.h"
#include "persistent_manifold.h"
#include "triangle_contacts.h"

/* btConvexTriangleCallback::processTriangle's first test (TestTriangleAgainstAabb2): the triangle
 * (the concave body's frame, scaled) against the convex's box there, grown by the triangles'
 * margin only. The BVH's quantized leaves are looser than the triangle's own box. */
static inline int btgTriangleTouchesConvexBox(BtgCollider c, BtgCollider mesh, BtgTriangleVerts tri)
{
    const BtgAabb b = btgConvexBoxInConcave(c.pose.pos, c.pose.rot, c.shape, mesh.pose.pos, mesh.pose.rot, mesh.shape, 0.0f);
    for (int k = 0; k < 3; ++k) {
        const float v0 = btgComp(tri.v[0], k), v1 = btgComp(tri.v[1], k), v2 = btgComp(tri.v[2], k);
        if (btgMin(btgMin(v0, v1), v2) > btgComp(b.hi, k)) return 0;
        if (btgMax(btgMax(v0, v1), v2) < btgComp(b.lo, k)) return 0;
    }
    return 1;
}

/* The one point stock's algorithm for (convex, triangle) adds: none for a triangle outside the
 * convex's box, else the sphere's detector, or GJK against the triangle
 * (btgCollideConvexTriangle). A manifold of at most one point. */
static inline BtgManifold btgCollideTrianglePoint(BtgCollider c, BtgCollider mesh, BtgTriangleVerts tri,
                                                  BTG_SHAPE_TABLES, float threshold)
{
    if (!btgTriangleTouchesConvexBox(c, mesh, tri)) return btgEmptyManifold(c.body, mesh.body);
    if (c.shape.type == BTG_SHAPE_SPHERE)
        return btgCollideSphereTriangle(c, mesh, tri, verts, faces, indices, edges, threshold);
    return btgCollideConvexTriangle(c, mesh, tri, verts, faces, indices, edges, threshold);
}

/* The manifold the pair kept last substep (convex body first), found through the warm-start
 * cache as btgPreviousManifold finds a GJK pair's: the entry of the pair's first manifold, whose
 * concave key is the whole shape's. Empty for a new pair or another kind's entry. */
static inline BtgPersistentManifold btgPreviousConcave(BtgPair p, int kind, int convexBody, int concaveBody,
                                                       BTG_CHILD_TABLE, BTG_CONST_GLOBAL uint* counters,
                                                       BTG_CONST_GLOBAL BtgCachedContact* cache, int cacheCapacity,
                                                       BTG_CONST_GLOBAL BtgPersistentManifold* gjkCache, int gjkCapacity)
{
    const BtgManifold key = btgPairKeyManifold(p, children);
    const uint capacity = (uint)(cacheCapacity < gjkCapacity ? cacheCapacity : gjkCapacity);
    const uint prevCount = counters[BTG_COUNTER_PREV_CONTACTS] < capacity ? counters[BTG_COUNTER_PREV_CONTACTS] : capacity;
    const int j = btgFindPrevContact(cache, (int)prevCount, key);
    if (j >= 0) {
        const BtgPersistentManifold prev = gjkCache[j];
        if (prev.bodyA == convexBody && prev.bodyB == concaveBody && prev.kind == kind && prev.numPoints >= 0 &&
            prev.numPoints <= BTG_MAX_POINTS)
            return prev;
    }
    return btgEmptyPersistent(convexBody, concaveBody, kind);
}

/* One substep of the pair's manifold: prev, then the point of each of its triangles'
 * manifolds region[first, end) (in the pair's order, at most one point each, in the walk's
 * order), then the refresh at the poses now. cv is the convex (A of the result), cc the concave;
 * concaveIsA says how the region's manifolds are turned. A compound's child (`child`) is first
 * refreshed too, as btCompoundCollisionAlgorithm refreshes its child algorithms' manifolds
 * before they collide (the points gone, the distances sortCachedPoints compares now's). dist
 * receives each kept point's refreshed distance. */
static inline BtgPersistentManifold btgConcaveStep(BtgPersistentManifold prev, BtgCollider cv, BtgCollider cc,
                                                   BTG_CONST_GLOBAL BtgManifold* region, int first, int end,
                                                   int concaveIsA, int child, float threshold, float* dist)
{
    BtgPersistentManifold m = child ? btgChildPreRefresh(prev, cv.pose, cc.pose, threshold) : prev;
    m.added = -1;
    m.addedMask = 0u;
    m.addedPoints = 0u;
    btgPersistentBegin(&m, dist);
    int adds = 0;
    for (int s = first; s < end; ++s) {
        if (region[s].numPoints <= 0) continue;
        const BtgManifoldPoint q = region[s].points[0];
        BtgFloat4 n = btgPointNormal(q), onB = btgPointOnB(q);
        if (concaveIsA) { /* the point on the concave side is the pair's A side */
            onB = onB + n * q.distance;
            n = -n;
        }
        btgPersistentAdd(&m, dist, &prev, n, onB, q.distance, cv.pose, cc.pose, threshold, q.featureId);
        adds += q.distance <= threshold;
    }
    if (adds > 1) m.added = -2; /* several points added this substep */
    btgPersistentRefresh(&m, dist, cv.pose, cc.pose, threshold);
    return m;
}

/* The groups of the manifold's points: group[k] for point k, points of one group with normals
 * within BTG_MESH_MERGE_COS of its first point's, numbered in the order of their first points.
 * Returns the number of groups. */
static inline int btgConcaveGroups(const BtgPersistentManifold* m, int* group)
{
    int n = 0, lead[BTG_MAX_POINTS];
    for (int k = 0; k < m->numPoints; ++k) {
        group[k] = -1;
        for (int g = 0; g < n && group[k] < 0; ++g)
            if (btgDot3(m->normal[k], m->normal[lead[g]]) >= BTG_MESH_MERGE_COS) group[k] = g;
        if (group[k] < 0) {
            lead[n] = k;
            group[k] = n++;
        }
    }
    return n;
}

/* Device manifold g of the pair (a, b) (its pair order): the points of group g (every point when
 * g < 0), each on the concave surface at the pose now with its own normal, refreshed distance and
 * triangle key; the concave side's key (BTG_NO_SUB_SHAPE, -1 - g) names the group (the whole
 * shape's for the first, so the next substep finds the pair's entry), the convex side's its
 * compound child's. *order receives, from *emitted on, each emitted point's index in m. */
static inline BtgManifold btgConcaveGroupManifold(const BtgPersistentManifold* m, const float* dist, const int* group,
                                                  int g, BtgPair p, BtgPose concavePose, int concaveIsA,
                                                  float threshold, BTG_CHILD_TABLE, int* order, int* emitted)
{
    BtgManifold out = btgEmptyManifold(m->bodyA, m->bodyB);
    for (int k = 0; k < m->numPoints; ++k) {
        if (g >= 0 && group[k] != g) continue;
        btgAddPoint(&out, btgXyz(m->normal[k]), btgPoseApply(concavePose, m->localB[k]), dist[k], m->subShape[k]);
        order[(*emitted)++] = k;
    }
    const int key = g > 0 ? -1 - g : BTG_NO_SUB_SHAPE;
    if (concaveIsA) {
        out = btgSwapManifold(out);
        out.partIdA = BTG_NO_SUB_SHAPE;
        out.indexA = key;
    } else {
        out.partIdB = BTG_NO_SUB_SHAPE;
        out.indexB = key;
    }
    return btgWithChildKeys(btgWithThreshold(out, threshold), p, children);
}

/* Bit e of the pair's added points in emission order (order[e]: the point's index in m). */
static inline uint btgAddedInOrder(const BtgPersistentManifold* m, const int* order, int emitted)
{
    uint bits = 0u;
    for (int e = 0; e < emitted; ++e)
        if ((m->addedMask >> m->id[order[e]]) & 1u) bits |= 1u << e;
    return bits;
}

/* The pair's stepped manifold m (refreshed distances dist) written as its device manifolds:
 * with one group at the pair's own slot; with several, group g at base + lo + g over its
 * triangles' manifolds (which btgConcaveStep has read), the slot left empty; with more groups
 * than triangles (old points kept beside fewer triangles now) all points at the slot in one,
 * whose rows then take the first point's normal. Sets m's addedPoints; returns the range. */
static inline BtgManifoldRange btgConcaveWrite(BtgPersistentManifold* m, const float* dist, BtgPair p, uint slot,
                                               uint lo, uint hi, BtgPose concavePose, int concaveIsA, float threshold,
                                               BTG_CHILD_TABLE, BTG_GLOBAL BtgManifold* manifolds, uint base)
{
    int group[BTG_MAX_POINTS], order[BTG_MAX_POINTS], emitted = 0;
    const int groups = btgConcaveGroups(m, group);
    BtgManifoldRange r;
    if (groups <= 1 || hi - lo < (uint)groups) {
        manifolds[slot] =
            btgConcaveGroupManifold(m, dist, group, -1, p, concavePose, concaveIsA, threshold, children, order, &emitted);
        r.start = (int)slot;
        r.count = m->numPoints > 0 ? 1 : 0;
    } else {
        for (int g = 0; g < groups; ++g)
            manifolds[base + lo + (uint)g] = btgConcaveGroupManifold(m, dist, group, g, p, concavePose, concaveIsA,
                                                                     threshold, children, order, &emitted);
        manifolds[slot] = btgWithChildKeys(btgEmptyManifold(p.a, p.b), p, children);
        r.start = (int)(base + lo);
        r.count = groups;
    }
    m->addedPoints = btgAddedInOrder(m, order, emitted);
    return r;
}

#endif
