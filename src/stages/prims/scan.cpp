// scan.cpp — host side of kernels/prims/scan.cl: one block-scan launch per level, recursing on
// the block totals until one block holds them all, then adding the offsets back level by level.
#include "stages/prims/scan.h"

#include "cl/program.h"

namespace btgpu {
namespace {

// Block size: a power of two the device accepts; 256 keeps local memory small on every GPU.
size_t scanBlockSize(cl::Context& ctx)
{
    size_t limit = ctx.device().maxWorkGroupSize < 256 ? ctx.device().maxWorkGroupSize : 256;
    size_t b = 1;
    while (b * 2 <= limit) b *= 2;
    return b;
}

void scanLevel(cl::Context& ctx, cl::Profiler* prof, cl::DeviceArray<uint>& data, size_t n,
               ScanScratch& scratch, size_t level, size_t block)
{
    size_t blocks = (n + block - 1) / block;
    if (scratch.levels.size() <= level) scratch.levels.resize(level + 1);
    cl::DeviceArray<uint>& sums = scratch.levels[level];
    sums.reserve(ctx, blocks);
    cl::Program& prog = ctx.program("prims/scan");
    cl::Launch(ctx, prog.kernel("scan_blocks"), prof).arg(data).arg(sums).arg(cl_uint(n)).local(block * sizeof(uint)).run(n, block);
    if (blocks <= 1) return;  // one block: its local exclusive scan is already the answer
    scanLevel(ctx, prof, sums, blocks, scratch, level + 1, block);
    cl::Launch(ctx, prog.kernel("scan_add_offsets"), prof).arg(data).arg(sums).arg(cl_uint(n)).run(n, block);
}

}  // namespace

void exclusiveScan(cl::Context& ctx, cl::Profiler* profiler, cl::DeviceArray<uint>& data, size_t n,
                   ScanScratch& scratch)
{
    if (n == 0) return;
    scanLevel(ctx, profiler, data, n, scratch, 0, scanBlockSize(ctx));
}

}  // namespace btgpu
