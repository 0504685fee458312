/* narrowphase_common.h — what every contact routine shares: the routine signature, body poses,
 * loading a pair's two bodies from the world columns, the manifold conventions (normal from B
 * to A, points on B with signed distance), and (device only) the kernel every pair-kind row
 * expands into. Routines compute in a canonical role order (sphere before hull before plane)
 * and btgSwapManifold restores the pair's own order afterwards. */
#ifndef BTG_NARROWPHASE_COMMON_H
#define BTG_NARROWPHASE_COMMON_H
#include "contact_reduce.h"
#include "math.h"
#include "counters.h"
#include "pair_kinds.h"

/* The shape tables a routine may read (hull vertices, faces, face-vertex indices, unique edge
 * directions, all rows of the shared tables): every routine takes them all, so the pair-kind
 * table calls any routine the same way,
 *     BtgManifold routine(BtgCollider a, BtgCollider b, BTG_SHAPE_TABLES, float threshold). */
#define BTG_SHAPE_TABLES                                                                             \
    BTG_CONST_GLOBAL BtgFloat4 *verts, BTG_CONST_GLOBAL BtgFace *faces, BTG_CONST_GLOBAL int *indices, \
        BTG_CONST_GLOBAL BtgFloat4 *edges
#define BTG_UNUSED_SHAPE_TABLES \
    (void)verts;                \
    (void)faces;                \
    (void)indices;              \
    (void)edges

typedef struct {
    BtgFloat4 pos; /* m, centre of mass */
    BtgMat3 rot;   /* body to world */
} BtgPose;

/* The point one step adds (Bullet's addContactPoint arguments). */
typedef struct {
    BtgFloat4 normal;  /* world unit normal from B towards A */
    BtgFloat4 pointB;  /* world point on B */
    float distance;    /* m, negative when penetrating */
    int valid;         /* 0: nothing within reach */
    int pad0, pad1;
} BtgConvexPoint;

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
    for (int k = 0; k < BTG_MAX_POINTS; ++k) {
        BtgManifoldPoint p;
        p.px = 0.0f;
        p.py = 0.0f;
        p.pz = 0.0f;
        p.distance = 0.0f;
        p.nx = 0.0f;
        p.ny = 1.0f;
        p.nz = 0.0f;
        p.featureId = BTG_FEATURE_UNKNOWN;
        m.points[k] = p;
    }
    m.partIdA = BTG_NO_SUB_SHAPE;
    m.indexA = BTG_NO_SUB_SHAPE;
    m.partIdB = BTG_NO_SUB_SHAPE;
    m.indexB = BTG_NO_SUB_SHAPE;
    m.bodyA = bodyA;
    m.bodyB = bodyB;
    m.numPoints = 0;
    m.breakingThreshold = 0.0f;
    return m;
}

/* A manifold point's vectors (w 0). */
static inline BtgFloat4 btgPointOnB(BtgManifoldPoint p) { return btgMake4(p.px, p.py, p.pz, 0.0f); }
static inline BtgFloat4 btgPointNormal(BtgManifoldPoint p) { return btgMake4(p.nx, p.ny, p.nz, 0.0f); }

static inline BtgManifoldPoint btgMakePoint(BtgFloat4 normal, BtgFloat4 pointB, float distance, uint featureId)
{
    BtgManifoldPoint p;
    p.px = pointB.x;
    p.py = pointB.y;
    p.pz = pointB.z;
    p.distance = distance;
    p.nx = normal.x;
    p.ny = normal.y;
    p.nz = normal.z;
    p.featureId = featureId;
    return p;
}

/* A pair's manifold carries the threshold it was found with. */
static inline BtgManifold btgWithThreshold(BtgManifold m, float threshold)
{
    m.breakingThreshold = threshold;
    return m;
}

static inline void btgAddPoint(BtgManifold* m, BtgFloat4 normal, BtgFloat4 pointB, float distance, uint featureId)
{
    if (m->numPoints >= BTG_MAX_POINTS) return;
    m->points[m->numPoints++] = btgMakePoint(normal, pointB, distance, featureId);
}

