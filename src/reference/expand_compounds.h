// expand_compounds.h (reference) — the compound expansion on the CPU, calling the same shared
// btgExpandPair as kernels/expand_compounds.cl, for tests to compare against exactly.
#pragma once
#include "shared/compound.h"

#include <vector>

namespace btgpu::ref {

// Each pair in order replaced by its leaf pairs (a pair without a compound stays itself);
// speculative: the soft step's grown tests (compound.h).
std::vector<BtgPair> referenceExpandCompounds(const std::vector<BtgPair>& pairs, const BtgFloat4* pos,
                                              const BtgFloat4* rot, const BtgBodyProps* props, const BtgShape* shapes,
                                              const BtgChild* children, bool speculative = true);

}  // namespace btgpu::ref
