#include "image/image_io.h"
#include "image/aov_images.h"
#include "image/stb_codecs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "support/temp_folder.h"
#include "util/error.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;

constexpr float kInf = std::numeric_limits<float>::infinity();

// Each test gets its own empty folder, removed afterwards.
class ImageIo : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return (dir / name).string(); }

    std::vector<std::string> filesInDir() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir))
            names.push_back(entry.path().filename().string());
        return names;
    }

    std::string readBytes(const std::string& name) const {
        std::ifstream in(path(name), std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }

    void writeBytes(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
    }

    test::TempFolder scratch_{"vkray-image-io"};
    const fs::path dir = scratch_.path();
};

// The message of the Error `f` throws; fails the test when it throws none.
template <typename F>
std::string errorOf(F f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no Error thrown";
    return "";
}

std::string bigEndian(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    return {char(bits >> 24), char(bits >> 16), char(bits >> 8), char(bits)};
}

std::string littleEndian(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    return {char(bits), char(bits >> 8), char(bits >> 16), char(bits >> 24)};
}

TEST_F(ImageIo, PngRoundTripRoundsAndClamps) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Image image{3, 1, 3, {0.5f, 2.0f, -1.0f, 0.25f, 1.0f, 0.0f, nan, kInf, 0.8f}};
    writeImage(path("a.png"), image);
    const Image back = readImage(path("a.png"));
    ASSERT_EQ(back.width, 3);
    ASSERT_EQ(back.height, 1);
    ASSERT_EQ(back.channels, 3);
    const std::vector<float> expected = {128 / 255.f, 1, 0,             // 0.5 rounds up; clamped
                                         64 / 255.f,  1, 0,             // 0.25 * 255 = 63.75
                                         0,           1, 204 / 255.f};  // NaN -> 0, +inf -> 1
    for (size_t i = 0; i < expected.size(); ++i)
        EXPECT_FLOAT_EQ(back.pixels[i], expected[i]) << "value " << i;
    EXPECT_NEAR(back.pixels[0], 0.5f, 1 / 255.f);
}

// A frame's colours staged straight to PNG bytes are the file that the
// float copy gives, and every other format still goes through that copy.
TEST_F(ImageIo, ColoursStagedFromTheFrameAreTheImagesFile) {
    Frame frame(5, 3);
    for (size_t i = 0; i < frame.pixelCount(); ++i)
        frame.color[i] = {0.1f * float(i), -0.5f + 0.2f * float(i), i == 7 ? kInf : 0.3f};
    for (const char* name : {"a.png", "a.pfm", "a.exr"}) {
        writeImage(path(std::string("copy-") + name), colorImage(frame));
        StagedFiles files;
        stageColor(files, path(name), frame);
        files.commit();
        std::ifstream a(path(std::string("copy-") + name), std::ios::binary),
            b(path(name), std::ios::binary);
        const std::string copied{std::istreambuf_iterator<char>(a), {}},
            direct{std::istreambuf_iterator<char>(b), {}};
        EXPECT_FALSE(direct.empty()) << name;
        EXPECT_EQ(direct, copied) << name;
    }
}

TEST_F(ImageIo, PngExtensionIsCaseInsensitiveAndTopRowStaysOnTop) {
    Image image{2, 2, 3, std::vector<float>(12, 0)};
    image.pixels[0] = 1;  // red marker at the top-left pixel
    writeImage(path("A.PNG"), image);
    const Image back = readImage(path("A.PNG"));
    EXPECT_EQ(back.pixels, image.pixels);
}

TEST_F(ImageIo, GreyPngReadsBackAsThreeChannels) {
    writeImage(path("g.png"), Image{2, 1, 1, {0, 1}});
    const Image back = readImage(path("g.png"));
    EXPECT_EQ(back.channels, 3);
    EXPECT_EQ(back.pixels, (std::vector<float>{0, 0, 0, 1, 1, 1}));
}

TEST_F(ImageIo, CorruptPngIsAnErrorNamingThePath) {
    writeBytes("bad.png", "not a png at all");
    EXPECT_NE(errorOf([&] { readImage(path("bad.png")); }).find(path("bad.png")),
              std::string::npos);
    writeBytes("empty.png", "");
    EXPECT_THROW(readImage(path("empty.png")), Error);
}

