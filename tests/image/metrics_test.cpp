#include "image/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "util/error.h"

namespace vkray {
namespace {

// A w x h colour image with every value `v`.
Image flat(int w, int h, float v, int channels = 3) {
    return Image{w, h, channels, std::vector<float>(size_t(w) * h * channels, v)};
}

float& at(Image& image, int x, int y, int c) {
    return image.pixels[(size_t(y) * image.width + x) * image.channels + c];
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST(CompareImages, IdenticalImagesPass) {
    const Image a = flat(4, 3, 0.5f);
    const CompareResult r = compareImages(a, a, {});
    EXPECT_EQ(r.maxAbsError, 0);
    EXPECT_EQ(r.rmse, 0);
    EXPECT_TRUE(std::isinf(r.psnr) && r.psnr > 0);
    EXPECT_EQ(r.pixelsOverThreshold, 0u);
    EXPECT_EQ(r.percentOverThreshold, 0);
    EXPECT_EQ(r.pixelCount, 12u);
    EXPECT_FALSE(r.idMismatches);
    EXPECT_TRUE(r.passed);
    const std::string report = formatCompareReport(r, {});
    EXPECT_TRUE(contains(report, "inf dB (identical)")) << report;
    EXPECT_TRUE(contains(report, "PASS")) << report;
    EXPECT_FALSE(contains(report, "object ids")) << report;
}

TEST(CompareImages, OnePixelDifferenceGivesExactNumbers) {
    const Image a = flat(4, 3, 0.5f);
    Image b = a;
    at(b, 2, 1, 1) = 0.75f;   // green of pixel (2, 1) differs by 0.25 (exact in binary)
    at(b, 2, 1, 2) = 0.625f;  // blue by 0.125: the pixel's error is still the max, 0.25
    const CompareResult r = compareImages(a, b, {});
    EXPECT_EQ(r.maxAbsError, 0.25);
    EXPECT_EQ(r.maxErrorX, 2);
    EXPECT_EQ(r.maxErrorY, 1);
    const double rmse = std::sqrt((0.25 * 0.25 + 0.125 * 0.125) / (12 * 3));
    EXPECT_DOUBLE_EQ(r.rmse, rmse);
    EXPECT_DOUBLE_EQ(r.psnr, 20 * std::log10(1 / rmse));
    EXPECT_EQ(r.pixelsOverThreshold, 1u);
    EXPECT_DOUBLE_EQ(r.percentOverThreshold, 100.0 / 12);
    EXPECT_FALSE(r.passed);  // default: no pixel may differ by more than 1e-6
    const std::string report = formatCompareReport(r, {});
    EXPECT_TRUE(contains(report, "max abs error   0.25 at (2, 1)\n")) << report;
    EXPECT_TRUE(contains(report, "over threshold  1 of 12 pixels (8.333 %)")) << report;
    EXPECT_TRUE(contains(report, "FAIL")) << report;
}

TEST(CompareImages, MaxErrorLocationIsTheFirstWorstPixel) {
    const Image a = flat(3, 2, 0);
    Image b = a;
    at(b, 0, 0, 0) = 0.25f;
    at(b, 1, 1, 2) = 0.5f;
    at(b, 2, 1, 0) = 0.5f;
    const CompareResult r = compareImages(a, b, {});
    EXPECT_EQ(r.maxAbsError, 0.5);
    EXPECT_EQ(r.maxErrorX, 1);
    EXPECT_EQ(r.maxErrorY, 1);
    EXPECT_EQ(r.pixelsOverThreshold, 3u);
}

TEST(CompareImages, ThresholdAndPercentBoundariesAreInclusive) {
    const Image a = flat(4, 3, 0.5f);
    Image b = a;
    at(b, 0, 0, 0) = 0.75f;  // one pixel of 12 with error 0.25

    // An error equal to the threshold is not over it.
    CompareResult r = compareImages(a, b, {0.25, 0});
    EXPECT_EQ(r.pixelsOverThreshold, 0u);
    EXPECT_TRUE(r.passed);
    r = compareImages(a, b, {0.2499, 0});
    EXPECT_EQ(r.pixelsOverThreshold, 1u);
    EXPECT_FALSE(r.passed);

    // Exactly the allowed percentage passes; just below it fails.
    EXPECT_TRUE(compareImages(a, b, {0.1, 100.0 / 12}).passed);
    EXPECT_FALSE(compareImages(a, b, {0.1, 8.3}).passed);
}

TEST(CompareImages, ValuesAreComparedClampedToZeroOne) {
    const Image a{2, 1, 3, {2.0f, -3.0f, 1.0f, 5.0f, 0.5f, 0.0f}};
    const Image b{2, 1, 3, {1.0f, 0.0f, 7.0f, 1.0f, 0.5f, -0.5f}};
    const CompareResult r = compareImages(a, b, {});
    EXPECT_EQ(r.maxAbsError, 0);
    EXPECT_EQ(r.rmse, 0);
    EXPECT_TRUE(r.passed);

    // Clamped but still different: 1.5 shows as 1, compared against 0.25.
    const CompareResult partial =
        compareImages(Image{1, 1, 1, {1.5f}}, Image{1, 1, 1, {0.25f}}, {});
    EXPECT_EQ(partial.maxAbsError, 0.75);
}

TEST(CompareImages, NanIsAFullError) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Image a = flat(2, 1, 0.5f);
    Image b = a;
    at(b, 1, 0, 2) = nan;
    const CompareResult r = compareImages(a, b, {0.5, 0});
    EXPECT_EQ(r.maxAbsError, 1);
    EXPECT_EQ(r.maxErrorX, 1);
    EXPECT_EQ(r.pixelsOverThreshold, 1u);
    EXPECT_FALSE(r.passed);
    // Never hidden, not even when both sides are NaN.
    EXPECT_EQ(compareImages(b, b, {}).maxAbsError, 1);
}

TEST(CompareImages, SizeOrChannelMismatchThrows) {
    try {
        compareImages(flat(640, 480, 0), flat(320, 240, 0), {});
        ADD_FAILURE() << "no Error thrown";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "images differ in size: 640x480 vs 320x240");
    }
    EXPECT_THROW(compareImages(flat(2, 2, 0, 3), flat(2, 2, 0, 1), {}), Error);
    EXPECT_THROW(diffImage(flat(2, 2, 0), flat(2, 3, 0)), Error);
    EXPECT_THROW(compareImages(Image{2, 2, 3, {0}}, Image{2, 2, 3, {0}}, {}), Error);  // malformed
}

TEST(CompareIds, CountsMismatchesAndLeavesPassedAlone) {
    const Image a{4, 3, 1, std::vector<float>(12, 0)};
    Image b = a;
    b.pixels[3] = -1;
    b.pixels[7] = 2;
    CompareResult r = compareImages(flat(4, 3, 0), flat(4, 3, 0), {});
    compareIds(a, b, r);
    ASSERT_TRUE(r.idMismatches);
    EXPECT_EQ(*r.idMismatches, 2u);
    EXPECT_DOUBLE_EQ(r.idMismatchPercent, 200.0 / 12);
    EXPECT_TRUE(r.passed);
    const std::string report = formatCompareReport(r, {});
    EXPECT_TRUE(contains(report, "object ids      2 of 12 pixels differ (16.67 %)\n")) << report;

    compareIds(a, a, r);
    EXPECT_EQ(*r.idMismatches, 0u);
    EXPECT_EQ(r.idMismatchPercent, 0);

    EXPECT_THROW(compareIds(flat(4, 3, 0), flat(4, 3, 0), r), Error);  // 3 channels
    EXPECT_THROW(compareIds(a, Image{3, 4, 1, std::vector<float>(12, 0)}, r), Error);
}

TEST(DiffImage, IsScaledClampedAbsoluteDifference) {
    const Image a{3, 1, 1, {0.5f, 2.0f, 0.0f}};
    const Image b{3, 1, 1, {0.75f, 0.5f, 0.125f}};
    const Image d = diffImage(a, b);
    EXPECT_EQ(d.width, 3);
    EXPECT_EQ(d.height, 1);
    EXPECT_EQ(d.channels, 1);
    EXPECT_EQ(d.pixels, (std::vector<float>{0.25f, 0.5f, 0.125f}));  // 2.0 counts as 1
    EXPECT_EQ(diffImage(a, b, 4).pixels, (std::vector<float>{1.0f, 1.0f, 0.5f}));

    const Image c = diffImage(flat(2, 2, 0.25f), flat(2, 2, 0.25f));
    EXPECT_EQ(c.channels, 3);
    EXPECT_EQ(c.pixels, std::vector<float>(12, 0));
}

TEST(FormatCompareReport, PrintsEveryLine) {
    CompareResult r;
    r.maxAbsError = 0.0123;
    r.maxErrorX = 12;
    r.maxErrorY = 40;
    r.rmse = 1.234e-3;
    r.psnr = 58.17;
    r.pixelsOverThreshold = 12;
    r.pixelCount = 19200;
    r.percentOverThreshold = 0.0625;
    r.idMismatches = 3;
    r.idMismatchPercent = 3 * 100.0 / 19200;
    r.passed = true;
    EXPECT_EQ(formatCompareReport(r, {0.02, 0.1}),
              "max abs error   0.0123 at (12, 40)\n"
              "RMSE            1.23e-03\n"
              "PSNR            58.2 dB\n"
              "over threshold  12 of 19200 pixels (0.0625 %) with error > 0.02, allowed 0.1 %\n"
              "object ids      3 of 19200 pixels differ (0.01562 %)\n"
              "result          PASS\n");
    r.passed = false;
    EXPECT_TRUE(contains(formatCompareReport(r, {}), "result          FAIL\n"));
}

}  // namespace
}  // namespace vkray
