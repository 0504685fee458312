// narrowphase.cpp (reference) — dispatches each pair by kind to the shared routines in
// kernels/shared/simple_contacts.h and clip.h, exactly as the kernels do.
#include "reference/narrowphase.h"

#include "shared/clip.h"
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
    switch (pairKind(pair, props, t)) {
    case BTG_PAIR_SPHERE_SPHERE: return btgWithThreshold(btgCollideSphereSphere(a, b, threshold), threshold);
    case BTG_PAIR_SPHERE_PLANE: return btgWithThreshold(btgCollideSpherePlane(a, b, threshold), threshold);
    case BTG_PAIR_SPHERE_HULL:
        return btgWithThreshold(btgCollideSphereHull(a, b, t.hullVertices, t.hullFaces, t.hullIndices, threshold),
                                threshold);
    case BTG_PAIR_HULL_PLANE: return btgWithThreshold(btgCollideHullPlane(a, b, t.hullVertices, threshold), threshold);
    case BTG_PAIR_HULL_HULL:
        return btgWithThreshold(
            btgCollideHullHull(a, b, t.hullVertices, t.hullFaces, t.hullIndices, t.hullEdges, threshold), threshold);
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
