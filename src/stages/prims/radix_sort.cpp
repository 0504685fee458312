// radix_sort.cpp — host side of kernels/prims/radix_sort.cl: per pass, chunk histograms, an
// exclusive scan of the digit-major histogram (global digit offsets per chunk), and a stable
// scatter into the other buffer; an odd number of passes ends with a copy back.
#include "stages/prims/radix_sort.h"

#include "cl/program.h"

#include <cstdlib>
#include <utility>

namespace btgpu {
namespace {
constexpr int kRadixBits = 4;
constexpr cl_uint kDigits = 1u << kRadixBits;
// Elements per work-item: the histogram holds 16 entries per chunk, so 64 keeps it at n/4.
constexpr cl_uint kChunk = 64;
// radix_sort.cl's BTG_RADIX_GROUP and BTG_RADIX_TILE.
constexpr size_t kTileGroup = 256;
constexpr cl_uint kTile = 1024;
constexpr cl_uint kFusedTiles = 512;

// A GPU's passes: count, scan, scatter by tiles of kTile keys (radix_sort.cl says why).
void tilePass(cl::Context& ctx, cl::Profiler* profiler, cl::Program& prog, cl::DeviceArray<uint>& kIn,
              cl::DeviceArray<uint>& vIn, cl::DeviceArray<uint>& kOut, cl::DeviceArray<uint>& vOut, size_t n,
              cl_uint shift, RadixScratch& scratch)
{
    const cl_uint numTiles = cl_uint((n + kTile - 1) / kTile);
    cl::Launch(ctx, prog.kernel("radix_tile_count"), profiler)
        .arg(kIn).arg(scratch.histogram).arg(cl_uint(n)).arg(shift).arg(numTiles)
        .run(size_t(numTiles) * kTileGroup, kTileGroup);
    // Up to kFusedTiles tiles each scatter work-group adds up the counts before its tile itself
    // (16 x tiles loads over its 256 work-items) where a scan launch would cost more. H100,
    // 2026-12-06, the pair sort's stage at 128 -> 512: cubes 32,768 0.23 -> 0.17 ms, 112,500
    // 0.48 -> 0.38.
    const cl_uint scanned = numTiles > kFusedTiles ? 1u : 0u;
    if (scanned)
        cl::Launch(ctx, prog.kernel("radix_tile_offsets"), profiler)
            .arg(scratch.histogram).arg(cl_uint(numTiles * kDigits))
            .run(kTileGroup, kTileGroup);
    cl::Launch(ctx, prog.kernel("radix_tile_scatter"), profiler)
        .arg(kIn).arg(vIn).arg(kOut).arg(vOut).arg(scratch.histogram).arg(cl_uint(n)).arg(shift).arg(numTiles)
        .arg(scanned)
        .run(size_t(numTiles) * kTileGroup, kTileGroup);
}
}  // namespace

int radixBitsFor(uint maxValue)
{
    int bits = 1;
    while (bits < 32 && (maxValue >> bits) != 0) ++bits;
    return bits;
}

void radixSort(cl::Context& ctx, cl::Profiler* profiler, cl::DeviceArray<uint>& keys,
               cl::DeviceArray<uint>& values, size_t n, int keyBits, RadixScratch& scratch, RadixPath path)
{
    if (n <= 1 || keyBits <= 0) return;
    if (keyBits > 32) keyBits = 32;
    // A CPU device runs a work-group's work-items one after another: its chunks walk their keys
    // in cache order, where a tile's local-memory barriers would cost it.
    // BTGPU_RADIX_CHUNKS=1 (for measuring) takes the chunks on a GPU too.
    static const bool chunksKnob = [] {
        const char* e = std::getenv("BTGPU_RADIX_CHUNKS");
        return e && e[0] == '1';
    }();
    // Up to one tile, every pass in one launch on one work-group (radix_tile_sort): a small
    // scene's sorts took two launches a pass on a GPU and three or more on a CPU device.
    // BTGPU_RADIX_ONE_TILE=0 (for measuring) leaves them to the passes.
    static const bool oneTileOff = [] {
        const char* e = std::getenv("BTGPU_RADIX_ONE_TILE");
        return e && e[0] == '0';
    }();
    // The tile kernels need work-groups of kTileGroup: a device offering fewer (PoCL with
    // POCL_MAX_WORK_GROUP_SIZE=64) takes the chunks.
    cl::Program& prog = ctx.program("prims/radix_sort");
    const bool tileGroups = cl::kernelGroupLimit(ctx, prog.kernel("radix_tile_scatter")) >= kTileGroup &&
                            cl::kernelGroupLimit(ctx, prog.kernel("radix_tile_sort")) >= kTileGroup;
    if (n <= kTile && tileGroups &&
        (path == RadixPath::OneTile || (path == RadixPath::Auto && !ctx.device().fewCpuCores() && !chunksKnob && !oneTileOff))) {
        cl::Launch(ctx, prog.kernel("radix_tile_sort"), profiler)
            .arg(keys).arg(values).arg(cl_uint(n)).arg(cl_uint((keyBits + kRadixBits - 1) / kRadixBits))
            .run(kTileGroup, kTileGroup);
        return;
    }
    // A CPU device of a few cores: one work-item sorts it all (radix_serial_sort) where the
    // passes took four launches each. BTGPU_RADIX_CHUNKS=1 takes the chunks there too.
    if (path == RadixPath::Serial || (path == RadixPath::Auto && ctx.device().fewCpuCores() && !chunksKnob)) {
        scratch.keysAlt.reserve(ctx, n);
        scratch.valuesAlt.reserve(ctx, n);
        const cl_uint bits = cl_uint((keyBits + kRadixBits - 1) / kRadixBits * kRadixBits);  // the passes' bits
        cl::Launch(ctx, prog.kernel("radix_serial_sort"), profiler)
            .arg(keys).arg(values).arg(scratch.keysAlt).arg(scratch.valuesAlt).arg(cl_uint(n)).arg(bits)
            .run(1);
        return;
    }
    const bool tiles = tileGroups && (path == RadixPath::Tiles || (path == RadixPath::Auto && ctx.device().isGpu && !chunksKnob));
    cl_uint numChunks = cl_uint((n + kChunk - 1) / kChunk);
    size_t histSize = tiles ? (n + kTile - 1) / kTile * kDigits : size_t(numChunks) * kDigits;
    scratch.keysAlt.reserve(ctx, n);
    scratch.valuesAlt.reserve(ctx, n);
    scratch.histogram.reserve(ctx, histSize);

    cl::DeviceArray<uint>* kIn = &keys;
    cl::DeviceArray<uint>* vIn = &values;
    cl::DeviceArray<uint>* kOut = &scratch.keysAlt;
    cl::DeviceArray<uint>* vOut = &scratch.valuesAlt;
    int passes = (keyBits + kRadixBits - 1) / kRadixBits;
    for (int p = 0; p < passes; ++p) {
        cl_uint shift = cl_uint(p * kRadixBits);
        if (tiles) {
            tilePass(ctx, profiler, prog, *kIn, *vIn, *kOut, *vOut, n, shift, scratch);
            std::swap(kIn, kOut);
            std::swap(vIn, vOut);
            continue;
        }
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
