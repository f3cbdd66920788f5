// Precision modes: parsing, what each mode does to the scene on the host
// (rebasing keeps every generic ray; float inverses break ill-conditioned
// transforms), the naive and fp64 shader variants, renders, and fp64's
// refusal on a device without shaderFloat64.
#include "gpu/precision.h"
#include "app/options.h"
#include "gpu/shader_compiler.h"
#include "gpu/shader_variant.h"
#include "numerics/bounded.h"
#include "reference/reference_tracer.h"
#include "scene/sdl_reader.h"
#include "support/cli_fixture.h"
#include "support/gpu_fixture.h"
#include "util/error.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace vkray {
namespace {

const char* kFarSceneForFp64 =
    "light 1e7 5 5 1 1 1\n"
    "push translate 10000001.3 0.2 -0.7 rotate 30 1 1 0 scale 2 1e-8 2 sphere pop\n";

TEST(Precision, ParsesTheThreeModes) {
    EXPECT_EQ(parsePrecision("--precision", "naive"), Precision::Naive);
    EXPECT_EQ(parsePrecision("--precision", "robust"), Precision::Robust);
    EXPECT_EQ(parsePrecision("--precision", "fp64"), Precision::Fp64);
    try {
        parsePrecision("--precision", "double");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "--precision: expected naive, robust or fp64, found 'double'");
    }
}

TEST(Precision, Fp64IsRefusedNamingADeviceWithoutShaderFloat64) {
    gpu::DeviceInfo device;
    device.index = 2;
    device.name = "Tiny GPU";
    device.shaderFloat64 = false;
    EXPECT_NO_THROW(gpu::requirePrecisionSupported(Precision::Naive, device));
    EXPECT_NO_THROW(gpu::requirePrecisionSupported(Precision::Robust, device));
    try {
        gpu::requirePrecisionSupported(Precision::Fp64, device);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("device 2 (Tiny GPU) has no shaderFloat64"),
                  std::string::npos)
            << e.what();
    }
    device.shaderFloat64 = true;
    EXPECT_NO_THROW(gpu::requirePrecisionSupported(Precision::Fp64, device));
}

TEST(Precision, EachModeDefinesBothFlagsZeroOrOne) {
    using D = std::vector<std::pair<std::string, std::string>>;
    EXPECT_EQ(precisionDefines(Precision::Naive),
              (D{{"VKRAY_PRECISION_NAIVE", "1"}, {"VKRAY_PRECISION_FP64", "0"}}));
    EXPECT_EQ(precisionDefines(Precision::Fp64),
              (D{{"VKRAY_PRECISION_NAIVE", "0"}, {"VKRAY_PRECISION_FP64", "1"}}));
    EXPECT_EQ(precisionDefines(Precision::Robust),
              (D{{"VKRAY_PRECISION_NAIVE", "0"}, {"VKRAY_PRECISION_FP64", "0"}}));
}

TEST(Precision, Fp64RebasesLikeRobust) {
    const Scene scene = parseSdl(kFarSceneForFp64, "t.sdl", {});
    Camera camera;
    camera.eye = {10000006.37, 4.1, 8.3};
    camera.look = {1e7, 0, 0};
    const CameraBasis basis = makeCameraBasis(camera, 64, 48);
    const GpuInputs robust = prepareGpuInputs(Precision::Robust, scene, basis);
    const GpuInputs fp64 = prepareGpuInputs(Precision::Fp64, scene, basis);
    EXPECT_EQ(fp64.camera.eye, glm::dvec3(0));
    EXPECT_EQ(fp64.scene.objects[0].objectFromWorld, robust.scene.objects[0].objectFromWorld);
    EXPECT_EQ(fp64.scene.lights[0].position, robust.scene.lights[0].position);
}

const char* kFarScene =
    "light 1e7 5 5 1 1 1\n"
    "push translate 10000001.3 0.2 -0.7 rotate 30 1 1 0 scale 2 1e-8 2 sphere pop\n"
    "push translate 9999998.6 0.2 0.4 union cube push translate 0 1 0 sphere pop pop\n";

