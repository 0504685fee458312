/* round_contacts.h — the soft step's fresh contact of a capsule (btCapsuleShape) or a cylinder
 * (btCylinderShape) on a box's face or a plane (btgCollideRoundOnFace, through
 * btgCollideSoftAfresh), as Box2D's capsule–polygon and Jolt's manifolds make them: a capsule's
 * segment clipped to the face, a point under each end of what is left; a cylinder's cap rims,
 * four points on each (the lowest and its quarter turns), those within reach reduced to four.
 *
 * Why not the persistent manifold stock keeps: its one GJK point a step, kept in both bodies'
 * frames until it drifts 2 cm apart, leaves points behind a rolling capsule or cylinder; each
 * carries its share of the weight at a lever arm that trails the axis, a torque that rolls the
 * body on. With the GPU's GJK point a few micrometres off the middle, a capsule laid at rest
 * on a box rolled away by itself (0.04 m/s after 10 s, growing; stock 1e-4), a capsule rolling
 * at 0.1 m/s sped up to 0.25 (stock to 0.40), a cylinder laid at rest rolled off at 0.49 m/s
 * (stock 0.54). Points made afresh each step from the current pose lie under the axis: no
 * torque about it. Where the body meets the box at an edge or corner (the GJK normal not within
 * BTG_ROUND_FACE_COS of a face's), or overhangs the face entirely, the one GJK point. */
#ifndef BTG_ROUND_CONTACTS_H
#define BTG_ROUND_CONTACTS_H
#include "gjk.h"
#include "simple_contacts.h"
#include "contact_reduce.h"

#define BTG_ROUND_FACE_COS 0.98f /* about 11 degrees: a face's contact, else an edge's or corner's */

static inline int btgIsCapsule(BtgShape s) { return s.type == BTG_SHAPE_CONVEX && s.convexType == BTG_CONVEX_CAPSULE; }
static inline int btgIsCylinder(BtgShape s) { return s.type == BTG_SHAPE_CONVEX && s.convexType == BTG_CONVEX_CYLINDER; }
static inline int btgIsRound(BtgShape s) { return btgIsCapsule(s) || btgIsCylinder(s); }

/* Whether a pair is a capsule or cylinder on a box or a plane (the soft step collides it afresh). */
static inline int btgRoundOnFace(BtgShape a, BtgShape b)
{
    const int faceA = a.type == BTG_SHAPE_BOX || a.type == BTG_SHAPE_PLANE;
    const int faceB = b.type == BTG_SHAPE_BOX || b.type == BTG_SHAPE_PLANE;
    return (btgIsRound(a) && faceB) || (btgIsRound(b) && faceA);
}

/* The face the round body r lies on: world normal n (from the face towards r) and constant w
 * (points p with n.p = w on it), bounded by up to four side planes (xyz outward, w: a point p
 * is over the face where every side's xyz.p <= w): a box's face its rectangle's four, a
 * triangle its three edges', a plane none. */
typedef struct {
    BtgFloat4 n;
    float w;
    int numSides;
    BtgFloat4 side[4];
} BtgRoundFace;

/* A plane's face (no sides). */
static inline BtgRoundFace btgPlaneFace(BtgCollider f)
{
    BtgRoundFace face;
    const BtgFloat4 plane = btgWorldPlane(f);
    face.n = btgXyz(plane);
    face.w = plane.w;
    face.numSides = 0;
    return face;
}

