// Thumbnails and heat maps for the reports.
#include "image/pictures.h"

#include "util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vkray {
namespace {

TEST(Pictures, ShrinkAveragesOrKeepsTheLargestOfEachBlockEdgesIncluded) {
    // 5 x 3, factor 2: blocks of 2x2, 1x2 at the right, 2x1 at the bottom, 1x1 in the corner.
    // clang-format off
    Image values{5, 3, 1, {1, 2, 3, 4, 5,
                           6, 7, 8, 9, 10,
                           11, 12, 13, 14, 15}};
    // clang-format on
    const Image mean = shrink(values, 2, Shrink::Average);
    ASSERT_EQ(mean.width, 3);
    ASSERT_EQ(mean.height, 2);
    EXPECT_EQ(mean.pixels, (std::vector<float>{4, 6, 7.5f, 11.5f, 13.5f, 15}));
    const Image largest = shrink(values, 2, Shrink::Largest);
    EXPECT_EQ(largest.pixels, (std::vector<float>{7, 9, 10, 12, 14, 15}));
    values.pixels[0] = std::numeric_limits<float>::quiet_NaN();  // a NaN error is never hidden
    EXPECT_TRUE(std::isnan(shrink(values, 2, Shrink::Largest).pixels[0]));
    // Channels stay apart.
    const Image rgb{2, 1, 3, {1, 0, 0, 0, 0, 1}};
    EXPECT_EQ(shrink(rgb, 2, Shrink::Average).pixels, (std::vector<float>{0.5f, 0, 0.5f}));
    EXPECT_EQ(shrink(rgb, 1, Shrink::Largest).pixels, rgb.pixels);
    EXPECT_THROW(shrink(rgb, 0, Shrink::Average), Error);
    EXPECT_EQ(shrinkFactorFor(Image{640, 480, 1, {}}, 160), 4);
    EXPECT_EQ(shrinkFactorFor(Image{641, 480, 1, {}}, 160), 5);
    EXPECT_EQ(shrinkFactorFor(Image{24, 18, 1, {}}, 160), 1);
}

TEST(Pictures, HeatScaleIsLogarithmicBetweenItsEnds) {
    const HeatScale scale{1e-4, 1};
    EXPECT_EQ(heatPosition(scale, 0), 0);
    EXPECT_EQ(heatPosition(scale, 1e-6), 0);
    EXPECT_EQ(heatPosition(scale, 1e-4), 0);
    EXPECT_DOUBLE_EQ(heatPosition(scale, 1e-2), 0.5);
    EXPECT_DOUBLE_EQ(heatPosition(scale, 1e-3), 0.25);
    EXPECT_EQ(heatPosition(scale, 1), 1);
    EXPECT_EQ(heatPosition(scale, 5), 1);
    EXPECT_EQ(heatPosition(scale, std::numeric_limits<double>::quiet_NaN()), 1);
}

TEST(Pictures, HeatColoursGrowBrighterFromBlackToPaleYellow) {
    const auto luminance = [](glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
    EXPECT_LT(luminance(heatColour(0)), 0.01);
    EXPECT_GT(luminance(heatColour(1)), 0.9);
    double last = -1;
    for (int k = 0; k <= 64; ++k) {
        const double l = luminance(heatColour(k / 64.0));
        EXPECT_GT(l, last) << k;  // readable in grey: brightness never falls back
        last = l;
    }
    const Image map = heatMap(Image{3, 1, 1, {0, 1e-2f, 1}}, HeatScale{1e-4, 1});
    ASSERT_EQ(map.channels, 3);
    EXPECT_EQ(map.pixels[3], heatColour(0.5).r);
    EXPECT_EQ(map.pixels[8], heatColour(1).b);
    EXPECT_THROW(heatMap(Image{1, 1, 3, {0, 0, 0}}, HeatScale{}), Error);
    EXPECT_EQ(hexColour({1, 0, 1}), "#ff00ff");
    EXPECT_EQ(hexColour({0.5f, 2, -1}), "#80ff00");
}

}  // namespace
}  // namespace vkray
