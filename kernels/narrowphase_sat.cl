/* narrowphase_sat.cl — Stage: narrowphase_sat, two btBoxShapes. The bullet mode (the default
 * solver) collides them as stock's box–box algorithm does (shared/box_box.h: btBoxBoxDetector's
 * points into the pair's persistent manifold, then its refresh); after the solve,
 * store_persistent_manifolds keeps the manifolds for the next substep
 * (shared/persistent_kernels.h), as the GJK program does for its kinds. The soft step
 * (speculative 1) takes each step's SAT clip with its speculative points up to the breaking
 * threshold instead (shared/clip.h), which its substeps need, and keeps no manifold.
 * Launch: collide_box_box any number of work-items, striding over the kind's range of the
 * kind-grouped pairs (kindRanges[BTG_KIND_RANGE_*(BTG_PAIR_BOX_BOX)], read on the device);
 * store_persistent_manifolds one work-item per contact slot.
 * Reads pairs, kindOrder, kindRanges, pos, rot, props (shape), shapes, children, hull tables,
 * counters, contactCache (to find a pair's previous manifold), gjkCache.
 * Writes manifolds[slot], pairManifolds[slot] and gjkPairState[slot] for every box pair slot
 * (numPoints 0 when apart and nothing kept); then gjkCache (in the warm-start cache's order). */
#include "shared/box_box.h"
#include "shared/clip.h"
#define BTG_PERSISTENT_STEP btgBoxBoxPairStep
#include "shared/persistent_kernels.h"

__kernel void collide_box_box(__global const BtgPair* restrict pairs, __global const uint* restrict kindOrder,
                              __global const uint* restrict kindRanges, int indirect,
                              __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                              __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                              __global const BtgChild* restrict children,
                              __global const BtgFloat4* restrict verts, __global const BtgFace* restrict faces,
                              __global const int* restrict indices, __global const BtgFloat4* restrict edges,
                              __global const uint* restrict counters,
                              __global const BtgCachedContact* restrict cache, int cacheCapacity,
                              __global const BtgPersistentManifold* restrict gjkCache, int gjkCapacity,
                              __global BtgManifold* restrict manifolds, __global BtgManifoldRange* restrict pairManifolds,
                              __global BtgPersistentManifold* restrict gjkPairState, int speculative)
{
    const int kind = BTG_PAIR_BOX_BOX;
    const uint end = kindRanges[BTG_KIND_RANGE_END(kind)];
    for (uint i = kindRanges[BTG_KIND_RANGE_START(kind)] + (uint)get_global_id(0); i < end; i += (uint)get_global_size(0)) {
        const uint slot = indirect ? kindOrder[i] : i;
        const BtgPair p = pairs[slot];
        BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, shapes, children);
        BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, shapes, children);
        const float t = btgPairThreshold(a.shape, b.shape);
        /* kind NONE: no pair takes it as a persistent manifold (the soft step's, or not boxes) */
        BtgPersistentManifold pm = btgEmptyPersistent(p.a, p.b, BTG_PAIR_NONE);
        BtgManifold m = btgEmptyManifold(p.a, p.b);
        if (btgPairKind(a.shape.type, b.shape.type) == kind) {
            if (speculative) {
                m = btgCollideHullHull(a, b, verts, faces, indices, edges, t);
            } else {
                float dist[BTG_MAX_POINTS];
                BtgPersistentManifold prev =
                    btgPreviousManifold(p, kind, children, counters, cache, cacheCapacity, gjkCache, gjkCapacity);
                pm = btgBoxBoxStep(prev, a, b, t, dist);
                m = btgManifoldFromPersistent(pm, dist, b.pose);
            }
        }
        m = btgWithChildKeys(btgWithThreshold(m, t), p, children);
        gjkPairState[slot] = pm;
        manifolds[slot] = m;
        pairManifolds[slot] = btgOneManifold((int)slot, m);
    }
}