/* A box's (f's) face: 1, 0: nothing within reach, -1: an edge or corner (*g its one point). */
static inline int btgRoundFaceOf(BtgCollider r, BtgCollider f, BTG_CONST_GLOBAL BtgFloat4* verts, float threshold,
                                 BtgRoundFace* face, BtgConvexPoint* g)
{
    face->numSides = 0;
    *g = btgGjkPoint(r, f, verts, threshold);
    if (!g->valid) return 0;
    const BtgFloat4 nl = btgMat3TMulVec(f.pose.rot, g->normal);
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (btgAbs(btgComp(nl, i)) > btgAbs(btgComp(nl, k))) k = i;
    if (btgAbs(btgComp(nl, k)) < BTG_ROUND_FACE_COS) return -1;
    BtgFloat4 e = btgZero4();
    btgSetComp(&e, k, btgComp(nl, k) < 0.0f ? -1.0f : 1.0f);
    face->n = btgMat3MulVec(f.pose.rot, e);
    face->w = btgDot3(face->n, f.pose.pos) + btgComp(f.shape.param, k);
    for (int i = 0; i < 3; ++i) {
        if (i == k) continue;
        BtgFloat4 a = btgZero4();
        btgSetComp(&a, i, 1.0f);
        const BtgFloat4 s = btgMat3MulVec(f.pose.rot, a);
        const float c = btgDot3(s, f.pose.pos), h = btgComp(f.shape.param, i);
        face->side[face->numSides++] = btgMake4(s.x, s.y, s.z, c + h);
        face->side[face->numSides++] = btgMake4(-s.x, -s.y, -s.z, h - c);
    }
    return 1;
}

/* Whether world point p lies over the face (inside every side plane). */
static inline int btgOverFace(const BtgRoundFace* face, BtgFloat4 p)
{
    for (int i = 0; i < face->numSides; ++i)
        if (btgDot3(face->side[i], p) > face->side[i].w) return 0;
    return 1;
}

/* A capsule (segment along upAxis, half height param.y, radius param.x) on the face: its
 * segment clipped to the face's sides, a point under each end of what is left, within the
 * threshold. 0 when the segment's shadow misses the face. */
static inline int btgCapsuleOnFaceCanonical(BtgManifold* m, BtgCollider c, const BtgRoundFace* face, float threshold)
{
    BtgFloat4 e = btgZero4();
    btgSetComp(&e, c.shape.upAxis, c.shape.param.y);
    const BtgFloat4 d = btgMat3MulVec(c.pose.rot, e);
    const BtgFloat4 p0 = btgXyz(c.pose.pos) - d, p1 = btgXyz(c.pose.pos) + d;
    float t0 = 0.0f, t1 = 1.0f;
    for (int i = 0; i < face->numSides; ++i) {
        /* the sides are perpendicular to the face: the shadow's ends are the segment's */
        const float a = btgDot3(face->side[i], p0) - face->side[i].w, b = btgDot3(face->side[i], p1) - face->side[i].w;
        if (a > 0.0f && b > 0.0f) return 0;
        if (a > 0.0f) t0 = btgMax(t0, a / (a - b));
        else if (b > 0.0f) t1 = btgMin(t1, a / (a - b));
    }
    if (t0 > t1) return 0;
    for (int end = 0; end < 2; ++end) {
        if (end == 1 && t1 == t0) break;
        const BtgFloat4 p = p0 + (p1 - p0) * (end == 0 ? t0 : t1);
        const float height = btgDot3(face->n, p) - face->w;
        const float dist = height - c.shape.param.x;
        if (dist < threshold) btgAddPoint(m, face->n, p - face->n * height, dist, BTG_FEATURE_VERTEX | (uint)end);
    }
    return 1;
}

/* A cylinder (core half extents param, radius along the first axis other than upAxis, its
 * margin around the core) on the face: on each cap the rim point lowest towards the face and its
 * three quarter turns (on a cap facing the face squarely, four points of its rim), each over the
 * face and within the threshold a candidate, reduced to four. 0 when none is. */
