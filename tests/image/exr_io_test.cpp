// OpenEXR: every AOV layer written and read back bit for bit, the image as
// linear float, OpenEXR's own exrheader listing the layers, and bad files
// refused with a message naming them.
#include "image/exr_io.h"
#include "image/aov_images.h"
#include "image/image_io.h"
#include "support/error_of.h"
#include "support/temp_folder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace vkray {
namespace {

namespace fs = std::filesystem;

constexpr float kInf = std::numeric_limits<float>::infinity();

class ExrIo : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return (dir / name).string(); }
    std::string readBytes(const std::string& name) const {
        std::ifstream in(path(name), std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    void writeBytes(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
    }
    std::vector<std::string> filesInDir() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir))
            names.push_back(entry.path().filename().string());
        return names;
    }

    test::TempFolder scratch_{"vkray-exr-io"};
    const fs::path dir = scratch_.path();
};

// Bit patterns, so that NaN, -0 and denormals count as they are stored.
std::vector<std::uint32_t> bits(const std::vector<float>& values) {
    std::vector<std::uint32_t> out;
    for (float v : values) out.push_back(std::bit_cast<std::uint32_t>(v));
    return out;
}

const std::vector<std::string> kAovChannels{"R",   "G",  "B",   "Z",   "N.X", "N.Y",
                                            "N.Z", "id", "P.X", "P.Y", "P.Z"};

// A 3x2 frame with values a clamp, a rounding or a half-float store would change.
Frame awkwardFrame() {
    Frame frame(3, 2);
    const float denormal = std::numeric_limits<float>::denorm_min();
    frame.color = {{0.1f, 2.5f, -0.25f},
                   {1e-30f, 65504.0f * 4, denormal},
                   {0, -0.0f, 1},
                   {std::nanf(""), kInf, 0.333333343f},
                   {1, 1, 1},
                   {0.5f, 0.25f, 0.125f}};
    frame.depth = {1.0f / 3, kInf, 12345.678f, 1e-7f, 7.0f, 0.5f};
    frame.normal = {{0, 0, 1},  {0, 0, 0},  {0.6f, 0.8f, 0},
                    {-1, 0, 0}, {0, -1, 0}, {0.267261f, 0.534522f, 0.801784f}};
    frame.id = {0, -1, 16777215, 2, 41, 7};
    return frame;
}

std::vector<glm::vec3> awkwardHitPoints() {
    return {{1, 2, 3},          {0, 0, 0}, {-1e7f, 3.25f, 1e-20f},
            {0.1f, 0.2f, 0.3f}, {5, 6, 7}, {-8, -9, -10}};
}

TEST_F(ExrIo, AovFileHoldsEveryLayerBitForBit) {
    const Frame frame = awkwardFrame();
    const std::vector<glm::vec3> points = awkwardHitPoints();
    writeAovs(path("aov.exr"), frame, points);
    EXPECT_EQ(filesInDir(), std::vector<std::string>{"aov.exr"});  // one file, no temporaries

    const std::string bytes = readBytes("aov.exr");
    std::vector<std::string> names = exrChannelNames(bytes, "aov.exr");
    std::vector<std::string> expected = kAovChannels;
    std::sort(names.begin(), names.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(names, expected);

    const ExrImage exr = decodeExr(bytes, "aov.exr", kAovChannels);
    ASSERT_EQ(exr.width, 3);
    ASSERT_EQ(exr.height, 2);
    const auto channel = [&](const std::string& name) {
        const ExrChannel* c = exr.find(name);
        EXPECT_NE(c, nullptr) << name;
        return c ? c->values : std::vector<float>{};
    };
    const auto column = [&](auto get) {
        std::vector<float> values;
        for (size_t i = 0; i < frame.pixelCount(); ++i) values.push_back(get(i));
        return bits(values);
    };
    const char* const colours[] = {"R", "G", "B"};
    const char* const axes[] = {"X", "Y", "Z"};
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(bits(channel(colours[c])), column([&](size_t i) { return frame.color[i][c]; }))
            << colours[c];
        EXPECT_EQ(bits(channel(std::string("N.") + axes[c])),
                  column([&](size_t i) { return frame.normal[i][c]; }));
        EXPECT_EQ(bits(channel(std::string("P.") + axes[c])),
                  column([&](size_t i) { return points[i][c]; }));
    }
    EXPECT_EQ(bits(channel("Z")), bits(frame.depth));
    EXPECT_EQ(channel("id"), (std::vector<float>{0, -1, 16777215, 2, 41, 7}));
    // The ids as compare reads them.
    const Image ids = readIds(path("aov.exr"));
    EXPECT_EQ(ids.channels, 1);
    EXPECT_EQ(ids.pixels, channel("id"));
    EXPECT_TRUE(hasIdChannel(path("aov.exr")));
}

