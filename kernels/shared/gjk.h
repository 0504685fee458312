/* gjk.h — the one contact point Bullet's convex algorithms find for a pair in one step: GJK
 * distance between the margin-less cores (btGjkPairDetector with the Voronoi simplex solver:
 * the closest points of the cores, then each pushed out by its margin), EPA on the full
 * shapes when the cores overlap (btGjkEpa2's penetration), the closed form of two capsules
 * or a capsule and a sphere (btConvexConvexAlgorithm's capsuleCapsuleDistance), and the
 * deepest support point of a convex against a plane (btConvexPlaneCollisionAlgorithm).
 * All in world space relative to the pair's mid-point, as Bullet's positionOffset. */
#ifndef BTG_GJK_H
#define BTG_GJK_H
#include "narrowphase_common.h"
#include "support.h"

#define BTG_GJK_MAX_ITERATIONS 64
#define BTG_GJK_REL_ERROR2 1.0e-6f /* Bullet's REL_ERROR2 */
#define BTG_GJK_EQUAL_VERTEX2 1.0e-4f /* m^2: btVoronoiSimplexSolver's equal-vertex threshold (single precision) */
#define BTG_EPA_MAX_VERTS 48
#define BTG_EPA_MAX_FACES 96
#define BTG_EPA_MAX_EDGES 48
#define BTG_EPA_MAX_ITERATIONS 40
#define BTG_EPA_ACCURACY 1.0e-4f /* m: Bullet's EPA_ACCURACY */


typedef struct {
    BtgFloat4 w; /* a - b */
    BtgFloat4 a; /* support point of A (relative to the offset) */
} BtgSupportVert;

typedef struct {
    BtgSupportVert v[4];
    int n;
} BtgSimplex;

static inline BtgConvexPoint btgNoPoint(void)
{
    BtgConvexPoint p;
    p.normal = btgMake4(0.0f, 1.0f, 0.0f, 0.0f);
    p.pointB = btgZero4();
    p.distance = 0.0f;
    p.valid = 0;
    p.pad0 = 0;
    p.pad1 = 0;
    return p;
}

static inline BtgConvexPoint btgMakeConvexPoint(BtgFloat4 normal, BtgFloat4 pointB, float distance)
{
    BtgConvexPoint p = btgNoPoint();
    p.normal = btgXyz(normal);
    p.pointB = btgXyz(pointB);
    p.distance = distance;
    p.valid = 1;
    return p;
}

/* Support of the Minkowski difference A - B along world d: A's farthest point along d minus
 * B's along -d; cores only, or full shapes. */
static inline BtgSupportVert btgMinkowskiSupport(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts,
                                                 BtgFloat4 d, BtgFloat4 offset, int full)
{
    BtgFloat4 da = btgMat3TMulVec(a.pose.rot, d);
    BtgFloat4 db = btgMat3TMulVec(b.pose.rot, -d);
    BtgFloat4 la = full ? btgSupportFull(a.shape, verts, da) : btgSupportCore(a.shape, verts, da);
    BtgFloat4 lb = full ? btgSupportFull(b.shape, verts, db) : btgSupportCore(b.shape, verts, db);
    BtgSupportVert s;
    s.a = btgXyz(a.pose.pos - offset) + btgMat3MulVec(a.pose.rot, la);
    BtgFloat4 pb = btgXyz(b.pose.pos - offset) + btgMat3MulVec(b.pose.rot, lb);
    s.w = s.a - pb;
    return s;
}

/* The point of the simplex closest to the origin (Ericson's closest-point routines). The simplex
 * keeps only the vertices whose hull holds that point, lambda their weights. *inside: a
 * tetrahedron that holds the origin. */