// M^-1 T(e) (p - e) = M^-1 p for every point: the generic rays are the same.
void expectSameGenericPoints(const SceneObject& a, const SceneObject& b, const glm::dvec3& e) {
    for (const glm::dvec3 p : {glm::dvec3(1e7, 0, 0), glm::dvec3(1e7 + 3.3, -2, 5), e}) {
        const glm::dvec3 ga(a.objectFromWorld * glm::dvec4(p, 1));
        const glm::dvec3 gb(b.objectFromWorld * glm::dvec4(p - e, 1));
        EXPECT_LE(glm::length(ga - gb), 1e-15 * (glm::length(ga) + 1e8 * glm::length(p))) << p.x;
    }
    const glm::dvec3 w(a.worldFromObject * glm::dvec4(0.3, 0.4, 0.5, 1));
    const glm::dvec3 wb(b.worldFromObject * glm::dvec4(0.3, 0.4, 0.5, 1));
    EXPECT_LE(glm::length(w - e - wb), 1e-8);
    ASSERT_EQ(a.operands.size(), b.operands.size());
    for (size_t i = 0; i < a.operands.size(); ++i)
        expectSameGenericPoints(a.operands[i], b.operands[i], e);
}

TEST(Precision, RobustRebasesTheWorldOnTheEye) {
    const Scene scene = parseSdl(kFarScene, "t.sdl", {});
    Camera camera;
    camera.eye = {10000006.37, 4.1, 8.3};
    camera.look = {1e7, 0, 0};
    const CameraBasis basis = makeCameraBasis(camera, 64, 48);
    const GpuInputs inputs = prepareGpuInputs(Precision::Robust, scene, basis);
    EXPECT_EQ(inputs.camera.eye, glm::dvec3(0));
    EXPECT_EQ(inputs.camera.n, basis.n);
    EXPECT_EQ(inputs.scene.lights[0].position, scene.lights[0].position - camera.eye);
    for (size_t i = 0; i < scene.objects.size(); ++i)
        expectSameGenericPoints(scene.objects[i], inputs.scene.objects[i], camera.eye);
    // The eye's generic coordinates are now a translation computed in double.
    const glm::dvec3 eyeGeneric(scene.objects[0].objectFromWorld * glm::dvec4(camera.eye, 1));
    const glm::dvec3 translation(inputs.scene.objects[0].objectFromWorld[3]);
    EXPECT_LE(glm::length(eyeGeneric - translation), 1e-7 * glm::length(eyeGeneric));
}

TEST(Precision, TheRebasedTranslationIsRoundedOnce) {
    // M^-1 (eye, 1) for objects 1e7 away, seen from 10: in plain double it
    // would carry u_double of 1e7 (1e-9); rounded once it is within half an
    // ulp of the exact value (computed here in float128), plus u^2 of 1e7.
    const Scene scene = parseSdl(kFarScene, "t.sdl", {});
    const glm::dvec3 eye{10000006.37, 4.1, 8.3};
    const Scene rebased = rebasedOnPoint(scene, eye);
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const glm::dmat4& m = scene.objects[i].objectFromWorld;
        for (int row = 0; row < 3; ++row) {
            numerics::Quad exact = m[3][row];
            for (int j = 0; j < 3; ++j) exact += numerics::Quad(m[j][row]) * numerics::Quad(eye[j]);
            const double got = rebased.objects[i].objectFromWorld[3][row];
            EXPECT_LE(double(abs(numerics::Quad(got) - exact)), 0x1p-53 * std::abs(got) + 1e-22)
                << "object " << i << " row " << row;
        }
    }
}

