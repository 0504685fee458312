// radix_sort.h — stable LSD radix sort of uint keys carrying uint values, 4 bits per pass;
// only the low keyBits bits are compared, so small keys take few passes. RadixScratch owns
// the ping-pong arrays, the digit histograms and the scan scratch (nothing reallocated per step).
// Two ways to the same answer (kernels/prims/radix_sort.cl): chunks of 64 keys a work-item on CPU
// devices, tiles of 1,024 keys a work-group on GPUs.
#pragma once
#include "stages/prims/scan.h"

namespace btgpu {

struct RadixScratch {
    cl::DeviceArray<uint> keysAlt;
    cl::DeviceArray<uint> valuesAlt;
    cl::DeviceArray<uint> histogram;  // 16 digits x chunks (or tiles), digit-major
    ScanScratch scan;
};

// Sorts keys[0, n) and values[0, n) by (key & ((1 << keyBits) - 1)), stably. n is a host-side
// count or capacity: the caller pads keys beyond the real count with 0xffffffff so they sort
// last (give keyBits one bit more than the real keys need if they may reach all ones).
// Auto: tiles on a GPU, chunks on a CPU device; the others for tests and measuring.
enum class RadixPath { Auto, Chunks, Tiles };
void radixSort(cl::Context& ctx, cl::Profiler* profiler, cl::DeviceArray<uint>& keys,
               cl::DeviceArray<uint>& values, size_t n, int keyBits, RadixScratch& scratch,
               RadixPath path = RadixPath::Auto);

// Bits needed to represent every value in [0, maxValue]: at least 1.
int radixBitsFor(uint maxValue);

}  // namespace btgpu
