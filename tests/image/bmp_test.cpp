// BMP, the format of Hill's pixmaps: read through stb's decoder, reached only
// by the .bmp extension and a "BM" signature, sizes checked before decoding.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <string>

#include "image/image_io.h"
#include "support/error_of.h"
#include "util/error.h"

namespace vkray {
namespace {

std::string littleEndian(std::uint32_t v, int bytes) {
    std::string out;
    for (int i = 0; i < bytes; ++i) out.push_back(char((v >> (8 * i)) & 0xffu));
    return out;
}

// A 24-bit uncompressed BMP (BITMAPINFOHEADER), written out by hand: rows
// bottom-up, each pixel B G R, each row padded to 4 bytes. pixel(x, y) gives
// the RGB of image row y (0 = top).
std::string bmp24(int width, int height, const std::function<std::uint32_t(int, int)>& pixel) {
    const int rowBytes = (width * 3 + 3) / 4 * 4;
    std::string data;
    for (int row = height - 1; row >= 0; --row) {
        std::string line;
        for (int x = 0; x < width; ++x) {
            const std::uint32_t rgb = pixel(x, row);
            line += {char(rgb & 0xff), char((rgb >> 8) & 0xff), char((rgb >> 16) & 0xff)};
        }
        line.resize(std::size_t(rowBytes), '\0');
        data += line;
    }
    const std::uint32_t offset = 14 + 40;
    return "BM" + littleEndian(offset + std::uint32_t(data.size()), 4) + littleEndian(0, 4) +
           littleEndian(offset, 4) + littleEndian(40, 4) + littleEndian(std::uint32_t(width), 4) +
           littleEndian(std::uint32_t(height), 4) + littleEndian(1, 2) + littleEndian(24, 2) +
           littleEndian(0, 4) + littleEndian(std::uint32_t(data.size()), 4) +
           littleEndian(2835, 4) + littleEndian(2835, 4) + littleEndian(0, 4) + littleEndian(0, 4) +
           data;
}

TEST(Bmp, TwentyFourBitPixelsComeBackTopRowFirst) {
    // 3 x 2, so each row needs padding (9 bytes -> 12).
    const auto pixel = [](int x, int y) {
        return std::uint32_t((40 * x + 10) << 16 | (100 * y + 20) << 8 | 200);
    };
    const Image image = decodeImage(bmp24(3, 2, pixel), "hill.bmp");
    ASSERT_EQ(image.width, 3);
    ASSERT_EQ(image.height, 2);
    ASSERT_EQ(image.channels, 3);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 3; ++x) {
            const float* rgb = &image.pixels[std::size_t(y * 3 + x) * 3];
            EXPECT_EQ(rgb[0], float(40 * x + 10) / 255.0f) << x << "," << y;
            EXPECT_EQ(rgb[1], float(100 * y + 20) / 255.0f) << x << "," << y;
            EXPECT_EQ(rgb[2], 200.0f / 255.0f) << x << "," << y;
        }
    }
}

TEST(Bmp, EachFormatIsReadOnlyUnderItsOwnNameAndSignature) {
    const std::string bmp = bmp24(1, 1, [](int, int) { return 0xffffffu; });
    EXPECT_EQ(errorOf([&] { decodeImage(bmp, "x.png"); }),
              "x.png: not a readable PNG file (no PNG signature)");
    EXPECT_EQ(errorOf([] { decodeImage(std::string("\x89PNG\r\n\x1a\n", 8), "x.bmp"); }),
              "x.bmp: not a readable BMP file (no 'BM' signature)");
    EXPECT_EQ(errorOf([] { decodeImage("BM", "x.bmp"); }),
              "x.bmp: truncated BMP: the file ends inside its header (2 bytes)");
    // vkray reads BMP but does not write it.
    EXPECT_EQ(errorOf([] {
                  writeImage("/nonexistent/x.bmp", Image{1, 1, 3, {0, 0, 0}});
              }),
              "/nonexistent/x.bmp: unsupported image format '.bmp' (use .png, .pfm or .exr)");
}

TEST(Bmp, OsTwoPalettesAreRefusedRatherThanDecodedBlack) {
    // fuzz/seeds/image/os2-1bit.bmp: stb_image 2.27 reads its palette as empty.
    const std::string bytes(
        "BM(\0\0\0\0\0\0\0 \0\0\0"            // file header: pixels at 32
        "\x0c\0\0\0\x08\0\x02\0\x01\0\x01\0"  // OS/2 header: 8 x 2, 1 bit
        "\0\0\0\xff\xff\0"                    // palette: black, cyan
        "\x55\0\0\0\xaa\0\0\0",               // rows, bottom first
        40);
    EXPECT_EQ(errorOf([&] { decodeImage(bytes, "os2.bmp"); }),
              "os2.bmp: OS/2 BMP files with a palette are not supported (save it as a Windows "
              "BMP or a PNG)");
}