TEST(Precision, NaiveInvertsInFloatAndLosesIllConditionedTransforms) {
    // Squashed between two rotations, so that no column of M carries the 1e-8
    // alone (a column scaling alone survives inversion in float).
    const Scene scene =
        parseSdl("rotate 30 1 1 0 scale 2 1e-8 2 rotate 40 0 1 1 cube", "t.sdl", {});
    const GpuInputs inputs =
        prepareGpuInputs(Precision::Naive, scene, makeCameraBasis(Camera{}, 4, 4));
    const auto offIdentity = [](const SceneObject& o) {
        const glm::dmat4 product = o.worldFromObject * o.objectFromWorld;
        double worst = 0;
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) {
                const double off = std::abs(product[c][r] - (c == r));
                worst = std::isnan(off) ? INFINITY : std::max(worst, off);  // float det may be 0
            }
        return worst;
    };
    EXPECT_LT(offIdentity(scene.objects[0]), 1e-7);  // composed in double from exact inverses
    EXPECT_GT(offIdentity(inputs.scene.objects[0]), 1e-2);  // cond(M) = 2e8 in float: lost or NaN
}

TEST(Precision, NaiveAndFp64VariantsCompileForEveryShape) {
    gpu::ShaderFeatures all;
    all.kinds.fill(true);
    all.shading.fill(true);
    for (Precision precision : {Precision::Naive, Precision::Fp64}) {
        for (bool bvh : {false, true}) {
            all.objectBvh = bvh;
            for (bool debug : {false, true}) {
                all.debugPixel = debug;
                EXPECT_NO_THROW(
                    gpu::compileComputeShader({test::kShaderDir, "trace.comp",
                                               gpu::definesFor(all, precisionDefines(precision))}))
                    << precisionName(precision) << " " << gpu::describe(all);
            }
        }
    }
}

TEST(PrecisionGpu, ModesAgreeOnAnEasySceneAndDifferFarAway) {
    // Near the origin both modes see the same sphere; at 1e7 naive moves it.
    for (const double offset : {0.0, 1e7}) {
        const std::string text = "camera eye " + std::to_string(offset + 0.3) + " 0 5 look " +
                                 std::to_string(offset) +
                                 " 0 0 fov 30\nlight 0 10 10 1 1 1\npush translate " +
                                 std::to_string(offset) + " 0 0 sphere pop\n";
        const Scene scene = parseSdl(text, "t.sdl", {});
        const CameraBasis camera = makeCameraBasis(*scene.camera, 32, 24);
        const RenderSettings settings{32, 24, 1};
        Frame frames[2];
        for (int m = 0; m < 2; ++m) {
            gpu::GpuTracer tracer(test::gpuContext(),
                                  {.shaderDirectory = test::kShaderDir,
                                   .precision = m == 0 ? Precision::Naive : Precision::Robust});
            frames[m] = tracer.render(scene, camera, settings);
        }
        double worst = 0;
        for (size_t i = 0; i < frames[0].pixelCount(); ++i)
            if (frames[0].id[i] >= 0 && frames[1].id[i] >= 0)
                worst = std::max(worst, double(std::abs(frames[0].depth[i] - frames[1].depth[i])));
        if (offset == 0) {
            EXPECT_LT(worst, 1e-5) << "near the origin";
        } else {
            EXPECT_GT(worst, 1e-2) << "1e7 away: the eye's 0.3 is lost in naive float";
        }
    }
}

TEST(PrecisionGpu, Fp64KeepsASquashBetweenTwoRotationsThatFloatLoses) {
    // Every generic axis mixes the 1e8-stretched one: M^-1 rounded to float
    // moves the disk by ~u 1e8 of its size (docs/numerics.md, "Known limits"); in double
    // it stays within ~1e-8.
    const Scene scene = parseSdl(
        "camera eye 3 4 5 look 0 0 0 up 0 1 0 fov 40\nlight 10 20 10 1 1 1\n"
        "push rotate 30 1 1 0 scale 2 1e-8 2 rotate 40 0 1 1 sphere pop\n",
        "t.sdl", {});
    const RenderSettings settings{40, 30, 1};
    const CameraBasis camera = makeCameraBasis(*scene.camera, settings.width, settings.height);
    const Frame cpu = reference::render(scene, camera, settings, {2});
    const auto idsDiffering = [&](Precision precision) {
        gpu::GpuTracer tracer(test::gpuContext(),
                              {.shaderDirectory = test::kShaderDir, .precision = precision});
        const Frame gpu = tracer.render(scene, camera, settings);
        size_t differ = 0;
        for (size_t i = 0; i < gpu.pixelCount(); ++i) differ += gpu.id[i] != cpu.id[i];
        return differ;
    };
    size_t disk = 0;
    for (size_t i = 0; i < cpu.pixelCount(); ++i) disk += cpu.id[i] == 0;
    ASSERT_GT(disk, cpu.pixelCount() / 10);
    EXPECT_GT(idsDiffering(Precision::Robust), disk / 10);
    EXPECT_EQ(idsDiffering(Precision::Fp64), 0u);
}

