/* sat.h — separating-axis search between two convex hulls: the face normals of both and the
 * cross products of their unique edge directions. Each axis is measured by the overlap of the
 * two projected vertex intervals, oriented by the smaller overlap (Bullet's TestSepAxis).
 * Ties are broken towards face axes (A's before B's) by fixed biases, so the chosen feature is
 * stable and deterministic when several axes are equally good (stacked equal boxes). */
#ifndef BTG_SAT_H
#define BTG_SAT_H
#include "narrowphase_common.h"

/* Face B or an edge pair must beat the best earlier axis by this much (m): 0.1 × Box2D v3's
 * 5 mm linear slop, as Box2D biases its SAT. */
#define BTG_SAT_FACE_BIAS 5e-4f
#define BTG_SAT_EDGE_BIAS 5e-4f
/* |eA × eB| below this (sine of the angle) means parallel edges: no axis of their own. */
#define BTG_SAT_PARALLEL 1e-3f

#define BTG_SAT_FACE_A 0
#define BTG_SAT_FACE_B 1
#define BTG_SAT_EDGE 2

typedef struct {
    BtgFloat4 axis;   /* world unit axis, oriented from A towards B */
    float separation; /* m, polyhedra only (margins not subtracted); negative: overlap depth */
    int feature;      /* BTG_SAT_* */
    int indexA;       /* face of A, or edge direction of A */
    int indexB;       /* face of B, or edge direction of B */
} BtgSatResult;

/* Projection interval of a hull's vertices onto world axis d. */
static inline void btgHullInterval(BtgCollider h, BTG_CONST_GLOBAL BtgFloat4* verts, BtgFloat4 d, float* lo, float* hi)
{
    BtgFloat4 dl = btgMat3TMulVec(h.pose.rot, d);
    float base = btgDot3(d, h.pose.pos);
    if (h.shape.type == BTG_SHAPE_BOX) {
        /* A box's vertices are exactly (+-hx, +-hy, +-hz) (shape_tables.cpp): the loop below
         * would find its largest projection at the vertex whose signs are dl's, the same
         * products |dl_i| h_i summed in the same order, and the smallest at the opposite vertex,
         * exactly its negation (rounding is monotone and symmetric). Bit for bit the loop's
         * interval, for 3 products instead of 8 dot products (the soft step's box pairs run
         * this SAT every step). */
        BtgFloat4 adl = btgMake4(btgAbs(dl.x), btgAbs(dl.y), btgAbs(dl.z), 0.0f);
        float r = btgDot3(adl, h.shape.param);
        *lo = base + (-r);
        *hi = base + r;
        return;
    }
    float mn = 0.0f, mx = 0.0f;
    for (int i = 0; i < h.shape.numVertices; ++i) {
        float s = btgDot3(dl, btgHullVertex(h.shape, verts, i));
        if (i == 0 || s < mn) mn = s;
        if (i == 0 || s > mx) mx = s;
    }
    *lo = base + mn;
    *hi = base + mx;
}

/* Separation along d (positive: a gap); *axis gets d or -d, whichever points from A to B. */
static inline float btgAxisSeparation(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts, BtgFloat4 d,
                                      BtgFloat4* axis)
{
    float loA, hiA, loB, hiB;
    btgHullInterval(a, verts, d, &loA, &hiA);
    btgHullInterval(b, verts, d, &loB, &hiB);
    float overlapPlus = hiA - loB;  /* B on the +d side of A */
    float overlapMinus = hiB - loA; /* B on the -d side */
    if (overlapPlus <= overlapMinus) {
        *axis = d;
        return -overlapPlus;
    }
    *axis = -d;
    return -overlapMinus;
}

/* Best axis; stops early once an axis separates by more than `reject` m. */
static inline BtgSatResult btgFindSeparatingAxis(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts,
                                                 BTG_CONST_GLOBAL BtgFace* faces, BTG_CONST_GLOBAL BtgFloat4* edges,
                                                 float reject)
{
    BtgSatResult best;
    best.axis = btgMake4(0.0f, 1.0f, 0.0f, 0.0f);
    best.separation = -3.0e38f;
    best.feature = BTG_SAT_FACE_A;
    best.indexA = -1;
    best.indexB = -1;
    /* A box's faces come in opposite pairs, +axis before -axis (shape_tables.cpp): the second
     * of a pair measures exactly the first's separation (every interval negated exactly), and
     * an equal separation never replaces the best, so it is skipped, bit for bit. */
    const int stepA = a.shape.type == BTG_SHAPE_BOX ? 2 : 1, stepB = b.shape.type == BTG_SHAPE_BOX ? 2 : 1;
    for (int f = 0; f < a.shape.numFaces; f += stepA) {
        BtgFloat4 axis;
        BtgFloat4 d = btgMat3MulVec(a.pose.rot, faces[a.shape.firstFace + f].plane);
        float s = btgAxisSeparation(a, b, verts, d, &axis);
        if (best.indexA < 0 || s > best.separation) {
            best.axis = axis;
            best.separation = s;
            best.indexA = f;
            if (s > reject) return best;
        }
    }
    for (int f = 0; f < b.shape.numFaces; f += stepB) {
        BtgFloat4 axis;
        BtgFloat4 d = btgMat3MulVec(b.pose.rot, faces[b.shape.firstFace + f].plane);
        float s = btgAxisSeparation(a, b, verts, d, &axis);
        if (s > best.separation + BTG_SAT_FACE_BIAS || (best.indexA < 0 && best.indexB < 0)) {
            best.axis = axis;
            best.separation = s;
            best.feature = BTG_SAT_FACE_B;
            best.indexA = -1;
            best.indexB = f;
            if (s > reject) return best;
        }
    }
    BtgSatResult edge = best;
    int haveEdge = 0;
    for (int i = 0; i < a.shape.numEdges; ++i) {
        BtgFloat4 ea = btgMat3MulVec(a.pose.rot, edges[a.shape.firstEdge + i]);
        for (int j = 0; j < b.shape.numEdges; ++j) {
            BtgFloat4 eb = btgMat3MulVec(b.pose.rot, edges[b.shape.firstEdge + j]);
            BtgFloat4 c = btgCross3(ea, eb);
            float len = btgLength3(c);
            if (len < BTG_SAT_PARALLEL) continue;
            BtgFloat4 axis;
            float s = btgAxisSeparation(a, b, verts, c * (1.0f / len), &axis);
            if (!haveEdge || s > edge.separation) {
                edge.axis = axis;
                edge.separation = s;
                edge.feature = BTG_SAT_EDGE;
                edge.indexA = i;
                edge.indexB = j;
                haveEdge = 1;
                if (s > reject) return edge;
            }
        }
    }
    if (haveEdge && edge.separation > best.separation + BTG_SAT_EDGE_BIAS) return edge;
    return best;
}

#endif
