// expand_compounds.cpp (reference) — each pair's leaf pairs counted, then written at its offset,
// as the kernels' count / scan / write passes do.
#include "reference/expand_compounds.h"

namespace btgpu::ref {

std::vector<BtgPair> referenceExpandCompounds(const std::vector<BtgPair>& pairs, const BtgFloat4* pos,
                                              const BtgFloat4* rot, const BtgBodyProps* props, const BtgShape* shapes,
                                              const BtgChild* children, bool speculative)
{
    std::vector<BtgPair> out;
    for (const BtgPair& p : pairs) {
        const uint n = btgExpandPair(p, pos, rot, props, shapes, children, nullptr, 0u, 0u, speculative ? 1 : 0);
        const size_t first = out.size();
        out.resize(first + n);
        btgExpandPair(p, pos, rot, props, shapes, children, out.data(), uint(first), uint(out.size()), speculative ? 1 : 0);
    }
    return out;
}

}  // namespace btgpu::ref
