// The dispatch order of a tile's workgroups: a permutation in which every
// contiguous run that a driver may hand one thread is an even sample.
#include "gpu/workgroup_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace vkray::gpu {
namespace {

std::vector<std::uint32_t> spread(std::size_t count) {
    std::vector<std::uint32_t> items(count);
    std::iota(items.begin(), items.end(), 0u);
    spreadForContiguousSplits(items);
    return items;
}

TEST(WorkgroupOrder, EvenGroupsComeFirstThenOdd) {
    EXPECT_EQ(spread(8), (std::vector<std::uint32_t>{0, 4, 2, 6, 1, 5, 3, 7}));
    // Positions whose reversal is past the end are left out: 5 of 8.
    EXPECT_EQ(spread(5), (std::vector<std::uint32_t>{0, 4, 2, 1, 3}));
    EXPECT_EQ(spread(1), (std::vector<std::uint32_t>{0}));
    EXPECT_TRUE(spread(0).empty());
}

TEST(WorkgroupOrder, IsAPermutationOfAnyCount) {
    for (std::size_t count : {2u, 3u, 7u, 100u, 1024u, 1025u, 4095u}) {
        std::vector<std::uint32_t> items = spread(count);
        std::sort(items.begin(), items.end());
        for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(items[i], i) << count << " groups";
    }
}

// Groups in rows, the costly ones together (the tile's lower half showing
// the scene): the halves and quarters of the list a driver hands its two or
// four threads each hold their share of the costly groups, to one group,
// where the rows' order gave one thread all of them.
TEST(WorkgroupOrder, EachContiguousRunHoldsItsShareOfACostlyRegion) {
    const std::size_t count = 1000;
    const auto costly = [&](std::uint32_t group) { return group >= count / 2; };
    const std::vector<std::uint32_t> items = spread(count);
    for (std::size_t threads : {2u, 4u}) {
        const std::size_t run = count / threads;
        for (std::size_t t = 0; t < threads; ++t) {
            const auto begin = items.begin() + std::ptrdiff_t(t * run);
            const long n = std::count_if(begin, begin + std::ptrdiff_t(run), costly);
            EXPECT_NEAR(double(n), double(run) / 2, 1.0) << threads << " threads, run " << t;
        }
    }
}

}  // namespace
}  // namespace vkray::gpu