TEST_F(ExrIo, ImageIsLinearUnclampedFloatAndReadsBack) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Image colour{2, 2, 3, {0.5f, 2.0f, -1.0f, 1e-8f, 1e6f, 0, nan, kInf, 0.8f, 1, 1, 1}};
    writeImage(path("c.EXR"), colour);
    const Image back = readImage(path("c.EXR"));
    EXPECT_EQ(back.width, 2);
    EXPECT_EQ(back.height, 2);
    EXPECT_EQ(back.channels, 3);
    EXPECT_EQ(bits(back.pixels), bits(colour.pixels));
    EXPECT_EQ(exrChannelNames(readBytes("c.EXR"), "c.EXR"),
              (std::vector<std::string>{"B", "G", "R"}));
    EXPECT_FALSE(hasIdChannel(path("c.EXR")));

    const Image grey{3, 1, 1, {0.25f, -3, 100}};
    writeImage(path("g.exr"), grey);
    const Image greyBack = readImage(path("g.exr"));
    EXPECT_EQ(greyBack.channels, 1);
    EXPECT_EQ(greyBack.pixels, grey.pixels);
    EXPECT_EQ(decodeImage(readBytes("g.exr"), "g.exr").pixels, grey.pixels);  // from memory too
}

// OpenEXR's own tool (Debian's openexr package) lists vkray's layers.
TEST_F(ExrIo, ExrheaderListsTheLayers) {
    if (std::system("command -v exrheader > /dev/null 2>&1") != 0)
        GTEST_SKIP()
            << "exrheader is not installed (Debian package openexr; scripts/install-deps.sh)";
    writeAovs(path("aov.exr"), awkwardFrame(), awkwardHitPoints());
    FILE* pipe = ::popen(("exrheader " + path("aov.exr") + " 2>&1").c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string listing;
    std::array<char, 4096> buffer;
    for (size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
        listing.append(buffer.data(), n);
    ASSERT_EQ(::pclose(pipe), 0) << listing;
    // "channels (type chlist):" then a line per channel: "    N.X, 32-bit floating-point, sampling
    // 1 1".
    const size_t channels = listing.find("channels (type chlist):");
    ASSERT_NE(channels, std::string::npos) << listing;
    for (const std::string& name : kAovChannels)
        EXPECT_NE(listing.find("\n    " + name + ", 32-bit floating-point", channels),
                  std::string::npos)
            << name << " not listed:\n"
            << listing;
    EXPECT_NE(listing.find("compression (type compression): zip"), std::string::npos) << listing;
}

// A file another writer made: OpenEXR's exrmaketiled copies vkray's into
// 2x2 tiles with PIZ compression; every layer reads back the same bits.
TEST_F(ExrIo, ReadsATiledPizCopyMadeByOpenExrsTools) {
    if (std::system("command -v exrmaketiled > /dev/null 2>&1") != 0)
        GTEST_SKIP()
            << "exrmaketiled is not installed (Debian package openexr; scripts/install-deps.sh)";
    writeAovs(path("aov.exr"), awkwardFrame(), awkwardHitPoints());
    ASSERT_EQ(std::system(("exrmaketiled -t 2 2 -z piz " + path("aov.exr") + " " +
                           path("tiled.exr") + " > /dev/null 2>&1")
                              .c_str()),
              0);
    const ExrImage original = decodeExr(readBytes("aov.exr"), "aov.exr", kAovChannels);
    const ExrImage tiled = decodeExr(readBytes("tiled.exr"), "tiled.exr", kAovChannels);
    ASSERT_EQ(tiled.width, 3);
    ASSERT_EQ(tiled.height, 2);
    for (size_t c = 0; c < kAovChannels.size(); ++c)
        EXPECT_EQ(bits(tiled.channels[c].values), bits(original.channels[c].values))
            << kAovChannels[c];
    EXPECT_NE(readBytes("tiled.exr"), readBytes("aov.exr"));  // another file, the same pixels
}

TEST_F(ExrIo, BadFilesAreRefusedWithTheirName) {
    writeAovs(path("good.exr"), awkwardFrame(), awkwardHitPoints());
    const std::string good = readBytes("good.exr");

    EXPECT_EQ(errorOf([&] { decodeImage("not an exr at all", "junk.exr"); }),
              "junk.exr: not a readable OpenEXR file (no OpenEXR signature)");
    EXPECT_EQ(errorOf([&] { decodeImage("", "empty.exr"); }),
              "empty.exr: not a readable OpenEXR file (no OpenEXR signature)");
    // Cut at every eighth of its length: never an image, always a message.
    for (size_t cut = 4; cut < good.size(); cut += good.size() / 8) {
        const std::string message = errorOf([&] { decodeImage(good.substr(0, cut), "cut.exr"); });
        EXPECT_EQ(message.rfind("cut.exr: not a readable OpenEXR file (", 0), 0u)
            << cut << ": " << message;
    }
    // Garbage after a good header: the pixel data is unreadable.
    std::string garbled = good;
    for (size_t i = garbled.size() / 2; i < garbled.size(); ++i) garbled[i] = char(i * 37);
    EXPECT_EQ(errorOf([&] { decodeImage(garbled, "garbled.exr"); }).rfind("garbled.exr: ", 0), 0u);

    // A channel that is not there names the ones that are.
    writeImage(path("colour.exr"), Image{1, 1, 3, {0, 0, 0}});
    EXPECT_EQ(errorOf([&] { readIds(path("colour.exr")); }),
              path("colour.exr") + ": the OpenEXR file has no channel id (it has B, G, R)");
    writeBytes("depth.exr", encodeExr(ExrImage{1, 1, {{"Z", {1}}}}, "depth.exr"));
    EXPECT_EQ(errorOf([&] { readImage(path("depth.exr")); }),
              path("depth.exr") + ": the OpenEXR file has no channel R (it has Z)");
}

TEST_F(ExrIo, AHeaderAskingForTooManyPixelsIsRefusedBeforeReading) {
    std::string bytes = encodeExr(ExrImage{1, 1, {{"Y", {1}}}}, "one.exr");
    // The dataWindow attribute: name, type "box2i", size 16, then min x, y and max x, y.
    const std::string attribute("dataWindow\0box2i\0", 17);
    const size_t at = bytes.find(attribute);
    ASSERT_NE(at, std::string::npos);
    const auto withMaxCorner = [&](std::int32_t x, std::int32_t y) {
        std::string patched = bytes;
        std::memcpy(&patched[at + attribute.size() + 4 + 8], &x, 4);
        std::memcpy(&patched[at + attribute.size() + 4 + 12], &y, 4);
        return patched;
    };
    EXPECT_EQ(errorOf([&] { decodeImage(withMaxCorner(100000, 100000), "huge.exr"); }),
              "huge.exr: the image is 100001x100001, above vkray's limit of 67108864 pixels "
              "(65536 per side)");
    EXPECT_EQ(errorOf([&] { decodeImage(withMaxCorner(19999, 19999), "many.exr"); }),
              "many.exr: the image is 20000x20000, above vkray's limit of 67108864 pixels "
              "(65536 per side)");
    EXPECT_EQ(errorOf([&] { decodeImage(withMaxCorner(-1, 0), "empty.exr"); }),
              "empty.exr: not a readable OpenEXR file (its data window is empty)");
    // Channels enough to make OpenEXR's line buffers huge: refused from the header.
    ExrImage wide{5000, 1, {}};
    for (int c = 0; c < 210; ++c)
        wide.channels.push_back({"c" + std::to_string(c), std::vector<float>(5000)});
    EXPECT_EQ(
        errorOf([&] { decodeImage(encodeExr(wide, "wide.exr"), "wide.exr"); }),
        "wide.exr: the OpenEXR file has 210 channels of 5000 pixels a line, above vkray's limit "
        "of 256 channels and 1048576 values a line");
    ExrImage many{1, 1, {}};
    for (int c = 0; c < 257; ++c) many.channels.push_back({"c" + std::to_string(c), {0}});
    EXPECT_EQ(errorOf([&] {
                  decodeImage(encodeExr(many, "many.exr"), "many.exr");
              }).find("has 257 channels"),
              std::string("many.exr: the OpenEXR file ").size());
}

TEST_F(ExrIo, WritesNothingForImagesItCannotWrite) {
    EXPECT_EQ(errorOf([&] {
                  encodeExr(ExrImage{2, 1, {{"R", {1}}}}, "short.exr");
              }),
              "cannot write short.exr: channel R holds 1 values, the image 2 pixels");
    EXPECT_EQ(errorOf([&] {
                  encodeExr(ExrImage{1, 1, {{"R", {1}}, {"R", {2}}}}, "twice.exr");
              }),
              "cannot write twice.exr: two channels are named R");
    EXPECT_THROW(writeImage(path("empty.exr"), Image{}), Error);
    EXPECT_THROW(writeAovs(path("few.exr"), awkwardFrame(), {}), Error);  // no hit points
    EXPECT_TRUE(filesInDir().empty());
}

}  // namespace
}  // namespace vkray
