// The stress report's pictures: marks where a mode is wrong, the oracle's
// view, and their way between MPI ranks and into the report.
#include "numerics/stress_pictures.h"

#include "image/image_io.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vkray::numerics {
namespace {

OraclePixel oracleHit(int id, RVec normal = {0, 0, 1}, RVec direction = {0, 0, -1}) {
    OraclePixel o;
    o.hit.id = id;
    o.hit.t = id >= 0 ? 4 : std::numeric_limits<Real>::infinity();
    o.hit.normal = normal;
    o.direction = direction;
    return o;
}

StressSample sampleOf(int id) {
    StressSample s;
    s.t = id >= 0 ? 4.0 : std::numeric_limits<double>::infinity();
    s.normal = glm::dvec3(0, 0, 1);
    s.object = id;
    return s;
}

std::vector<float> pixel(const Image& image, size_t i) {
    return {image.pixels[i * 3], image.pixels[i * 3 + 1], image.pixels[i * 3 + 2]};
}

TEST(StressPictures, MarksFlipsWrongIdsAndAcneInTheirColours) {
    Frame frame(5, 1);
    for (glm::vec3& c : frame.color) c = {0.2f, 0.4f, 0.6f};
    frame.color[3] = {2, -1, std::nanf("")};  // shown clamped
    // A flip, a wrong id, an agreeing pixel with acne, both missing, one set aside.
    std::vector<OraclePixel> oracle{oracleHit(0), oracleHit(0), oracleHit(1), oracleHit(-1),
                                    oracleHit(0)};
    oracle[4].setAside[kFloat] = true;
    const std::vector<StressSample> samples{sampleOf(-1), sampleOf(1), sampleOf(1), sampleOf(-1),
                                            sampleOf(-1)};
    const ModePicture picture = markedPicture("robust", frame, oracle, samples, kFloat, {2});
    EXPECT_EQ(picture.mode, "robust");
    EXPECT_EQ(picture.flips, 1u);
    EXPECT_EQ(picture.wrongIds, 1u);
    EXPECT_EQ(picture.acne, 1u);
    const Image image = decodeImage(picture.png, "marked.png");
    ASSERT_EQ(image.width, 5);
    EXPECT_EQ(pixel(image, 0), (std::vector<float>{1, 0, 1}));  // flip: magenta
    EXPECT_EQ(pixel(image, 1), (std::vector<float>{1, 1, 0}));  // wrong id: yellow
    EXPECT_EQ(pixel(image, 2), (std::vector<float>{0, 1, 1}));  // acne: cyan
    EXPECT_EQ(pixel(image, 3), (std::vector<float>{1, 0, 0}));  // the image, clamped, NaN as 0
    EXPECT_EQ(pixel(image, 4), (std::vector<float>{51.0f / 255, 102.0f / 255,
                                                   153.0f / 255}));  // set aside: unmarked
}

// Wider than kStressPictureWidth: shrunk, every mark kept (the strongest of a block).
TEST(StressPictures, ShrunkPicturesKeepEveryMark) {
    Frame frame(330, 1);  // shrunk by 2 to 165
    for (size_t i = 0; i < frame.pixelCount(); ++i)
        frame.color[i] = i % 2 ? glm::vec3(1) : glm::vec3(0);
    std::vector<OraclePixel> oracle(frame.pixelCount(), oracleHit(0));
    std::vector<StressSample> samples(frame.pixelCount(), sampleOf(0));
    samples[1] = sampleOf(-1);  // a flip beside acne at pixel 0
    samples[3] = sampleOf(1);   // a wrong id
    const ModePicture picture = markedPicture("naive", frame, oracle, samples, kFloat, {0, 329});
    EXPECT_EQ(picture.flips, 1u);
    EXPECT_EQ(picture.wrongIds, 1u);
    EXPECT_EQ(picture.acne, 2u);
    const Image image = decodeImage(picture.png, "shrunk.png");
    ASSERT_EQ(image.width, 165);
    EXPECT_EQ(pixel(image, 0), (std::vector<float>{1, 0, 1}));  // the flip wins over acne
    EXPECT_EQ(pixel(image, 1), (std::vector<float>{1, 1, 0}));  // the wrong id
    EXPECT_EQ(pixel(image, 2),
              (std::vector<float>{128.0f / 255, 128.0f / 255, 128.0f / 255}));  // the mean
    EXPECT_EQ(pixel(image, 164), (std::vector<float>{0, 1, 1}));  // acne in the last pixel
    EXPECT_EQ(decodeImage(oraclePng(Scene{}, std::vector<OraclePixel>(330, oracleHit(-1)), 330, 1),
                          "o.png")
                  .width,
              165);
}

TEST(StressPictures, OracleViewShadesDiffuseByFacingOverTheBackground) {
    Scene scene;
    scene.background = {0.2, 0.4, 1.0};
    SceneObject object;
    object.material.diffuse = {0.8, 0.4, 0.2};
    scene.objects.push_back(object);
    // Facing the ray, then at 60 degrees to it (|n.d| = 1/2), then nothing.
    const Real s = sqrt(Real(3)) / 2;
    const std::vector<OraclePixel> oracle{oracleHit(0), oracleHit(0, {0, 0, 1}, {s, 0, Real(-0.5)}),
                                          oracleHit(-1)};
    const Image image = oraclePicture(scene, oracle, 3, 1);
    EXPECT_EQ(pixel(image, 0), (std::vector<float>{0.8f, 0.4f, 0.2f}));
    const double half = 0.25 + 0.75 * 0.5;
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(pixel(image, 1)[size_t(c)], object.material.diffuse[c] * half, 1e-6);
    EXPECT_EQ(pixel(image, 2), (std::vector<float>{0.2f, 0.4f, 1.0f}));
    EXPECT_THROW(oraclePicture(scene, oracle, 2, 1), Error);
}

TEST(StressPictures, TravelAsBytesAndBecomeAGalleryWithTheMarksLegend) {
    StressPicture picture{"tiny",
                          std::string("\x89PNG\0oracle", 11),
                          {{"naive", "n", 3, 2, 1}, {"robust", "r", 0, 0, 0}}};
    const StressPicture back = decodePicture(encodePicture(picture));
    EXPECT_EQ(back.caseName, "tiny");
    EXPECT_EQ(back.oraclePng, picture.oraclePng);
    ASSERT_EQ(back.modes.size(), 2u);
    EXPECT_EQ(back.modes[0].png, "n");
    EXPECT_EQ(back.modes[0].flips, 3u);
    EXPECT_EQ(back.modes[0].wrongIds, 2u);
    EXPECT_EQ(back.modes[0].acne, 1u);
    EXPECT_THROW(decodePicture(encodePicture(picture).substr(0, 20)), Error);

    Report report;
    addStressPictures(report, {picture, back});
    ASSERT_EQ(report.galleries.size(), 1u);
    const Gallery& gallery = report.galleries[0];
    ASSERT_EQ(gallery.legend.size(), 3u);
    EXPECT_EQ(gallery.legend[0].colour, "#ff00ff");
    EXPECT_EQ(gallery.legend[2].colour, "#00ffff");
    ASSERT_EQ(gallery.groups.size(), 2u);
    ASSERT_EQ(gallery.groups[0].figures.size(), 3u);
    EXPECT_EQ(gallery.groups[0].figures[0].caption, "oracle (long double)");
    EXPECT_EQ(gallery.groups[0].figures[1].caption, "naive: 3 flips, 2 wrong ids, 1 acne pixel");
    EXPECT_EQ(gallery.groups[0].figures[2].caption, "robust: 0 flips, 0 wrong ids, 0 acne pixels");
}

}  // namespace
}  // namespace vkray::numerics
