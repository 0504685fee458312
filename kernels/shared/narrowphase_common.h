/* narrowphase_common.h — what every contact routine shares: pair kinds, body poses, loading a
 * pair's two bodies from the world columns, and the manifold conventions (normal from B to A,
 * points on B with signed distance). Routines compute in a canonical role order (sphere before
 * hull before plane) and btgSwapManifold restores the pair's own order afterwards. */
#ifndef BTG_NARROWPHASE_COMMON_H
#define BTG_NARROWPHASE_COMMON_H
#include "contact_reduce.h"
#include "math.h"

/* Pair kinds: one kernel owns each. */
#define BTG_PAIR_NONE 0 /* plane–plane: never produced by the broadphase (both static) */
#define BTG_PAIR_SPHERE_SPHERE 1
#define BTG_PAIR_SPHERE_HULL 2
#define BTG_PAIR_SPHERE_PLANE 3
#define BTG_PAIR_HULL_PLANE 4
#define BTG_PAIR_HULL_HULL 5

static inline int btgPairKind(int ta, int tb)
{
    int lo = ta < tb ? ta : tb, hi = ta < tb ? tb : ta;
    if (lo == BTG_SHAPE_SPHERE) {
        if (hi == BTG_SHAPE_SPHERE) return BTG_PAIR_SPHERE_SPHERE;
        return hi == BTG_SHAPE_HULL ? BTG_PAIR_SPHERE_HULL : BTG_PAIR_SPHERE_PLANE;
    }
    if (lo == BTG_SHAPE_HULL) return hi == BTG_SHAPE_HULL ? BTG_PAIR_HULL_HULL : BTG_PAIR_HULL_PLANE;
    return BTG_PAIR_NONE;
}

typedef struct {
    BtgFloat4 pos; /* m, centre of mass */
    BtgMat3 rot;   /* body to world */
} BtgPose;

/* One side of a pair: where the body is and what shape it has. */
typedef struct {
    BtgPose pose;
    BtgShape shape;
    int body;
    int pad0, pad1, pad2;
} BtgCollider;

/* The pair's contact breaking threshold, m: the smaller of the two shapes' (Bullet's
 * btCollisionDispatcher::getNewManifold with CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD). */
static inline float btgPairThreshold(BtgShape a, BtgShape b)
{
    return a.breakingThreshold < b.breakingThreshold ? a.breakingThreshold : b.breakingThreshold;
}

static inline BtgFloat4 btgPoseApply(BtgPose p, BtgFloat4 v) { return btgXyz(p.pos) + btgMat3MulVec(p.rot, v); }
static inline BtgFloat4 btgPoseApplyInv(BtgPose p, BtgFloat4 world) { return btgMat3TMulVec(p.rot, btgXyz(world - p.pos)); }

static inline BtgCollider btgLoadCollider(int body, BTG_CONST_GLOBAL BtgFloat4* pos, BTG_CONST_GLOBAL BtgFloat4* rot,
                                          BTG_CONST_GLOBAL BtgBodyProps* props, BTG_CONST_GLOBAL BtgShape* shapes)
{
    BtgCollider c;
    c.pose.pos = btgXyz(pos[body]);
    c.pose.rot = btgQuatToMat3(rot[body]);
    c.shape = shapes[props[body].shape];
    c.body = body;
    c.pad0 = 0;
    c.pad1 = 0;
    c.pad2 = 0;
    return c;
}

static inline BtgManifold btgEmptyManifold(int bodyA, int bodyB)
{
    BtgManifold m;
    m.normal = btgMake4(0.0f, 1.0f, 0.0f, 0.0f);
    for (int k = 0; k < BTG_MAX_POINTS; ++k) m.pointB[k] = btgZero4();
    m.bodyA = bodyA;
    m.bodyB = bodyB;
    m.numPoints = 0;
    m.breakingThreshold = 0.0f;
    return m;
}

/* A pair's manifold carries the threshold it was found with. */
static inline BtgManifold btgWithThreshold(BtgManifold m, float threshold)
{
    m.breakingThreshold = threshold;
    return m;
}

static inline void btgAddPoint(BtgManifold* m, BtgFloat4 pointB, float distance)
{
    if (m->numPoints >= BTG_MAX_POINTS) return;
    BtgFloat4 p = btgXyz(pointB);
    p.w = distance;
    m->pointB[m->numPoints++] = p;
}

/* The same contact seen with A and B exchanged: the normal flips and each point moves to the
 * other surface (point on A = pointB + normal * distance). */
static inline BtgManifold btgSwapManifold(BtgManifold m)
{
    BtgManifold s = m;
    s.bodyA = m.bodyB;
    s.bodyB = m.bodyA;
    s.normal = -btgXyz(m.normal);
    for (int k = 0; k < m.numPoints; ++k) {
        BtgFloat4 p = btgXyz(m.pointB[k]) + btgXyz(m.normal) * m.pointB[k].w;
        p.w = m.pointB[k].w;
        s.pointB[k] = p;
    }
    return s;
}

/* A hull vertex and a face's k-th loop vertex, shape-local. */
static inline BtgFloat4 btgHullVertex(BtgShape s, BTG_CONST_GLOBAL BtgFloat4* verts, int i)
{
    return btgXyz(verts[s.firstVertex + i]);
}
static inline BtgFloat4 btgFaceVertex(BtgShape s, BtgFace f, BTG_CONST_GLOBAL BtgFloat4* verts,
                                      BTG_CONST_GLOBAL int* indices, int k)
{
    return btgXyz(verts[s.firstVertex + indices[f.firstIndex + k]]);
}

#endif
