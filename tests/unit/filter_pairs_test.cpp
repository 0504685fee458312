// filter_pairs_test.cpp — the pair filter: on the device, exactly the ranges of the ignored
// pairs present in the sorted pair list are emptied (as the reference), others untouched,
// ignored pairs absent from the list change nothing; and a pair count past capacity is clamped.
#include "reference/filter_pairs.h"
#include "stages/filter_pairs.h"
#include "test_device.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <random>

using namespace btgpu;

TEST(FilterPairs, EmptiesExactlyTheIgnoredPairsRanges)
{
    std::mt19937 rng(7);
    std::vector<BtgPair> pairs;
    for (int a = 0; a < 60; ++a)
        for (int b = a + 1; b < 60; ++b)
            if (rng() % 7 == 0) pairs.push_back({a, b, BTG_WHOLE_BODY, BTG_WHOLE_BODY});
    std::vector<BtgManifoldRange> ranges(pairs.size());
    for (size_t i = 0; i < ranges.size(); ++i) ranges[i] = {int(i), 1 + int(i % 3)};
    // Every 5th pair of the list, plus some that are not in it.
    std::vector<BtgPair> ignored;
    for (size_t i = 0; i < pairs.size(); i += 5) ignored.push_back(pairs[i]);
    ignored.push_back({3, 200, BTG_WHOLE_BODY, BTG_WHOLE_BODY});
    ignored.push_back({59, 61, BTG_WHOLE_BODY, BTG_WHOLE_BODY});
    std::sort(ignored.begin(), ignored.end(), [](BtgPair x, BtgPair y) { return x.a < y.a || (x.a == y.a && x.b < y.b); });
    std::vector<BtgManifoldRange> expect = ranges;
    ref::filterPairs(ignored, pairs, expect);

    DeviceWorld w(test::context());
    w.pairCapacity = pairs.size();
    w.pairs.upload(w.ctx, pairs);
    w.pairManifolds.upload(w.ctx, ranges);
    w.ignoredPairs.upload(w.ctx, ignored);
    w.numIgnoredPairs = int(ignored.size());
    std::vector<uint> counters(kNumCounters, 0u);
    counters[kPairCount] = uint(pairs.size()) + 100;  // an overflowed count: clamped to capacity
    w.counters.upload(w.ctx, counters);
    filterPairs(w);
    std::vector<BtgManifoldRange> got = w.pairManifolds.download(w.ctx, pairs.size());
    int emptied = 0;
    for (size_t i = 0; i < pairs.size(); ++i) {
        EXPECT_EQ(got[i].count, expect[i].count) << i;
        EXPECT_EQ(got[i].start, ranges[i].start) << i;  // the slot stays
        const bool isIgnored = i % 5 == 0;
        EXPECT_EQ(got[i].count == 0, isIgnored) << i;
        emptied += got[i].count == 0;
    }
    EXPECT_EQ(emptied, int((pairs.size() + 4) / 5));
}

// A compound's body pair is several leaf pairs in a row with the same bodies (expand_compounds):
// an ignored body pair empties every one of them, on the device as in the reference.
TEST(FilterPairs, EmptiesEveryLeafPairOfAnIgnoredCompoundPair)
{
    std::vector<BtgPair> pairs = {{0, 1, 0, 0}, {0, 2, 0, 1}, {0, 2, 0, 2}, {0, 2, 0, 3},
                                  {1, 2, 0, 1}, {1, 2, 0, 2}, {2, 3, 1, 0}, {2, 3, 3, 0}};
    std::vector<BtgManifoldRange> ranges(pairs.size());
    for (size_t i = 0; i < ranges.size(); ++i) ranges[i] = {int(i), 1};
    const std::vector<BtgPair> ignored = {{0, 2, 0, 0}, {2, 3, 0, 0}};
    std::vector<BtgManifoldRange> expect = ranges;
    ref::filterPairs(ignored, pairs, expect);

    DeviceWorld w(test::context());
    w.pairCapacity = pairs.size();
    w.pairs.upload(w.ctx, pairs);
    w.pairManifolds.upload(w.ctx, ranges);
    w.ignoredPairs.upload(w.ctx, ignored);
    w.numIgnoredPairs = int(ignored.size());
    std::vector<uint> counters(kNumCounters, 0u);
    counters[kPairCount] = uint(pairs.size());
    w.counters.upload(w.ctx, counters);
    filterPairs(w);
    std::vector<BtgManifoldRange> got = w.pairManifolds.download(w.ctx, pairs.size());
    const int emptied[] = {0, 1, 1, 1, 0, 0, 1, 1};
    for (size_t i = 0; i < pairs.size(); ++i) {
        EXPECT_EQ(expect[i].count, 1 - emptied[i]) << i;
        EXPECT_EQ(got[i].count, expect[i].count) << i;
    }
}
