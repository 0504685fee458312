// scan_test.cpp — the device exclusive scan equals the CPU reference exactly, across sizes
// that hit no block, one partial block, exactly one block and two and three recursion levels.
#include "reference/prims/scan.h"
#include "stages/prims/scan.h"
#include "test_device.h"

#include <gtest/gtest.h>
#include <random>

using namespace btgpu;

namespace {
void checkScan(size_t n, uint maxValue, unsigned seed)
{
    cl::Context& ctx = test::context();
    std::mt19937 rng(seed);
    std::vector<uint> host(n);
    for (uint& x : host) x = maxValue ? uint(rng() % (uint64_t(maxValue) + 1)) : 0u;
    cl::DeviceArray<uint> dev;
    dev.reserve(ctx, n ? n : 1);
    dev.upload(ctx, host);
    ScanScratch scratch;
    exclusiveScan(ctx, nullptr, dev, n, scratch);
    std::vector<uint> got = dev.download(ctx, n);
    ref::exclusiveScan(host);
    ASSERT_EQ(got, host) << "n=" << n;
}
}  // namespace

TEST(Scan, MatchesReferenceAcrossSizes)
{
    for (size_t n : {size_t(0), size_t(1), size_t(63), size_t(64), size_t(256), size_t(257), size_t(1000), size_t(100000)})
        checkScan(n, 1000, unsigned(n) + 1);
}

TEST(Scan, WrapsLikeUint)
{
    checkScan(5000, 0xffffffffu, 7);
}

TEST(Scan, ReusesScratchForDifferentSizes)
{
    cl::Context& ctx = test::context();
    ScanScratch scratch;
    for (size_t n : {size_t(70000), size_t(10), size_t(300)}) {
        std::vector<uint> host(n, 1u);
        cl::DeviceArray<uint> dev;
        dev.upload(ctx, host);
        exclusiveScan(ctx, nullptr, dev, n, scratch);
        std::vector<uint> got = dev.download(ctx, n);
        for (size_t i = 0; i < n; ++i) ASSERT_EQ(got[i], uint(i)) << "n=" << n << " i=" << i;
    }
}
