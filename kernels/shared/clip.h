/* clip.h — hull–hull contact points after the SAT (sat.h). Face axis: the reference face is
 * the face most aligned with the axis on the hull that owns it, the incident face the most
 * anti-parallel face of the other hull; the incident polygon is clipped by the reference face's
 * side planes (Sutherland–Hodgman) and the points below the reference plane kept. Edge axis:
 * the closest points of the two supporting edges (one point, exact depth, as Box2D v3 and
 * Gregorius do); clipping is the fallback when no supporting edge is found. */
#ifndef BTG_CLIP_H
#define BTG_CLIP_H
#include "sat.h"

/* Private polygon buffers: a clipped polygon has at most (incident face vertices + reference
 * face vertices) corners, so faces of up to 32 vertices each are exact; corners beyond the
 * buffer are dropped (a hull with bigger faces should be split by the shape builder). */
#define BTG_MAX_POLY 64
#define BTG_EDGE_PARALLEL_COS 0.9999f /* a face edge runs along a unique edge direction */

/* Most aligned (sign 1) or most anti-parallel (sign -1) face of h with world direction d. */
static inline int btgExtremeFace(BtgCollider h, BTG_CONST_GLOBAL BtgFace* faces, BtgFloat4 d, float sign)
{
    BtgFloat4 dl = btgMat3TMulVec(h.pose.rot, d) * sign;
    int best = 0;
    float bestDot = 0.0f;
    for (int f = 0; f < h.shape.numFaces; ++f) {
        float c = btgDot3(faces[h.shape.firstFace + f].plane, dl);
        if (f == 0 || c > bestDot) {
            bestDot = c;
            best = f;
        }
    }
    return best;
}

/* One Sutherland–Hodgman step against the plane planeN.x = planeD (keeps the side <= 0).
 * Each corner carries the labels of its two polygon edges, (incoming << 8) | outgoing, as
 * box3d's polygon clipping does: a corner cut on the edge prev -> cur takes that edge and the
 * clipping plane's label `side`, so the labels name the corner by the features that make it. */
static inline int btgClipPolygon(const BtgFloat4* in, const uint* inLabels, int n, BtgFloat4 planeN, float planeD,
                                 uint side, BtgFloat4* out, uint* outLabels)
{
    int m = 0;
    if (n == 0) return 0;
    BtgFloat4 prev = in[n - 1];
    float dp = btgDot3(planeN, prev) - planeD;
    for (int i = 0; i < n; ++i) {
        BtgFloat4 cur = in[i];
        uint label = inLabels[i];
        float dc = btgDot3(planeN, cur) - planeD;
        if ((dc <= 0.0f) != (dp <= 0.0f) && m < BTG_MAX_POLY) {
            uint edge = label >> 8; /* the polygon edge prev -> cur */
            outLabels[m] = dp <= 0.0f ? (edge << 8) | side : (side << 8) | edge;
            out[m++] = prev + (cur - prev) * (dp / (dp - dc));
        }
        if (dc <= 0.0f && m < BTG_MAX_POLY) {
            outLabels[m] = label;
            out[m++] = cur;
        }
        prev = cur;
        dp = dc;
    }
    return m;
}

/* Clipping of the incident face of `inc` against reference face `refFace` of `ref`.
 * refIsA says which hull of the pair the reference belongs to (for the output conventions).
 * Each point's feature id is BTG_FEATURE_CLIP with its corner's faces and edge labels (types.h):
 * edges are labelled by hull (A or B), not by role, and the pair is flipped when B is the
 * reference, because B's loop runs the other way round the same polygon. */
