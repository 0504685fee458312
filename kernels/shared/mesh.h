/* mesh.h — triangle meshes on the device: the mesh table (one row per btBvhTriangleMeshShape,
 * shared by every body and scaled wrapper that uses it), Bullet's own quantized BVH nodes with
 * their escape indices (btQuantizedBvh, slide 56 of the talk), and the midphase walk that
 * finds the triangles under a convex body's AABB exactly as btQuantizedBvh's stackless walk
 * does (same quantization, same overlap test), shared by kernels/midphase.cl and its reference. */
#ifndef BTG_MESH_H
#define BTG_MESH_H
#include "aabb.h"
#include "math.h"
#include "pair_kinds.h"
#include "types.h"

/* Bullet's MAX_NUM_PARTS_IN_BITS: a leaf holds (part << 21) | triangle index. */
#define BTG_BVH_PART_SHIFT 21
#define BTG_BVH_TRIANGLE_MASK 0x1fffff

/* One mesh: its BVH's quantization and its rows in the node, triangle and part tables. */
typedef struct {
    BtgFloat4 bvhMin;          /* m, mesh-local: Bullet's m_bvhAabbMin; w 0 */
    BtgFloat4 bvhMax;          /* m: m_bvhAabbMax; w 0 */
    BtgFloat4 bvhQuantization; /* 1/m: m_bvhQuantization; w 0 */
    int firstNode;             /* rows in the node table (BtgBvhNode) */
    int numNodes;              /* Bullet's m_curNodeIndex: the walk's end */
    int firstTriangle;         /* rows in the triangle table */
    int numTriangles;
    int firstPart;             /* rows in the part table: first triangle of each part */
    int numParts;
    int pad0;
    int pad1;
} BtgMesh;

/* btQuantizedBvhNode packed in 4-byte words: unsigned short min[3], max[3], then the escape
 * index (negative: internal node, skip this many nodes when the box misses) or the leaf's
 * (part << 21) | triangle. */
typedef struct {
    uint minXY;    /* min x | min y << 16 */
    uint minZMaxX; /* min z | max x << 16 */
    uint maxYZ;    /* max y | max z << 16 */
    int escapeOrTriangle;
} BtgBvhNode;

/* One triangle: the rows of its three vertices in the mesh vertex table (BtgFloat4, m,
 * mesh-local, the mesh interface's scaling applied, as Bullet's node callback reads them). */
typedef struct {
    int v0;
    int v1;
    int v2;
    int pad0;
} BtgTriangle;

/* One (convex, triangle) sub-pair the midphase found: the broadphase pair's slot and the
 * triangle, by its row in the triangle table and by Bullet's (part id, triangle index). */
typedef struct {
    int pair;     /* slot in pairs */
    int triangle; /* row in the triangle table */
    int partId;   /* Bullet's m_partId of the triangle's points */
    int index;    /* Bullet's m_index: the triangle within its part */
} BtgSubPair;

/* The pair slot whose manifold lies at `slot`: its own (slot < base, the pair slots), or a
 * convex–concave pair's group manifold in the sub-pair region (base + s: sub-pair s's pair). */
static inline uint btgManifoldPair(uint slot, uint base, BTG_CONST_GLOBAL BtgSubPair* subPairs, uint subPairCapacity)
{
    if (slot < base) return slot;
    return slot - base < subPairCapacity ? (uint)subPairs[slot - base].pair : 0xffffffffu;
}

/* A quantized box: min xyz and max xyz. */
typedef struct {
    uint lo[3];
    uint hi[3];
} BtgQuantizedBox;

/* btQuantizedBvh::quantizeWithClamp: clamp into the BVH's box, then floor to an even value
 * (min) or round up to an odd one (max). */
static inline uint btgQuantizeAxis(float p, float lo, float hi, float q, int isMax)
{
    float c = p < lo ? lo : p;
    c = c > hi ? hi : c;
    float v = (c - lo) * q;
    if (isMax) return (((uint)(v + 1.0f)) & 0xffffu) | 1u;
    return ((uint)v) & 0xfffeu;
}

