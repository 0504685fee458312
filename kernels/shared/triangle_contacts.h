/* triangle_contacts.h — contacts of a convex shape against one mesh triangle (the rows of
 * program "narrowphase_mesh" in pair_kinds.h): sphere–triangle as Bullet's SphereTriangleDetector
 * computes it, hull–triangle by SAT rejection and clipping against the triangle as a face
 * (clip.h's scheme; the triangle's normal, turned to the hull's side, for every point). A
 * triangle is passed by value (its three vertices in the mesh body's frame), so later convex
 * kinds can take it as a small convex of their own. Canonical roles: the convex is A, the
 * mesh B; the kernel swaps when the pair has them the other way round. */
#ifndef BTG_TRIANGLE_CONTACTS_H
#define BTG_TRIANGLE_CONTACTS_H
#include "clip.h"
#include "concave.h"
#include "gjk.h"
#include "round_contacts.h"

#define BTG_FLT_EPSILON 1.1920929e-07f /* Bullet's SIMD_EPSILON (float build) */

/* Bullet's SegmentSqrDistance (SphereTriangleDetector.cpp). */
static inline float btgSegmentSqrDistance(BtgFloat4 from, BtgFloat4 to, BtgFloat4 p, BtgFloat4* nearest)
{
    BtgFloat4 diff = p - from;
    BtgFloat4 v = to - from;
    float t = btgDot3(v, diff);
    if (t > 0.0f) {
        float dotVV = btgDot3(v, v);
        if (t < dotVV) {
            t = t * (1.0f / dotVV); /* btScalar /= : times the reciprocal */
            diff = diff - v * t;
        } else {
            t = 1.0f;
            diff = diff - v;
        }
    } else {
        t = 0.0f;
    }
    *nearest = from + v * t;
    return btgDot3(diff, diff);
}

/* SphereTriangleDetector::pointInTriangle. */
static inline int btgPointInTriangle(BtgTriangleVerts t, BtgFloat4 n, BtgFloat4 p)
{
    BtgFloat4 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[1], e3 = t.v[0] - t.v[2];
    float r1 = btgDot3(btgCross3(e1, n), p - t.v[0]);
    float r2 = btgDot3(btgCross3(e2, n), p - t.v[1]);
    float r3 = btgDot3(btgCross3(e3, n), p - t.v[2]);
    return (r1 > 0.0f && r2 > 0.0f && r3 > 0.0f) || (r1 <= 0.0f && r2 <= 0.0f && r3 <= 0.0f);
}

/* SphereTriangleDetector::collide in the mesh's frame: the face when the centre projects into
 * the triangle, else the nearest edge within radius + threshold; one point on the triangle,
 * normal from it to the centre (the triangle's own normal when the centre lies on it). */
static inline BtgManifold btgCollideSphereTriangle(BtgCollider s, BtgCollider mesh, BtgTriangleVerts tri,
                                                   BTG_SHAPE_TABLES, float threshold)
{
    BTG_UNUSED_SHAPE_TABLES;
    BtgManifold m = btgEmptyManifold(s.body, mesh.body);
    BtgFloat4 c = btgPoseApplyInv(mesh.pose, s.pose.pos);
    float radius = s.shape.param.x;
    float rt = radius + threshold;
    BtgFloat4 n = btgCross3(tri.v[1] - tri.v[0], tri.v[2] - tri.v[0]);
    float l2 = btgDot3(n, n);
    if (!(l2 >= BTG_FLT_EPSILON * BTG_FLT_EPSILON)) return m;
    n = n * (1.0f / btgSqrt(l2));
    float fromPlane = btgDot3(c - tri.v[0], n);
    if (fromPlane < 0.0f) {
        fromPlane = -fromPlane;
        n = -n;
    }
    if (!(fromPlane < rt)) return m;
    int has = 0;
    BtgFloat4 contact = btgZero4();
    if (btgPointInTriangle(tri, n, c)) {
        has = 1;
        contact = c - n * fromPlane;
    } else {
        float minD2 = rt * rt;
        for (int i = 0; i < 3; ++i) {
            BtgFloat4 nearest;
            float d2 = btgSegmentSqrDistance(tri.v[i], tri.v[(i + 1) % 3], c, &nearest);
            if (d2 < minD2) {
                minD2 = d2;
                has = 1;
                contact = nearest;
            }
        }
    }
    if (!has) return m;
    BtgFloat4 toCentre = c - contact;
    float d2 = btgDot3(toCentre, toCentre);
    if (!(d2 < rt * rt)) return m;
    BtgFloat4 nl;
    float depth;
    if (d2 > BTG_FLT_EPSILON) {
        float dist = btgSqrt(d2);
        nl = toCentre * (1.0f / btgLength3(toCentre));
        depth = dist - radius;
    } else {
        nl = n;
        depth = -radius;
    }
    btgAddPoint(&m, btgMat3MulVec(mesh.pose.rot, nl), btgPoseApply(mesh.pose, contact), depth, BTG_FEATURE_SINGLE);
    return m;
}

