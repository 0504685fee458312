/* polyhedral_contacts.h — stock's contacts of two hulls that both have polyhedral features
 * (btConvexConvexAlgorithm with m_enableSatConvex off, Bullet's default), into the pair's
 * persistent manifold: GJK between the full shapes gives the normal and a point, added with the
 * margins taken off (the points lie on the polyhedra; btWithoutMarginResult); only when the
 * polyhedra overlap is the face of B most along the normal clipped against the side planes of
 * A's face most against it (btPolyhedralContactClipping::clipHullAgainstHull and
 * clipFaceAgainstHull), and every clipped corner within the threshold of A's face plane, its
 * depth clamped from below, is added in the order Bullet adds it; then the refresh. The
 * sequence of adds is what makes the manifold stock's: a new point replaces the cached one
 * nearest to it or, with four held, the one sortCachedPoints picks. */
#ifndef BTG_POLYHEDRAL_CONTACTS_H
#define BTG_POLYHEDRAL_CONTACTS_H
#include "gjk.h"
#include "persistent_manifold.h"
#include "box_box.h"

/* Corners of a clipped face: Bullet's arrays grow as needed; a face of n corners clipped by m
 * planes has at most n + m, so faces up to 32 corners clipped by faces up to 32 are exact. A
 * corner beyond the buffer is not added. */
#define BTG_POLY_CLIP_MAX 64

/* btPolyhedralContactClipping::clipFace: the part of polygon `in` behind the plane
 * n.x + e < 0 (Sutherland–Hodgman from the last corner, as Bullet walks it). */
static inline int btgClipFaceBehind(const BtgFloat4* in, int count, BtgFloat4 n, float e, BtgFloat4* out)
{
    int m = 0;
    if (count < 2) return 0;
    BtgFloat4 first = in[count - 1];
    float ds = btgDot3(n, first) + e;
    for (int i = 0; i < count; ++i) {
        BtgFloat4 end = in[i];
        float de = btgDot3(n, end) + e;
        if (ds < 0.0f) {
            if (m < BTG_POLY_CLIP_MAX) out[m++] = de < 0.0f ? end : first + (end - first) * (ds * 1.0f / (ds - de));
        } else if (de < 0.0f) {
            if (m < BTG_POLY_CLIP_MAX) out[m++] = first + (end - first) * (ds * 1.0f / (ds - de));
            if (m < BTG_POLY_CLIP_MAX) out[m++] = end;
        }
        first = end;
        ds = de;
    }
    return m;
}

/* The face of hull h whose world normal has the largest (sign 1) or smallest (sign -1) dot
 * with n; the first on a tie, as Bullet's strict comparisons. */
static inline int btgFaceAlong(BtgCollider h, BTG_CONST_GLOBAL BtgFace* faces, BtgFloat4 n, float sign)
{
    int best = -1;
    float bestDot = 0.0f;
    for (int f = 0; f < h.shape.numFaces; ++f) {
        float d = sign * btgDot3(btgMat3MulVec(h.pose.rot, faces[h.shape.firstFace + f].plane), n);
        if (best < 0 || d > bestDot) {
            best = f;
            bestDot = d;
        }
    }
    return best;
}

/* clipHullAgainstHull with Bullet's arguments: the normal from B towards A, minDist the depth
 * floor, maxDist the threshold. */
