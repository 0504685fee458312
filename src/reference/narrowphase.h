// narrowphase.h (reference) — the narrowphase on the CPU, calling the same shared contact
// routines as kernels/narrowphase.cl and narrowphase_sat.cl, for tests to compare against.
#pragma once
#include "reference/midphase.h"
#include "shared/types.h"

#include <vector>

namespace btgpu::ref {

// Host copies of the shape tables (DeviceWorld's shapes and hull columns).
struct ShapeTablesView {
    const BtgShape* shapes = nullptr;
    const BtgFloat4* hullVertices = nullptr;
    const BtgFace* hullFaces = nullptr;
    const int* hullIndices = nullptr;
    const BtgFloat4* hullEdges = nullptr;
    const BtgChild* children = nullptr;  // compound leaves (pairs naming a leaf read them)
};

// BTG_PAIR_* kind of a pair (shared/pair_kinds.h).
int pairKind(const BtgPair& pair, const BtgBodyProps* props, const ShapeTablesView& t);

// The manifold the device writes for one pair (bodyA = pair.a, bodyB = pair.b); a pair of a
// kind with a persistent manifold as its first step (the manifold it had is empty).
// speculative: the soft step's (the pairs btgSoftCollidesAfresh names collided afresh, with
// speculative points).
BtgManifold referenceContact(const BtgPair& pair, const BtgFloat4* pos, const BtgFloat4* rot,
                             const BtgBodyProps* props, const ShapeTablesView& t, bool speculative = false);

// Every pair in order; plane–plane pairs (owned by no kernel) come back empty.
std::vector<BtgManifold> referenceNarrowphase(const std::vector<BtgPair>& pairs, const BtgFloat4* pos,
                                              const BtgFloat4* rot, const BtgBodyProps* props,
                                              const ShapeTablesView& t);

// One convex–mesh pair as the midphase and "narrowphase_mesh" make it: the manifold of each
// of its sub-pairs by the kind's triangle routine, then gathered (btgGatherMeshManifolds);
// returns the pair's manifolds (as many as pairManifolds' count, in order).
std::vector<BtgManifold> referenceMeshPair(const std::vector<BtgSubPair>& subPairs, const BtgPair* pairs,
                                           const BtgFloat4* pos, const BtgFloat4* rot, const BtgBodyProps* props,
                                           const ShapeTablesView& t, const MeshTablesView& m);

// The manifold of one sub-pair (before gathering), as the triangle kernels write it: the row's
// routine (the soft step's clip) or, `persistent` (the bullet mode), stock's one point.
BtgManifold referenceTriangleContact(const BtgSubPair& sp, const BtgPair* pairs, const BtgFloat4* pos,
                                     const BtgFloat4* rot, const BtgBodyProps* props, const ShapeTablesView& t,
                                     const MeshTablesView& m, bool persistent);

// One convex–concave pair (slot `slot`) in the bullet mode, as gather_mesh_manifolds steps it:
// prev (the manifold it kept, convex first; btgEmptyPersistent for a new pair), then its
// sub-pairs' points, refreshed; its manifolds in range order and its state (convex first).
struct ConcavePairResult {
    std::vector<BtgManifold> manifolds;
    BtgPersistentManifold state;
};
ConcavePairResult referenceConcavePair(const std::vector<BtgSubPair>& subPairs, int slot, const BtgPair* pairs,
                                       const BtgFloat4* pos, const BtgFloat4* rot, const BtgBodyProps* props,
                                       const ShapeTablesView& t, const MeshTablesView& m,
                                       const BtgPersistentManifold& prev);

}  // namespace btgpu::ref
