#include "image/aov_images.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace vkray {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(ImageFromFrame, CopiesEachArrayInPixelOrder) {
    Frame frame(2, 1);
    frame.color = {{0.1f, 0.2f, 3.0f}, {-1, 0, 1}};
    frame.depth = {1.5f, kInf};
    frame.normal = {{0, 1, 0}, {0, 0, 0}};
    frame.id = {7, -1};

    const Image color = colorImage(frame);
    EXPECT_EQ(color.width, 2);
    EXPECT_EQ(color.height, 1);
    EXPECT_EQ(color.channels, 3);
    EXPECT_EQ(color.pixels, (std::vector<float>{0.1f, 0.2f, 3.0f, -1, 0, 1}));  // unclamped

    const Image depth = depthImage(frame);
    EXPECT_EQ(depth.channels, 1);
    EXPECT_EQ(depth.pixels, (std::vector<float>{1.5f, kInf}));

    const Image normal = normalImage(frame);
    EXPECT_EQ(normal.channels, 3);
    EXPECT_EQ(normal.pixels, (std::vector<float>{0, 1, 0, 0, 0, 0}));

    const Image id = idImage(frame);
    EXPECT_EQ(id.channels, 1);
    EXPECT_EQ(id.pixels, (std::vector<float>{7, -1}));
}

}  // namespace
}  // namespace vkray
