// The stress-output variant (shaders/stress_output.glsl): what the mode's own
// shader found for a pixel's primary ray and the secondary rays of its hit,
// on rays whose answers are known in closed form.
#include "support/gpu_fixture.h"

#include "scene/sdl_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace vkray {
namespace {

struct OnePixel {
    StressSample sample;
    Frame frame;
};

// The centre pixel of a 1x1 image looking from `eye` down -z.
OnePixel centrePixel(const std::string& sdl, Precision precision, double eyeZ) {
    const Scene scene = parseSdl(sdl, "t.sdl", {});
    Camera camera;
    camera.eye = {0, 0, eyeZ};
    camera.look = {0, 0, 0};
    camera.up = {0, 1, 0};
    gpu::GpuTracer tracer(test::gpuContext(),
                          {.shaderDirectory = test::kShaderDir, .precision = precision});
    std::vector<StressSample> samples;
    OnePixel pixel;
    pixel.frame =
        tracer.renderStressOutput(scene, makeCameraBasis(camera, 1, 1), {1, 1, 1}, samples);
    EXPECT_EQ(samples.size(), 1u);
    pixel.sample = samples.at(0);
    return pixel;
}

// A unit sphere seen from (0, 0, 5.1): t = 4.1 at (0, 0, 1), normal +z. 4.1 is
// no float: fp64's t must be the double nearest it, robust's the float.
const char* kSphere = "light 0 0 10 1 1 1\nsphere\n";

TEST(StressOutput, TAndTheNormalAsEachModeComputesThem) {
    for (Precision precision : kAllPrecisions) {
        SCOPED_TRACE(precisionName(precision));
        const OnePixel p = centrePixel(kSphere, precision, 5.1);
        const StressSample& s = p.sample;
        EXPECT_EQ(s.object, 0);
        EXPECT_EQ(s.inDouble, precision == Precision::Fp64);
        if (precision == Precision::Fp64) {
            EXPECT_NEAR(s.t, 4.1, 4 * 0x1p-52 * 4.1);
            EXPECT_NE(s.t, double(float(s.t)));  // not a float
        } else {
            EXPECT_EQ(s.t, double(float(s.t)));
            EXPECT_NEAR(s.t, 4.1, 4 * 0x1p-23 * 4.1);
        }
        EXPECT_NEAR(s.normal.z, 1, 1e-7);
        // The same t as the frame's depth, to float.
        EXPECT_EQ(float(s.t), p.frame.depth[0]);
    }
}

TEST(StressOutput, AMissHasNoHitAndNoFeelers) {
    const StressSample s =
        centrePixel("light 0 0 10 1 1 1\npush translate 5 0 0 sphere pop\n", Precision::Robust, 5)
            .sample;
    EXPECT_EQ(s.object, -1);
    EXPECT_TRUE(std::isinf(s.t));
    EXPECT_EQ(s.feelersTraced, 0u);
}

TEST(StressOutput, FeelersVerdictsAndTheObjectTheyLeft) {
    // Light 0 above the hit (0, 0, 1), to one side: its feeler is clear. Light 1
    // at (0, 0, -10), behind the surface: no feeler. Light 2 above, behind a
    // small sphere at (0, 0, 3): its feeler meets that sphere, not the one it left.
    const char* scene =
        "light 5 0 10 1 1 1 light 0 0 -10 1 1 1 light 0 0.2 20 1 1 1\n"
        "sphere\npush translate 0 0.1 3 scale 0.5 0.5 0.5 sphere pop\n";
    for (Precision precision : kAllPrecisions) {
        SCOPED_TRACE(precisionName(precision));
        const StressSample s = centrePixel(scene, precision, 1.5).sample;
        ASSERT_EQ(s.object, 0);
        EXPECT_EQ(s.feelersTraced, 0b101u);
        EXPECT_EQ(s.feelersMet, 0b100u);
        EXPECT_EQ(s.feelersMetLeft, 0u);
    }
}

TEST(StressOutput, RefractedRayLeavesThroughTheFarSide) {
    // A glass sphere head-on: the refracted ray goes straight through and
    // leaves at (0, 0, -1), -6.1 from the eye along z: 2 from the entry,
    // less the secondary-ray offset it starts at (1e-4 in naive mode).
    const char* scene = "transparency 0.9 speedOfLight 0.667 sphere\n";
    for (Precision precision : kAllPrecisions) {
        SCOPED_TRACE(precisionName(precision));
        const StressSample s = centrePixel(scene, precision, 5.1).sample;
        ASSERT_TRUE(s.refractedTraced);
        EXPECT_EQ(s.refractedObject, 0);
        EXPECT_NEAR(s.refractedT, 2, 2e-4);
        EXPECT_NEAR(s.refractedPoint.z, -6.1, 1e-5);
    }
}

TEST(StressOutput, WithoutTheOffsetAFeelerMeetsTheSurfaceItLeaves) {
    // A sphere of radius 1000 at 3.5e4 from the origin, seen from 30 above,
    // lit from above (the stress case acne_large_sphere): starting on the
    // surface (VKRAY_FAULT=no-offset), the feeler of 43 of the 192 pixels
    // meets it again at once; with the offset, none.
    const char* scene =
        "light 20500 33000 10500 1 1 1\n"
        "push translate 20000.3 29000 10000.7 scale 1000 1000 1000 sphere pop\n";
    const Scene parsed = parseSdl(scene, "t.sdl", {});
    Camera camera;
    camera.eye = {20000, 30030, 10060};
    camera.look = {20000, 30000, 10000};
    camera.up = {0, 1, 0};
    const CameraBasis basis = makeCameraBasis(camera, 16, 12);
    const auto selfHits = [&] {
        gpu::GpuTracer tracer(test::gpuContext(), {.shaderDirectory = test::kShaderDir});
        std::vector<StressSample> samples;
        tracer.renderStressOutput(parsed, basis, {16, 12, 1}, samples);
        int count = 0;
        for (const StressSample& s : samples) count += s.feelersMetLeft != 0;
        return count;
    };
    EXPECT_EQ(selfHits(), 0);
    setenv("VKRAY_FAULT", "no-offset", 1);
    const int faulted = selfHits();
    unsetenv("VKRAY_FAULT");
    EXPECT_GT(faulted, 16 * 12 / 8);
}

}  // namespace
}  // namespace vkray