using PrecisionCli = test::CliTest;

TEST_F(PrecisionCli, RenderTakesEachPrecision) {
    const std::string s = scene("s.sdl", "camera eye 0 0 5\nlight 5 5 5 1 1 1\nsphere\n");
    test::RunResult naive = test::vkray("render " + s + " -o " + path("n.png") +
                                        " --size 32x24 --precision naive --check");
    EXPECT_EQ(naive.status, 0) << naive.output;
    EXPECT_NE(naive.output.find("precision naive"), std::string::npos) << naive.output;
    // lavapipe has shaderFloat64; the fault hook hides it.
    test::RunResult fp64 = test::vkray("render " + s + " -o " + path("f.png") +
                                       " --size 32x24 --precision fp64 --check");
    EXPECT_EQ(fp64.status, 0) << fp64.output;
    EXPECT_NE(fp64.output.find("precision fp64"), std::string::npos) << fp64.output;
    test::RunResult refused =
        test::vkray("render " + s + " -o " + path("g.png") + " --size 32x24 --precision fp64",
                    "VKRAY_FAULT=no-float64");
    EXPECT_EQ(refused.status, 1) << refused.output;
    EXPECT_NE(refused.output.find("has no shaderFloat64"), std::string::npos) << refused.output;
    EXPECT_FALSE(test::fs::exists(path("g.png")));
    test::RunResult cpu =
        test::vkray("render " + s + " --cpu --precision naive -o " + path("c.png"));
    EXPECT_EQ(cpu.status, 1);
    EXPECT_NE(cpu.output.find("--precision applies to the GPU"), std::string::npos) << cpu.output;
    test::RunResult bad = test::vkray("render " + s + " --precision half");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("expected naive, robust or fp64"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace vkray

namespace vkray {
namespace {

TEST(PrecisionOptions, StressAndReportTakeTheirFlagsOnly) {
    Options o = parseOptions({"render", "s.sdl", "--precision", "naive"});
    EXPECT_EQ(o.precision, Precision::Naive);
    EXPECT_TRUE(o.precisionGiven);
    o = parseOptions({"pixel", "s.sdl", "1", "2", "--precision=robust"});
    EXPECT_EQ(o.precision, Precision::Robust);
    o = parseOptions(
        {"stress", "--cases", "torus", "--size", "32x24", "--out", "d", "--cases-dir", "c"});
    EXPECT_EQ(o.command, Command::Stress);
    EXPECT_EQ(o.casesPattern, "torus");
    EXPECT_EQ(o.outDirectory, "d");
    EXPECT_EQ(o.casesDirectory, "c");
    EXPECT_EQ(o.width, 32);
    o = parseOptions({"report", "s.sdl", "--out", "r", "--fov", "40"});
    EXPECT_EQ(o.command, Command::Report);
    EXPECT_EQ(o.scenePath, "s.sdl");
    EXPECT_THROW(parseOptions({"render", "s.sdl", "--out", "d"}), Error);
    o = parseOptions({"stress", "--precision", "naive"});  // that mode only
    EXPECT_TRUE(o.precisionGiven);
    EXPECT_THROW(parseOptions({"report", "s.sdl", "--block", "2"}),
                 Error);  // report sweeps the block
    EXPECT_THROW(parseOptions({"report"}), Error);
    EXPECT_THROW(parseOptions({"stress", "extra"}), Error);
    EXPECT_THROW(parseOptions({"render", "s.sdl", "--precision", "half"}), Error);
}

}  // namespace
}  // namespace vkray
