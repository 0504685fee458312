/* simple_contacts.h — contacts for the pairs that need no SAT: sphere–hull, sphere–box and
 * sphere–plane (the rows of program "narrowphase" in pair_kinds.h), and the soft step's fresh
 * sphere–sphere and hull–plane (btgCollideSoftAfresh, soft_afresh.h, in program "narrowphase_gjk"). Each
 * btgCollide* takes the pair's two colliders in the pair's own order (A = pair.a) and returns
 * its manifold; hull margins grow the polyhedron outwards. */
#ifndef BTG_SIMPLE_CONTACTS_H
#define BTG_SIMPLE_CONTACTS_H
#include "narrowphase_common.h"

#define BTG_DEGENERATE_DIST 1e-6f /* m: below this a direction between centres is undefined */

/* World plane of a plane collider: xyz unit normal, w constant (points p with n.p = w). */
static inline BtgFloat4 btgWorldPlane(BtgCollider p)
{
    BtgFloat4 n = btgMat3MulVec(p.pose.rot, btgXyz(p.shape.param));
    n.w = p.shape.param.w + btgDot3(n, p.pose.pos);
    return n;
}

/* Closest point to p (shape-local) on a face polygon: the projection when it falls inside the
 * counter-clockwise loop, else the closest point on the loop's edges. */
static inline BtgFloat4 btgClosestOnFace(BtgFloat4 p, BtgShape s, BtgFace f, BTG_CONST_GLOBAL BtgFloat4* verts,
                                         BTG_CONST_GLOBAL int* indices)
{
    BtgFloat4 n = btgXyz(f.plane);
    BtgFloat4 pp = p - n * (btgDot3(n, p) + f.plane.w);
    int inside = 1;
    for (int k = 0; k < f.numIndices && inside; ++k) {
        BtgFloat4 v0 = btgFaceVertex(s, f, verts, indices, k);
        BtgFloat4 v1 = btgFaceVertex(s, f, verts, indices, k + 1 < f.numIndices ? k + 1 : 0);
        if (btgDot3(btgCross3(n, v1 - v0), pp - v0) < 0.0f) inside = 0;
    }
    if (inside) return pp;
    BtgFloat4 best = pp;
    float bestD2 = 0.0f;
    for (int k = 0; k < f.numIndices; ++k) {
        BtgFloat4 v0 = btgFaceVertex(s, f, verts, indices, k);
        BtgFloat4 v1 = btgFaceVertex(s, f, verts, indices, k + 1 < f.numIndices ? k + 1 : 0);
        BtgFloat4 e = v1 - v0;
        float ee = btgDot3(e, e);
        float t = ee > 0.0f ? btgClamp(btgDot3(p - v0, e) / ee, 0.0f, 1.0f) : 0.0f;
        BtgFloat4 q = v0 + e * t;
        BtgFloat4 d = p - q;
        float d2 = btgDot3(d, d);
        if (k == 0 || d2 < bestD2) {
            best = q;
            bestD2 = d2;
        }
    }
    return best;
}

static inline BtgManifold btgCollideSphereSphere(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    BTG_UNUSED_SHAPE_TABLES;
    BtgManifold m = btgEmptyManifold(a.body, b.body);
    BtgFloat4 d = a.pose.pos - b.pose.pos;
    float len = btgLength3(d);
    float ra = a.shape.param.x, rb = b.shape.param.x;
    float dist = len - ra - rb;
    if (dist >= threshold) return m;
    /* concentric spheres: any direction will do; Bullet picks +x */
    BtgFloat4 n = len > BTG_DEGENERATE_DIST ? btgXyz(d) * (1.0f / len) : btgMake4(1.0f, 0.0f, 0.0f, 0.0f);
    btgAddPoint(&m, n, btgXyz(b.pose.pos) + n * rb, dist, BTG_FEATURE_SINGLE);
    return m;
}

/* Canonical order: sphere s is A, plane p is B. */
static inline BtgManifold btgSpherePlaneCanonical(BtgCollider s, BtgCollider p, float threshold)
{
    BtgManifold m = btgEmptyManifold(s.body, p.body);
    BtgFloat4 plane = btgWorldPlane(p);
    BtgFloat4 n = btgXyz(plane);
    BtgFloat4 c = btgXyz(s.pose.pos);
    float h = btgDot3(n, c) - plane.w;
    float dist = h - s.shape.param.x;
    if (dist >= threshold) return m;
    btgAddPoint(&m, n, c - n * h, dist, BTG_FEATURE_SINGLE);
    return m;
}

static inline BtgManifold btgCollideSpherePlane(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    BTG_UNUSED_SHAPE_TABLES;
    if (a.shape.type == BTG_SHAPE_SPHERE) return btgSpherePlaneCanonical(a, b, threshold);
    return btgSwapManifold(btgSpherePlaneCanonical(b, a, threshold));
}

