// Anti-aliasing in the CPU reference: spp jittered samples per pixel, the
// mean colour, the AOVs of sample 0, and the same image for the same seed.
#include "reference/reference_tracer.h"

#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"
#include "util/error.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace vkray::reference {
namespace {

// A white emissive square on black, seen straight on: its edges cut pixels.
// Plus a mirror and a glass ball, so samples also take secondary rays.
Scene edgeScene() {
    Scene scene = parseSdl(
        "background 0 0 0 ambient 0 0 0 diffuse 0 0 0 emissive 1 1 1 "
        "push scale 1.03 0.71 1 square pop\n"
        "emissive 0 0 0 reflectivity 0.8 translate 0 0 -1 scale 3 3 1 plane\n"
        "reflectivity 0 transparency 0.9 speedOfLight 0.7 translate 0.9 0.6 1 "
        "scale 0.3 0.3 0.3 sphere\n"
        "camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 40",
        "aa.sdl", {});
    loadSceneGeometry(scene, false, nullptr);
    return scene;
}

RenderSettings settings(int spp, std::uint32_t seed) {
    RenderSettings s;
    s.width = 24;
    s.height = 18;
    s.spp = spp;
    s.seed = seed;
    return s;
}

Frame renderWith(const Scene& scene, const RenderSettings& s, int threads = 2) {
    return render(scene, makeCameraBasis(*scene.camera, s.width, s.height), s,
                  ReferenceOptions{threads});
}

bool sameBytes(const Frame& a, const Frame& b) {
    return a.color.size() == b.color.size() &&
           std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof a.color[0]) == 0 &&
           std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof a.depth[0]) == 0 &&
           std::memcmp(a.normal.data(), b.normal.data(), a.normal.size() * sizeof a.normal[0]) ==
               0 &&
           a.id == b.id;
}

TEST(AntiAliasing, SameSeedSameBytesDifferentSeedDifferentImage) {
    const Scene scene = edgeScene();
    const Frame first = renderWith(scene, settings(4, 7), 1);
    EXPECT_TRUE(sameBytes(first, renderWith(scene, settings(4, 7), 1)));
    EXPECT_TRUE(sameBytes(first, renderWith(scene, settings(4, 7), 3)));  // any thread count
    const Frame other = renderWith(scene, settings(4, 8));
    EXPECT_NE(first.color, other.color);
    EXPECT_FALSE(sameBytes(first, renderWith(scene, settings(1, 7))));
}

TEST(AntiAliasing, EdgePixelsAverageTheirSamples) {
    // The square is white (emissive 1, nothing else reaches it at full weight),
    // so a pixel that its edge cuts holds k/16 for the k samples on it.
    const Scene scene = edgeScene();
    const Frame frame = renderWith(scene, settings(16, 3));
    const Frame sharp = renderWith(scene, settings(1, 3));
    int partial = 0;
    for (int y = 0; y < frame.height; ++y) {
        for (int x = 0; x < frame.width; ++x) {
            const size_t i = frame.index(x, y);
            if (sharp.id[i] != 0 || frame.id[i] != 0) continue;
            const double red = frame.color[i].r;
            if (red < 1) {
                ++partial;
                EXPECT_GT(red, 0) << x << "," << y;
            }
        }
    }
    EXPECT_GT(partial, 0);  // the edges are smoothed somewhere
}

TEST(AntiAliasing, AovsComeFromSampleZero) {
    const Scene scene = edgeScene();
    const RenderSettings s = settings(9, 5);
    const Frame frame = renderWith(scene, s);
    const CameraBasis camera = makeCameraBasis(*scene.camera, s.width, s.height);
    for (const auto& [x, y] : {std::pair{3, 4}, std::pair{12, 9}, std::pair{20, 15}}) {
        const PixelTrace trace = tracePixel(scene, camera, s, x, y);  // sample 0's ray
        const size_t i = frame.index(x, y);
        EXPECT_EQ(frame.id[i], trace.hitObject) << x << "," << y;
        EXPECT_EQ(frame.depth[i], float(trace.t)) << x << "," << y;
        const PixelSample sample = jitteredSample(x, y, s, 0);
        EXPECT_NE(sample.px, x + 0.5);  // not the centre: the sample really moved
    }
}

TEST(AntiAliasing, OneSampleIsThePixelCentreAsBefore) {
    // spp 1 ignores the seed: the ray through the pixel centre.
    const Scene scene = edgeScene();
    EXPECT_TRUE(sameBytes(renderWith(scene, settings(1, 0)), renderWith(scene, settings(1, 99))));
}

TEST(AntiAliasing, RefusesSampleCountsOutsideTheRange) {
    const Scene scene = edgeScene();
    for (const int spp : {0, -1, kMaxSpp + 1}) {
        try {
            renderWith(scene, settings(spp, 0));
            ADD_FAILURE() << "spp " << spp << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("samples per pixel must be 1..4096"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(AntiAliasing, SamplesTracedOneAtATimeAverageToTheWhole) {
    // `vkray view` traces the samples one a pass: sample k alone is the k-th
    // term of the whole render's mean, and only sample 0 gives AOVs. (In
    // double the sum of the parts need not be the very bits of the whole: a
    // bound of a few ulps of a colour in [0, 1].)
    const Scene scene = edgeScene();
    const Frame whole = renderWith(scene, settings(5, 3));
    std::vector<glm::dvec3> sum(whole.pixelCount(), glm::dvec3(0));
    for (int k = 0; k < 5; ++k) {
        RenderSettings one = settings(5, 3);
        one.firstSample = k;
        one.sampleCount = 1;
        const Frame part = renderWith(scene, one);
        for (size_t i = 0; i < part.pixelCount(); ++i) {
            sum[i] += glm::dvec3(part.color[i]);
            if (k > 0) {
                ASSERT_EQ(part.id[i], -1) << "sample " << k << " gave AOVs";
                ASSERT_EQ(part.depth[i], 0.0f);
            } else {
                ASSERT_EQ(part.id[i], whole.id[i]);
                ASSERT_EQ(part.depth[i], whole.depth[i]);
            }
        }
    }
    for (size_t i = 0; i < whole.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(sum[i][c] / 5, whole.color[i][c], 1e-6 * std::max(1.0f, whole.color[i][c]))
                << i;
}

TEST(AntiAliasing, RefusesSamplesBeyondThePixels) {
    const Scene scene = edgeScene();
    RenderSettings beyond = settings(4, 0);
    beyond.firstSample = 3;
    beyond.sampleCount = 2;  // samples 3 and 4 of 0 .. 3
    try {
        renderWith(scene, beyond);
        ADD_FAILURE() << "samples 3 .. 4 of 4 were accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("samples 3 .. 4 are not among the pixel's 4"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace vkray::reference
