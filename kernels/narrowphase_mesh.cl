/* narrowphase_mesh.cl — Stage: narrowphase, convex against mesh triangles: one kernel per row of
 * BTG_PAIR_KINDS_NARROWPHASE_MESH (shared/pair_kinds.h) over the midphase's sub-pairs; then
 * gather_mesh_manifolds makes each pair's manifolds from its triangles'. In the bullet mode
 * (persistent) each triangle gives the one point stock's algorithm for it adds
 * (btgCollideTrianglePoint) and the gather steps the pair's persistent manifold as stock's
 * btConvexConcaveCollisionAlgorithm does (shared/concave_manifold.h); for the soft step
 * (speculative) each triangle is clipped by the row's routine and the gather merges the
 * triangles' manifolds afresh every substep (btgGatherMeshManifolds). After the solve,
 * store_persistent_manifolds (shared/persistent_kernels.h) keeps the manifolds for the next
 * substep, as in the box and GJK programs.
 * Launch: the triangle kernels (the soft step's, one a kind; the bullet mode's one
 * collide_triangle_points for all) any number of work-items striding over the sub-pairs
 * (counters[BTG_COUNTER_SUB_PAIRS], read on the device); gather_mesh_manifolds any number
 * striding over the mesh pairs (kindRanges, read on the device).
 * Reads subPairs, subPairOffsets (the midphase's), pairs, kindOrder, kindRanges, pos, rot, props,
 * shapes, hull tables, the concave tables (shared/concave.h); the gather also the warm-start
 * cache and gjkCache (a pair's previous manifold). Writes manifolds[base + s] for each sub-pair s
 * (base: the first manifold slot past the pair slots); the gather then each mesh pair's
 * manifolds (one at its slot, or its groups from base + its first sub-pair on, overwriting its
 * triangles'), pairManifolds[slot] and gjkPairState[slot]. */
#include "shared/counters.h"
#include "shared/concave_manifold.h"
#include "shared/persistent_kernels.h"

/* A kind no pair has: the kernel takes every sub-pair (collide_triangle_points). */
#define BTG_ANY_MESH_KIND (-1)

#define BTG_TRIANGLE_KERNEL(program, kind, shapeA, shapeB, routine, kernel)                                        \
    __kernel void kernel(__global const BtgSubPair* restrict subPairs, __global const uint* restrict counters,      \
                         uint capacity, __global const BtgPair* restrict pairs,                                     \
                         __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,            \
                         __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,     \
                         __global const BtgChild* restrict children,                                                \
                         __global const BtgFloat4* restrict verts, __global const BtgFace* restrict faces,          \
                         __global const int* restrict indices, __global const BtgFloat4* restrict edges,            \
                         __global const BtgMesh* restrict meshes, __global const BtgBvhNode* restrict nodes,        \
                         __global const int* restrict parts, __global const BtgTriangle* restrict triangles,        \
                         __global const BtgFloat4* restrict meshVerts,                                              \
                         __global const BtgHeightfield* restrict heightfields, __global const float* restrict heights, \
                         __global BtgManifold* restrict manifolds, uint base)                                       \
    {                                                                                                               \
        const uint n = min(counters[BTG_COUNTER_SUB_PAIRS], capacity);                                              \
        for (uint s = (uint)get_global_id(0); s < n; s += (uint)get_global_size(0)) {                               \
            const BtgSubPair sp = subPairs[s];                                                                      \
            const BtgPair p = pairs[sp.pair];                                                                       \
            BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, shapes, children);                           \
            BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, shapes, children);                           \
            if ((kind) != BTG_ANY_MESH_KIND && btgPairKind(a.shape.type, b.shape.type) != (kind)) continue;        \
            manifolds[base + s] = btgWithChildKeys(btgTriangleManifold(a, b, sp, verts, faces, indices, edges, routine), \
                                                   p, children);                                                    \
        }                                                                                                           \
    }

BTG_PAIR_KINDS_NARROWPHASE_MESH(BTG_TRIANGLE_KERNEL)

/* The bullet mode's triangles, every mesh kind in one kernel: each the one point stock's algorithm
 * for it adds (btgCollideTrianglePoint; GJK compiled once, not once a kind). */
