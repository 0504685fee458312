// narrowphase.cpp (reference) — dispatches each pair by kind through the pair-kind table
// (kernels/shared/pair_kinds.h) to the shared routines in simple_contacts.h and clip.h,
// exactly as the kernels the table expands into do.
#include "reference/narrowphase.h"

#include "shared/clip.h"
#include "shared/compound.h"
#include "shared/concave_manifold.h"
#include "shared/polyhedral_contacts.h"
#include "shared/soft_afresh.h"
#include "shared/triangle_contacts.h"

namespace btgpu::ref {

int pairKind(const BtgPair& pair, const BtgBodyProps* props, const ShapeTablesView& t)
{
    return btgPairKindOf(pair, props, t.shapes, t.children);
}

BtgManifold referenceContact(const BtgPair& pair, const BtgFloat4* pos, const BtgFloat4* rot,
                             const BtgBodyProps* props, const ShapeTablesView& t, bool speculative)
{
    BtgCollider a = btgLoadPairCollider(pair, 0, pos, rot, props, t.shapes, t.children);
    BtgCollider b = btgLoadPairCollider(pair, 1, pos, rot, props, t.shapes, t.children);
    const float threshold = btgPairThreshold(a.shape, b.shape);
    const BtgFloat4 *verts = t.hullVertices, *edges = t.hullEdges;
    const BtgFace* faces = t.hullFaces;
    const int* indices = t.hullIndices;
    if (speculative && btgSoftCollidesAfresh(pairKind(pair, props, t), a.shape, b.shape))  // narrowphase_gjk.cl's
        return btgWithChildKeys(
            btgWithThreshold(btgCollideSoftAfresh(a, b, verts, faces, indices, edges, threshold), threshold), pair,
            t.children);
    switch (pairKind(pair, props, t)) {
#define BTGPU_REFERENCE_ROW(program, kind, shapeA, shapeB, routine, kernel) \
    case kind:                                                              \
        return btgWithChildKeys(btgWithThreshold(routine(a, b, verts, faces, indices, edges, threshold), threshold), \
                                pair, t.children);
        BTG_PAIR_KINDS_CONVEX(BTGPU_REFERENCE_ROW)
        BTG_PAIR_KINDS_NARROWPHASE_GJK(BTGPU_REFERENCE_ROW)
#undef BTGPU_REFERENCE_ROW
    default: return btgWithChildKeys(btgEmptyManifold(pair.a, pair.b), pair, t.children);
    }
}

std::vector<BtgManifold> referenceNarrowphase(const std::vector<BtgPair>& pairs, const BtgFloat4* pos,
                                              const BtgFloat4* rot, const BtgBodyProps* props,
                                              const ShapeTablesView& t)
{
    std::vector<BtgManifold> out;
    out.reserve(pairs.size());
    for (const BtgPair& p : pairs) out.push_back(referenceContact(p, pos, rot, props, t));
    return out;
}

BtgManifold referenceTriangleContact(const BtgSubPair& sp, const BtgPair* pairs, const BtgFloat4* pos,
                                     const BtgFloat4* rot, const BtgBodyProps* props, const ShapeTablesView& t,
                                     const MeshTablesView& mt, bool persistent)
{
    const BtgPair p = pairs[sp.pair];
    BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, t.shapes, t.children);
    BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, t.shapes, t.children);
    const BtgFloat4 *verts = t.hullVertices, *edges = t.hullEdges;
    const BtgFace* faces = t.hullFaces;
    const int* indices = t.hullIndices;
    const BtgMesh* meshes = mt.meshes;
    const BtgBvhNode* nodes = mt.nodes;
    const int* parts = mt.parts;
    const BtgTriangle* triangles = mt.triangles;
    const BtgFloat4* meshVerts = mt.vertices;
    const BtgHeightfield* heightfields = mt.heightfields;
    const float* heights = mt.heights;
    const int kind = btgPairKind(a.shape.type, b.shape.type);
    if (persistent && btgIsConcaveKind(kind))
        return btgWithChildKeys(btgTriangleManifold(a, b, sp, verts, faces, indices, edges, btgCollideTrianglePoint), p,
                                t.children);
    switch (kind) {
#define BTGPU_REFERENCE_TRIANGLE_ROW(program, kind, shapeA, shapeB, routine, kernel) \
    case kind: return btgWithChildKeys(btgTriangleManifold(a, b, sp, verts, faces, indices, edges, routine), p, t.children);
        BTG_PAIR_KINDS_NARROWPHASE_MESH(BTGPU_REFERENCE_TRIANGLE_ROW)
#undef BTGPU_REFERENCE_TRIANGLE_ROW
    default: return btgEmptyManifold(p.a, p.b);
    }
}

std::vector<BtgManifold> referenceMeshPair(const std::vector<BtgSubPair>& subPairs, const BtgPair* pairs,
                                           const BtgFloat4* pos, const BtgFloat4* rot, const BtgBodyProps* props,
                                           const ShapeTablesView& t, const MeshTablesView& m)
{
    std::vector<BtgManifold> region;
    for (const BtgSubPair& sp : subPairs) region.push_back(referenceTriangleContact(sp, pairs, pos, rot, props, t, m, false));
    if (region.empty()) return region;
    region.resize(size_t(btgGatherMeshManifolds(region.data(), 0, int(region.size()))));
    return region;
}

ConcavePairResult referenceConcavePair(const std::vector<BtgSubPair>& subPairs, int slot, const BtgPair* pairs,
                                       const BtgFloat4* pos, const BtgFloat4* rot, const BtgBodyProps* props,
                                       const ShapeTablesView& t, const MeshTablesView& m,
                                       const BtgPersistentManifold& prev)
{
    // The device's layout in small: slot 0 the pair's, the sub-pairs' region from 1 on.
    std::vector<BtgManifold> region(1 + subPairs.size());
    for (size_t s = 0; s < subPairs.size(); ++s)
        region[1 + s] = referenceTriangleContact(subPairs[s], pairs, pos, rot, props, t, m, true);
    const BtgPair p = pairs[slot];
    const BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, t.shapes, t.children);
    const BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, t.shapes, t.children);
    const int concaveIsA = btgIsConcave(a.shape.type);
    const BtgCollider cv = concaveIsA ? b : a, cc = concaveIsA ? a : b;
    const float threshold = btgPairThreshold(a.shape, b.shape);
    float dist[BTG_MAX_POINTS];
    const int n = int(subPairs.size());
    ConcavePairResult out;
    out.state = btgConcaveStep(prev, cv, cc, region.data() + 1, 0, n, concaveIsA,
                               (concaveIsA ? p.childB : p.childA) != BTG_WHOLE_BODY, threshold, dist);
    const BtgManifoldRange r = btgConcaveWrite(&out.state, dist, p, 0u, 0u, uint(n), cc.pose, concaveIsA, threshold,
                                               t.children, region.data(), 1u);
    for (int k = 0; k < r.count; ++k) out.manifolds.push_back(region[size_t(r.start + k)]);
    return out;
}

}  // namespace btgpu::ref