static inline BtgQuantizedBox btgQuantizeBox(BtgMesh m, BtgAabb box)
{
    BtgQuantizedBox b;
    b.lo[0] = btgQuantizeAxis(box.lo.x, m.bvhMin.x, m.bvhMax.x, m.bvhQuantization.x, 0);
    b.lo[1] = btgQuantizeAxis(box.lo.y, m.bvhMin.y, m.bvhMax.y, m.bvhQuantization.y, 0);
    b.lo[2] = btgQuantizeAxis(box.lo.z, m.bvhMin.z, m.bvhMax.z, m.bvhQuantization.z, 0);
    b.hi[0] = btgQuantizeAxis(box.hi.x, m.bvhMin.x, m.bvhMax.x, m.bvhQuantization.x, 1);
    b.hi[1] = btgQuantizeAxis(box.hi.y, m.bvhMin.y, m.bvhMax.y, m.bvhQuantization.y, 1);
    b.hi[2] = btgQuantizeAxis(box.hi.z, m.bvhMin.z, m.bvhMax.z, m.bvhQuantization.z, 1);
    return b;
}

/* testQuantizedAabbAgainstQuantizedAabb. */
static inline int btgNodeOverlaps(BtgBvhNode n, BtgQuantizedBox q)
{
    uint minX = n.minXY & 0xffffu, minY = n.minXY >> 16, minZ = n.minZMaxX & 0xffffu;
    uint maxX = n.minZMaxX >> 16, maxY = n.maxYZ & 0xffffu, maxZ = n.maxYZ >> 16;
    return q.lo[0] <= maxX && q.hi[0] >= minX && q.lo[1] <= maxY && q.hi[1] >= minY && q.lo[2] <= maxZ &&
           q.hi[2] >= minZ;
}

/* The convex's box in the concave body's frame before a scaled wrapper's scaling is undone (the
 * box btConvexTriangleCallback tests each triangle against, TestTriangleAgainstAabb2), from the
 * rotation matrices of the two poses; grown by the triangles' margin and by `threshold`. */
static inline BtgAabb btgConvexBoxInConcave(BtgFloat4 convexPos, BtgMat3 convexRot, BtgShape convex, BtgFloat4 meshPos,
                                            BtgMat3 meshRot, BtgShape mesh, float threshold)
{
    BtgMat3 rm = meshRot;
    BtgMat3 rel = btgMat3Mul(btgMat3Transpose(rm), convexRot);
    BtgFloat4 t = btgMat3TMulVec(rm, btgXyz(convexPos - meshPos));
    BtgFloat4 halfExt = btgXyz(convex.localAabbMax - convex.localAabbMin) * 0.5f;
    BtgFloat4 localCentre = btgXyz(convex.localAabbMax + convex.localAabbMin) * 0.5f;
    if (convex.type == BTG_SHAPE_SPHERE) {
        halfExt = btgMake4(convex.param.x, convex.param.x, convex.param.x, 0.0f);
        localCentre = btgZero4();
    }
    BtgFloat4 a0 = btgMake4(btgAbs(rel.r0.x), btgAbs(rel.r0.y), btgAbs(rel.r0.z), 0.0f);
    BtgFloat4 a1 = btgMake4(btgAbs(rel.r1.x), btgAbs(rel.r1.y), btgAbs(rel.r1.z), 0.0f);
    BtgFloat4 a2 = btgMake4(btgAbs(rel.r2.x), btgAbs(rel.r2.y), btgAbs(rel.r2.z), 0.0f);
    BtgFloat4 centre = btgMat3MulVec(rel, localCentre) + t;
    float grow = mesh.margin + threshold;
    BtgFloat4 extent = btgMake4(btgDot3(a0, halfExt) + grow, btgDot3(a1, halfExt) + grow,
                                btgDot3(a2, halfExt) + grow, 0.0f);
    BtgAabb box;
    box.lo = centre - extent;
    box.hi = centre + extent;
    return box;
}

/* The box the midphase queries, in the mesh's unscaled BVH frame: the convex's local AABB
 * (margin included) carried into the mesh body's frame (btTransformAabb of T_mesh^-1 T_convex,
 * as btConvexTriangleCallback::setTimeStepAndCounters), grown by the triangles' margin and by
 * `threshold`, then divided by a scaled wrapper's scaling (btScaledBvhTriangleMeshShape::
 * processAllTriangles, negative scaling included). Bullet grows by the margin only, and so does
 * the bullet mode, whose manifolds persist as stock's (threshold 0); the soft step builds each
 * manifold afresh, so it finds the points stock's manifold would keep by growing the box by the
 * pair's threshold (the triangles' contacts are still kept only below it). */
