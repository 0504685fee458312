// narrowphase_gjk.cpp (reference) — the loop of kernels/narrowphase_gjk.cl's collide kernels on
// the CPU (btgPairStep, btgManifoldFromPersistent), for tests.
#include "reference/narrowphase_gjk.h"

#include "shared/compound.h"
#include "shared/polyhedral_contacts.h"

namespace btgpu::ref {

GjkStep referenceGjkStep(const std::vector<BtgPair>& pairs, const BtgFloat4* pos, const BtgFloat4* rot,
                         const BtgBodyProps* props, const ShapeTablesView& t,
                         const std::vector<BtgPersistentManifold>& previous)
{
    GjkStep out;
    for (size_t i = 0; i < pairs.size(); ++i) {
        const BtgPair& p = pairs[i];
        BtgCollider a = btgLoadPairCollider(p, 0, pos, rot, props, t.shapes, t.children);
        BtgCollider b = btgLoadPairCollider(p, 1, pos, rot, props, t.shapes, t.children);
        const float threshold = btgPairThreshold(a.shape, b.shape);
        const int kind = btgPairKind(a.shape.type, b.shape.type);
        BtgPersistentManifold prev = i < previous.size() ? previous[i] : btgEmptyPersistent(p.a, p.b, kind);
        if (p.childA != BTG_WHOLE_BODY || p.childB != BTG_WHOLE_BODY) prev = btgChildPreRefresh(prev, a.pose, b.pose, threshold);
        float dist[BTG_MAX_POINTS];
        BtgPersistentManifold pm =
            btgPairStep(prev, a, b, t.hullVertices, t.hullFaces, t.hullIndices, t.hullEdges, threshold, dist);
        pm.kind = kind;
        out.states.push_back(pm);
        out.manifolds.push_back(
            btgWithChildKeys(btgWithThreshold(btgManifoldFromPersistent(pm, dist, b.pose), threshold), p, t.children));
    }
    return out;
}

}  // namespace btgpu::ref
