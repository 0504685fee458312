/* narrowphase_mesh.cl — Stage: narrowphase, convex against mesh triangles: one kernel per row of
 * BTG_PAIR_KINDS_NARROWPHASE_MESH (shared/pair_kinds.h) over the midphase's sub-pairs, each the
 * row's routine from shared/triangle_contacts.h; then gather_mesh_manifolds makes each pair's
 * manifolds from its triangles' (btgGatherMeshManifolds).
 * Launch: the triangle kernels any number of work-items striding over the sub-pairs
 * (counters[BTG_COUNTER_SUB_PAIRS], read on the device); gather_mesh_manifolds any number
 * striding over the mesh pairs (kindRanges, read on the device).
 * Reads subPairs, subPairOffsets (the midphase's), pairs, kindOrder, kindRanges, pos, rot, props,
 * shapes, hull tables, the concave tables (shared/concave.h). Writes manifolds[base + s] for each
 * sub-pair s (base: the first manifold slot past the pair slots), compacted and merged per pair
 * by the gather, which writes pairManifolds[slot] = (base + first, count) and an empty
 * manifolds[slot] for each mesh pair. */
#include "shared/counters.h"
#include "shared/triangle_contacts.h"
#include "shared/compound.h"

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
            if (btgPairKind(a.shape.type, b.shape.type) != (kind)) continue;                                       \
            manifolds[base + s] = btgWithChildKeys(btgTriangleManifold(a, b, sp, verts, faces, indices, edges, routine), \
                                                   p, children);                                                    \
        }                                                                                                           \
    }

BTG_PAIR_KINDS_NARROWPHASE_MESH(BTG_TRIANGLE_KERNEL)

__kernel void gather_mesh_manifolds(__global const uint* restrict kindRanges, __global const uint* restrict kindOrder,
                                    int indirect, __global const BtgPair* restrict pairs,
                                    __global const uint* restrict offsets, uint countSlots, uint capacity,
                                    __global BtgManifold* restrict manifolds, uint base,
                                    __global BtgManifoldRange* restrict pairManifolds)
{
    uint start, end;
    btgMeshPairRange(kindRanges, &start, &end);
    for (uint i = (uint)get_global_id(0); i + 1u < countSlots && start + i < end; i += (uint)get_global_size(0)) {
        const uint slot = indirect ? kindOrder[start + i] : start + i;
        const uint lo = min(offsets[i], capacity), hi = min(offsets[i + 1u], capacity);
        const BtgPair p = pairs[slot];
        manifolds[slot] = btgEmptyManifold(p.a, p.b);
        BtgManifoldRange r;
        r.start = (int)(base + lo);
        r.count = btgGatherMeshManifolds(manifolds + base, (int)lo, (int)hi);
        pairManifolds[slot] = r;
    }
}
