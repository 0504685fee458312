/* narrowphase.cl — Stage: narrowphase, the pair kinds that need no SAT.
 * Launch: one work-item per pair slot (pairCapacity); items past counters[kPairCount] and
 * pairs of another kind return at once, so each pair is written by exactly one kernel.
 * Reads pairs, counters, pos, rot, props (shape), shapes, hullVertices/Faces/Indices.
 * Writes manifolds[i] for the pairs of the kernel's kind (numPoints 0 when apart). */
#include "shared/simple_contacts.h"

#include "shared/counters.h"

/* Loads pair i's colliders; 0 when i is past the count or the pair is of another kind. */
static inline int btgLoadPairOfKind(int kind, __global const BtgPair* restrict pairs, __global const uint* restrict counters,
                                    uint capacity, __global const BtgFloat4* restrict pos, __global const BtgFloat4* restrict rot,
                                    __global const BtgBodyProps* restrict props, __global const BtgShape* restrict shapes,
                                    BtgCollider* a, BtgCollider* b)
{
    uint i = (uint)get_global_id(0);
    uint count = min(counters[BTG_COUNTER_PAIRS], capacity);
    if (i >= count) return 0;
    BtgPair p = pairs[i];
    int ta = shapes[props[p.a].shape].type, tb = shapes[props[p.b].shape].type;
    if (btgPairKind(ta, tb) != kind) return 0;
    *a = btgLoadCollider(p.a, pos, rot, props, shapes);
    *b = btgLoadCollider(p.b, pos, rot, props, shapes);
    return 1;
}

__kernel void collide_sphere_sphere(__global const BtgPair* restrict pairs, __global const uint* restrict counters,
                                    uint capacity, __global const BtgFloat4* restrict pos,
                                    __global const BtgFloat4* restrict rot, __global const BtgBodyProps* restrict props,
                                    __global const BtgShape* restrict shapes,
                                    __global BtgManifold* restrict manifolds)
{
    BtgCollider a, b;
    if (!btgLoadPairOfKind(BTG_PAIR_SPHERE_SPHERE, pairs, counters, capacity, pos, rot, props, shapes, &a, &b)) return;
    const float t = btgPairThreshold(a.shape, b.shape);
    manifolds[get_global_id(0)] = btgWithThreshold(btgCollideSphereSphere(a, b, t), t);
}

__kernel void collide_sphere_plane(__global const BtgPair* restrict pairs, __global const uint* restrict counters,
                                   uint capacity, __global const BtgFloat4* restrict pos,
                                   __global const BtgFloat4* restrict rot, __global const BtgBodyProps* restrict props,
                                   __global const BtgShape* restrict shapes,
                                   __global BtgManifold* restrict manifolds)
{
    BtgCollider a, b;
    if (!btgLoadPairOfKind(BTG_PAIR_SPHERE_PLANE, pairs, counters, capacity, pos, rot, props, shapes, &a, &b)) return;
    const float t = btgPairThreshold(a.shape, b.shape);
    manifolds[get_global_id(0)] = btgWithThreshold(btgCollideSpherePlane(a, b, t), t);
}

__kernel void collide_sphere_hull(__global const BtgPair* restrict pairs, __global const uint* restrict counters,
                                  uint capacity, __global const BtgFloat4* restrict pos,
                                  __global const BtgFloat4* restrict rot, __global const BtgBodyProps* restrict props,
                                  __global const BtgShape* restrict shapes, __global const BtgFloat4* restrict hullVertices,
                                  __global const BtgFace* restrict hullFaces, __global const int* restrict hullIndices,
                                  __global BtgManifold* restrict manifolds)
{
    BtgCollider a, b;
    if (!btgLoadPairOfKind(BTG_PAIR_SPHERE_HULL, pairs, counters, capacity, pos, rot, props, shapes, &a, &b)) return;
    const float t = btgPairThreshold(a.shape, b.shape);
    manifolds[get_global_id(0)] = btgWithThreshold(btgCollideSphereHull(a, b, hullVertices, hullFaces, hullIndices, t), t);
}

__kernel void collide_hull_plane(__global const BtgPair* restrict pairs, __global const uint* restrict counters,
                                 uint capacity, __global const BtgFloat4* restrict pos,
                                 __global const BtgFloat4* restrict rot, __global const BtgBodyProps* restrict props,
                                 __global const BtgShape* restrict shapes, __global const BtgFloat4* restrict hullVertices,
                                 __global BtgManifold* restrict manifolds)
{
    BtgCollider a, b;
    if (!btgLoadPairOfKind(BTG_PAIR_HULL_PLANE, pairs, counters, capacity, pos, rot, props, shapes, &a, &b)) return;
    const float t = btgPairThreshold(a.shape, b.shape);
    manifolds[get_global_id(0)] = btgWithThreshold(btgCollideHullPlane(a, b, hullVertices, t), t);
}
