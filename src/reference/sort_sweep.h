// sort_sweep.h (reference) — the sort-and-sweep pass on the CPU, with the kernel's shared
// functions (shared/sort_sweep.h, shared/broadphase.h) and its summation order, so the axis
// is the device's exactly and the pairs are those of the small rows (btgGridded).
#pragma once
#include "shared/types.h"

#include <vector>

namespace btgpu::ref {
// The sweep axis (0 x, 1 y, 2 z) the device's sap_axis picks for these rows.
uint sortSweepAxis(const std::vector<BtgFloat4>& aabbMin, const std::vector<BtgFloat4>& aabbMax,
                   const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes);
// Allowed AABB-overlapping pairs (a < b) among the small rows, sorted by (a, b).
std::vector<BtgPair> sortSweepPairs(const std::vector<BtgFloat4>& aabbMin, const std::vector<BtgFloat4>& aabbMax,
                                    const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes);
}  // namespace btgpu::ref