static inline BtgAabb btgMidphaseBox(BtgFloat4 convexPos, BtgFloat4 convexRot, BtgShape convex, BtgFloat4 meshPos,
                                     BtgFloat4 meshRot, BtgShape mesh, float threshold)
{
    BtgAabb box = btgConvexBoxInConcave(convexPos, btgQuatToMat3(convexRot), convex, meshPos, btgQuatToMat3(meshRot), mesh,
                                        threshold);
    /* times 1/s, as Bullet computes it (exact for the usual scaling of 1) */
    BtgFloat4 s = mesh.param;
    BtgFloat4 inv = btgMake4(1.0f / s.x, 1.0f / s.y, 1.0f / s.z, 0.0f);
    BtgAabb out;
    out.lo = btgMake4(s.x >= 0.0f ? box.lo.x * inv.x : box.hi.x * inv.x, s.y >= 0.0f ? box.lo.y * inv.y : box.hi.y * inv.y,
                      s.z >= 0.0f ? box.lo.z * inv.z : box.hi.z * inv.z, 0.0f);
    out.hi = btgMake4(s.x <= 0.0f ? box.lo.x * inv.x : box.hi.x * inv.x, s.y <= 0.0f ? box.lo.y * inv.y : box.hi.y * inv.y,
                      s.z <= 0.0f ? box.lo.z * inv.z : box.hi.z * inv.z, 0.0f);
    return out;
}

/* The midphase walk of one (convex, mesh) pair: btQuantizedBvh::walkStacklessQuantizedTree
 * from node 0 to the end, in its order. Counts the leaves whose box overlaps; when `out` is
 * given, writes sub-pairs from out[first] on, never past out[capacity - 1]. Returns the count. */
static inline uint btgMidphaseWalk(BtgMesh m, BTG_CONST_GLOBAL BtgBvhNode* nodes, BTG_CONST_GLOBAL int* parts,
                                   BtgQuantizedBox q, int pairSlot, BTG_GLOBAL BtgSubPair* out, uint first,
                                   uint capacity)
{
    uint found = 0;
    int i = 0;
    while (i < m.numNodes) {
        BtgBvhNode n = nodes[m.firstNode + i];
        int overlap = btgNodeOverlaps(n, q);
        int leaf = n.escapeOrTriangle >= 0;
        if (leaf && overlap) {
            if (out && first + found < capacity) {
                int part = n.escapeOrTriangle >> BTG_BVH_PART_SHIFT;
                int index = n.escapeOrTriangle & BTG_BVH_TRIANGLE_MASK;
                BtgSubPair s;
                s.pair = pairSlot;
                s.triangle = m.firstTriangle + parts[m.firstPart + part] + index;
                s.partId = part;
                s.index = index;
                out[first + found] = s;
            }
            ++found;
        }
        i += (overlap || leaf) ? 1 : -n.escapeOrTriangle;
    }
    return found;
}

/* A mesh triangle's three vertices in the mesh body's frame (a scaled wrapper's scaling applied,
 * as btScaledTriangleCallback does). */
static inline void btgTriangleVertices(BtgShape mesh, BtgTriangle t, BTG_CONST_GLOBAL BtgFloat4* meshVerts,
                                       BtgFloat4* v)
{
    BtgFloat4 s = btgXyz(mesh.param);
    v[0] = btgXyz(meshVerts[t.v0]) * s;
    v[1] = btgXyz(meshVerts[t.v1]) * s;
    v[2] = btgXyz(meshVerts[t.v2]) * s;
}

/* The convex–mesh pairs in the kind-grouped order (find_pairs): the mesh kinds are consecutive
 * ids, so their ranges are one; with a single kind in the scene the others' ranges are empty
 * at 0, hence the min and max. */
static inline void btgMeshPairRange(BTG_CONST_GLOBAL uint* kindRanges, uint* start, uint* end)
{
    uint lo = 0u, hi = 0u;
    int any = 0;
    for (int k = BTG_FIRST_MESH_PAIR_KIND; k <= BTG_LAST_MESH_PAIR_KIND; ++k) {
        uint a = kindRanges[BTG_KIND_RANGE_START(k)], b = kindRanges[BTG_KIND_RANGE_END(k)];
        if (b <= a) continue;
        lo = any && lo < a ? lo : a;
        hi = any && hi > b ? hi : b;
        any = 1;
    }
    *start = lo;
    *end = hi;
}

#ifndef __OPENCL_C_VERSION__
static_assert(sizeof(BtgMesh) == 80, "BtgMesh layout");
static_assert(sizeof(BtgBvhNode) == 16, "BtgBvhNode layout");
static_assert(sizeof(BtgTriangle) == 16, "BtgTriangle layout");
static_assert(sizeof(BtgSubPair) == 16, "BtgSubPair layout");
#endif

#endif
