// manifold_table_test.cpp — the fill's manifold table (compat/manifold_table.h) against
// std::unordered_map under long random runs of inserts, erases and lookups at every load the
// table grows through: the same keys found, a node's address kept while its key stays, each live
// node visited once, and erased slots never hiding a key later in its probe run (keys made to
// collide on purpose: few distinct low hash bits).
#include "../../compat/manifold_table.h"  // Bullet-free; compat/ is not on the tests' include path

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <unordered_map>

namespace {

struct Key {
    uint64_t a, b;
    bool operator==(const Key& o) const { return a == o.a && b == o.b; }
};
// Deliberately weak: 6 home slots, the table's last six at any size, so every probe run is long
// and wraps around the table's end (the backward shift's cyclic case).
struct CollidingHash {
    size_t operator()(const Key& k) const { return ~size_t(0) - size_t((k.a * 7 + k.b) % 6); }
};
struct GoodHash {
    size_t operator()(const Key& k) const { return size_t(k.a * 0x9E3779B97F4A7C15ull ^ (k.b + (k.a >> 7))); }
};
struct StdHash {
    size_t operator()(const Key& k) const { return size_t(k.a * 31 + k.b); }
};

template <typename Hash>
void randomRun(unsigned seed, int ops, int keySpace)
{
    btgpu::ManifoldTable<Key, int, Hash> table;
    std::unordered_map<Key, int, StdHash> truth;
    std::unordered_map<Key, const void*, StdHash> address;
    std::mt19937 rng(seed);
    for (int op = 0; op < ops; ++op) {
        const Key k{uint64_t(rng() % unsigned(keySpace)) * 16u, uint64_t(rng() % 3u)};
        const unsigned what = rng() % 10u;
        if (what < 5) {  // insert (or find what is there)
            auto* node = table.insert(k);
            ASSERT_NE(node, nullptr);
            ASSERT_TRUE(node->first == k);
            auto it = truth.find(k);
            if (it == truth.end()) {
                ASSERT_EQ(node->second, 0) << "a new node's entry starts value-initialised";
                node->second = op + 1;
                truth[k] = op + 1;
                address[k] = node;
            } else {
                ASSERT_EQ(node->second, it->second);
                ASSERT_EQ(static_cast<const void*>(node), address[k]) << "a kept key's node moved";
            }
        } else if (what < 8) {  // erase
            auto* node = table.find(k);
            ASSERT_EQ(node != nullptr, truth.count(k) > 0);
            if (node) {
                table.erase(node);
                truth.erase(k);
                address.erase(k);
            }
        } else {  // look up, with the hash given
            auto* node = table.find(k, Hash()(k));
            auto it = truth.find(k);
            ASSERT_EQ(node != nullptr, it != truth.end());
            if (node) ASSERT_EQ(node->second, it->second);
        }
        ASSERT_EQ(table.size(), truth.size());
    }
    // Every key still there is found where it was; every live node is visited once.
    for (const auto& [k, v] : truth) {
        auto* node = table.find(k);
        ASSERT_NE(node, nullptr);
        ASSERT_EQ(node->second, v);
        ASSERT_EQ(static_cast<const void*>(node), address[k]);
    }
    std::set<const void*> seen;
    table.forEach([&](auto* node) {
        ASSERT_TRUE(seen.insert(node).second);
        ASSERT_EQ(truth.count(node->first), 1u);
    });
    ASSERT_EQ(seen.size(), truth.size());
}

}  // namespace

TEST(ManifoldTable, AgreesWithAMapUnderRandomInsertsAndErases)
{
    for (unsigned seed = 1; seed <= 4; ++seed) {
        randomRun<GoodHash>(seed, 60000, 4000);    // grows to ~8,000 keys, then churns
        randomRun<GoodHash>(seed + 100, 20000, 40);  // a small table that empties and refills
    }
}

TEST(ManifoldTable, LongCollidingRunsSurviveErases)
{
    for (unsigned seed = 1; seed <= 4; ++seed) randomRun<CollidingHash>(seed, 20000, 300);
}

TEST(ManifoldTable, ClearThenReuse)
{
    btgpu::ManifoldTable<Key, int, GoodHash> table;
    for (uint64_t i = 0; i < 1000; ++i) table.insert(Key{i, 0})->second = int(i);
    table.clear();
    EXPECT_EQ(table.size(), 0u);
    EXPECT_EQ(table.find(Key{5, 0}), nullptr);
    for (uint64_t i = 0; i < 100; ++i) table.insert(Key{i, 1})->second = int(i);
    for (uint64_t i = 0; i < 100; ++i) {
        ASSERT_NE(table.find(Key{i, 1}), nullptr);
        EXPECT_EQ(table.find(Key{i, 1})->second, int(i));
        EXPECT_EQ(table.find(Key{i, 0}), nullptr);
    }
}