static inline int btgCylinderOnFaceCanonical(BtgManifold* m, BtgCollider c, const BtgRoundFace* face, float threshold)
{
    const int up = c.shape.upAxis, xx = up == 0 ? 1 : 0, zz = up == 2 ? 1 : 2;
    const float radius = btgComp(c.shape.param, xx), halfHeight = btgComp(c.shape.param, up);
    const BtgFloat4 nl = btgMat3TMulVec(c.pose.rot, face->n);
    /* the rim's lowest direction in the caps' plane (shape-local): against the face's normal */
    const float vx = -btgComp(nl, xx), vz = -btgComp(nl, zz), len = btgSqrt(vx * vx + vz * vz);
    const float cx = len > 1e-6f ? vx / len : 1.0f, cz = len > 1e-6f ? vz / len : 0.0f;
    BtgFloat4 pts[8];
    uint ids[8];
    int n = 0;
    for (int cap = 0; cap < 2; ++cap)
        for (int q = 0; q < 4; ++q) {
            /* quarter turn q of (cx, cz): (cx, cz), (-cz, cx), (-cx, -cz), (cz, -cx) */
            const float rx = q == 0 ? cx : q == 1 ? -cz : q == 2 ? -cx : cz;
            const float rz = q == 0 ? cz : q == 1 ? cx : q == 2 ? -cz : -cx;
            BtgFloat4 onCore = btgZero4();
            btgSetComp(&onCore, xx, rx * radius);
            btgSetComp(&onCore, zz, rz * radius);
            btgSetComp(&onCore, up, cap == 0 ? -halfHeight : halfHeight);
            const BtgFloat4 p = btgPoseApply(c.pose, onCore);
            const float height = btgDot3(face->n, p) - face->w;
            const float dist = height - c.shape.margin;
            const BtgFloat4 onFace = p - face->n * height;
            if (dist >= threshold || !btgOverFace(face, onFace)) continue;
            pts[n] = btgMake4(onFace.x, onFace.y, onFace.z, dist);
            ids[n] = BTG_FEATURE_VERTEX | (uint)(4 * cap + q);
            ++n;
        }
    if (n == 0) return 0;
    btgReduceArray(pts, ids, n, face->n, m);
    return 1;
}

/* The body laid on the face (1), or 0 where its shadow misses it. */
static inline int btgRoundLaid(BtgManifold* m, BtgCollider r, const BtgRoundFace* face, float threshold)
{
    return btgIsCapsule(r.shape) ? btgCapsuleOnFaceCanonical(m, r, face, threshold)
                                 : btgCylinderOnFaceCanonical(m, r, face, threshold);
}

/* Canonical order: the capsule or cylinder r is A, the plane f is B. No GJK: collide_fresh's. */
static inline BtgManifold btgRoundOnPlaneCanonical(BtgCollider r, BtgCollider f, float threshold)
{
    BtgManifold m = btgEmptyManifold(r.body, f.body);
    const BtgRoundFace face = btgPlaneFace(f);
    btgRoundLaid(&m, r, &face, threshold);
    return m;
}

/* Canonical order: the capsule or cylinder r is A, the box f is B. */
static inline BtgManifold btgRoundOnBoxCanonical(BtgCollider r, BtgCollider f, BTG_CONST_GLOBAL BtgFloat4* verts,
                                                 float threshold)
{
    BtgManifold m = btgEmptyManifold(r.body, f.body);
    BtgRoundFace face;
    BtgConvexPoint g = btgNoPoint();
    const int found = btgRoundFaceOf(r, f, verts, threshold, &face, &g);
    if (found == 0) return m;
    if (found > 0 && btgRoundLaid(&m, r, &face, threshold)) return m;
    /* an edge or corner, or overhanging the face: GJK's point */
    btgAddPoint(&m, g.normal, g.pointB, g.distance, BTG_FEATURE_VERTEX | 8u);
    return m;
}

/* A capsule or cylinder and a plane, either order (no GJK). */
static inline BtgManifold btgCollideRoundOnPlane(BtgCollider a, BtgCollider b, float threshold)
{
    if (btgIsRound(a.shape)) return btgRoundOnPlaneCanonical(a, b, threshold);
    return btgSwapManifold(btgRoundOnPlaneCanonical(b, a, threshold));
}

/* A capsule or cylinder and a box or plane, either order. */
static inline BtgManifold btgCollideRoundOnFace(BtgCollider a, BtgCollider b, BTG_CONST_GLOBAL BtgFloat4* verts,
                                                float threshold)
{
    if (a.shape.type == BTG_SHAPE_PLANE || b.shape.type == BTG_SHAPE_PLANE) return btgCollideRoundOnPlane(a, b, threshold);
    if (btgIsRound(a.shape)) return btgRoundOnBoxCanonical(a, b, verts, threshold);
    return btgSwapManifold(btgRoundOnBoxCanonical(b, a, verts, threshold));
}

#endif
