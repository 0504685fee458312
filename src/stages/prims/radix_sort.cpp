// radix_sort.cpp — host side of kernels/prims/radix_sort.cl: per pass, chunk histograms, an
// exclusive scan of the digit-major histogram (global digit offsets per chunk), and a stable
// scatter into the other buffer; an odd number of passes ends with a copy back.
#include "stages/prims/radix_sort.h"

#include "cl/program.h"

#include <utility>

namespace btgpu {
namespace {
constexpr int kRadixBits = 4;
constexpr cl_uint kDigits = 1u << kRadixBits;
// Elements per work-item: the histogram holds 16 entries per chunk, so 64 keeps it at n/4.
constexpr cl_uint kChunk = 64;
}  // namespace

int radixBitsFor(uint maxValue)
{
    int bits = 1;
    while (bits < 32 && (maxValue >> bits) != 0) ++bits;
    return bits;
}

void radixSort(cl::Context& ctx, cl::Profiler* profiler, cl::DeviceArray<uint>& keys,
               cl::DeviceArray<uint>& values, size_t n, int keyBits, RadixScratch& scratch)
{
    if (n <= 1 || keyBits <= 0) return;
    if (keyBits > 32) keyBits = 32;
    cl_uint numChunks = cl_uint((n + kChunk - 1) / kChunk);
    size_t histSize = size_t(numChunks) * kDigits;
    scratch.keysAlt.reserve(ctx, n);
    scratch.valuesAlt.reserve(ctx, n);
    scratch.histogram.reserve(ctx, histSize);
    cl::Program& prog = ctx.program("prims/radix_sort");

    cl::DeviceArray<uint>* kIn = &keys;
    cl::DeviceArray<uint>* vIn = &values;
    cl::DeviceArray<uint>* kOut = &scratch.keysAlt;
    cl::DeviceArray<uint>* vOut = &scratch.valuesAlt;
    int passes = (keyBits + kRadixBits - 1) / kRadixBits;
    for (int p = 0; p < passes; ++p) {
        cl_uint shift = cl_uint(p * kRadixBits);
        cl::Launch(ctx, prog.kernel("radix_histogram"), profiler)
            .arg(*kIn).arg(scratch.histogram).arg(cl_uint(n)).arg(shift).arg(kChunk).arg(numChunks)
            .run(numChunks);
        exclusiveScan(ctx, profiler, scratch.histogram, histSize, scratch.scan);
        cl::Launch(ctx, prog.kernel("radix_scatter"), profiler)
            .arg(*kIn).arg(*vIn).arg(*kOut).arg(*vOut).arg(scratch.histogram).arg(cl_uint(n)).arg(shift)
            .arg(kChunk).arg(numChunks)
            .run(numChunks);
        std::swap(kIn, kOut);
        std::swap(vIn, vOut);
    }
    if (kIn != &keys) {
        keys.copyFrom(ctx, *kIn, n);
        values.copyFrom(ctx, *vIn, n);
    }
}

}  // namespace btgpu
