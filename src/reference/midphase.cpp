// midphase.cpp (reference) — each pair's walk counted, then written at its offset, as the
// kernels' count / scan / write passes do.
#include "reference/midphase.h"

namespace btgpu::ref {

std::vector<BtgSubPair> referenceMidphase(const std::vector<int>& slots, const BtgPair* pairs, const BtgFloat4* pos,
                                          const BtgFloat4* rot, const BtgBodyProps* props, const BtgShape* shapes,
                                          const MeshTablesView& m, const BtgChild* children, bool persistent)
{
    std::vector<BtgSubPair> out;
    for (int slot : slots) {
        const BtgPair& p = pairs[slot];
        uint n = btgMidphasePair(p, slot, pos, rot, props, shapes, children, m.meshes, m.nodes, m.parts, m.triangles, m.vertices,
                                 m.heightfields, m.heights, nullptr, 0u, 0u, persistent ? 1 : 0);
        size_t first = out.size();
        out.resize(first + n);
        btgMidphasePair(p, slot, pos, rot, props, shapes, children, m.meshes, m.nodes, m.parts, m.triangles, m.vertices,
                        m.heightfields, m.heights, out.data(), uint(first), uint(out.size()), persistent ? 1 : 0);
    }
    return out;
}

}  // namespace btgpu::ref