/* Canonical order: sphere s is A, hull h is B. Outside the polyhedron the closest surface point
 * lies on a face the centre is in front of; inside, the face of least penetration is used. */
static inline BtgManifold btgSphereHullCanonical(BtgCollider s, BtgCollider h, BTG_CONST_GLOBAL BtgFloat4* verts,
                                                 BTG_CONST_GLOBAL BtgFace* faces, BTG_CONST_GLOBAL int* indices,
                                                 float threshold)
{
    BtgManifold m = btgEmptyManifold(s.body, h.body);
    float r = s.shape.param.x, margin = h.shape.margin;
    BtgFloat4 c = btgPoseApplyInv(h.pose, s.pose.pos);
    int bestFace = 0;
    float maxSep = 0.0f;
    for (int f = 0; f < h.shape.numFaces; ++f) {
        BtgFloat4 pl = faces[h.shape.firstFace + f].plane;
        float sep = btgDot3(pl, c) + pl.w;
        if (f == 0 || sep > maxSep) {
            maxSep = sep;
            bestFace = f;
        }
    }
    /* the largest face separation is a lower bound of the distance */
    if (h.shape.numFaces == 0 || maxSep - r - margin >= threshold) return m;
    BtgFloat4 faceN = btgXyz(faces[h.shape.firstFace + bestFace].plane);
    BtgFloat4 q, nl;
    float polyDist;
    if (maxSep <= 0.0f) {
        q = c - faceN * maxSep;
        nl = faceN;
        polyDist = maxSep;
    } else {
        float bestD2 = 0.0f;
        int found = 0;
        q = c;
        for (int f = 0; f < h.shape.numFaces; ++f) {
            BtgFace face = faces[h.shape.firstFace + f];
            if (btgDot3(face.plane, c) + face.plane.w <= 0.0f) continue;
            BtgFloat4 qf = btgClosestOnFace(c, h.shape, face, verts, indices);
            BtgFloat4 d = c - qf;
            float d2 = btgDot3(d, d);
            if (!found || d2 < bestD2) {
                q = qf;
                bestD2 = d2;
                found = 1;
            }
        }
        polyDist = btgSqrt(bestD2);
        nl = polyDist > BTG_DEGENERATE_DIST ? btgXyz(c - q) * (1.0f / polyDist) : faceN;
    }
    float dist = polyDist - r - margin;
    if (dist >= threshold) return m;
    BtgFloat4 n = btgMat3MulVec(h.pose.rot, nl);
    btgAddPoint(&m, n, btgPoseApply(h.pose, q) + n * margin, dist, BTG_FEATURE_SINGLE);
    return m;
}

static inline BtgManifold btgCollideSphereHull(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    (void)edges;
    if (a.shape.type == BTG_SHAPE_SPHERE) return btgSphereHullCanonical(a, b, verts, faces, indices, threshold);
    return btgSwapManifold(btgSphereHullCanonical(b, a, verts, faces, indices, threshold));
}

/* Canonical order: hull h is A, plane p is B. Every hull vertex below the threshold is a
 * candidate (its projection on the plane, feature BTG_FEATURE_VERTEX | its number); the
 * reduction streams over the vertices three times instead of buffering them, so hulls of any
 * vertex count are handled. */
static inline BtgManifold btgHullPlaneCanonical(BtgCollider h, BtgCollider p, BTG_CONST_GLOBAL BtgFloat4* verts,
                                                float threshold)
{
    BtgManifold m = btgEmptyManifold(h.body, p.body);
    BtgFloat4 plane = btgWorldPlane(p);
    BtgFloat4 n = btgXyz(plane);
    BtgFloat4 nl = btgMat3TMulVec(h.pose.rot, n); /* heights from local vertices, one dot each */
    float base = btgDot3(n, h.pose.pos) - plane.w;
    BtgReduceState st;
    btgReduceBegin(&st, n);
    for (int pass = 0; pass < 3; ++pass) {
        for (int i = 0; i < h.shape.numVertices; ++i) {
            BtgFloat4 v = btgHullVertex(h.shape, verts, i);
            float height = base + btgDot3(nl, v);
            float dist = height - h.shape.margin;
            if (dist >= threshold) continue;
            BtgFloat4 c = btgPoseApply(h.pose, v) - n * height;
            c.w = dist;
            btgReduceVisit(&st, pass, c, BTG_FEATURE_VERTEX | (uint)i);
        }
        btgReduceEndPass(&st, pass);
    }
    btgReduceWrite(&st, &m);
    return m;
}

/* A box or hull and a plane, either order (a box's row holds its eight corners, margin 0). */
static inline BtgManifold btgCollideHullPlane(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    (void)faces;
    (void)indices;
    (void)edges;
    if (b.shape.type == BTG_SHAPE_PLANE) return btgHullPlaneCanonical(a, b, verts, threshold);
    return btgSwapManifold(btgHullPlaneCanonical(b, a, verts, threshold));
}

#endif
