// update_aabbs.h (reference) — CPU world AABBs calling the kernel's own btgBodyAabb.
#pragma once
#include "shared/types.h"

#include <vector>

namespace btgpu::ref {
// Fills aabbMin/aabbMax (resized to pos.size()) for every body row.
void updateAabbs(const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot,
                 const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes, float threshold,
                 std::vector<BtgFloat4>& aabbMin, std::vector<BtgFloat4>& aabbMax);
}  // namespace btgpu::ref
