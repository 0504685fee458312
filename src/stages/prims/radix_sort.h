// radix_sort.h — stable LSD radix sort of uint keys carrying uint values, 4 bits per pass;
// only the low keyBits bits are compared, so small keys take few passes. RadixScratch owns
// the ping-pong arrays, the digit histograms and the scan scratch (nothing reallocated per step).
// Four ways to the same answer (kernels/prims/radix_sort.cl): on CPU devices one work-item's
// sort (8-bit digits over the same bits), or chunks of 64 keys a work-item a pass; on GPUs tiles
// of 1,024 keys a work-group, and up to one tile every pass in one launch.
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
// Auto: a CPU device of a few cores (DeviceInfo::fewCpuCores) the serial sort; else up to
// 1,024 keys one tile in one launch, beyond that tiles on a GPU and chunks on a CPU device; the
// others for tests and measuring (OneTile beyond 1,024 keys: the chunks).
enum class RadixPath { Auto, Chunks, Tiles, OneTile, Serial };
void radixSort(cl::Context& ctx, cl::Profiler* profiler, cl::DeviceArray<uint>& keys,
               cl::DeviceArray<uint>& values, size_t n, int keyBits, RadixScratch& scratch,
               RadixPath path = RadixPath::Auto);

// Bits needed to represent every value in [0, maxValue]: at least 1.
int radixBitsFor(uint maxValue);

}  // namespace btgpu