/* Separation of hull h (A) and the world triangle w (B) along d; *axis: d or -d, from A to B. */
static inline float btgHullTriangleSeparation(BtgCollider h, BTG_CONST_GLOBAL BtgFloat4* verts, const BtgFloat4* w,
                                              BtgFloat4 d, BtgFloat4* axis)
{
    float loA, hiA;
    btgHullInterval(h, verts, d, &loA, &hiA);
    float p0 = btgDot3(d, w[0]), p1 = btgDot3(d, w[1]), p2 = btgDot3(d, w[2]);
    float loB = btgMin(p0, btgMin(p1, p2)), hiB = btgMax(p0, btgMax(p1, p2));
    float overlapPlus = hiA - loB, overlapMinus = hiB - loA;
    if (overlapPlus <= overlapMinus) {
        *axis = d;
        return -overlapPlus;
    }
    *axis = -d;
    return -overlapMinus;
}

/* Clips polygon poly[0, n) (labels alongside) by the planes side[k].xyz . p <= side[k].w; the
 * result is left in poly. */
static inline int btgClipBySides(BtgFloat4* poly, uint* labels, int n, const BtgFloat4* side, const uint* sideLabel,
                                 int numSides)
{
    BtgFloat4 tmp[BTG_MAX_POLY];
    uint tmpLabels[BTG_MAX_POLY];
    for (int k = 0; k < numSides && n > 0; ++k) {
        n = btgClipPolygon(poly, labels, n, btgXyz(side[k]), side[k].w, sideLabel[k], tmp, tmpLabels);
        for (int i = 0; i < n; ++i) {
            poly[i] = tmp[i];
            labels[i] = tmpLabels[i];
        }
    }
    return n;
}

/* Hull h (A) against one triangle (B): rejected when any SAT axis (the hull's faces, the
 * triangle's normal, the edge pairs) separates them beyond the threshold; else the triangle is
 * the reference face and the hull's most anti-parallel face is clipped by its sides. Reduced to
 * at most 4 points with the triangle's normal. */
