// shaders/sampling.h as C++ sees it (the shader compiles the same text):
// pinned hash values, worked out independently of this code, and the
// stratification of jitteredSample.
#include "shaders/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <utility>

#include "render/camera.h"

namespace vkray {
namespace {

using sampling::sampleColumns;
using sampling::sampleOffsetX;
using sampling::sampleOffsetY;
using sampling::sampleRandom;
using sampling::sampleRows;

// Reference values computed outside this code base (a Python transcription
// of the spec: h = lowbias32(seed ^ lowbias32(pixel ^ lowbias32(2k + dim))),
// ξ = (h >> 8) / 2^24).
TEST(Sampling, LowBias32MatchesPinnedValues) {
    EXPECT_EQ(sampling::lowbias32(0u), 0u);  // zero is its fixed point
    EXPECT_EQ(sampling::lowbias32(1u), 0x688990c0u);
}

TEST(Sampling, FirstValuesForSeedZeroPixelZero) {
    EXPECT_EQ(sampleRandom(0, 0, 0, 0), 0.0f);
    EXPECT_EQ(sampleRandom(0, 0, 0, 1), 2359452.0f / 16777216.0f);      // h = 0x24009c6d
    EXPECT_EQ(sampleRandom(0, 0, 1, 0), 5757736.0f / 16777216.0f);      // h = 0x57db2856
    EXPECT_EQ(sampleRandom(0, 0, 1, 1), 11855066.0f / 16777216.0f);     // h = 0xb4e4da13
    EXPECT_EQ(sampleRandom(7, 12345, 3, 1), 3977206.0f / 16777216.0f);  // h = 0x3caff662
}

TEST(Sampling, ValuesLieInTheUnitIntervalAndAverageOneHalf) {
    double sum = 0;
    int count = 0;
    for (std::uint32_t pixel = 0; pixel < 100; ++pixel) {
        for (std::uint32_t k = 0; k < 50; ++k) {
            for (std::uint32_t dim = 0; dim < 2; ++dim) {
                const float xi = sampleRandom(42, pixel, k, dim);
                ASSERT_GE(xi, 0.0f);
                ASSERT_LT(xi, 1.0f);
                sum += xi;
                ++count;
            }
        }
    }
    // 10000 uniform values: the mean's standard deviation is 0.0029.
    EXPECT_NEAR(sum / count, 0.5, 0.015);
}

TEST(Sampling, SeedPixelSampleAndDimensionEachChangeTheValue) {
    const float base = sampleRandom(1, 2, 3, 0);
    EXPECT_NE(base, sampleRandom(2, 2, 3, 0));
    EXPECT_NE(base, sampleRandom(1, 3, 3, 0));
    EXPECT_NE(base, sampleRandom(1, 2, 4, 0));
    EXPECT_NE(base, sampleRandom(1, 2, 3, 1));
}

TEST(Sampling, GridIsCeilSqrtColumnsByEnoughRows) {
    const std::pair<std::uint32_t, std::uint32_t> expected[] = {
        {1, 1}, {2, 2}, {3, 2}, {4, 2}, {5, 3}, {9, 3}, {10, 4}, {16, 4}, {17, 5}, {4096, 64}};
    for (const auto& [n, columns] : expected) {
        EXPECT_EQ(sampleColumns(n), columns) << n;
        EXPECT_EQ(sampleRows(n), (n + columns - 1) / columns) << n;
    }
    EXPECT_EQ(sampleRows(3), 2u);  // 2 x 2, the last row half full
    EXPECT_EQ(sampleRows(5), 2u);  // 3 x 2
}

// Every sample lies in its own cell of the m x rows grid, and the cells of
// k = 0 .. n - 1 are all different: each row but the last is full.
TEST(Sampling, StrataCoverEachCellOnce) {
    for (const std::uint32_t n : {2u, 3u, 4u, 5u, 7u, 9u, 16u, 30u, 64u}) {
        const std::uint32_t m = sampleColumns(n), rows = sampleRows(n);
        for (const std::uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
            for (const std::uint32_t pixel : {0u, 17u, 640u * 480u - 1u}) {
                std::set<std::pair<std::uint32_t, std::uint32_t>> cells;
                for (std::uint32_t k = 0; k < n; ++k) {
                    const double x = sampleOffsetX(seed, pixel, k, n);
                    const double y = sampleOffsetY(seed, pixel, k, n);
                    ASSERT_GE(x, 0.0);
                    ASSERT_LT(x, 1.0);
                    ASSERT_GE(y, 0.0);
                    ASSERT_LT(y, 1.0);
                    const auto column = std::uint32_t(std::floor(x * m));
                    const auto row = std::uint32_t(std::floor(y * rows));
                    // In its own cell (float rounding may put it on the cell's far edge).
                    EXPECT_TRUE(column == k % m || (column == k % m + 1 && x * m == column))
                        << "n " << n << " k " << k << " x " << x;
                    EXPECT_TRUE(row == k / m || (row == k / m + 1 && y * rows == row))
                        << "n " << n << " k " << k << " y " << y;
                    cells.insert({k % m, k / m});
                }
                EXPECT_EQ(cells.size(), n);
                for (std::uint32_t r = 0; r + 1 < rows; ++r)
                    for (std::uint32_t c = 0; c < m; ++c) EXPECT_TRUE(cells.count({c, r}));
            }
        }
    }
}

TEST(Sampling, OffsetStaysBelowOneForTheLargestRandomValue) {
    // (m - 1 + (1 - 2^-24)) / m rounds to 1 in float for m = 3; it must not.
    EXPECT_LT(sampling::belowOne(1.0f), 1.0f);
    EXPECT_EQ(sampling::belowOne(0.5f), 0.5f);
}

TEST(JitteredSample, OneSampleIsThePixelOrBlockCentre) {
    RenderSettings settings;
    settings.width = 10;
    settings.height = 10;
    const PixelSample centre = jitteredSample(3, 4, settings, 0);
    EXPECT_EQ(centre.px, 3.5);
    EXPECT_EQ(centre.py, 4.5);
    settings.block = 4;
    const PixelSample block = jitteredSample(5, 6, settings, 0);
    EXPECT_EQ(block.px, 6.0);  // block (4..7, 4..7): centre (6, 6)
    EXPECT_EQ(block.py, 6.0);
}

TEST(JitteredSample, SamplesFallInThePixelAtTheSharedOffsets) {
    RenderSettings settings;
    settings.width = 20;
    settings.height = 10;
    settings.spp = 4;
    settings.seed = 9;
    for (int k = 0; k < 4; ++k) {
        const PixelSample s = jitteredSample(7, 3, settings, k);
        const std::uint32_t pixel = 3 * 20 + 7;
        EXPECT_EQ(s.px, 7 + double(sampleOffsetX(9, pixel, std::uint32_t(k), 4)));
        EXPECT_EQ(s.py, 3 + double(sampleOffsetY(9, pixel, std::uint32_t(k), 4)));
    }
    // With a block, the block's first pixel draws, and the offsets span the block.
    settings.block = 3;
    const PixelSample s = jitteredSample(8, 5, settings, 2);  // block at (6, 3)
    const std::uint32_t first = 3 * 20 + 6;
    EXPECT_EQ(s.px, 6 + 3 * double(sampleOffsetX(9, first, 2, 4)));
    EXPECT_EQ(s.py, 3 + 3 * double(sampleOffsetY(9, first, 2, 4)));
}

}  // namespace
}  // namespace vkray
