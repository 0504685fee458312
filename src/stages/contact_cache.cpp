// contact_cache.cpp — host launchers of the contacts stage: a two-level scan of the pairs'
// manifold counts compacts their manifolds with points into `contacts` (pair order), then each
// contact warm-starts from the cached manifold it continues (three launches, no readback);
// after the solve one launch stores the solved contacts as the next substep's cache.
#include "stages/contact_cache.h"

#include "cl/program.h"
#include "stages/prims/scan.h"

#include <algorithm>

namespace btgpu {

namespace {
// Both scan kernels must run with the same group size (block sums are per group).
size_t scanGroupSize(cl::Context& ctx, cl_kernel a, cl_kernel b)
{
    size_t ga = cl::kernelWorkGroupSize(ctx, a), gb = cl::kernelWorkGroupSize(ctx, b);
    return std::max<size_t>(1, std::min({ga, gb, ctx.device().maxWorkGroupSize, size_t(256)}));
}
}  // namespace

void buildContacts(DeviceWorld& w, const BtgStepParams& params)
{
    cl::Context& ctx = w.ctx;
    cl::Program& prog = ctx.program("contact_cache");
    cl_kernel count = prog.kernel("count_contacts");
    cl_kernel scan = prog.kernel("scan_blocks");
    cl_kernel write = prog.kernel("write_contacts");
    size_t group = scanGroupSize(ctx, count, write);
    int pairCapacity = int(std::min(w.pairCapacity, w.pairManifolds.capacity()));
    size_t numBlocks = (size_t(pairCapacity) + group - 1) / group;
    w.solverScratch.blockSums.reserve(ctx, std::max<size_t>(numBlocks, 1));
    w.contacts.reserveExact(ctx, std::max<size_t>(w.contactCapacity, 1));
    w.contactManifolds.reserveExact(ctx, std::max<size_t>(w.contactCapacity, 1));
    w.contactCache.reserveExact(ctx, 1, true);
    w.gjkPairState.reserve(ctx, 1);  // read only with friction anchors, whose pairs wrote it
    int contactCapacity = int(std::min({w.contactCapacity, w.contacts.capacity(), w.contactManifolds.capacity()}));
    int cacheCapacity = int(w.contactCache.capacity());

    if (numBlocks > 0)
        cl::Launch(ctx, count, &w.profiler).arg(w.pairManifolds).arg(w.counters).arg(pairCapacity)
            .arg(w.solverScratch.blockSums).local(group * sizeof(cl_uint)).run(numBlocks * group, group);
    cl::Launch(ctx, scan, &w.profiler).arg(w.solverScratch.blockSums).arg(int(numBlocks)).arg(w.counters)
        .arg(contactCapacity).run(1, 1);
    if (numBlocks > 0)
        cl::Launch(ctx, write, &w.profiler).arg(w.pairManifolds).arg(w.manifolds).arg(w.counters).arg(pairCapacity)
            .arg(w.solverScratch.blockSums).arg(w.pos).arg(w.rot).arg(w.props).arg(w.contactCache).arg(cacheCapacity)
            .arg(w.contacts).arg(w.contactManifolds).arg(contactCapacity).arg(w.gjkPairState)
            .arg(int(w.gjkPairState.capacity())).arg(params).local(group * sizeof(cl_uint))
            .run(numBlocks * group, group);
}

void noteCarried(DeviceWorld& w, bool carry)
{
    cl::Context& ctx = w.ctx;
    const size_t cacheCapacity = std::max<size_t>(w.contactCache.capacity(), 1);
    w.carryRank.reserve(ctx, cacheCapacity + 1);
    w.carrying = carry;
    w.carryCapacity = cacheCapacity;
    if (!carry) return;
    cl::Launch(ctx, ctx.program("contact_cache").kernel("carry_flags"), &w.profiler)
        .arg(w.contactCache).arg(w.counters).arg(int(cacheCapacity)).arg(w.numBodies).arg(w.props).arg(w.carryRank)
        .run(cacheCapacity + 1);
    exclusiveScan(ctx, &w.profiler, w.carryRank, cacheCapacity + 1, w.carryScan);
}

void storeContactCache(DeviceWorld& w, bool count, bool overSoftRows)
{
    cl::Context& ctx = w.ctx;
    w.contactCache.reserveExact(ctx, std::max<size_t>(w.contactCapacity, 1), true);
    const size_t cacheCapacity = w.contactCache.capacity();
    // The new cache beside the old one: the soft step's dead rows (then copied back), or a
    // second buffer the two swap with.
    const cl::ArrayView<BtgCachedContact> next =
        w.solverScratch.afterSolve(ctx, w.contactCacheNext, cacheCapacity, overSoftRows);
    w.carryRank.reserve(ctx, cacheCapacity + 1);
    w.cachePos.reserve(ctx, std::max<size_t>(w.contactCapacity, 1));
    w.carryPos.reserve(ctx, cacheCapacity);
    // ranked against a smaller cache (grown since): carry nothing this substep
    const int carry = w.carrying && w.carryCapacity == cacheCapacity ? 1 : 0;
    int contactCapacity = int(std::min({w.contactCapacity, w.contacts.capacity(), w.contactManifolds.capacity()}));
    cl::Program& prog = ctx.program("contact_cache");
    cl::Launch(ctx, prog.kernel("store_contact_cache"), &w.profiler)
        .arg(w.contacts).arg(w.contactManifolds).arg(w.manifolds).arg(w.counters).arg(contactCapacity).arg(w.rot)
        .arg(w.contactCache).arg(int(cacheCapacity)).arg(next).arg(w.carryRank).arg(carry).arg(w.cachePos)
        .run(std::max({size_t(std::max(contactCapacity, 1)), cacheCapacity}));
    if (carry)
        cl::Launch(ctx, prog.kernel("carry_contact_cache"), &w.profiler)
            .arg(w.contactCache).arg(w.counters).arg(int(cacheCapacity)).arg(contactCapacity).arg(w.contacts)
            .arg(w.carryRank).arg(carry).arg(next).arg(w.carryPos)
            .run(cacheCapacity);
    if (overSoftRows)
        cl::Launch(ctx, prog.kernel("copy_cache_back"), &w.profiler)
            .arg(next).arg(w.counters).arg(contactCapacity).arg(int(cacheCapacity)).arg(w.carryRank).arg(carry)
            .arg(w.contactCache).run(cacheCapacity);
    else
        std::swap(w.contactCache, w.contactCacheNext);
    w.carrying = carry != 0;
    if (count) countCache(w);
}

void countCache(DeviceWorld& w)
{
    cl::Context& ctx = w.ctx;
    const size_t cacheCapacity = w.contactCache.capacity();
    int contactCapacity = int(std::min({w.contactCapacity, w.contacts.capacity(), w.contactManifolds.capacity()}));
    cl::Launch(ctx, ctx.program("contact_cache").kernel("count_cache"), &w.profiler)
        .arg(w.counters).arg(contactCapacity).arg(int(cacheCapacity)).arg(w.carryRank).arg(w.carrying ? 1 : 0)
        .run(1, 1);
    w.carrying = false;
}

}  // namespace btgpu