TEST_F(ImageIo, PfmRoundTripIsExact) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // Infinities, a NaN, a denormal, -0 and awkward decimals: every bit must survive.
    const std::vector<float> values = {0.1f, -2.5f, 1e30f, kInf,  -kInf,      1e-42f,
                                       0,    -0.0f, 1,     3.25f, 7,          8,
                                       0.3f, 0.6f,  0.9f,  nan,   12345.678f, -1};
    const Image color{2, 3, 3, values};
    writeImage(path("c.pfm"), color);
    const Image back = readImage(path("c.pfm"));
    ASSERT_EQ(back.width, 2);
    ASSERT_EQ(back.height, 3);
    ASSERT_EQ(back.channels, 3);
    ASSERT_EQ(back.pixels.size(), color.pixels.size());
    for (size_t i = 0; i < color.pixels.size(); ++i) {
        if (std::isnan(color.pixels[i]))
            EXPECT_TRUE(std::isnan(back.pixels[i])) << "value " << i;
        else
            EXPECT_EQ(back.pixels[i], color.pixels[i]) << "value " << i;
    }
    EXPECT_TRUE(std::signbit(back.pixels[7]));  // -0 stays -0

    const Image ids{3, 1, 1, {-1, 0, 41}};
    writeImage(path("ids.PFM"), ids);
    const Image idsBack = readImage(path("ids.PFM"));
    EXPECT_EQ(idsBack.channels, 1);
    EXPECT_EQ(idsBack.pixels, ids.pixels);
}

TEST_F(ImageIo, PfmStoresRowsBottomToTopAndReadsThemBackTopDown) {
    // 2x2 grey image; the top-left pixel is the marker.
    const Image image{2, 2, 1, {9, 1, 2, 3}};
    writeImage(path("rows.pfm"), image);
    const std::string header = "Pf\n2 2\n-1.0\n";
    const std::string expected = header + littleEndian(2) + littleEndian(3) +  // bottom row
                                 littleEndian(9) + littleEndian(1);            // top row
    EXPECT_EQ(readBytes("rows.pfm"), expected);
    EXPECT_EQ(readImage(path("rows.pfm")).pixels, image.pixels);

    const Image color{1, 2, 3, {1, 2, 3, 4, 5, 6}};
    writeImage(path("rows3.pfm"), color);
    EXPECT_EQ(readBytes("rows3.pfm"), "PF\n1 2\n-1.0\n" + littleEndian(4) + littleEndian(5) +
                                          littleEndian(6) + littleEndian(1) + littleEndian(2) +
                                          littleEndian(3));
}

TEST_F(ImageIo, PfmReadsBigEndianAndFreeWhitespaceInTheHeader) {
    // Positive scale: big-endian. Header tokens on one line, extra blanks between them.
    writeBytes("be.pfm", "Pf  2\t 2\n\n 1.0\n" + bigEndian(3) + bigEndian(4) + bigEndian(-1) +
                             bigEndian(kInf));
    const Image be = readImage(path("be.pfm"));
    EXPECT_EQ(be.width, 2);
    EXPECT_EQ(be.height, 2);
    EXPECT_EQ(be.channels, 1);
    EXPECT_EQ(be.pixels, (std::vector<float>{-1, kInf, 3, 4}));

    // A scale other than -1 is accepted; the values are not rescaled.
    writeBytes("le.pfm",
               "PF\r\n1 1\r\n-4.0\n" + littleEndian(0.5f) + littleEndian(1) + littleEndian(2));
    EXPECT_EQ(readImage(path("le.pfm")).pixels, (std::vector<float>{0.5f, 1, 2}));
}

TEST_F(ImageIo, MalformedPfmIsAnErrorSayingWhatIsWrong) {
    const std::string data16 = std::string(16, '\0');
    struct Case {
        const char* name;
        std::string bytes;
        const char* expected;  // part of the message
    };
    const std::vector<Case> cases = {
        {"trunc.pfm", "Pf\n2 2\n-1.0\n" + std::string(15, '\0'), "truncated"},
        {"trail.pfm", "Pf\n2 2\n-1.0\n" + std::string(17, '\0'), "trailing"},
        {"magic.pfm", "P6\n2 2\n-1.0\n" + data16, "'PF'"},
        {"huge.pfm", "PF\n999999999 999999999\n-1.0\n" + data16, "outside"},
        {"zero.pfm", "Pf\n0 2\n-1.0\n" + data16, "outside"},
        {"neg.pfm", "Pf\n-2 2\n-1.0\n" + data16, "outside"},
        {"word.pfm", "Pf\n2 two\n-1.0\n" + data16, "height"},
        {"scale0.pfm", "Pf\n2 2\n0\n" + data16, "scale"},
        {"noscale.pfm", "Pf\n2 2", "header"},
        {"empty.pfm", "", "header"},
    };
    for (const Case& c : cases) {
        writeBytes(c.name, c.bytes);
        const std::string message = errorOf([&] { readImage(path(c.name)); });
        EXPECT_NE(message.find(path(c.name)), std::string::npos) << message;
        EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    }
}

