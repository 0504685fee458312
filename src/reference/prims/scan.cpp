// scan.cpp (reference) — sequential exclusive prefix sum.
#include "reference/prims/scan.h"

namespace btgpu::ref {
void exclusiveScan(std::vector<uint>& data)
{
    uint sum = 0;
    for (uint& x : data) {
        uint v = x;
        x = sum;
        sum += v;
    }
}
}  // namespace btgpu::ref
