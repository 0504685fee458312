// scan.h (reference) — CPU exclusive prefix sum, the oracle for kernels/prims/scan.cl.
#pragma once
#include <vector>

namespace btgpu::ref {
using uint = unsigned int;
// Exclusive prefix sum in place, wrapping like the kernel's uint arithmetic.
void exclusiveScan(std::vector<uint>& data);
}  // namespace btgpu::ref