TEST_F(ImageIo, MissingFileIsAnError) {
    const std::string message = errorOf([&] { readImage(path("nope.pfm")); });
    EXPECT_EQ(message, "cannot read " + path("nope.pfm") + ": No such file or directory");
    EXPECT_EQ(errorOf([&] { readImage(dir.string() + "/sub.png"); }).find("cannot read"), 0u);
}

TEST_F(ImageIo, ReadingADirectoryIsAnError) {
    fs::create_directory(dir / "d.png");
    EXPECT_EQ(errorOf([&] { readImage(path("d.png")); }),
              "cannot read " + path("d.png") + ": Is a directory");
}

TEST_F(ImageIo, UnknownExtensionIsAnErrorAndCreatesNothing) {
    const Image image{1, 1, 3, {0, 0, 0}};
    EXPECT_EQ(errorOf([&] { writeImage(path("x.jpg"), image); }),
              path("x.jpg") + ": unsupported image format '.jpg' (use .png, .pfm or .exr)");
    EXPECT_THROW(writeImage(path("noext"), image), Error);
    EXPECT_THROW(readImage(path("x.tif")), Error);
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(ImageIo, ImageWithBadShapeIsAnErrorAndCreatesNothing) {
    EXPECT_THROW(writeImage(path("two.pfm"), Image{1, 1, 2, {0, 0}}), Error);
    EXPECT_THROW(writeImage(path("short.png"), Image{2, 2, 3, {0, 0, 0}}), Error);
    EXPECT_THROW(writeImage(path("empty.png"), Image{}), Error);
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(ImageIo, WriteIntoMissingFolderIsAnErrorAndLeavesNothing) {
    const std::string target = path("no/such/dir/out.png");
    const std::string message = errorOf([&] { writeImage(target, Image{1, 1, 3, {0, 0, 0}}); });
    EXPECT_EQ(message, "cannot write " + target + ": No such file or directory");
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(ImageIo, FailedRenameLeavesTheDestinationAndNoTemporaryFile) {
    // The destination is a directory: the temporary is written, the rename fails.
    fs::create_directory(dir / "taken.pfm");
    fs::create_directory(dir / "taken.pfm" / "inside");
    const std::string message = errorOf([&] {
        writeImage(path("taken.pfm"), Image{1, 1, 1, {5}});
    });
    EXPECT_EQ(message.find("cannot write " + path("taken.pfm") + ": "), 0u) << message;
    EXPECT_EQ(filesInDir(), std::vector<std::string>{"taken.pfm"});
    EXPECT_TRUE(fs::is_directory(dir / "taken.pfm" / "inside"));
}

TEST_F(ImageIo, WriteAovsWritesDepthNormalAndIds) {
    Frame frame(2, 1);
    frame.depth = {2.5f, kInf};
    frame.normal = {{0, 0, 1}, {0, 0, 0}};
    frame.id = {3, -1};
    writeAovs(path("aov"), frame, {});
    EXPECT_EQ(filesInDir().size(), 3u);

    const Image depth = readImage(path("aov.depth.pfm"));
    EXPECT_EQ(depth.channels, 1);
    EXPECT_EQ(depth.pixels, (std::vector<float>{2.5f, kInf}));
    const Image normal = readImage(path("aov.normal.pfm"));
    EXPECT_EQ(normal.channels, 3);
    EXPECT_EQ(normal.pixels, (std::vector<float>{0, 0, 1, 0, 0, 0}));
    const Image ids = readImage(path("aov.id.pfm"));
    EXPECT_EQ(ids.channels, 1);
    EXPECT_EQ(ids.pixels, (std::vector<float>{3, -1}));
}

TEST(PngByte, RoundsClampsAndReadsBackEveryByte) {
    EXPECT_EQ(pngByte(-1.0f), 0);
    EXPECT_EQ(pngByte(2.0f), 255);
    EXPECT_EQ(pngByte(std::nanf("")), 0);
    EXPECT_EQ(pngByte(0.5f / 255), 1);  // half rounds up
    EXPECT_EQ(pngByte(std::nextafter(0.5f / 255, 0.0f)), 0);
    // The view's screenshot holds byte b as b / 255: each reads back as b.
    for (int b = 0; b < 256; ++b) EXPECT_EQ(pngByte(float(b) / 255.0f), b) << b;
}

}  // namespace
}  // namespace vkray