BTG_TRIANGLE_KERNEL(narrowphase_mesh, BTG_ANY_MESH_KIND, 0, 0, btgCollideTrianglePoint, collide_triangle_points)

/* One mesh pair's manifold stepped as stock's (the bullet mode), written as btgConcaveWrite lays
 * it out, its state at its slot for the store and the report. */
static void btgStepConcavePair(uint slot, BtgPair p, uint lo, uint hi, __global const BtgFloat4* restrict pos,
                               __global const BtgFloat4* restrict rot, __global const BtgBodyProps* restrict props,
                               __global const BtgShape* restrict shapes, __global const BtgChild* restrict children,
                               __global const uint* restrict counters,
                               __global const BtgCachedContact* restrict cache, int cacheCapacity,
                               __global const BtgPersistentManifold* restrict gjkCache, int gjkCapacity,
                               __global BtgManifold* restrict manifolds, uint base,
                               __global BtgManifoldRange* restrict pairManifolds,
                               __global BtgPersistentManifold* restrict gjkPairState)
{
    const BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, shapes, children);
    const BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, shapes, children);
    const int concaveIsA = btgIsConcave(a.shape.type);
    const BtgCollider cv = concaveIsA ? b : a, cc = concaveIsA ? a : b;
    const int kind = btgPairKind(a.shape.type, b.shape.type);
    const float t = btgPairThreshold(a.shape, b.shape);
    float dist[BTG_MAX_POINTS];
    const BtgPersistentManifold prev =
        btgPreviousConcave(p, kind, cv.body, cc.body, children, counters, cache, cacheCapacity, gjkCache, gjkCapacity);
    BtgPersistentManifold pm = btgConcaveStep(prev, cv, cc, manifolds + base, (int)lo, (int)hi, concaveIsA,
                                              (concaveIsA ? p.childB : p.childA) != BTG_WHOLE_BODY, t, dist);
    pairManifolds[slot] = btgConcaveWrite(&pm, dist, p, slot, lo, hi, cc.pose, concaveIsA, t, children, manifolds, base);
    gjkPairState[slot] = pm;
}

__kernel void gather_mesh_manifolds(__global const uint* restrict kindRanges, __global const uint* restrict kindOrder,
                                    int indirect, __global const BtgPair* restrict pairs,
                                    __global const uint* restrict offsets, uint countSlots, uint capacity,
                                    __global BtgManifold* restrict manifolds, uint base,
                                    __global BtgManifoldRange* restrict pairManifolds, int persistent,
                                    __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                                    __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                                    __global const BtgChild* restrict children, __global const uint* restrict counters,
                                    __global const BtgCachedContact* restrict cache, int cacheCapacity,
                                    __global const BtgPersistentManifold* restrict gjkCache, int gjkCapacity,
                                    __global BtgPersistentManifold* restrict gjkPairState, int stateCapacity)
{
    uint start, end;
    btgMeshPairRange(kindRanges, &start, &end);
    for (uint i = (uint)get_global_id(0); i + 1u < countSlots && start + i < end; i += (uint)get_global_size(0)) {
        const uint slot = indirect ? kindOrder[start + i] : start + i;
        const uint lo = min(offsets[i], capacity), hi = min(offsets[i + 1u], capacity);
        const BtgPair p = pairs[slot];
        if (persistent) {
            btgStepConcavePair(slot, p, lo, hi, pos, rot, props, shapes, children, counters, cache, cacheCapacity,
                               gjkCache, gjkCapacity, manifolds, base, pairManifolds, gjkPairState);
            continue;
        }
        manifolds[slot] = btgEmptyManifold(p.a, p.b);
        BtgManifoldRange r;
        r.start = (int)(base + lo);
        r.count = btgGatherMeshManifolds(manifolds + base, (int)lo, (int)hi);
        pairManifolds[slot] = r;
        /* nothing kept: the store finds no kind (and without GJK pairs no state is held at all) */
        if ((int)slot < stateCapacity) gjkPairState[slot] = btgEmptyPersistent(p.a, p.b, BTG_PAIR_NONE);
    }
}