TEST(Bmp, ClaimingTooManyPixelsIsRefusedBeforeDecoding) {
    std::string big = bmp24(1, 1, [](int, int) { return 0u; });
    big.replace(18, 8, littleEndian(20000, 4) + littleEndian(20000, 4));  // width, height
    EXPECT_EQ(errorOf([&] { decodeImage(big, "big.bmp"); }),
              "big.bmp: the image is 20000x20000, above vkray's limit of 67108864 pixels "
              "(65536 per side)");
}

// Found by fuzz/image_fuzz.cpp (at 4 bits per pixel): stb decodes an OS/2
// header of width and height 0 into a 0 x 0 "image".
TEST(BmpFuzzRegression, ZeroSizedImageIsRefused) {
    const std::string bytes(
        "BMPF\n2\x01\0\0\0\x1a\0\0\0"     // file header: pixels at 26
        "\x0c\0\0\0\0\0\0\0\x01\0\x18\0"  // OS/2 header: 0 x 0, 24 bits
        "\0\0\x01\0\0\0>\xfe",
        34);
    EXPECT_EQ(errorOf([&] { decodeImage(bytes, "fuzz.bmp"); }),
              "fuzz.bmp: not a readable BMP file (it has no pixels: 0x0)");
}

// Found by fuzz/image_fuzz.cpp (at 1 bit per pixel; at 24 now that paletted
// OS/2 files are refused first): 25 bytes whose OS/2 header claims 6400 x
// 7424 pixels kept stb busy for seconds filling the missing rows with zeros.
TEST(BmpFuzzRegression, HugeClaimInATinyFileIsRefusedAtOnce) {
    const std::string bytes(
        "BMPF\n2\x01\0\0\0\xfa\x01\0\0"      // file header: pixels at 506
        "\x0c\0\0\0\0\x19\0\x1d\x01\0\x18",  // OS/2 header: 6400 x 7424, 24 bits (cut)
        25);
    EXPECT_EQ(errorOf([&] { decodeImage(bytes, "fuzz.bmp"); }),
              "fuzz.bmp: truncated BMP: the file ends inside its header (25 bytes)");
    // Its header completed, the pixel rows it promises are missing.
    EXPECT_EQ(errorOf([&] { decodeImage(bytes + '\0', "fuzz.bmp"); }),
              "fuzz.bmp: truncated BMP: a 6400x7424 image of 24 bits per pixel needs "
              "142541306 bytes, the file has 26");
}

// Found by fuzz/image_fuzz.cpp: a V5 header with a negative (top-down)
// height of -196606 and compression code 0xbd000000, which stb took for
// uncompressed and filled with zeros for seconds.
TEST(BmpFuzzRegression, NegativeHeightsAndUnknownCompressionAreChecked) {
    std::string topDown = bmp24(2, 2, [](int, int) { return 0u; });
    topDown.replace(22, 4, littleEndian(std::uint32_t(-196606), 4));
    EXPECT_EQ(errorOf([&] { decodeImage(topDown, "fuzz.bmp"); }),
              "fuzz.bmp: the image is 2x196606, above vkray's limit of 67108864 pixels (65536 "
              "per side)");
    std::string compressed = bmp24(2, 2, [](int, int) { return 0u; });
    compressed.replace(30, 4, littleEndian(0xbd000000u, 4));
    EXPECT_EQ(errorOf([&] { decodeImage(compressed, "fuzz.bmp"); }),
              "fuzz.bmp: BMP compression 3170893824 is not supported (only uncompressed BMP "
              "files are read)");
    // A small top-down file reads the right way up.
    std::string small = bmp24(1, 2, [](int, int y) { return y == 0 ? 0xff0000u : 0x0000ffu; });
    small.replace(22, 4, littleEndian(std::uint32_t(-2), 4));  // rows now stored top first
    const Image image = decodeImage(small, "small.bmp");
    EXPECT_EQ(image.pixels[2], 1.0f);  // top row: what was stored first (blue)
    EXPECT_EQ(image.pixels[3], 1.0f);  // bottom row: red
}

TEST(Bmp, ATruncatedFileIsAnErrorNotABlackImage) {
    // stb would read zeros for the missing rows.
    std::string cut = bmp24(4, 4, [](int, int) { return 0xffffffu; });
    cut.resize(cut.size() - 12);  // the last row (4 x 3 bytes, no padding)
    EXPECT_EQ(errorOf([&] { decodeImage(cut, "cut.bmp"); }),
              "cut.bmp: truncated BMP: a 4x4 image of 24 bits per pixel needs 102 bytes, the "
              "file has 90");
}

}  // namespace
}  // namespace vkray