/* The same contact seen with A and B exchanged: each normal flips, each point moves to the
 * other surface (point on A = point on B + normal * distance), the sub-shape keys change sides;
 * the feature ids stay (they only have to match those of the same roles next step). */
static inline BtgManifold btgSwapManifold(BtgManifold m)
{
    BtgManifold s = m;
    s.bodyA = m.bodyB;
    s.bodyB = m.bodyA;
    s.partIdA = m.partIdB;
    s.indexA = m.indexB;
    s.partIdB = m.partIdA;
    s.indexB = m.indexA;
    for (int k = 0; k < m.numPoints; ++k) {
        BtgManifoldPoint p = m.points[k];
        BtgFloat4 n = btgPointNormal(p);
        s.points[k] = btgMakePoint(-n, btgPointOnB(p) + n * p.distance, p.distance, p.featureId);
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

/* The range of a pair whose one manifold sits at its own slot: that manifold if it has points. */
static inline BtgManifoldRange btgOneManifold(int slot, BtgManifold m)
{
    BtgManifoldRange r;
    r.start = slot;
    r.count = m.numPoints > 0 ? 1 : 0;
    return r;
}

#ifdef __OPENCL_C_VERSION__
/* The kernel of one pair-kind row: its routine over the kind's range of the kind-grouped pairs
 * (find_pairs). Launch: as many work-items as the host likes (it cannot know the range's size
 * without a readback); they stride over the range, read from kindRanges on the device. The pair
 * in range slot i is pairs[kindOrder[i]] (indirect), or pairs[i] when the scene has this one kind
 * (a side may be a compound's leaf: btgLoadPairCollider, compound.h, which the kernel file includes)
 * only (find_pairs then sorts nothing). A pair whose shapes are not this row's (a stale plan)
 * gets no points rather than another kind's routine. Writes manifolds[slot] of each pair in the
 * range (numPoints 0 when apart; manifolds stay in pair order) and pairManifolds[slot], the
 * pair's range of manifolds with points (btgOneManifold). */
#define BTG_NARROWPHASE_KERNEL(program, kind, shapeA, shapeB, routine, kernel)                                     \
    __kernel void kernel(__global const BtgPair* restrict pairs, __global const uint* restrict kindOrder,          \
                         __global const uint* restrict kindRanges, int indirect,                                    \
                         __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,            \
                         __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,     \
                         __global const BtgChild* restrict children,                                                \
                         __global const BtgFloat4* restrict verts, __global const BtgFace* restrict faces,          \
                         __global const int* restrict indices, __global const BtgFloat4* restrict edges,            \
                         __global BtgManifold* restrict manifolds,                                                  \
                         __global BtgManifoldRange* restrict pairManifolds)                                         \
    {                                                                                                               \
        const uint end = kindRanges[BTG_KIND_RANGE_END(kind)];                                                      \
        for (uint i = kindRanges[BTG_KIND_RANGE_START(kind)] + (uint)get_global_id(0); i < end;                    \
             i += (uint)get_global_size(0)) {                                                                      \
            const uint slot = indirect ? kindOrder[i] : i;                                                          \
            const BtgPair p = pairs[slot];                                                                          \
            BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, shapes, children);                           \
            BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, shapes, children);                           \
            const float t = btgPairThreshold(a.shape, b.shape);                                                     \
            const BtgManifold m = btgWithChildKeys(                                                                 \
                btgPairKind(a.shape.type, b.shape.type) == (kind)                                                   \
                    ? btgWithThreshold(routine(a, b, verts, faces, indices, edges, t), t)                           \
                    : btgEmptyManifold(p.a, p.b),                                                                   \
                p, children);                                                                                       \
            manifolds[slot] = m;                                                                                    \
            pairManifolds[slot] = btgOneManifold((int)slot, m);                                                     \
        }                                                                                                           \
    }
#endif

#endif
