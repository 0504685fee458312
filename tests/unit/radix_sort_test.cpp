// radix_sort_test.cpp — the device radix sort equals a CPU stable sort exactly (keys and the
// values they carry, so stability is checked), for several sizes and key widths, with the
// caller's 0xffffffff padding beyond the real count; every way (the serial sort and the chunks,
// the CPU devices', tiles, the GPUs', and one tile in one launch) on whatever device the tests run.
#include "reference/prims/radix_sort.h"
#include "stages/prims/radix_sort.h"
#include "test_device.h"

#include <gtest/gtest.h>
#include <random>

using namespace btgpu;

namespace {
void checkSort(size_t n, int keyBits, unsigned seed, size_t padding = 0, RadixPath path = RadixPath::Auto)
{
    cl::Context& ctx = test::context();
    std::mt19937 rng(seed);
    // Few distinct keys relative to n so that many ties test stability.
    uint range = keyBits >= 32 ? 0xffffffffu : (1u << keyBits) - 1u;
    if (n > 0 && range > n / 2 && (seed & 1)) range = uint(n / 2);
    size_t total = n + padding;
    std::vector<uint> keys(total, 0xffffffffu), values(total);
    for (size_t i = 0; i < n; ++i) keys[i] = uint(uint64_t(rng()) % (uint64_t(range) + 1));
    for (size_t i = 0; i < total; ++i) values[i] = uint(i);
    cl::DeviceArray<uint> dk, dv;
    dk.reserve(ctx, total ? total : 1);
    dv.reserve(ctx, total ? total : 1);
    dk.upload(ctx, keys);
    dv.upload(ctx, values);
    RadixScratch scratch;
    radixSort(ctx, nullptr, dk, dv, total, keyBits, scratch, path);
    std::vector<uint> gotK = dk.download(ctx, total), gotV = dv.download(ctx, total);
    ref::radixSort(keys, values, keyBits);
    ASSERT_EQ(gotK, keys) << "n=" << n << " bits=" << keyBits << " path=" << int(path);
    ASSERT_EQ(gotV, values) << "n=" << n << " bits=" << keyBits << " path=" << int(path);
}
}  // namespace

TEST(RadixSort, MatchesReferenceAcrossSizesAndWidths)
{
    for (size_t n : {size_t(0), size_t(1), size_t(63), size_t(64), size_t(1000), size_t(100000)})
        for (int bits : {3, 4, 13, 32})
            checkSort(n, bits, unsigned(n * 31 + bits));
}

// The tiles' edges: one key, a tile less one, a tile, a tile and one, many tiles with a partial
// last one (1,024 keys a tile), each scatter adding up the counts itself (up to 512 tiles) and
// after the scan launch (600,000 keys: 586 tiles, more counts than its work-group's work-items).
TEST(RadixSort, ChunksAndTilesAgreeWithTheReference)
{
    for (RadixPath path : {RadixPath::Chunks, RadixPath::Tiles})
        for (size_t n : {size_t(2), size_t(1023), size_t(1024), size_t(1025), size_t(5000), size_t(200000), size_t(600000)})
            for (int bits : {4, 9, 30})
                checkSort(n, bits, unsigned(n * 7 + bits), n % 3 == 0 ? 100 : 0, path);
}

// One tile sorted in one launch (every pass in local memory): up to a whole tile, an odd and an
// even number of passes, padding included.
TEST(RadixSort, OneTileAgreesWithTheReference)
{
    for (size_t n : {size_t(2), size_t(3), size_t(255), size_t(256), size_t(257), size_t(700), size_t(1024)})
        for (int bits : {1, 4, 9, 13, 30, 32})
            checkSort(n, bits, unsigned(n * 13 + bits), 0, RadixPath::OneTile);
    checkSort(900, 13, 77, 124, RadixPath::OneTile);
}

// A CPU device's one-work-item sort (8-bit digits): an odd and an even number of its passes, a
// last pass of 4 bits, padding, and passes skipped where every key shares the digit.
TEST(RadixSort, SerialAgreesWithTheReference)
{
    for (size_t n : {size_t(1), size_t(2), size_t(1000), size_t(5000), size_t(100000)})
        for (int bits : {1, 4, 9, 12, 13, 20, 30, 32})
            checkSort(n, bits, unsigned(n * 11 + bits), n % 2 == 0 ? 37 : 0, RadixPath::Serial);
}

// Keys with bits above keyBits (within its last 4-bit digit) order as the chunks' passes order
// them: the serial sort compares the same bits.
TEST(RadixSort, SerialComparesTheChunksBits)
{
    cl::Context& ctx = test::context();
    std::mt19937 rng(3);
    for (int bits : {5, 13, 22}) {
        std::vector<uint> keys(3000), values(3000);
        for (size_t i = 0; i < keys.size(); ++i) {
            keys[i] = rng();
            values[i] = uint(i);
        }
        std::vector<uint> got[2][2];
        int k = 0;
        for (RadixPath path : {RadixPath::Chunks, RadixPath::Serial}) {
            cl::DeviceArray<uint> dk, dv;
            dk.upload(ctx, keys);
            dv.upload(ctx, values);
            RadixScratch scratch;
            radixSort(ctx, nullptr, dk, dv, keys.size(), bits, scratch, path);
            got[k][0] = dk.download(ctx, keys.size());
            got[k][1] = dv.download(ctx, keys.size());
            ++k;
        }
        EXPECT_EQ(got[0][0], got[1][0]) << "bits " << bits;
        EXPECT_EQ(got[0][1], got[1][1]) << "bits " << bits;
    }
}

TEST(RadixSort, PaddingSortsLast)
{
    // Keys use 12 bits; the caller sorts 13 so padding (all ones) stays after every real key.
    checkSort(1000, 13, 5, 300);
    cl::Context& ctx = test::context();
    std::vector<uint> keys = {4095, 3, 0xffffffffu, 0xffffffffu}, values = {0, 1, 2, 3};
    cl::DeviceArray<uint> dk, dv;
    dk.upload(ctx, keys);
    dv.upload(ctx, values);
    RadixScratch scratch;
    radixSort(ctx, nullptr, dk, dv, keys.size(), radixBitsFor(4095) + 1, scratch);
    EXPECT_EQ(dk.download(ctx, 4), (std::vector<uint>{3, 4095, 0xffffffffu, 0xffffffffu}));
    EXPECT_EQ(dv.download(ctx, 4), (std::vector<uint>{1, 0, 2, 3}));
}

TEST(RadixSort, BitsFor)
{
    EXPECT_EQ(radixBitsFor(0), 1);
    EXPECT_EQ(radixBitsFor(1), 1);
    EXPECT_EQ(radixBitsFor(2), 2);
    EXPECT_EQ(radixBitsFor(4095), 12);
    EXPECT_EQ(radixBitsFor(4096), 13);
    EXPECT_EQ(radixBitsFor(0xffffffffu), 32);
}
