// midphase.h (reference) — the midphase on the CPU, calling the same shared walk as
// kernels/midphase.cl (btgMidphasePair), for tests to compare against exactly.
#pragma once
#include "shared/concave.h"

#include <vector>

namespace btgpu::ref {

// Host copies of the mesh tables (DeviceWorld's mesh columns).
struct MeshTablesView {
    const BtgMesh* meshes = nullptr;
    const BtgBvhNode* nodes = nullptr;
    const BtgTriangle* triangles = nullptr;
    const BtgFloat4* vertices = nullptr;
    const int* parts = nullptr;
    const BtgHeightfield* heightfields = nullptr;
    const float* heights = nullptr;
};

// The sub-pairs of each (slot, pair) in the order given (the device's: the mesh kinds' range of
// the kind-grouped pairs), each pair's triangles in the BVH walk's order; `persistent`: the
// bullet mode's box (stock's, grown by no threshold), else the soft step's.
std::vector<BtgSubPair> referenceMidphase(const std::vector<int>& slots, const BtgPair* pairs, const BtgFloat4* pos,
                                          const BtgFloat4* rot, const BtgBodyProps* props, const BtgShape* shapes,
                                          const MeshTablesView& m, const BtgChild* children = nullptr,
                                          bool persistent = false);

}  // namespace btgpu::ref
