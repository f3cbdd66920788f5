// `vkray pixel`'s two sides: the GPU's debug-pixel variant and the CPU
// reference trace the same ray and record the same steps.
#include "support/gpu_fixture.h"

#include "reference/reference_tracer.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vkray {
namespace {

PixelTrace gpuTrace(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
                    int x, int y) {
    gpu::GpuTracer tracer(test::gpuContext(), {.shaderDirectory = test::kShaderDir});
    return tracer.tracePixel(scene, camera, settings, x, y);
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(PixelTrace, BothSidesRecordTheSameStepsOnAnAnalyticRay) {
    // Eye (0, 0, 5) looking down -z at a unit sphere moved to (0, 0, -2) and a
    // plane z = 0 moved to z = -10: the centre ray meets the sphere at t = 6.
    const Scene scene = parseSdl(
        "camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 60\n"
        "light 0 0 10 1 1 1 light 0 10 0 0.5 0.5 0.5\n"
        "push translate 0 0 -10 plane pop\n"
        "diffuse 0.5 0.25 0.125 emissive 0.1 0 0\n"
        "push translate 0 0 -2 sphere pop\n",
        "t.sdl", {});
    const RenderSettings settings{5, 5, 1};
    const CameraBasis camera = makeCameraBasis(*scene.camera, 5, 5);
    const PixelTrace gpu = gpuTrace(scene, camera, settings, 2, 2);
    const PixelTrace cpu = reference::tracePixel(scene, camera, settings, 2, 2);

    for (const PixelTrace* trace : {&gpu, &cpu}) {
        ASSERT_EQ(trace->objects.size(), 2u);
        ASSERT_EQ(trace->lights.size(), 2u);
        EXPECT_EQ(trace->hitObject, 1);
        EXPECT_NEAR(trace->t, 6.0, 1e-6);
        expectNear(trace->point, {0, 0, -1}, 1e-6);
        expectNear(trace->normal, {0, 0, 1}, 1e-6);
        // Each object on its own: the plane at t = 15, the sphere at t = 6.
        ASSERT_TRUE(trace->objects[0].t && trace->objects[1].t);
        EXPECT_NEAR(*trace->objects[0].t, 15.0, 1e-5);
        EXPECT_NEAR(*trace->objects[1].t, 6.0, 1e-6);
        // The sphere's generic ray starts at (0, 0, 7).
        expectNear(trace->objects[1].genericOrigin, {0, 0, 7}, 1e-6);
        expectNear(trace->emissive, {0.1, 0, 0}, 1e-7);
        // Light 0 straight above the hit: m.s = 1, diffuse = the material's.
        EXPECT_NEAR(trace->lights[0].mDotS, 1.0, 1e-6);
        expectNear(trace->lights[0].diffuse, {0.5, 0.25, 0.125}, 1e-6);
    }
    expectNear(gpu.color, cpu.color, 1e-5);
    expectNear(gpu.lights[1].diffuse, cpu.lights[1].diffuse, 1e-5);
    EXPECT_NEAR(gpu.lights[1].mDotH, cpu.lights[1].mDotH, 1e-5);
}

TEST(PixelTrace, TAndTheNormalAtTheModesPrecisionAndEachFeelersVerdict) {
    // From (0, 0, 5.1) the unit sphere is hit at t = 4.1 (no float). Light 0
    // is clear, light 1 behind the small sphere at (0, 1.5, 3).
    const Scene scene = parseSdl(
        "camera eye 0 0 5.1 look 0 0 0 up 0 1 0 fov 60\n"
        "light 5 0 10 1 1 1 light 0 3 5 1 1 1\n"
        "sphere push translate 0 1.5 3 scale 0.5 0.5 0.5 sphere pop\n",
        "t.sdl", {});
    const RenderSettings settings{5, 5, 1};
    const CameraBasis camera = makeCameraBasis(*scene.camera, 5, 5);
    for (Precision precision : {Precision::Robust, Precision::Fp64}) {
        SCOPED_TRACE(precisionName(precision));
        gpu::GpuTracer tracer(test::gpuContext(),
                              {.shaderDirectory = test::kShaderDir, .precision = precision});
        const PixelTrace gpu = tracer.tracePixel(scene, camera, settings, 2, 2);
        const bool fp64 = precision == Precision::Fp64;
        EXPECT_EQ(gpu.digits, 9);
        EXPECT_EQ(gpu.geometryDigits, fp64 ? 17 : 9);
        EXPECT_NEAR(gpu.t, 4.1, fp64 ? 1e-15 : 1e-6);
        EXPECT_EQ(gpu.t == double(float(gpu.t)), !fp64);
        ASSERT_EQ(gpu.lights.size(), 2u);
        EXPECT_EQ(gpu.lights[0].feelerMet, std::optional<bool>(false));
        EXPECT_EQ(gpu.lights[1].feelerMet, std::optional<bool>(true));
        EXPECT_EQ(gpu.lights[1].feelerMetLeft, std::optional<bool>(false));
    }
    const PixelTrace cpu = reference::tracePixel(scene, camera, settings, 2, 2);
    EXPECT_EQ(cpu.geometryDigits, 17);
    EXPECT_NEAR(cpu.t, 4.1, 1e-15);
    EXPECT_EQ(cpu.lights[0].feelerMet, std::optional<bool>(false));
    EXPECT_EQ(cpu.lights[1].feelerMet, std::optional<bool>(true));
}

TEST(PixelTrace, AMissRecordsTheBackground) {
    const Scene scene = parseSdl(
        "camera eye 0 0 5 background 0.25 0.5 0.75\n"
        "push translate 100 0 0 sphere pop\n",
        "t.sdl", {});
    const RenderSettings settings{3, 3, 1};
    const CameraBasis camera = makeCameraBasis(*scene.camera, 3, 3);
    for (const PixelTrace& trace : {gpuTrace(scene, camera, settings, 1, 1),
                                    reference::tracePixel(scene, camera, settings, 1, 1)}) {
        EXPECT_EQ(trace.hitObject, -1);
        EXPECT_TRUE(std::isinf(trace.t));
        ASSERT_EQ(trace.objects.size(), 1u);
        EXPECT_FALSE(trace.objects[0].t.has_value());
        expectNear(trace.color, {0.25, 0.5, 0.75}, 1e-7);
    }
}

TEST(PixelTrace, BlockPixelsTraceTheirBlocksRay) {
    const Scene scene = parseSdl("camera eye 0 0 5\nsphere\n", "t.sdl", {});
    const RenderSettings settings{9, 9, 3};
    const CameraBasis camera = makeCameraBasis(*scene.camera, 9, 9);
    // Pixels (3, 3) and (5, 5) share the centre block, whose ray is the centre's.
    const PixelTrace a = gpuTrace(scene, camera, settings, 3, 3);
    const PixelTrace b = gpuTrace(scene, camera, settings, 5, 5);
    expectNear(a.rayDirection, {0, 0, -1}, 1e-7);
    expectNear(b.rayDirection, a.rayDirection, 0);
}

// `vkray pixel --spp N --seed S --sample K`: both sides trace sample K's
// jittered ray, and its colour is the colour a render of that one sample gives.
TEST(PixelTrace, OneSampleOfManyIsTracedAsARenderTracesIt) {
    const Scene scene = parseSdl(
        "camera eye 0 0 5 fov 40 background 0.2 0.3 0.4\n"
        "light 3 4 10 1 1 1\n"
        "diffuse 0.5 0.25 0.125 texture 1 parameters 4 0.1 0 0 0\n"
        "push translate 0 0 -2 sphere pop\n",
        "t.sdl", {});
    RenderSettings settings{7, 7, 1, 9, 12345};
    const CameraBasis camera = makeCameraBasis(*scene.camera, 7, 7);
    gpu::GpuTracer tracer(test::gpuContext(), {.shaderDirectory = test::kShaderDir});
    for (const int k : {0, 4, 8}) {
        SCOPED_TRACE(k);
        settings.firstSample = k;
        settings.sampleCount = 1;
        const PixelTrace gpu = tracer.tracePixel(scene, camera, settings, 2, 3);
        const PixelTrace cpu = reference::tracePixel(scene, camera, settings, 2, 3);
        const glm::dvec3 d = primaryDirection(camera, settings, jitteredSample(2, 3, settings, k));
        expectNear(gpu.rayDirection, d, 1e-7);
        expectNear(cpu.rayDirection, d, 0);
        const Frame one = tracer.render(scene, camera, settings);
        expectNear(gpu.color, glm::dvec3(one.color[one.index(2, 3)]), 1e-6);
        expectNear(cpu.color, gpu.color, 1e-5);
    }
    // Sample 4's ray is not the centre's.
    settings.firstSample = 4;
    EXPECT_GT(glm::length(tracer.tracePixel(scene, camera, settings, 2, 3).rayDirection -
                          primaryDirection(camera, settings, {2.5, 3.5})),
              1e-4);
}

}  // namespace
}  // namespace vkray