static inline BtgManifold btgClipFaces(BtgCollider ref, int refFace, BtgCollider inc, int refIsA,
                                       BTG_CONST_GLOBAL BtgFloat4* verts, BTG_CONST_GLOBAL BtgFace* faces,
                                       BTG_CONST_GLOBAL int* indices, float threshold, BtgManifold m)
{
    BtgFace rf = faces[ref.shape.firstFace + refFace];
    BtgFloat4 nRef = btgMat3MulVec(ref.pose.rot, rf.plane); /* out of ref, towards inc */
    int incFace = btgExtremeFace(inc, faces, nRef, -1.0f);
    BtgFace inf = faces[inc.shape.firstFace + incFace];
    BtgFloat4 bufA[BTG_MAX_POLY];
    BtgFloat4 bufB[BTG_MAX_POLY];
    uint labA[BTG_MAX_POLY];
    uint labB[BTG_MAX_POLY];
    int n = 0;
    for (int k = 0; k < inf.numIndices && n < BTG_MAX_POLY; ++k)
        bufA[n++] = btgPoseApply(inc.pose, btgFaceVertex(inc.shape, inf, verts, indices, k));
    const uint refOwner = refIsA ? 0u : BTG_FEATURE_EDGE_OF_B, incOwner = refIsA ? BTG_FEATURE_EDGE_OF_B : 0u;
    /* corner k of the incident loop: between its edges k - 1 and k */
    for (int k = 0; k < n; ++k)
        labA[k] = ((incOwner | (uint)((k + n - 1) % n & 0x7f)) << 8) | incOwner | (uint)(k & 0x7f);
    int inA = 1;
    for (int k = 0; k < rf.numIndices && n > 0; ++k) {
        BtgFloat4 v0 = btgPoseApply(ref.pose, btgFaceVertex(ref.shape, rf, verts, indices, k));
        BtgFloat4 v1 = btgPoseApply(ref.pose, btgFaceVertex(ref.shape, rf, verts, indices, k + 1 < rf.numIndices ? k + 1 : 0));
        BtgFloat4 side = btgCross3(v1 - v0, nRef); /* outward for a counter-clockwise loop */
        float d = btgDot3(side, v0);
        uint label = refOwner | (uint)(k & 0x7f);
        n = inA ? btgClipPolygon(bufA, labA, n, side, d, label, bufB, labB)
                : btgClipPolygon(bufB, labB, n, side, d, label, bufA, labA);
        inA = !inA;
    }
    BtgFloat4* poly = inA ? bufA : bufB;
    uint* labels = inA ? labA : labB;
    const int faceA = refIsA ? refFace : incFace, faceB = refIsA ? incFace : refFace;
    const uint faceBits = BTG_FEATURE_CLIP | ((uint)(faceA & 0x7f) << 23) | ((uint)(faceB & 0x7f) << 16);
    float refD = btgDot3(nRef, btgPoseApply(ref.pose, btgFaceVertex(ref.shape, rf, verts, indices, 0)));
    float margins = ref.shape.margin + inc.shape.margin;
    float marginB = refIsA ? inc.shape.margin : ref.shape.margin;
    BtgFloat4 normal = refIsA ? -nRef : nRef; /* from B towards A */
    int kept = 0;
    for (int i = 0; i < n; ++i) {
        BtgFloat4 p = poly[i];
        float depth = btgDot3(nRef, p) - refD;
        float dist = depth - margins;
        if (dist >= threshold) continue;
        /* p lies on the incident hull, p - nRef*depth on the reference face */
        BtgFloat4 onB = refIsA ? btgXyz(p) : btgXyz(p) - nRef * depth;
        BtgFloat4 c = onB + normal * marginB;
        c.w = dist;
        uint pair = refIsA ? labels[i] : ((labels[i] & 0xffu) << 8) | (labels[i] >> 8);
        labels[kept] = faceBits | pair;
        poly[kept++] = c; /* kept <= i: compacting in place is safe */
    }
    if (kept > 0) btgReduceArray(poly, labels, kept, normal, &m);
    return m;
}

/* The edge of h running along unique direction e (local) that is extreme along world d
 * (sign 1: largest projection, -1: smallest); returns 0 when no face edge runs along e. */
static inline int btgSupportEdge(BtgCollider h, BTG_CONST_GLOBAL BtgFloat4* verts, BTG_CONST_GLOBAL BtgFace* faces,
                                 BTG_CONST_GLOBAL int* indices, BtgFloat4 e, BtgFloat4 d, float sign, BtgFloat4* p0,
                                 BtgFloat4* p1)
{
    BtgFloat4 dl = btgMat3TMulVec(h.pose.rot, d) * sign;
    int found = 0;
    float best = 0.0f;
    for (int f = 0; f < h.shape.numFaces; ++f) {
        BtgFace face = faces[h.shape.firstFace + f];
        for (int k = 0; k < face.numIndices; ++k) {
            BtgFloat4 v0 = btgFaceVertex(h.shape, face, verts, indices, k);
            BtgFloat4 v1 = btgFaceVertex(h.shape, face, verts, indices, k + 1 < face.numIndices ? k + 1 : 0);
            BtgFloat4 dir = v1 - v0;
            float len = btgLength3(dir);
            if (len <= 0.0f || btgAbs(btgDot3(dir, e)) < BTG_EDGE_PARALLEL_COS * len) continue;
            float s = btgDot3(dl, v0 + v1);
            if (!found || s > best) {
                best = s;
                *p0 = v0;
                *p1 = v1;
                found = 1;
            }
        }
    }
    if (found) {
        *p0 = btgPoseApply(h.pose, *p0);
        *p1 = btgPoseApply(h.pose, *p1);
    }
    return found;
}