static inline BtgFloat4 btgClosestOnTriangle(BtgFloat4 a, BtgFloat4 b, BtgFloat4 c, float* l, int* keep)
{
    BtgFloat4 ab = b - a, ac = c - a, ap = -a;
    float d1 = btgDot3(ab, ap), d2 = btgDot3(ac, ap);
    keep[0] = 1;
    keep[1] = 0;
    keep[2] = 0;
    l[0] = 1.0f;
    l[1] = 0.0f;
    l[2] = 0.0f;
    if (d1 <= 0.0f && d2 <= 0.0f) return a;
    BtgFloat4 bp = -b;
    float d3 = btgDot3(ab, bp), d4 = btgDot3(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) {
        keep[0] = 0;
        keep[1] = 1;
        l[0] = 0.0f;
        l[1] = 1.0f;
        return b;
    }
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        float v = d1 / (d1 - d3);
        keep[1] = 1;
        l[0] = 1.0f - v;
        l[1] = v;
        return a + ab * v;
    }
    BtgFloat4 cp = -c;
    float d5 = btgDot3(ab, cp), d6 = btgDot3(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) {
        keep[0] = 0;
        keep[2] = 1;
        l[0] = 0.0f;
        l[2] = 1.0f;
        return c;
    }
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        float w = d2 / (d2 - d6);
        keep[2] = 1;
        l[0] = 1.0f - w;
        l[2] = w;
        return a + ac * w;
    }
    float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        keep[0] = 0;
        keep[1] = 1;
        keep[2] = 1;
        l[0] = 0.0f;
        l[1] = 1.0f - w;
        l[2] = w;
        return b + (c - b) * w;
    }
    float denom = 1.0f / (va + vb + vc);
    float v = vb * denom, w = vc * denom;
    keep[1] = 1;
    keep[2] = 1;
    l[0] = 1.0f - v - w;
    l[1] = v;
    l[2] = w;
    return a + ab * v + ac * w;
}

static inline void btgSimplexKeep(BtgSimplex* s, const int* keep, const float* lin, float* lambda)
{
    BtgSimplex r = *s;
    r.n = 0;
    for (int i = 0; i < s->n; ++i)
        if (keep[i]) {
            lambda[r.n] = lin[i];
            r.v[r.n++] = s->v[i];
        }
    *s = r;
}

/* *inside: the origin lies within the tetrahedron; *degenerate: the tetrahedron is flat (six
 * times its volume below 1e-4, btVoronoiSimplexSolver's CATCH_DEGENERATE_TETRAHEDRON in single
 * precision), where no side of a face can be told: the caller keeps the simplex before the last
 * vertex, as Bullet's closest() fails there and its pair detector keeps the last points. */
