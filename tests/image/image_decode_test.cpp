// decodeImage: images from memory (what the image fuzz target drives), the
// size limits checked before decoding, and the inputs fuzzing found.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "support/error_of.h"
#include "util/error.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;

std::string bigEndian32(std::uint32_t v) {
    return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::uint32_t crc32(const std::string& bytes) {
    std::uint32_t crc = 0xffffffffu;
    for (const char c : bytes) {
        crc ^= std::uint8_t(c);
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

// One PNG chunk: length, type, data, CRC.
std::string pngChunk(const std::string& type, const std::string& data) {
    return bigEndian32(std::uint32_t(data.size())) + type + data + bigEndian32(crc32(type + data));
}

// A PNG signature and IHDR chunk for an 8-bit RGB image of the given size,
// with no pixel data after it: what a hostile or truncated file looks like.
std::string pngHeaderOnly(std::uint32_t width, std::uint32_t height) {
    return std::string("\x89PNG\r\n\x1a\n", 8) +
           pngChunk("IHDR", bigEndian32(width) + bigEndian32(height) +
                                std::string("\x08\x02\x00\x00\x00", 5));
}

// `raw` (filter bytes and pixels) as a zlib stream of one stored block.
std::string zlibStored(const std::string& raw) {
    std::uint32_t a = 1, b = 0;  // Adler-32
    for (const char c : raw) {
        a = (a + std::uint8_t(c)) % 65521;
        b = (b + a) % 65521;
    }
    const auto n = std::uint16_t(raw.size());
    return std::string("\x78\x01\x01", 3) + char(n & 0xff) + char(n >> 8) + char(~n & 0xff) +
           char((~n >> 8) & 0xff) + raw + bigEndian32(b << 16 | a);
}

TEST(DecodeImage, GivesWhatReadImageGivesForTheSameBytes) {
    const fs::path dir =
        fs::path(::testing::TempDir()) / ("vkray-decode-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const char* name : {"a.png", "a.pfm"}) {
        const std::string path = (dir / name).string();
        writeImage(path, Image{2, 1, 3, {0, 0.5f, 1, 1, 0.25f, 0}});
        std::ifstream in(path, std::ios::binary);
        const std::string bytes{std::istreambuf_iterator<char>(in),
                                std::istreambuf_iterator<char>()};
        const Image fromFile = readImage(path);
        const Image fromBytes = decodeImage(bytes, path);
        EXPECT_EQ(fromBytes.width, 2);
        EXPECT_EQ(fromBytes.channels, 3);
        EXPECT_EQ(fromBytes.pixels, fromFile.pixels) << name;
    }
    fs::remove_all(dir);
}

TEST(DecodeImage, ExtensionChoosesTheFormat) {
    EXPECT_EQ(errorOf([] { decodeImage("PF\n1 1\n-1\n", "x.tiff"); }),
              "x.tiff: unsupported image format '.tiff' (use .png, .pfm or .exr, or .bmp to read)");
    // PFM bytes under a .png name are read as PNG, and refused as such.
    EXPECT_EQ(errorOf([] { decodeImage("Pf\n1 1\n-1\n\0\0\0\0", "x.png"); }).rfind("x.png: ", 0),
              0u);
}

TEST(DecodeImage, PngClaimingTooManyPixelsIsRefusedBeforeDecoding) {
    // stb would allocate 300 MB for this one before noticing that the data is
    // missing; vkray refuses it from the header.
    EXPECT_EQ(errorOf([] { decodeImage(pngHeaderOnly(10000, 10000), "big.png"); }),
              "big.png: the image is 10000x10000, above vkray's limit of 67108864 pixels "
              "(65536 per side)");
    // Beyond 2^30 bytes stb refuses by itself.
    EXPECT_EQ(errorOf([] { decodeImage(pngHeaderOnly(100000, 100000), "big.png"); }),
              "big.png: not a readable PNG file (too large)");
    // Within the limits, the missing data is the error.
    EXPECT_EQ(errorOf([] {
                  decodeImage(pngHeaderOnly(64, 64), "small.png");
              }).rfind("small.png: not a readable PNG file (", 0),
              0u);
}

// Found by fuzz/image_fuzz.cpp: a first IDAT chunk of length 0 made stb_image
// memcpy through a null pointer (UBSan: "null pointer passed as argument 1",
// fatal in scripts/test-sanitizers.sh). Such chunks are dropped before stb.
TEST(DecodeImageFuzzRegression, EmptyFirstIdatChunkIsSkipped) {
    const std::string header = pngHeaderOnly(1, 1);
    const std::string pixel = zlibStored(std::string("\x00\x33\x66\xff", 4));
    const Image image =
        decodeImage(header + pngChunk("IDAT", "") + pngChunk("IDAT", pixel) + pngChunk("IEND", ""),
                    "empty-idat.png");
    EXPECT_EQ(image.pixels, (std::vector<float>{0x33 / 255.f, 0x66 / 255.f, 1}));
}

// Found by fuzz/image_fuzz.cpp (twice): a 73-byte file whose IDAT chunk
// claims 1.6 GB made stb allocate that much before reading it (a timeout
// under ASan; an allocation failure on a small machine). Chunks that run past
// the end of the file are refused.
TEST(DecodeImageFuzzRegression, ChunkLongerThanTheFileIsRefusedBeforeAllocating) {
    const unsigned char found[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x01, 0xe7,
        0x48, 0x00, 0x00, 0x63, 0x00, 0x70, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x31, 0x2e,
        0x30, 0x0a, 0x63, 0x60, 0x64, 0xc8, 0xa6, 0x00, 0x00, 0x30, 0x60, 0x00, 0x00, 0x6f, 0xe4,
        0x78, 0x49, 0x48, 0x44, 0x52, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    const std::string bytes(reinterpret_cast<const char*>(found), sizeof found);
    EXPECT_EQ(errorOf([&] { decodeImage(bytes, "found.png"); }),
              "found.png: corrupt PNG: the 'IDAT' chunk at byte 33 runs past the end of the file "
              "(it claims 1660973068 bytes of data; 32 bytes are left)");
    // The second one found: the length and type of the last chunk are there,
    // its data and CRC are not.
    const unsigned char second[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
        0x44, 0x52, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 0x01, 0x02, 0x03, 0x00, 0x00,
        0x00, 0x84, 0x52, 0xe7, 0x5e, 0x00, 0x00, 0x00, 0x0c, 0x50, 0x4c, 0x54, 0x45, 0x00,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1d, 0x00, 0x1c, 0x8e, 0xf4, 0xf5, 0x21, 0x00,
        0x00, 0x74, 0x52, 0x4e, 0x53, 0x49, 0x44, 0x41, 0x54, 0x60, 0x82};
    EXPECT_EQ(errorOf([&] {
                  decodeImage(std::string(reinterpret_cast<const char*>(second), sizeof second),
                              "second.png");
              }),
              "second.png: corrupt PNG: the 'IDAT' chunk at byte 57 runs past the end of the "
              "file (it claims 1951551059 bytes of data; 2 bytes are left)");
    // Unprintable chunk types are shown with '?'.
    EXPECT_EQ(errorOf([&] {
                  decodeImage(pngHeaderOnly(1, 1) + std::string("\x00\x00\x01\x00x\x9c"
                                                                "1.\0\0\0\0",
                                                                12),
                              "t.png");
              }),
              "t.png: corrupt PNG: the 'x?1.' chunk at byte 33 runs past the end of the file (it "
              "claims 256 bytes of data; 4 bytes are left)");
}

// Found by fuzz/image_fuzz.cpp: this 80-byte PNG claims 8451x7426 pixels
// (within the limits) and holds 23 bytes of compressed data; stb allocated
// 188 MB for it before finding the data short (a timeout under ASan). Data
// that cannot hold the image (deflate packs at most 1032:1, a pixel takes at
// least a bit) is refused first.
TEST(DecodeImageFuzzRegression, CompressedDataTooShortForTheImageIsRefusedBeforeAllocating) {
    const unsigned char found[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
        0x44, 0x52, 0x00, 0x00, 0x21, 0x03, 0x00, 0x00, 0x1d, 0x02, 0x08, 0x02, 0x00, 0x00,
        0x00, 0x12, 0x16, 0xf1, 0x4d, 0x00, 0x00, 0x00, 0x17, 0x49, 0x44, 0x41, 0x54, 0x78,
        0x9c, 0x63, 0xf8, 0xdf, 0xc0, 0xc0, 0x00, 0xc1, 0xa4, 0x22, 0x72, 0x89, 0x50, 0x4e,
        0x47, 0x0d, 0x02, 0x00, 0x00, 0x59, 0x04, 0xc0, 0xe4, 0x24, 0x98, 0xcb, 0x00, 0x00,
        0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    EXPECT_EQ(errorOf([&] {
                  decodeImage(std::string(reinterpret_cast<const char*>(found), sizeof found),
                              "found.png");
              }),
              "found.png: not a readable PNG file (its 8451x7426 pixels need at least 7602 bytes "
              "of compressed data; its IDAT chunks hold 23)");
    // At the bound itself the data is handed to stb: a 1032:1 stream of
    // 8 * 1032 one-bit pixels is possible in principle.
    const std::string header = pngHeaderOnly(8 * 1032, 1);
    EXPECT_EQ(errorOf([&] {
                  decodeImage(header + pngChunk("IDAT", "x") + pngChunk("IEND", ""), "edge.png");
              }).find("need at least"),
              std::string::npos);
}

TEST(DecodeImage, PfmClaimingTooManyPixelsIsRefused) {
    EXPECT_EQ(errorOf([] { decodeImage("PF\n10000 10000\n-1\n", "big.pfm"); }),
              "big.pfm: the image is 10000x10000, above vkray's limit of 67108864 pixels "
              "(65536 per side)");
}

}  // namespace
}  // namespace vkray