/* Closest points of segments p1q1 and p2q2 (Ericson, Real-Time Collision Detection 5.1.9). */
static inline void btgClosestSegments(BtgFloat4 p1, BtgFloat4 q1, BtgFloat4 p2, BtgFloat4 q2, BtgFloat4* c1, BtgFloat4* c2)
{
    BtgFloat4 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    float a = btgDot3(d1, d1), e = btgDot3(d2, d2), f = btgDot3(d2, r);
    float c = btgDot3(d1, r), b = btgDot3(d1, d2);
    float denom = a * e - b * b;
    float s = denom > 1e-12f ? btgClamp((b * f - c * e) / denom, 0.0f, 1.0f) : 0.0f;
    float t = (b * s + f) / e;
    if (t < 0.0f) {
        t = 0.0f;
        s = btgClamp(-c / a, 0.0f, 1.0f);
    } else if (t > 1.0f) {
        t = 1.0f;
        s = btgClamp((b - c) / a, 0.0f, 1.0f);
    }
    *c1 = p1 + d1 * s;
    *c2 = p2 + d2 * t;
}

/* The hull–hull routine of the pair-kind table (program "narrowphase_sat"). */
static inline BtgManifold btgCollideHullHull(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold)
{
    BtgManifold m = btgEmptyManifold(a.body, b.body);
    float margins = a.shape.margin + b.shape.margin;
    BtgSatResult sat = btgFindSeparatingAxis(a, b, verts, faces, edges, threshold + margins);
    if (sat.separation - margins >= threshold) return m;
    BtgFloat4 d = sat.axis; /* A towards B */
    if (sat.feature == BTG_SAT_EDGE) {
        BtgFloat4 a0, a1, b0, b1;
        if (btgSupportEdge(a, verts, faces, indices, edges[a.shape.firstEdge + sat.indexA], d, 1.0f, &a0, &a1) &&
            btgSupportEdge(b, verts, faces, indices, edges[b.shape.firstEdge + sat.indexB], d, -1.0f, &b0, &b1)) {
            BtgFloat4 pa, pb;
            btgClosestSegments(a0, a1, b0, b1, &pa, &pb);
            float dist = btgDot3(d, pb - pa) - margins;
            if (dist < threshold)
                btgAddPoint(&m, -d, pb - d * b.shape.margin, dist,
                            BTG_FEATURE_EDGES | ((uint)(sat.indexA & 0x7fff) << 15) | (uint)(sat.indexB & 0x7fff));
            return m;
        }
    }
    int refIsA;
    if (sat.feature == BTG_SAT_FACE_A) {
        refIsA = 1;
    } else if (sat.feature == BTG_SAT_FACE_B) {
        refIsA = 0;
    } else {
        /* edge fallback: the hull whose best face is more aligned with the axis is the reference */
        int fa = btgExtremeFace(a, faces, d, 1.0f), fb = btgExtremeFace(b, faces, -d, 1.0f);
        float ca = btgDot3(btgMat3MulVec(a.pose.rot, faces[a.shape.firstFace + fa].plane), d);
        float cb = -btgDot3(btgMat3MulVec(b.pose.rot, faces[b.shape.firstFace + fb].plane), d);
        refIsA = ca >= cb;
    }
    if (refIsA) return btgClipFaces(a, btgExtremeFace(a, faces, d, 1.0f), b, 1, verts, faces, indices, threshold, m);
    return btgClipFaces(b, btgExtremeFace(b, faces, -d, 1.0f), a, 0, verts, faces, indices, threshold, m);
}

#endif