static inline BtgFloat4 btgSimplexClosest(BtgSimplex* s, float* lambda, int* inside, int* degenerate)
{
    *inside = 0;
    *degenerate = 0;
    if (s->n == 1) {
        lambda[0] = 1.0f;
        return s->v[0].w;
    }
    if (s->n == 2) {
        BtgFloat4 a = s->v[0].w, ab = s->v[1].w - a;
        float ee = btgDot3(ab, ab);
        float t = ee > 0.0f ? -btgDot3(a, ab) / ee : 0.0f;
        if (t <= 0.0f) {
            s->n = 1;
            lambda[0] = 1.0f;
            return a;
        }
        if (t >= 1.0f) {
            s->v[0] = s->v[1];
            s->n = 1;
            lambda[0] = 1.0f;
            return s->v[0].w;
        }
        lambda[0] = 1.0f - t;
        lambda[1] = t;
        return a + ab * t;
    }
    if (s->n == 3) {
        float l[4];
        int keep[4];
        BtgFloat4 p = btgClosestOnTriangle(s->v[0].w, s->v[1].w, s->v[2].w, l, keep);
        keep[3] = 0;
        btgSimplexKeep(s, keep, l, lambda);
        return p;
    }
    /* tetrahedron: the faces the origin lies outside of */
    {
        const BtgFloat4 a = s->v[0].w;
        const float vol6 = btgDot3(s->v[3].w - a, btgCross3(s->v[1].w - a, s->v[2].w - a));
        if (vol6 * vol6 < 1.0e-4f * 1.0e-4f) {
            *degenerate = 1;
            return btgZero4();
        }
    }
    const int faces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
    float bestD2 = 3.0e38f;
    BtgFloat4 best = btgZero4();
    int bestKeep[4] = {0, 0, 0, 0};
    float bestL[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    int anyOutside = 0;
    for (int f = 0; f < 4; ++f) {
        BtgFloat4 a = s->v[faces[f][0]].w, b = s->v[faces[f][1]].w, c = s->v[faces[f][2]].w;
        BtgFloat4 d = s->v[faces[f][3]].w;
        BtgFloat4 n = btgCross3(b - a, c - a);
        float so = -btgDot3(a, n), sd = btgDot3(d - a, n);
        if (so * sd > 0.0f) continue; /* origin on the same side as the fourth vertex */
        anyOutside = 1;
        float l[3];
        int keep[3];
        BtgFloat4 p = btgClosestOnTriangle(a, b, c, l, keep);
        float d2 = btgDot3(p, p);
        if (d2 < bestD2) {
            bestD2 = d2;
            best = p;
            for (int k = 0; k < 4; ++k) {
                bestKeep[k] = 0;
                bestL[k] = 0.0f;
            }
            for (int k = 0; k < 3; ++k) {
                bestKeep[faces[f][k]] = keep[k];
                bestL[faces[f][k]] = l[k];
            }
        }
    }
    if (!anyOutside) {
        *inside = 1;
        return btgZero4();
    }
    btgSimplexKeep(s, bestKeep, bestL, lambda);
    return best;
}

/* The closest points of the cores. Returns 1 with *v the separating axis (the closest point of
 * A - B, from B's to A's), *pa and *pb the cores' points (relative to offset; pa - pb is v but
 * where the last vertex made the distance grow, below); 0 when the cores overlap or touch; -1
 * when they are farther apart than maxDist (Bullet's early out). */
static inline int btgGjkCores(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts, BtgFloat4 offset,
                              float maxDist, BtgFloat4* v, BtgFloat4* pa, BtgFloat4* pb)
{
    BtgSimplex s;
    s.n = 0;
    for (int k = 0; k < 4; ++k) {
        s.v[k].w = btgZero4();
        s.v[k].a = btgZero4();
    }
    float lambda[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    BtgFloat4 axis = btgMake4(0.0f, 1.0f, 0.0f, 0.0f); /* Bullet's first separating axis */
    float vv = 3.0e38f;
    const float maxDist2 = maxDist * maxDist;
    BtgFloat4 closest = axis; /* the simplex's closest point (the axis until the last step) */
    BtgFloat4 lastW = btgZero4();
    int haveLast = 0;
    for (int it = 0; it < BTG_GJK_MAX_ITERATIONS; ++it) {
        BtgSupportVert w = btgMinkowskiSupport(a, b, verts, -axis, offset, 0);
        float delta = btgDot3(axis, w.w);
        if (delta > 0.0f && delta * delta > vv * maxDist2) return -1;
        /* Bullet's inSimplex: a support point within 1 cm (squared distance 1e-4,
         * VORONOI_DEFAULT_EQUAL_VERTEX_THRESHOLD) of one the simplex holds, or the last one added
         * (even if the simplex dropped it since), ends the search. Only exact repeats did: a
         * long box's face corner met again 0.1 mm off made a sliver the closest point of which
         * was metres off, and the wheel on it lost its contact or got one 4 m away. */
        int dup = haveLast && w.w.x == lastW.x && w.w.y == lastW.y && w.w.z == lastW.z;
        for (int i = 0; i < s.n; ++i) {
            const BtgFloat4 e = s.v[i].w - w.w;
            if (btgDot3(e, e) <= BTG_GJK_EQUAL_VERTEX2) dup = 1;
        }
        if (dup) break;
        if (vv - delta <= vv * BTG_GJK_REL_ERROR2) break;
        const BtgSimplex before = s;
        const float lambdaBefore[4] = {lambda[0], lambda[1], lambda[2], lambda[3]};
        s.v[s.n++] = w;
        lastW = w.w;
        haveLast = 1;
        int inside = 0, flat = 0;
        BtgFloat4 nv = btgSimplexClosest(&s, lambda, &inside, &flat);
        float nvv = btgDot3(nv, nv);
        /* a flat tetrahedron (the box's four face corners): Bullet's closest() fails and the
         * last points stand, so the simplex before this vertex is the answer (taken as inside,
         * it sent a resting contact to EPA, whose witness was 3.9 m off) */
        if (flat) {
            s = before;
            for (int k = 0; k < 4; ++k) lambda[k] = lambdaBefore[k];
            break;
        }
        if (inside) return 0;
        if (nvv < BTG_GJK_REL_ERROR2) return 0; /* touching cores: EPA decides */
        /* No progress (Bullet's previous - squared <= epsilon x previous), or a closest point
         * farther than the last, which only rounding makes (a 100 m box's corners 50 m out and a
         * capsule's segment parallel to its face: 0.2403 after 0.2400, the axis tilted 2 to 4
         * degrees): Bullet stops with the last axis (its normal and distance) and the new
         * simplex's points. Taking the new axis tilted a resting capsule's normals, and their
         * sideways push rolled it. */
        if (vv - nvv <= BTG_SUPPORT_EPSILON * vv) {
            closest = nv;
            break;
        }
        axis = nv;
        closest = nv;
        vv = nvv;
    }
    BtgFloat4 p = btgZero4();
    for (int i = 0; i < s.n; ++i) p = p + s.v[i].a * lambda[i];
    *v = axis;
    *pa = p;
    *pb = p - closest;
    return 1;
}

/* A tetrahedron of full-shape support points holding the origin (GJK as a boolean test).
 * Returns 0 when none is found (the shapes only touch, or are degenerate). */
static inline int btgEncloseOrigin(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts, BtgFloat4 offset,
                                   BtgSimplex* s)
{
    BtgFloat4 d = btgXyz(a.pose.pos - b.pose.pos);
    if (btgDot3(d, d) < 1e-12f) d = btgMake4(1.0f, 0.0f, 0.0f, 0.0f);
    s->v[0] = btgMinkowskiSupport(a, b, verts, d, offset, 1);
    s->n = 1;
    d = -s->v[0].w;
    for (int it = 0; it < BTG_GJK_MAX_ITERATIONS; ++it) {
        if (btgDot3(d, d) < 1e-14f) return 0;
        BtgSupportVert p = btgMinkowskiSupport(a, b, verts, d, offset, 1);
        if (btgDot3(p.w, d) <= 0.0f) return 0;
        s->v[s->n++] = p;
        BtgFloat4 A = p.w, ao = -A;
        if (s->n == 2) {
            BtgFloat4 ab = s->v[0].w - A;
            if (btgDot3(ab, ao) > 0.0f) {
                d = btgCross3(btgCross3(ab, ao), ab);
            } else {
                s->v[0] = p;
                s->n = 1;
                d = ao;
            }
        } else if (s->n == 3) {
            BtgSupportVert C = s->v[0], B = s->v[1];
            BtgFloat4 ab = B.w - A, ac = C.w - A, abc = btgCross3(ab, ac);
            if (btgDot3(btgCross3(abc, ac), ao) > 0.0f) {
                s->v[0] = C;
                s->v[1] = p;
                s->n = 2;
                d = btgCross3(btgCross3(ac, ao), ac);
            } else if (btgDot3(btgCross3(ab, abc), ao) > 0.0f) {
                s->v[0] = B;
                s->v[1] = p;
                s->n = 2;
                d = btgCross3(btgCross3(ab, ao), ab);
            } else if (btgDot3(abc, ao) > 0.0f) {
                d = abc;
            } else {
                s->v[0] = B;
                s->v[1] = C;
                d = -abc;
            }
        } else {
            BtgSupportVert D = s->v[0], C = s->v[1], B = s->v[2];
            BtgFloat4 ab = B.w - A, ac = C.w - A, ad = D.w - A;
            BtgFloat4 abc = btgCross3(ab, ac), acd = btgCross3(ac, ad), adb = btgCross3(ad, ab);
            if (btgDot3(abc, ao) > 0.0f) {
                s->v[0] = C;
                s->v[1] = B;
                s->v[2] = p;
                s->n = 3;
                d = abc;
            } else if (btgDot3(acd, ao) > 0.0f) {
                s->v[0] = D;
                s->v[1] = C;
                s->v[2] = p;
                s->n = 3;
                d = acd;
            } else if (btgDot3(adb, ao) > 0.0f) {
                s->v[0] = B;
                s->v[1] = D;
                s->v[2] = p;
                s->n = 3;
                d = adb;
            } else {
                return 1;
            }
        }
    }
    return 0;
}

typedef struct {
    int v0, v1, v2, alive;
    BtgFloat4 n; /* unit outward normal; w: distance of the plane from the origin */
} BtgEpaFace;

static inline int btgEpaMakeFace(BtgEpaFace* f, const BtgSupportVert* vs, int i0, int i1, int i2)
{
    BtgFloat4 n = btgCross3(vs[i1].w - vs[i0].w, vs[i2].w - vs[i0].w);
    float len = btgLength3(n);
    if (len < 1e-12f) return 0;
    n = n * (1.0f / len);
    f->v0 = i0;
    f->v1 = i1;
    f->v2 = i2;
    f->alive = 1;
    f->n = btgMake4(n.x, n.y, n.z, btgDot3(n, vs[i0].w));
    return 1;
}

/* EPA from the tetrahedron s (btGjkEpa2's expansion, simplified: faces that see the new support
 * point are removed and the horizon is re-closed). Returns 1 with A's and B's witness points
 * (relative to offset): the closest face's point, as btGjkEpa2::Penetration reports them. */
static inline int btgEpa(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts, BtgFloat4 offset,
                         BtgSimplex s, BtgFloat4* pa, BtgFloat4* pb)
{
    BtgSupportVert vs[BTG_EPA_MAX_VERTS];
    BtgEpaFace faces[BTG_EPA_MAX_FACES];
    int edges[BTG_EPA_MAX_EDGES][2];
    int nv = 4, nf = 0;
    for (int i = 0; i < 4; ++i) vs[i] = s.v[i];
    BtgFloat4 centre = (vs[0].w + vs[1].w + vs[2].w + vs[3].w) * 0.25f;
    const int init[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    for (int f = 0; f < 4; ++f) {
        int i0 = init[f][0], i1 = init[f][1], i2 = init[f][2];
        BtgFloat4 n = btgCross3(vs[i1].w - vs[i0].w, vs[i2].w - vs[i0].w);
        if (btgDot3(n, vs[i0].w - centre) < 0.0f) {
            int t = i1;
            i1 = i2;
            i2 = t;
        }
        if (!btgEpaMakeFace(&faces[nf], vs, i0, i1, i2)) return 0;
        ++nf;
    }
    int best = 0;
    for (int it = 0; it < BTG_EPA_MAX_ITERATIONS; ++it) {
        best = -1;
        for (int f = 0; f < nf; ++f)
            if (faces[f].alive && (best < 0 || faces[f].n.w < faces[best].n.w)) best = f;
        if (best < 0) return 0;
        BtgFloat4 n = btgXyz(faces[best].n);
        BtgSupportVert p = btgMinkowskiSupport(a, b, verts, n, offset, 1);
        if (btgDot3(p.w, n) - faces[best].n.w < BTG_EPA_ACCURACY) break;
        if (nv >= BTG_EPA_MAX_VERTS) break;
        const int pi = nv;
        vs[nv++] = p;
        int ne = 0, overflow = 0;
        for (int f = 0; f < nf; ++f) {
            if (!faces[f].alive || btgDot3(btgXyz(faces[f].n), p.w - vs[faces[f].v0].w) <= 0.0f) continue;
            faces[f].alive = 0;
            const int fv[3] = {faces[f].v0, faces[f].v1, faces[f].v2};
            for (int k = 0; k < 3; ++k) {
                const int e0 = fv[k], e1 = fv[k == 2 ? 0 : k + 1];
                int found = -1;
                for (int e = 0; e < ne; ++e)
                    if (edges[e][0] == e1 && edges[e][1] == e0) found = e;
                if (found >= 0) {
                    edges[found][0] = edges[ne - 1][0];
                    edges[found][1] = edges[ne - 1][1];
                    --ne;
                } else if (ne < BTG_EPA_MAX_EDGES) {
                    edges[ne][0] = e0;
                    edges[ne][1] = e1;
                    ++ne;
                } else {
                    overflow = 1;
                }
            }
        }
        if (overflow) break;
        /* reuse dead face slots first */
        int slot = 0;
        for (int e = 0; e < ne; ++e) {
            while (slot < nf && faces[slot].alive) ++slot;
            if (slot >= BTG_EPA_MAX_FACES) {
                overflow = 1;
                break;
            }
            BtgEpaFace f;
            if (!btgEpaMakeFace(&f, vs, edges[e][0], edges[e][1], pi)) continue;
            faces[slot] = f;
            if (slot == nf) ++nf;
            ++slot;
        }
        if (overflow) break;
    }
    best = -1;
    for (int f = 0; f < nf; ++f)
        if (faces[f].alive && (best < 0 || faces[f].n.w < faces[best].n.w)) best = f;
    if (best < 0) return 0;
    BtgEpaFace f = faces[best];
    BtgFloat4 q = btgXyz(f.n) * f.n.w;
    BtgFloat4 w0 = vs[f.v0].w, w1 = vs[f.v1].w, w2 = vs[f.v2].w;
    /* btGjkEpa2::Penetration's weights: the unsigned areas the projection makes with each edge,
     * normalized, so the witness stays within the face's support points even where the
     * projection falls outside the face (a flat contact, a triangle's zero thickness): signed
     * barycentrics there put it metres away on the surface's plane. */
    float l0 = btgLength3(btgCross3(w1 - q, w2 - q)), l1 = btgLength3(btgCross3(w2 - q, w0 - q)),
          l2 = btgLength3(btgCross3(w0 - q, w1 - q));
    const float sum = l0 + l1 + l2;
    if (sum > 0.0f) {
        l0 = l0 / sum;
        l1 = l1 / sum;
        l2 = l2 / sum;
    } else {
        l0 = 1.0f;
        l1 = l2 = 0.0f;
    }
    *pa = vs[f.v0].a * l0 + vs[f.v1].a * l1 + vs[f.v2].a * l2;
    *pb = *pa - q;
    return 1;
}

/* The depth along one axis n (B towards A) when neither GJK nor EPA gives an answer. */
static inline BtgConvexPoint btgAxisPoint(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts,
                                          BtgFloat4 offset, BtgFloat4 n)
{
    BtgSupportVert s = btgMinkowskiSupport(a, b, verts, -n, offset, 1);
    float dist = -btgDot3(s.w, -n);
    BtgFloat4 pb = s.a - s.w;
    return btgMakeConvexPoint(n, pb + offset, dist);
}

/* Bullet's btGjkPairDetector for the pair: the point it reports, if any, within `threshold`. */
static inline BtgConvexPoint btgGjkPoint(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts, float threshold)
{
    const BtgFloat4 offset = btgXyz(a.pose.pos + b.pose.pos) * 0.5f;
    const float ma = btgCoreMargin(a.shape), mb = btgCoreMargin(b.shape);
    BtgFloat4 v = btgMake4(0.0f, 1.0f, 0.0f, 0.0f), pa = btgZero4(), pbCore = btgZero4();
    const int r = btgGjkCores(a, b, verts, offset, ma + mb + threshold, &v, &pa, &pbCore);
    if (r < 0) return btgNoPoint();
    if (r > 0) {
        const float s = btgLength3(v);
        BtgFloat4 n = v * (1.0f / s);
        BtgConvexPoint p = btgMakeConvexPoint(n, pbCore + n * mb + offset, s - ma - mb);
        return p.distance <= threshold ? p : btgNoPoint();
    }
    BtgSimplex s;
    BtgFloat4 wa, wb;
    if (btgEncloseOrigin(a, b, verts, offset, &s) && s.n == 4 && btgEpa(a, b, verts, offset, s, &wa, &wb)) {
        BtgFloat4 d = wb - wa;
        float len = btgLength3(d);
        if (len > BTG_SUPPORT_EPSILON) return btgMakeConvexPoint(d * (1.0f / len), wb + offset, -len);
    }
    /* the shapes only touch: their depth along the cores' last axis (or the centres') */
    BtgFloat4 n = btgDot3(v, v) > 1e-12f ? btgNormalize3(v) : btgNormalize3(a.pose.pos - b.pose.pos);
    BtgConvexPoint p = btgAxisPoint(a, b, verts, offset, n);
    return p.distance <= threshold ? p : btgNoPoint();
}

/* capsuleCapsuleDistance: the closest points of the two segments (a sphere is a segment of
 * length 0 along its y axis), as btConvexConvexAlgorithm's segmentsClosestPoints. */
static inline BtgConvexPoint btgCapsulePoint(BtgCollider a, BtgCollider b, float threshold)
{
    const int upA = a.shape.type == BTG_SHAPE_SPHERE ? 1 : a.shape.upAxis;
    const int upB = b.shape.type == BTG_SHAPE_SPHERE ? 1 : b.shape.upAxis;
    const float hA = a.shape.type == BTG_SHAPE_SPHERE ? 0.0f : a.shape.param.y;
    const float hB = b.shape.type == BTG_SHAPE_SPHERE ? 0.0f : b.shape.param.y;
    const float rA = a.shape.param.x, rB = b.shape.param.x;
    BtgFloat4 ea = btgZero4(), eb = btgZero4();
    btgSetComp(&ea, upA, 1.0f);
    btgSetComp(&eb, upB, 1.0f);
    const BtgFloat4 dirA = btgMat3MulVec(a.pose.rot, ea), dirB = btgMat3MulVec(b.pose.rot, eb);
    const BtgFloat4 translation = btgXyz(b.pose.pos - a.pose.pos);
    const float ab = btgDot3(dirA, dirB), at = btgDot3(dirA, translation), bt = btgDot3(dirB, translation);
    const float denom = 1.0f - ab * ab;
    float tA = denom == 0.0f ? 0.0f : btgClamp((at - bt * ab) / denom, -hA, hA);
    float tB = tA * ab - bt;
    if (tB < -hB) {
        tB = -hB;
        tA = btgClamp(tB * ab + at, -hA, hA);
    } else if (tB > hB) {
        tB = hB;
        tA = btgClamp(tB * ab + at, -hA, hA);
    }
    const BtgFloat4 offsetB = dirB * tB;
    const BtgFloat4 pts = translation - dirA * tA + offsetB;
    const float len2 = btgDot3(pts, pts);
    const float dist = btgSqrt(len2) - rA - rB;
    if (dist >= threshold) return btgNoPoint();
    BtgFloat4 n;
    if (len2 <= BTG_SUPPORT_EPSILON * BTG_SUPPORT_EPSILON) {
        BtgFloat4 q;
        btgPlaneSpace(dirA, &n, &q);
    } else {
        n = pts * (-1.0f / btgSqrt(len2));
    }
    return btgMakeConvexPoint(n, btgXyz(b.pose.pos) + offsetB + n * rB, dist);
}

/* btConvexPlaneCollisionAlgorithm::collideSingleContact: the full convex's support point
 * against the plane, projected onto it. Canonical order: convex c is A, plane p is B. */
static inline BtgConvexPoint btgPlanePoint(BtgCollider c, BtgCollider p, BTG_CONST_GLOBAL BtgFloat4* verts, float threshold)
{
    BtgFloat4 n = btgMat3MulVec(p.pose.rot, btgXyz(p.shape.param));
    const float w = p.shape.param.w + btgDot3(n, p.pose.pos);
    BtgFloat4 support = btgSupportForPlane(c.shape, verts, btgMat3TMulVec(c.pose.rot, -n));
    BtgFloat4 vtx = btgPoseApply(c.pose, support);
    const float dist = btgDot3(n, vtx) - w;
    if (dist >= threshold) return btgNoPoint();
    return btgMakeConvexPoint(n, vtx - n * dist, dist);
}

#define BTG_SPHERE_PAIR_EPSILON 1.1920929e-07f /* Bullet's SIMD_EPSILON (float build) */
/* btSphereSphereCollisionAlgorithm: a point only while the two spheres touch (the distance of
 * their centres <= the radii's sum; none apart, however near), on B's surface along the line of
 * the centres (+x for concentric ones, as Bullet: a length below its SIMD_EPSILON). */
static inline BtgConvexPoint btgSpherePairPoint(BtgCollider a, BtgCollider b)
{
    const BtgFloat4 d = btgXyz(a.pose.pos - b.pose.pos);
    const float len = btgLength3(d);
    const float ra = a.shape.param.x, rb = b.shape.param.x;
    if (len > ra + rb) return btgNoPoint();
    const BtgFloat4 n = len > BTG_SPHERE_PAIR_EPSILON ? d * (1.0f / len) : btgMake4(1.0f, 0.0f, 0.0f, 0.0f);
    return btgMakeConvexPoint(n, btgXyz(b.pose.pos) + n * rb, len - (ra + rb));
}

/* The point Bullet's algorithm for this pair adds in one step (pair order: A = a). */
static inline BtgConvexPoint btgConvexPairPoint(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts,
                                                float threshold)
{
    if (a.shape.type == BTG_SHAPE_SPHERE && b.shape.type == BTG_SHAPE_SPHERE) return btgSpherePairPoint(a, b);
    if (b.shape.type == BTG_SHAPE_PLANE) return btgPlanePoint(a, b, verts, threshold);
    if (a.shape.type == BTG_SHAPE_PLANE) {
        BtgConvexPoint p = btgPlanePoint(b, a, verts, threshold);
        if (p.valid) p = btgMakeConvexPoint(-p.normal, p.pointB + p.normal * p.distance, p.distance);
        return p;
    }
    const uint round = BTG_CONVEX_FLAG_CAPSULE | BTG_CONVEX_FLAG_SPHERE;
    if ((a.shape.convexFlags & round) && (b.shape.convexFlags & round) &&
        ((a.shape.convexFlags | b.shape.convexFlags) & BTG_CONVEX_FLAG_CAPSULE))
        return btgCapsulePoint(a, b, threshold);
    return btgGjkPoint(a, b, verts, threshold);
}

#endif
