// narrowphase_gjk.h (reference) — the GJK narrowphase on the CPU with the same shared code as
// kernels/narrowphase_gjk.cl: each pair's new point into its previous persistent manifold.
#pragma once
#include "reference/narrowphase.h"
#include "shared/types.h"

#include <vector>

namespace btgpu::ref {

struct GjkStep {
    std::vector<BtgManifold> manifolds;           // per pair, as the device writes manifolds[slot]
    std::vector<BtgPersistentManifold> states;    // per pair, gjkPairState[slot]
};

// One substep for `pairs` (each of a GJK kind) whose previous manifolds are `previous` (same
// index; numPoints 0 for a new pair).
GjkStep referenceGjkStep(const std::vector<BtgPair>& pairs, const BtgFloat4* pos, const BtgFloat4* rot,
                         const BtgBodyProps* props, const ShapeTablesView& t,
                         const std::vector<BtgPersistentManifold>& previous);

}  // namespace btgpu::ref