static inline BtgManifold btgCollideHullTriangle(BtgCollider h, BtgCollider mesh, BtgTriangleVerts tri,
                                                 BTG_SHAPE_TABLES, float threshold)
{
    BtgManifold m = btgEmptyManifold(h.body, mesh.body);
    BtgFloat4 w[3];
    for (int k = 0; k < 3; ++k) w[k] = btgPoseApply(mesh.pose, tri.v[k]);
    BtgFloat4 nt = btgCross3(w[1] - w[0], w[2] - w[0]);
    float ntLen = btgLength3(nt);
    if (!(ntLen > 1e-12f) || h.shape.numFaces == 0) return m;
    nt = nt * (1.0f / ntLen);
    const float margins = h.shape.margin + mesh.shape.margin;
    const float reject = threshold + margins;
    /* Apart along some axis by more than the threshold: no contact. The axes only reject: a
     * triangle is a piece of a surface, so a hull in contact range of it takes its normal,
     * turned to the side of the hull's centre. Bullet's per-triangle GJK gives, where a hull
     * overlaps a triangle's edge by less than it sinks into the plane, the edge's normal: a
     * sideways "ghost" push at every internal edge of a flat mesh (what
     * btAdjustInternalEdgeContacts exists to remove, behind gContactAddedCallback). */
    BtgFloat4 axis;
    if (btgHullTriangleSeparation(h, verts, w, nt, &axis) > reject) return m;
    for (int f = 0; f < h.shape.numFaces; ++f)
        if (btgHullTriangleSeparation(h, verts, w, btgMat3MulVec(h.pose.rot, faces[h.shape.firstFace + f].plane), &axis) >
            reject)
            return m;
    for (int i = 0; i < h.shape.numEdges; ++i) {
        BtgFloat4 ea = btgMat3MulVec(h.pose.rot, edges[h.shape.firstEdge + i]);
        for (int j = 0; j < 3; ++j) {
            BtgFloat4 eb = w[(j + 1) % 3] - w[j];
            float ebLen = btgLength3(eb);
            if (!(ebLen > 0.0f)) continue;
            BtgFloat4 c = btgCross3(ea, eb * (1.0f / ebLen));
            float len = btgLength3(c);
            if (len < BTG_SAT_PARALLEL) continue;
            if (btgHullTriangleSeparation(h, verts, w, c * (1.0f / len), &axis) > reject) return m;
        }
    }
    /* The triangle is the reference face; the hull's face most anti-parallel to its normal is
     * clipped by the triangle's three side planes. */
    const BtgFloat4 nRef = btgDot3(nt, btgXyz(h.pose.pos) - w[0]) >= 0.0f ? nt : -nt; /* towards the hull */
    const int faceA = btgExtremeFace(h, faces, nRef, -1.0f);
    BtgFace inf = faces[h.shape.firstFace + faceA];
    BtgFloat4 poly[BTG_MAX_POLY];
    uint labels[BTG_MAX_POLY];
    BtgFloat4 side[3];
    uint sideLabel[3];
    int n = 0;
    for (int k = 0; k < inf.numIndices && n < BTG_MAX_POLY; ++k) {
        poly[n] = btgPoseApply(h.pose, btgFaceVertex(h.shape, inf, verts, indices, k));
        labels[n] = ((uint)((k + inf.numIndices - 1) % inf.numIndices & 0x7f) << 8) | (uint)(k & 0x7f);
        ++n;
    }
    for (int k = 0; k < 3; ++k) {
        BtgFloat4 sk = btgCross3(w[(k + 1) % 3] - w[k], nRef);
        if (btgDot3(sk, w[(k + 2) % 3] - w[k]) > 0.0f) sk = -sk; /* outward whatever the winding */
        sk.w = btgDot3(sk, w[k]);
        side[k] = sk;
        sideLabel[k] = BTG_FEATURE_EDGE_OF_B | (uint)k;
    }
    n = btgClipBySides(poly, labels, n, side, sideLabel, 3);
    const float refD = btgDot3(nRef, w[0]);
    const BtgFloat4 normal = nRef; /* from the triangle (B) towards the hull (A) */
    const uint faceBits = BTG_FEATURE_CLIP | ((uint)(faceA & 0x7f) << 23);
    int kept = 0;
    for (int i = 0; i < n; ++i) {
        BtgFloat4 p = poly[i];
        float depth = btgDot3(nRef, p) - refD;
        float dist = depth - margins;
        if (dist >= threshold) continue;
        /* p lies on the hull, p - nRef*depth on the triangle */
        BtgFloat4 onB = btgXyz(p) - nRef * depth;
        BtgFloat4 c = onB + normal * mesh.shape.margin;
        c.w = dist;
        labels[kept] = faceBits | (labels[i] & 0xffffu);
        poly[kept++] = c;
    }
    if (kept > 0) btgReduceArray(poly, labels, kept, normal, &m);
    return m;
}

/* A support-function convex c (A) against one triangle (B), as stock's
 * btConvexConcaveCollisionAlgorithm runs it: btConvexConvexAlgorithm between the convex and a
 * btTriangleShape in the mesh body's frame whose margin is the concave shape's, i.e. GJK on the
 * cores (EPA when they overlap), one point per triangle. None of capsule, cylinder, cone,
 * multi-sphere, convex mesh or featureless hull has polyhedral features, so stock clips nothing
 * here (and the capsule closed forms take only capsule/sphere pairs). */
static inline BtgCollider btgTriangleCollider(BtgCollider mesh, BtgTriangleVerts tri)
{
    BtgCollider t = mesh;
    t.shape.type = BTG_SHAPE_CONVEX;
    t.shape.convexType = BTG_CONVEX_TRIANGLE;
    t.shape.convexFlags = 0u;
    t.shape.localAabbMin = btgXyz(tri.v[0]);
    t.shape.localAabbMax = btgXyz(tri.v[1]);
    t.shape.param = btgXyz(tri.v[2]);
    t.shape.numVertices = 0;
    return t;
}

static inline BtgManifold btgCollideConvexTriangle(BtgCollider c, BtgCollider mesh, BtgTriangleVerts tri,
                                                   BTG_SHAPE_TABLES, float threshold)
{
    BTG_UNUSED_SHAPE_TABLES;
    BtgManifold m = btgEmptyManifold(c.body, mesh.body);
    const BtgConvexPoint p = btgGjkPoint(c, btgTriangleCollider(mesh, tri), verts, threshold);
    if (p.valid) btgAddPoint(&m, p.normal, p.pointB, p.distance, BTG_FEATURE_SINGLE);
    return m;
}

