// radix_sort.h — stable LSD radix sort of uint keys carrying uint values, 4 bits per pass;
// only the low keyBits bits are compared, so small keys take few passes. RadixScratch owns
// the ping-pong arrays, the digit histograms and the scan scratch (nothing reallocated per step).
#pragma once
#include "stages/prims/scan.h"

namespace btgpu {

struct RadixScratch {
    cl::DeviceArray<uint> keysAlt;
    cl::DeviceArray<uint> valuesAlt;
    cl::DeviceArray<uint> histogram;  // 16 digits x chunks, digit-major
    ScanScratch scan;
};

// Sorts keys[0, n) and values[0, n) by (key & ((1 << keyBits) - 1)), stably. n is a host-side
// count or capacity: the caller pads keys beyond the real count with 0xffffffff so they sort
// last (give keyBits one bit more than the real keys need if they may reach all ones).
void radixSort(cl::Context& ctx, cl::Profiler* profiler, cl::DeviceArray<uint>& keys,
               cl::DeviceArray<uint>& values, size_t n, int keyBits, RadixScratch& scratch);

// Bits needed to represent every value in [0, maxValue]: at least 1.
int radixBitsFor(uint maxValue);

}  // namespace btgpu
