#include <gtest/gtest.h>

#include <random>
#include <unordered_map>

#include "plan/candidates.hpp"

using namespace scaffold;

// The flat table answers as std::unordered_map does, for keys packed to 32
// bits and for the wide ones beside them, through many growths.
TEST(BarTable, AnswersAsAnUnorderedMap) {
    plan::BarTable<bool> table;
    std::unordered_map<plan::BarKey, bool, plan::BarKeyHash> ref;
    std::mt19937 rng(5);
    std::uniform_int_distribution<long> near(-2000, 2000), pick(0, 20);
    auto key = [&] {
        // Nearby coordinates (they crowd the hash), sometimes beyond 32 bits.
        long far = pick(rng) == 0 ? (long{1} << 40) : 0;
        return plan::BarKey{near(rng) + far, near(rng), near(rng) * 7, near(rng), pick(rng)};
    };
    EXPECT_TRUE(table.empty());
    for (int i = 0; i < 20000; ++i) {
        const plan::BarKey k = key();
        const bool v = pick(rng) % 2;
        table.insert(k, v);
        ref.emplace(k, v);  // the first value stays, in both
        const plan::BarKey q = key();
        const bool* got = table.find(q);
        auto it = ref.find(q);
        ASSERT_EQ(got != nullptr, it != ref.end());
        if (got) {
            ASSERT_EQ(*got, it->second);
        }
    }
    for (const auto& [k, v] : ref) {
        ASSERT_TRUE(table.contains(k));
        ASSERT_EQ(*table.find(k), v);
    }
    EXPECT_FALSE(table.empty());
}

// The table probes by the hash's low bits: keys a few microns apart in any
// one coordinate (a bar's ends along a sweep line, a column's places) must
// spread over them as random ones would. 4096 keys into 4096 slots fill
// about 1 - 1/e of them (2589) at random; the identity fills 64 for the
// grids below, a hash that mixes only the first coordinate 64 too.
TEST(BarTable, NearbyKeysSpreadOverTheLowBits) {
    auto filled = [](auto make) {
        std::vector<char> slot(4096, 0);
        int n = 0;
        for (long i = 0; i < 64; ++i)
            for (long j = 0; j < 64; ++j) {
                const std::size_t h = plan::BarKeyHash{}(make(i, j)) & 4095;
                n += !slot[h];
                slot[h] = 1;
            }
        return n;
    };
    const long x = 123456, y = -65432, z = 20200;
    EXPECT_GT(filled([&](long i, long j) { return plan::BarKey{x + 64 * i, y + 64 * j, z, 0, 0}; }), 2450);
    EXPECT_GT(filled([&](long i, long j) { return plan::BarKey{x, y, x + i, y + j, z}; }), 2450);
    EXPECT_GT(filled([&](long i, long j) { return plan::BarKey{x, y, z, 1000 * i, 200 * j}; }), 2450);
}
