// narrowphase.cpp (reference) — dispatches each pair by kind through the pair-kind table
// (kernels/shared/pair_kinds.h) to the shared routines in simple_contacts.h and clip.h,
// exactly as the kernels the table expands into do.
#include "reference/narrowphase.h"

#include "shared/clip.h"
#include "shared/polyhedral_contacts.h"
#include "shared/simple_contacts.h"

namespace btgpu::ref {

int pairKind(const BtgPair& pair, const BtgBodyProps* props, const ShapeTablesView& t)
{
    return btgPairKind(t.shapes[props[pair.a].shape].type, t.shapes[props[pair.b].shape].type);
}

BtgManifold referenceContact(const BtgPair& pair, const BtgFloat4* pos, const BtgFloat4* rot,
                             const BtgBodyProps* props, const ShapeTablesView& t)
{
    BtgCollider a = btgLoadCollider(pair.a, pos, rot, props, t.shapes);
    BtgCollider b = btgLoadCollider(pair.b, pos, rot, props, t.shapes);
    const float threshold = btgPairThreshold(a.shape, b.shape);
    const BtgFloat4 *verts = t.hullVertices, *edges = t.hullEdges;
    const BtgFace* faces = t.hullFaces;
    const int* indices = t.hullIndices;
    switch (pairKind(pair, props, t)) {
#define BTGPU_REFERENCE_ROW(program, kind, shapeA, shapeB, routine, kernel) \
    case kind: return btgWithThreshold(routine(a, b, verts, faces, indices, edges, threshold), threshold);
        BTG_PAIR_KINDS(BTGPU_REFERENCE_ROW)
#undef BTGPU_REFERENCE_ROW
    default: return btgEmptyManifold(pair.a, pair.b);
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

}  // namespace btgpu::ref
