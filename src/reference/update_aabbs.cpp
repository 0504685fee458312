// update_aabbs.cpp (reference) — a loop over btgBodyAabb, the function the kernel runs.
#include "reference/update_aabbs.h"

#include "shared/aabb.h"

namespace btgpu::ref {
void updateAabbs(const std::vector<BtgFloat4>& pos, const std::vector<BtgFloat4>& rot,
                 const std::vector<BtgBodyProps>& props, const std::vector<BtgShape>& shapes, float threshold,
                 std::vector<BtgFloat4>& aabbMin, std::vector<BtgFloat4>& aabbMax)
{
    aabbMin.resize(pos.size());
    aabbMax.resize(pos.size());
    for (size_t i = 0; i < pos.size(); ++i) {
        BtgAabb a = (props[i].flags & BTG_BODY_EXCLUDED)
                        ? btgEmptyAabb()
                        : btgBodyAabb(pos[i], rot[i], shapes[size_t(props[i].shape)], props[i].flags, threshold);
        aabbMin[i] = a.lo;
        aabbMax[i] = a.hi;
    }
}
}  // namespace btgpu::ref
