// radix_sort.h (reference) — CPU stable key/value sort on the low keyBits bits, the oracle for
// kernels/prims/radix_sort.cl.
#pragma once
#include <vector>

namespace btgpu::ref {
using uint = unsigned int;
// Sorts keys and values together by (key & low keyBits mask), keeping equal keys in order.
void radixSort(std::vector<uint>& keys, std::vector<uint>& values, int keyBits);
}  // namespace btgpu::ref
