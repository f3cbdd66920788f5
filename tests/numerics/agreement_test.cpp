// The margin rule: a difference the bound explains is set aside and
// counted; any other fails, on one pixel as on many.
#include "numerics/agreement.h"

#include "reference/reference_tracer.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>

#include <string>

namespace vkray {
namespace {

Scene sceneOf(const std::string& text) {
    Scene scene = parseSdl(text, "agreement.sdl", {});
    loadSceneGeometry(scene, false, nullptr);
    return scene;
}

// A checkered sphere and a cube on a lit floor, seen from about 12.
const char* const kScene =
    "light 5 8 6 1 1 1\n"
    "background 0.1 0.1 0.2\n"
    "push rotate -90 1 0 0 diffuse 0.5 0.5 0.5 plane pop\n"
    "push translate 0 1 0 diffuse 0.8 0.3 0.2 texture 1 parameters 4 0.25 1 1 1 sphere pop\n"
    "push translate 2.5 0.7 0 rotate 30 0 1 0 scale 0.7 0.7 0.7 diffuse 0.2 0.7 0.3 cube pop\n";

struct Renders {
    Scene scene;
    RenderSettings settings{96, 72, 1};
    CameraBasis camera;
    Frame cpu;
};

Renders renders(const glm::dvec3& eye) {
    Renders r;
    r.scene = sceneOf(kScene);
    r.camera = makeCameraBasis(Camera{eye, {0.8, 0.8, 0}, {0, 1, 0}, 40, {}}, r.settings.width,
                               r.settings.height);
    r.cpu = reference::render(r.scene, r.camera, r.settings);
    return r;
}

const glm::dvec3 kEye{4, 5, 11};

TEST(Agreement, TheSameFramesAgreeWithNothingSetAside) {
    const Renders r = renders(kEye);
    const Agreement a =
        judgeAgreement(r.scene, r.camera, r.settings, Precision::Robust, r.cpu, r.cpu, {});
    EXPECT_TRUE(a.passed);
    EXPECT_EQ(a.differing, 0u);
    EXPECT_EQ(a.setAside, 0u);
    EXPECT_EQ(a.pixels, 96u * 72u);
}

TEST(Agreement, OneWrongPixelInsideAnObjectFails) {
    const Renders r = renders(kEye);
    Frame gpu = r.cpu;
    // The middle of the image is on the sphere, away from any edge.
    const std::size_t i = gpu.index(48, 36);
    ASSERT_EQ(gpu.id[i], 1);
    gpu.color[i] += glm::vec3(0.03f, 0, 0);
    const Agreement a =
        judgeAgreement(r.scene, r.camera, r.settings, Precision::Robust, gpu, r.cpu, {});
    EXPECT_FALSE(a.passed);
    EXPECT_EQ(a.differing, 1u);
    EXPECT_EQ(a.unexplained, 1u);
    ASSERT_EQ(a.firstUnexplained.size(), 1u);
    EXPECT_EQ(a.firstUnexplained[0], std::make_pair(48, 36));
    EXPECT_EQ(a.verdicts[i], PixelVerdict::Unexplained);
    // A wrong depth or normal there fails alike; so does a wrong id.
    for (int what = 0; what < 3; ++what) {
        Frame wrong = r.cpu;
        if (what == 0) wrong.depth[i] *= 1.001f;
        if (what == 1) wrong.normal[i] = -wrong.normal[i];
        if (what == 2) wrong.id[i] = 2;
        EXPECT_EQ(judgeAgreement(r.scene, r.camera, r.settings, Precision::Robust, wrong, r.cpu, {})
                      .unexplained,
                  1u)
            << what;
    }
}

TEST(Agreement, ColoursAreComparedUnclamped) {
    // Above white, 0.03 of 1.5 is 2 % (within the threshold, relative there);
    // 0.1 of 1.5 is not.
    Renders r = renders(kEye);
    const std::size_t i = r.cpu.index(48, 36);
    r.cpu.color[i] = glm::vec3(1.5f);
    Frame gpu = r.cpu;
    gpu.color[i] = glm::vec3(1.53f);
    EXPECT_EQ(
        judgeAgreement(r.scene, r.camera, r.settings, Precision::Robust, gpu, r.cpu, {}).differing,
        0u);
    gpu.color[i] = glm::vec3(1.6f);
    EXPECT_EQ(
        judgeAgreement(r.scene, r.camera, r.settings, Precision::Robust, gpu, r.cpu, {}).differing,
        1u);
}

TEST(Agreement, AnEyeMovedWithinTheBoundIsExplainedAndOneMovedBeyondItIsNot) {
    // The "GPU" is the reference itself from an eye moved by 2^-20 of its
    // distance (within robust's 2^-18): every pixel that changes is one a
    // decision within the bound turns, and is set aside. Moved by 1e-3 of
    // its distance, silhouettes and cell borders move beyond the bound: the
    // pixels they cross are unexplained.
    const Renders r = renders(kEye);
    const double distance = glm::length(kEye - glm::dvec3(0.8, 0.8, 0));
    const glm::dvec3 across = glm::normalize(glm::dvec3(1, -1, 0));
    for (const double shift : {0x1p-20, 1e-3}) {
        const Renders moved = renders(kEye + shift * distance * across);
        const Agreement a =
            judgeAgreement(r.scene, r.camera, r.settings, Precision::Robust, moved.cpu, r.cpu, {});
        if (shift < 1e-4) {
            EXPECT_EQ(a.unexplained, 0u);
            EXPECT_EQ(a.setAside, a.differing);
        } else {
            EXPECT_GT(a.unexplained, 10u);
        }
    }
}

}  // namespace
}  // namespace vkray
