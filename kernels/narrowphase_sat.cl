/* narrowphase_sat.cl — Stage: narrowphase, hull–hull pairs (SAT, then clipping or the
 * closest points of two edges, reduced to at most 4 points; see shared/sat.h and clip.h).
 * Launch: one work-item per pair slot (pairCapacity); items past counters[kPairCount] and
 * pairs that are not hull–hull return at once.
 * Reads pairs, counters, pos, rot, props (shape), shapes, hullVertices/Faces/Indices/Edges.
 * Writes manifolds[i] for every hull–hull pair i (numPoints 0 when apart). */
#include "shared/clip.h"

#include "shared/counters.h"

__kernel void collide_hull_hull(__global const BtgPair* restrict pairs, __global const uint* restrict counters,
                                uint capacity, __global const BtgFloat4* restrict pos,
                                __global const BtgFloat4* restrict rot, __global const BtgBodyProps* restrict props,
                                __global const BtgShape* restrict shapes, __global const BtgFloat4* restrict hullVertices,
                                __global const BtgFace* restrict hullFaces, __global const int* restrict hullIndices,
                                __global const BtgFloat4* restrict hullEdges,
                                __global BtgManifold* restrict manifolds)
{
    uint i = (uint)get_global_id(0);
    if (i >= min(counters[BTG_COUNTER_PAIRS], capacity)) return;
    BtgPair p = pairs[i];
    if (btgPairKind(shapes[props[p.a].shape].type, shapes[props[p.b].shape].type) != BTG_PAIR_HULL_HULL) return;
    BtgCollider a = btgLoadCollider(p.a, pos, rot, props, shapes);
    BtgCollider b = btgLoadCollider(p.b, pos, rot, props, shapes);
    const float t = btgPairThreshold(a.shape, b.shape);
    manifolds[i] = btgWithThreshold(btgCollideHullHull(a, b, hullVertices, hullFaces, hullIndices, hullEdges, t), t);
}