/* The soft step's routine for a convex known by its support function against one triangle:
 * GJK's one point, but a capsule or cylinder lying on the triangle (GJK's normal within
 * BTG_ROUND_FACE_COS of the triangle's) laid on its face as on a box's (round_contacts.h: the
 * triangle's edges bound the face; a body across two triangles gets each one's part), so the
 * points under a rolling body lie under its axis rather than where GJK's point lands. */
static inline BtgManifold btgCollideConvexTriangleFresh(BtgCollider c, BtgCollider mesh, BtgTriangleVerts tri,
                                                        BTG_SHAPE_TABLES, float threshold)
{
    const BtgManifold m = btgCollideConvexTriangle(c, mesh, tri, verts, faces, indices, edges, threshold);
    if (m.numPoints == 0 || !btgIsRound(c.shape)) return m;
    BtgFloat4 w[3];
    for (int i = 0; i < 3; ++i) w[i] = btgPoseApply(mesh.pose, tri.v[i]);
    BtgFloat4 n = btgCross3(w[1] - w[0], w[2] - w[0]);
    const float len = btgLength3(n);
    if (!(len > 1e-12f)) return m;
    n = n * (1.0f / len);
    const BtgFloat4 g = btgMake4(m.points[0].nx, m.points[0].ny, m.points[0].nz, 0.0f);
    if (btgDot3(n, g) < 0.0f) n = -n; /* towards the convex */
    if (btgDot3(n, g) < BTG_ROUND_FACE_COS) return m;
    BtgRoundFace face;
    face.n = n;
    face.w = btgDot3(n, w[0]);
    face.numSides = 3;
    for (int i = 0; i < 3; ++i) {
        const BtgFloat4 a = w[i], b = w[i == 2 ? 0 : i + 1], o = w[i == 0 ? 2 : i - 1];
        BtgFloat4 side = btgNormalize3(btgCross3(b - a, n));
        if (btgDot3(side, o - a) > 0.0f) side = -side; /* outward: away from the third vertex */
        face.side[i] = btgMake4(side.x, side.y, side.z, btgDot3(side, a));
    }
    face.side[3] = btgZero4();
    BtgManifold laid = btgEmptyManifold(c.body, mesh.body);
    const int over = btgIsCapsule(c.shape) ? btgCapsuleOnFaceCanonical(&laid, c, &face, threshold)
                                           : btgCylinderOnFaceCanonical(&laid, c, &face, threshold);
    return over ? laid : m;
}

/* A concave manifold point's feature id is its triangle's sub-shape key, so every point keeps
 * its own (Bullet's per-point m_partId / m_index on the concave side) even in a manifold that
 * merges several triangles: a mesh triangle as Bullet's BVH leaf names it, (part << 21) |
 * index; a heightfield triangle as j * 2 (width - 1) + part id (part id 2x + t, index j). The
 * points of one triangle share it; the warm start then matches them by position within the
 * threshold. The one key equal to BTG_FEATURE_UNKNOWN (part 511, index 2^21 - 1) has bit 31 set,
 * which btgTriangleKeyPart masks off. */
static inline uint btgTriangleKey(BtgShape concave, BtgSubPair sp)
{
    uint key = concave.type == BTG_SHAPE_HEIGHTFIELD ? (uint)sp.triangle
                                                     : ((uint)sp.partId << BTG_BVH_PART_SHIFT) | (uint)sp.index;
    return key == BTG_FEATURE_UNKNOWN ? key | 0x80000000u : key;
}
/* A mesh point's (part id, triangle index) back from its feature id (heightfields: divide by
 * 2 (width - 1) for the index, the remainder is the part id). */
static inline int btgTriangleKeyPart(uint key) { return (int)((key & 0x7fffffffu) >> BTG_BVH_PART_SHIFT); }
static inline int btgTriangleKeyIndex(uint key) { return (int)(key & BTG_BVH_TRIANGLE_MASK); }

/* A triangle routine's manifold (convex A, concave B) for the pair (a, b): each point's feature
 * id its triangle's key (btgTriangleKey), the triangle's keys (Bullet's part id and triangle
 * index) on the concave side of the manifold, the pair's own order and threshold. */
static inline BtgManifold btgFinishTriangle(BtgCollider a, BtgCollider b, BtgSubPair sp, BtgManifold m)
{
    const uint key = btgTriangleKey(btgIsConcave(a.shape.type) ? a.shape : b.shape, sp);
    for (int k = 0; k < m.numPoints; ++k) m.points[k].featureId = key;
    m.partIdB = sp.partId;
    m.indexB = sp.index;
    if (btgIsConcave(a.shape.type)) m = btgSwapManifold(m);
    m.breakingThreshold = btgPairThreshold(a.shape, b.shape);
    return m;
}

