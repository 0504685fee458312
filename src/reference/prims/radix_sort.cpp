// radix_sort.cpp (reference) — std::stable_sort of indices by masked key.
#include "reference/prims/radix_sort.h"

#include <algorithm>
#include <numeric>

namespace btgpu::ref {
void radixSort(std::vector<uint>& keys, std::vector<uint>& values, int keyBits)
{
    if (keyBits <= 0) return;
    uint mask = keyBits >= 32 ? 0xffffffffu : ((1u << keyBits) - 1u);
    std::vector<size_t> order(keys.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return (keys[a] & mask) < (keys[b] & mask); });
    std::vector<uint> k(keys.size()), v(values.size());
    for (size_t i = 0; i < order.size(); ++i) {
        k[i] = keys[order[i]];
        v[i] = values[order[i]];
    }
    keys.swap(k);
    values.swap(v);
}
}  // namespace btgpu::ref