static inline void btgClipHullsIntoManifold(BtgPersistentManifold* m, float* dist, const BtgPersistentManifold* prev,
                                            BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, BtgFloat4 normal,
                                            float minDist, float maxDist)
{
    (void)edges;
    const BtgFloat4 n = btgNormalize3(normal);
    const int faceB = btgFaceAlong(b, faces, n, 1.0f);
    const int faceA = btgFaceAlong(a, faces, n, -1.0f);
    if (faceB < 0 || faceA < 0) return;
    BtgFloat4 bufA[BTG_POLY_CLIP_MAX], bufB[BTG_POLY_CLIP_MAX];
    BtgFloat4* in = bufA;
    BtgFloat4* out = bufB;
    const BtgFace fb = faces[b.shape.firstFace + faceB];
    int count = 0;
    for (int i = 0; i < fb.numIndices && count < BTG_POLY_CLIP_MAX; ++i)
        in[count++] = btgPoseApply(b.pose, btgXyz(verts[b.shape.firstVertex + indices[fb.firstIndex + i]]));
    const BtgFace fa = faces[a.shape.firstFace + faceA];
    const BtgFloat4 normalA = btgMat3MulVec(a.pose.rot, btgXyz(fa.plane));
    for (int e0 = 0; e0 < fa.numIndices; ++e0) {
        BtgFloat4 va = btgXyz(verts[a.shape.firstVertex + indices[fa.firstIndex + e0]]);
        BtgFloat4 vb = btgXyz(verts[a.shape.firstVertex + indices[fa.firstIndex + (e0 + 1) % fa.numIndices]]);
        BtgFloat4 worldEdge = btgMat3MulVec(a.pose.rot, va - vb);
        BtgFloat4 planeN = -btgCross3(worldEdge, normalA);
        float planeE = -btgDot3(btgPoseApply(a.pose, va), planeN);
        count = btgClipFaceBehind(in, count, planeN, planeE, out);
        BtgFloat4* t = in;
        in = out;
        out = t;
    }
    const float planeE = fa.plane.w - btgDot3(normalA, a.pose.pos);
    for (int i = 0; i < count; ++i) {
        float depth = btgDot3(normalA, in[i]) + planeE;
        if (depth <= minDist) depth = minDist;
        if (depth <= maxDist) btgPersistentAdd(m, dist, prev, n, in[i], depth, a.pose, b.pose, maxDist, BTG_FEATURE_UNKNOWN);
    }
}

/* One substep of a featured hull pair's manifold (the pair order: A = a). */
static inline BtgPersistentManifold btgPolyhedralStep(BtgPersistentManifold prev, BtgCollider a, BtgCollider b,
                                                      BTG_SHAPE_TABLES, float threshold, float* dist)
{
    BtgPersistentManifold m = prev;
    m.added = -1;
    m.addedMask = 0u;
    btgPersistentBegin(&m, dist);
    const BtgConvexPoint g = btgGjkPoint(a, b, verts, threshold);
    if (g.valid) {
        const float d = g.distance + a.shape.margin + b.shape.margin;
        btgPersistentAdd(&m, dist, &prev, g.normal, g.pointB - g.normal * b.shape.margin, d, a.pose, b.pose,
                         threshold, BTG_FEATURE_UNKNOWN);
        if (d < 0.0f) {
            btgClipHullsIntoManifold(&m, dist, &prev, a, b, verts, faces, indices, edges, g.normal, d - threshold,
                                     threshold);
            m.added = -2; /* the clipped points too: several added this substep */
        }
    }
    btgPersistentRefresh(&m, dist, a.pose, b.pose, threshold);
    return m;
}

/* Every pair with a persistent manifold: featured hull pairs as above, two boxes as stock's box
 * algorithm (box_box.h, the SAT program's), the others the one point their algorithm adds (gjk.h). */
static inline BtgPersistentManifold btgPairStep(BtgPersistentManifold prev, BtgCollider a, BtgCollider b,
                                                BTG_SHAPE_TABLES, float threshold, float* dist)
{
    if (a.shape.type == BTG_SHAPE_HULL && b.shape.type == BTG_SHAPE_HULL)
        return btgPolyhedralStep(prev, a, b, verts, faces, indices, edges, threshold, dist);
    if (a.shape.type == BTG_SHAPE_BOX && b.shape.type == BTG_SHAPE_BOX) return btgBoxBoxStep(prev, a, b, threshold, dist);
    const BtgConvexPoint p = btgConvexPairPoint(a, b, verts, threshold);
    /* Bullet 3.24's btSphereSphereCollisionAlgorithm clears its manifold every step
     * (CLEAR_MANIFOLD): two spheres hold only the point made now, while they touch */
    if (a.shape.type == BTG_SHAPE_SPHERE && b.shape.type == BTG_SHAPE_SPHERE) prev.numPoints = 0;
    return btgPersistentStep(prev, p, a.pose, b.pose, threshold, dist);
}

/* A pair's manifold when it has no previous one (its first step): the routine every row of the
 * GJK program names, so the CPU reference and tests can call it like any other. */
static inline BtgManifold btgCollideGjk(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    float dist[BTG_MAX_POINTS];
    BtgPersistentManifold pm =
        btgPairStep(btgEmptyPersistent(a.body, b.body, 0), a, b, verts, faces, indices, edges, threshold, dist);
    return btgManifoldFromPersistent(pm, dist, b.pose);
}

#endif