/* The routine on the pair's convex and triangle, in canonical roles, returned in the pair's own
 * order with the triangle's keys on the concave side and its ids made distinct per triangle. */
#define btgTriangleManifold(a, b, sp, verts, faces, indices, edges, routine)                                      \
    btgFinishTriangle(a, b, sp,                                                                                    \
                      routine(btgIsConcave(a.shape.type) ? b : a, btgIsConcave(a.shape.type) ? a : b,              \
                              btgConcaveTriangle(btgIsConcave(a.shape.type) ? a.shape : b.shape, sp,               \
                                                 BTG_CONCAVE_TABLE_ARGS),                                          \
                              verts, faces, indices, edges, btgPairThreshold(a.shape, b.shape)))

/* Normals within this cosine (about 0.8 degrees) share one manifold of a convex–mesh pair. */
#define BTG_MESH_MERGE_COS 0.9999f

/* contact_reduce.h's choice (deepest, farthest from it, largest triangle each side) for the
 * points of two triangles; when they lie on one line (a box edge along a slope, across the
 * triangles) and the deepest is inside the segment, the far end beyond it is kept too, so the
 * contact spans the whole segment. */
static inline void btgReduceMerged(const BtgFloat4* pts, const uint* ids, int n, BtgFloat4 normal, BtgManifold* m)
{
    btgReduceArray(pts, ids, n, normal, m);
    if (m->numPoints != 2) return;
    BtgFloat4 p0 = btgPointOnB(m->points[0]), p1 = btgPointOnB(m->points[1]);
    BtgFloat4 d01 = btgInPlane(p1 - p0, normal);
    float reach = btgDot3(d01, d01);
    int best = -1;
    float bestD2 = 0.0f;
    for (int i = 0; i < n; ++i) {
        BtgFloat4 d = btgInPlane(btgXyz(pts[i]) - p1, normal);
        float d2 = btgDot3(d, d);
        float limit = btgSqrt(reach) + BTG_REDUCE_MIN_DIST;
        if (d2 > limit * limit && (best < 0 || d2 > bestD2)) {
            best = i;
            bestD2 = d2;
        }
    }
    if (best < 0) return;
    BtgFloat4 c = pts[best];
    btgAddPoint(m, normal, btgXyz(c), c.w, ids[best]);
}

/* The manifolds of one convex–mesh pair from its triangles' (region[first, end), in the
 * midphase's order): those with points are compacted to the front, and one whose normal is
 * within BTG_MESH_MERGE_COS of an earlier one's is merged into it (its points and the earlier
 * one's reduced to at most 4 along the earlier normal, keeping the earlier one's keys: the
 * first triangle's). A flat mesh gives one manifold, as stock's one manifold per pair; points
 * of triangles at an angle stay in manifolds of their own, because a contact's solver rows
 * carry one normal (stock's manifold has one per point). Returns how many are left. */
static inline int btgGatherMeshManifolds(BTG_GLOBAL BtgManifold* region, int first, int end)
{
    int out = 0;
    for (int s = first; s < end; ++s) {
        BtgManifold t = region[s];
        if (t.numPoints == 0) continue;
        BtgFloat4 n = btgPointNormal(t.points[0]);
        int merged = 0;
        for (int k = 0; k < out && !merged; ++k) {
            BtgManifold o = region[first + k];
            BtgFloat4 on = btgPointNormal(o.points[0]);
            if (!(btgDot3(on, n) >= BTG_MESH_MERGE_COS)) continue;
            BtgFloat4 pts[2 * BTG_MAX_POINTS];
            uint ids[2 * BTG_MAX_POINTS];
            int c = 0;
            for (int j = 0; j < o.numPoints; ++j, ++c) {
                pts[c] = btgPointOnB(o.points[j]);
                pts[c].w = o.points[j].distance;
                ids[c] = o.points[j].featureId;
            }
            for (int j = 0; j < t.numPoints; ++j, ++c) {
                pts[c] = btgPointOnB(t.points[j]);
                pts[c].w = t.points[j].distance;
                ids[c] = t.points[j].featureId;
            }
            btgReduceMerged(pts, ids, c, on, &o);
            region[first + k] = o;
            merged = 1;
        }
        if (!merged) region[first + out++] = t;
    }
    return out;
}

#endif
