// Scenes of a few lines on which the GPU once drew something other than
// the CPU reference, pinned so that it cannot again. Each states what went
// wrong; the bound is `render --check`'s default (colour within 0.02 on all
// but 0.1 % of the pixels) and object ids equal everywhere.
#include "support/frame_difference.h"
#include "support/gpu_fixture.h"
#include "support/temp_folder.h"

#include "image/aov_images.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "numerics/agreement.h"
#include "reference/reference_tracer.h"

#include <glm/common.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace vkray {
namespace {

struct Renders {
    Frame gpu, cpu;
};

Renders renderBoth(const std::string& sdl, const RenderSettings& settings) {
    Scene scene = parseSdl(sdl, "regression.sdl", {}, nullptr);
    loadSceneGeometry(scene, false, nullptr);
    const CameraBasis camera = makeCameraBasis(*scene.camera, settings.width, settings.height);
    return {test::renderOnGpu(scene, camera, settings), reference::render(scene, camera, settings)};
}

void expectAgreement(const Renders& r) {
    const test::FrameDifference d = test::frameDifference(r.gpu, r.cpu, 0.02);
    EXPECT_EQ(d.ids, 0u);
    EXPECT_LE(double(d.over), 0.001 * double(r.cpu.pixelCount()))
        << d.over << " pixels differ by more than 0.02 (largest " << d.maxColor << ")";
}

TEST(AgreementRegressions, EyeInsideALoneSphereLitFromOutside) {
    // The variant once left the shadow code out for a lone sphere, as if it
    // could not shadow itself; from inside, the light outside is behind the
    // far wall for every point that faces it: 57 % of the pixels were lit.
    const Renders r = renderBoth(
        "camera eye 0 0 0 look -1 0.2 0.1 up 0 1 0 fov 70\n"
        "light 10 2 1 1 1 1\ndiffuse 0.8 0.7 0.6\n"
        "push scale 3 3 3 sphere pop\n",
        {64, 48});
    expectAgreement(r);
}

TEST(AgreementRegressions, EyeInsideALoneCubeLitFromOutside) {
    const Renders r = renderBoth(
        "camera eye 0.2 0.1 0 look 1 0.3 0.2 up 0 1 0 fov 70\n"
        "light -9 5 2 1 1 1\ndiffuse 0.6 0.7 0.8\n"
        "push rotate 20 0 1 0 scale 2 3 2 cube pop\n",
        {64, 48});
    expectAgreement(r);
}

TEST(AgreementRegressions, CoincidentSurfacesUnderTheObjectBvhGoToTheLowerIndex) {
    // A def used twice puts two spheres on the same surface, among 20 others
    // (an object BVH). Their hits tie within the tie tolerance, which the
    // lower index wins, as in the reference, whatever order the BVH visits
    // them: the walk keeps a box whose object would tie (it once culled
    // boxes at the closest t, not at the t a tie still accepts).
    std::string sdl =
        "camera eye 0 0 1000 look 0 0 0 up 0 1 0 fov 2\nlight 500 800 900 1 1 1\n"
        "diffuse 0.8 0.2 0.2 def ball { push translate 0.3 0.2 0 scale 7 7 7 "
        "sphere pop } use ball\n";
    for (int i = 0; i < 20; ++i)
        sdl += "diffuse 0.2 0.8 0.2 push translate " + std::to_string(4 * (i % 5) - 8) + " " +
               std::to_string(5 * (i / 5) - 8) + " -40 scale 2 2 2 sphere pop\n";
    sdl += "diffuse 0.2 0.2 0.8 use ball\n";
    const Renders r = renderBoth(sdl, {80, 60});
    expectAgreement(r);
    size_t front = 0;
    for (size_t i = 0; i < r.gpu.pixelCount(); ++i) {
        EXPECT_NE(r.gpu.id[i], 21) << "the later copy won a tie at pixel " << i;
        front += r.gpu.id[i] == 0;
    }
    EXPECT_GT(front, r.gpu.pixelCount() / 20);  // the pair covers the middle of the view
}

// A tapered cylinder with s < 0 is an hourglass: two nappes meeting at
// z = 1 / (1 - s), a top cap of radius |s|. The GPU once took it for convex:
// the first and last crossing, no top cap, the axis as the upper nappe's
// normal, one span in CSG: 4.1 % of these pixels off for s = -1, 1.2 % for
// s = -0.5, 11 % in the difference below.
const char* const kHourglassView =
    "camera eye 3.5 1.2 1.3 look 0 0 0.45 up 0 0 1 fov 45\n"
    "light 4 -3 6 1 1 1\nlight -3 4 -2 0.5 0.5 0.5\nglobalAmbient 0.2 0.2 0.2\n"
    "ambient 0.2 0.2 0.2 diffuse 0.8 0.5 0.3\n";

TEST(AgreementRegressions, HourglassTaperMinusOne) {
    expectAgreement(renderBoth(std::string(kHourglassView) + "taperedCylinder -1\n", {96, 72}));
}

TEST(AgreementRegressions, HourglassTaperMinusHalf) {
    expectAgreement(renderBoth(std::string(kHourglassView) + "taperedCylinder -0.5\n", {96, 72}));
}

TEST(AgreementRegressions, HourglassInCsgHasTwoSpans) {
    // Seen from below, less the box z <= 0.45: the waist's gap shows the
    // upper nappe, not a cut face across the whole hourglass.
    expectAgreement(
        renderBoth("camera eye 3 -1.5 -2 look 0 0 0.5 up 0 0 1 fov 45\n"
                   "light 4 -3 -6 1 1 1\nlight -3 4 2 0.5 0.5 0.5\n"
                   "globalAmbient 0.2 0.2 0.2 ambient 0.2 0.2 0.2 diffuse 0.8 0.5 0.3\n"
                   "difference taperedCylinder -1\n"
                   "  push translate 0 0 -0.55 scale 2 2 1 cube pop\n",
                   {96, 72}));
}

// Wood rings of width 1/k once had a boundary at radius 1, on the cylinder's
// own wall: float and double picked different rings (5.7 % of these pixels
// at either width).
TEST(AgreementRegressions, WoodRingsOnACylinderWall) {
    for (const char* width : {"0.1", "0.25"}) {
        SCOPED_TRACE(width);
        expectAgreement(renderBoth(std::string("camera eye 3 2.5 2.5 look 0 0 0.5 up 0 0 1 fov 45\n"
                                               "light 5 4 8 1 1 1\nglobalAmbient 0.3 0.3 0.3\n"
                                               "ambient 0.3 0.3 0.3 diffuse 0.7 0.7 0.7\n"
                                               "texture 2 parameters 4 ") +
                                       width + " 0.55 0.35 0.15\ncylinder\n",
                                   {96, 72}));
    }
}

// Scenes `vkray difftest` drew on which the GPU and the CPU reference
// disagreed (tests/data/difftest/*.sdl, each file's header says why), with
// the render settings of the run that found them, compared as `render
// --check` compares (colours clamped to what a display shows): no pixel
// over 0.02, object ids equal.
Renders renderInMode(const Scene& scene, const RenderSettings& settings, Precision precision) {
    const CameraBasis camera = makeCameraBasis(*scene.camera, settings.width, settings.height);
    gpu::GpuTracer tracer(test::gpuContext(),
                          {.shaderDirectory = test::kShaderDir, .precision = precision});
    return {tracer.render(scene, camera, settings), reference::render(scene, camera, settings)};
}

void expectSceneAgrees(const Scene& scene, const RenderSettings& settings, Precision precision) {
    const Renders r = renderInMode(scene, settings, precision);
    CompareResult result = compareImages(colorImage(r.gpu), colorImage(r.cpu), {0.02, 0.1});
    compareIds(idImage(r.gpu), idImage(r.cpu), result);
    EXPECT_EQ(result.pixelsOverThreshold, 0u) << "largest difference " << result.maxAbsError;
    EXPECT_EQ(result.idMismatches.value_or(1), 0u);
}

void expectDifftestSceneAgrees(const std::string& name, const RenderSettings& settings,
                               Precision precision) {
    SCOPED_TRACE(name);
    expectSceneAgrees(loadScene(test::kDataDir + "/difftest/" + name, {}, nullptr), settings,
                      precision);
}

TEST(AgreementRegressions, AReflectionPassingACornerMissesItAsTheReferencesDoes) {
    expectDifftestSceneAgrees("reflected_corner.sdl", {32, 24, 1, 16, 3904793813u},
                              Precision::Robust);
}

TEST(AgreementRegressions, MirrorsNineLevelsDeep) {
    expectDifftestSceneAgrees("deep_mirrors.sdl", {32, 24, 1, 9, 3748471141u}, Precision::Robust);
}

TEST(AgreementRegressions, AThinUnionFarAwayIsDrawnByBoth) {
    expectDifftestSceneAgrees("thin_union_far.sdl", {40, 30, 1, 2, 3236972483u}, Precision::Fp64);
}

// A wood floor seen to its horizon: the row just above the horizon hits it
// 1.4e5 away, where neither GPU mode places the hit to a ring (robust: its
// float ray direction; fp64: the texture evaluated in float there), so the
// rings drawn on that row differ from the reference's (robust 15 of its 32
// pixels, fp64 1). A limit, not a bug: every other row agrees, and the same
// floor untextured, as `vkray difftest` now draws planes, agrees everywhere.
TEST(AgreementRegressions, ATexturedPlaneDiffersOnlyOnItsHorizonsRow) {
    const std::string path = test::kDataDir + "/difftest/textured_plane_horizon.sdl";
    const RenderSettings settings{32, 24, 1, 1, 3366176552u};
    const int horizonRow = 7;
    const std::string wood = "texture 2 parameters 4 0.426165 0.392217 0.726759 0.816635";
    std::ifstream in(path);
    std::string sdl((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t floor = sdl.find(wood);
    ASSERT_NE(floor, std::string::npos);
    for (const Precision precision : {Precision::Robust, Precision::Fp64}) {
        SCOPED_TRACE(precisionName(precision));
        const Renders r = renderInMode(loadScene(path, {}, nullptr), settings, precision);
        std::size_t offRow = 0;
        for (std::size_t i = 0; i < r.cpu.pixelCount(); ++i) {
            EXPECT_EQ(r.gpu.id[i], r.cpu.id[i]) << "pixel " << i;
            const glm::vec3 d = glm::abs(r.gpu.color[i] - r.cpu.color[i]);
            if (std::max(d.x, std::max(d.y, d.z)) > 0.02f && int(i) / settings.width != horizonRow)
                ++offRow;
        }
        EXPECT_EQ(offRow, 0u) << "pixels off beyond the horizon's row";

        Scene plain = parseSdl(std::string(sdl).replace(floor, wood.size(), "texture 0"),
                               "textured_plane_horizon.sdl", {}, nullptr);
        loadSceneGeometry(plain, false, nullptr);
        expectAgreement(renderInMode(plain, settings, precision));
    }
}

// Under the margin rule every pixel a floor's horizon makes differ is one the
// mode's bound explains: its texture looked up to the side and along the
// ray, across the rings a grazing ray's rounding moves it over (fp64's one
// pixel of the wood floor's row above had been left unexplained); and
// fp64's jittered samples are placed in double, as the reference places
// them.
std::size_t unexplainedPixels(const std::string& name, const RenderSettings& settings,
                              Precision precision) {
    const Scene scene = loadScene(test::kDataDir + "/difftest/" + name, {}, nullptr);
    RenderSettings withAovs = settings;
    withAovs.aovs = true;
    const CameraBasis camera = makeCameraBasis(*scene.camera, settings.width, settings.height);
    gpu::GpuTracer tracer(test::gpuContext(),
                          {.shaderDirectory = test::kShaderDir, .precision = precision});
    const Frame gpu = tracer.render(scene, camera, withAovs);
    const Frame cpu = reference::render(scene, camera, withAovs);
    const Agreement a = judgeAgreement(scene, camera, withAovs, precision, gpu, cpu, {});
    std::printf("%s %s: %zu differ, %zu set aside, %zu unexplained\n", name.c_str(),
                precisionName(precision), a.differing, a.setAside, a.unexplained);
    return a.unexplained;
}

// Every differing pixel of the pinned scene explained, in robust and fp64.
void expectExplainedInRobustAndFp64(const std::string& name, const RenderSettings& settings) {
    for (const Precision precision : {Precision::Robust, Precision::Fp64}) {
        SCOPED_TRACE(precisionName(precision));
        EXPECT_EQ(unexplainedPixels(name, settings, precision), 0u);
    }
}

TEST(AgreementRegressions, FloorsToTheirHorizonDifferOnlyWhereTheMarginRuleExplains) {
    for (const Precision precision : {Precision::Robust, Precision::Fp64}) {
        SCOPED_TRACE(precisionName(precision));
        EXPECT_EQ(
            unexplainedPixels("textured_plane_horizon.sdl", {32, 24, 1, 1, 3366176552u}, precision),
            0u);
        EXPECT_EQ(unexplainedPixels("checkered_floor_horizon.sdl", {160, 120, 1, 4, 0}, precision),
                  0u);
    }
}

// A pixmap's row border on a face seen through glass: the plays must not
// start feelers inside the face they leave (the file's header says how).
TEST(AgreementRegressions, ATexelBorderOnAFaceSeenThroughGlassIsExplained) {
    expectExplainedInRobustAndFp64("texel_border_through_glass.sdl", {160, 120});
}

// A refracted ray that meets a glass cube again at an edge: the plays'
// feelers must leave as the GPU's do (the file's header says how).
TEST(AgreementRegressions, AFeelerFromAnEdgeInsideGlassIsExplained) {
    EXPECT_EQ(
        unexplainedPixels("refracted_to_an_edge.sdl", {40, 30, 1, 4, 32334305u}, Precision::Robust),
        0u);
}

// A reflected ray that the GPU's offset carries past a plane crossing the
// floor: the GPU's own geometry must be one of the plays.
TEST(AgreementRegressions, AReflectionStartedPastACrossingPlaneIsExplained) {
    EXPECT_EQ(unexplainedPixels("reflected_past_a_crossing_plane.sdl", {32, 24, 1, 16, 3887158881u},
                                Precision::Robust),
              0u);
}

// A grazing ray leaving a glass plane from its back (the file's header says
// how): it goes straight on, in every mode.
TEST(AgreementRegressions, AGrazingRayThroughAPlaneGoesStraightOn) {
    expectExplainedInRobustAndFp64("grazing_through_a_plane.sdl", {40, 30});
}

// A refracted ray leaving a hit that a ray from far across the scene met
// (the file's header says how): its offset covers the far origin's rounding.
TEST(AgreementRegressions, ARayFromAcrossTheSceneLeavesTheSurfaceItMet) {
    expectExplainedInRobustAndFp64("glass_cube_met_across_a_sphere.sdl", {40, 30});
}

// A feeler past a cube's edge under an unchanged texel (the file's header
// says how): the plays move the rays with the textures left where the hits are.
TEST(AgreementRegressions, AFeelerPastAnEdgeUnderTheSameTexelIsExplained) {
    EXPECT_EQ(unexplainedPixels("feeler_past_an_edge_under_a_texel.sdl", {24, 18}, Precision::Fp64),
              0u);
}

// A reflection whose offset's step lands past the next face of a buckyball
// (the file's header says how): the GPU's step lands in float.
TEST(AgreementRegressions, AStepLandingPastTheNextFaceIsExplained) {
    EXPECT_EQ(unexplainedPixels("reflection_past_a_buckyball_edge.sdl", {24, 18, 1, 2, 3551097776u},
                                Precision::Robust),
              0u);
}

// A sphere's texel row chosen by the shader's own asin (the file's header
// says how): the driver's may be 4096 float spacings off.
TEST(AgreementRegressions, ASpheresTexelRowIsTheReferencesClearOfTheBorder) {
    expectExplainedInRobustAndFp64("sphere_texel_row_from_inside.sdl", {40, 30, 1, 2, 1207818942u});
}

// The corner of a cube in a squashed union far away (the file's header says
// how): a real thin chord, drawn by both.
TEST(AgreementRegressions, ACubesCornerInASquashedUnionIsNoSliver) {
    EXPECT_EQ(unexplainedPixels("cube_corner_in_a_squashed_union.sdl", {40, 30, 1, 9, 4264315813u},
                                Precision::Fp64),
              0u);
}

// Texel rows and columns of a fine pixmap (128 x 512 texels, a checker) on a
// sphere seen from its centre and on a torus: each texel is chosen from the
// shader's own atan2 and asin. With the driver's (lavapipe 22.3), 172 of
// the sphere's 19 200 pixels fell in another texel than the reference's and
// no play explained them; with the shader's, none differs.
TEST(AgreementRegressions, FineTexelsOnASphereAndATorusAreTheReferences) {
    const test::TempFolder folder("fine-texels");
    Image checker;
    checker.width = 128;
    checker.height = 512;
    checker.channels = 3;
    for (int y = 0; y < checker.height; ++y)
        for (int x = 0; x < checker.width; ++x) {
            const bool odd = (x + y) % 2 != 0;
            checker.pixels.insert(checker.pixels.end(),
                                  {odd ? 0.85f : 0.15f, 0.15f, odd ? 0.15f : 0.85f});
        }
    std::ofstream(folder.path() / "fine.png", std::ios::binary) << pngBytes(checker);
    const std::string material =
        "globalAmbient 1 1 1 makePixmap 0 fine.png\n"
        "ambient 1 1 1 diffuse 0 0 0 specular 0 0 0 texture 3 parameters 1 0\n";
    const std::pair<const char*, std::string> scenes[] = {
        {"sphere.sdl", "camera eye 0 0 0 look 1 0.3 -0.6 up 0 0 1 fov 100\n" + material +
                           "push rotate 20 1 2 3 scale 2 2 2 sphere pop\n"},
        {"torus.sdl", "camera eye 0.3 0.4 3 look 0 0 0 up 0 1 0 fov 70\n" + material + "torus\n"}};
    for (const auto& [name, sdl] : scenes) {
        SCOPED_TRACE(name);
        std::ofstream(folder.path() / name) << sdl;
        const Scene scene = loadScene((folder.path() / name).string(), {}, nullptr);
        const RenderSettings settings{160, 120};
        const CameraBasis camera = makeCameraBasis(*scene.camera, 160, 120);
        gpu::GpuTracer tracer(test::gpuContext(), {.shaderDirectory = test::kShaderDir});
        const Frame gpu = tracer.render(scene, camera, settings);
        const Frame cpu = reference::render(scene, camera, settings);
        const Agreement a =
            judgeAgreement(scene, camera, settings, Precision::Robust, gpu, cpu, {});
        EXPECT_EQ(a.unexplained, 0u);
        EXPECT_EQ(a.differing, 0u);
    }
}

// A ray grazing a huge torus from just above it (the file's header says
// how): a hit, where rounding gives one, is an entry lit as one.
TEST(AgreementRegressions, ATorusGrazedFromJustAboveIsEnteredNotLeft) {
    EXPECT_EQ(unexplainedPixels("torus_grazed_from_above.sdl", {40, 30, 1, 9, 3878126044u},
                                Precision::Robust),
              0u);
}

// Two samples a pixel, each a primary ray and a shadow feeler, within 1000
// counted loop turns a ray in both modes: each tile in one dispatch.
void expectWalksWithin1000Turns(const Scene& scene) {
    const RenderSettings settings{32, 24, 1, 2, 0};
    const CameraBasis camera = makeCameraBasis(*scene.camera, settings.width, settings.height);
    for (const Precision precision : {Precision::Robust, Precision::Fp64}) {
        SCOPED_TRACE(precisionName(precision));
        gpu::GpuTracer tracer(
            test::gpuContext(),
            {.shaderDirectory = test::kShaderDir, .precision = precision, .turnBudget = 1000});
        gpu::GpuRenderStats stats;
        tracer.render(scene, camera, settings, &stats);
        EXPECT_EQ(stats.dispatches, stats.tiles);
        EXPECT_EQ(stats.tilesRedone, 0u);
    }
}

// A teapot squashed by 1.8e-6 between two rotations, seen from 9.6e4: its
// generic eye is 4e10 away. The fp64 GPU refused it at the loop limit; it now
// draws it as the reference does.
TEST(AgreementRegressions, ATeapotSquashedBetweenRotationsFarAwayIsDrawn) {
    expectDifftestSceneAgrees("squashed_teapot_far.sdl", {32, 24, 1, 2, 0}, Precision::Fp64);
}

// The same teapot's mesh walks, in both modes. Every walk had met all of
// the BVH's boxes and tested all 16256 triangles (robust: 28 466 counted
// turns a walk). Robust's image is not compared: float rounds a generic eye
// 4e10 away by ~2e3 generic units, far outside its envelope
// (docs/numerics.md).
TEST(AgreementRegressions, ATeapotSquashedBetweenRotationsFarAwayWalksOnlyTheBoxesItMeets) {
    const Scene scene =
        loadScene(test::kDataDir + "/difftest/squashed_teapot_far.sdl", {}, nullptr);
    expectWalksWithin1000Turns(scene);
}

// The same teapot among nine spheres out of view: an object BVH, whose walk
// enters the mesh itself and walks its BVH from the same start.
TEST(AgreementRegressions, ATeapotSquashedFarAwayInAnObjectBvhIsDrawnAndWalkedAsAlone) {
    const std::string path = test::kDataDir + "/difftest/squashed_teapot_far.sdl";
    std::ifstream in(path);
    std::string sdl((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (int i = 0; i < 9; ++i)
        sdl += "push translate 500 " + std::to_string(3 * i) + " 0 sphere pop\n";
    Scene scene = parseSdl(sdl, path, {}, nullptr);
    loadSceneGeometry(scene, false, nullptr);
    ASSERT_TRUE(gpu::featuresOf(scene, {32, 24, 1, 2, 0}, false).objectBvh);
    expectSceneAgrees(scene, {32, 24, 1, 2, 0}, Precision::Fp64);
    expectWalksWithin1000Turns(scene);
}

// A cube and an extruded square that coincide with it, among spheres (an
// object BVH, whose walk enters the mesh): their faces tie, and the lower
// object index wins on the GPU as in the reference, in either order.
TEST(AgreementRegressions, AMeshCoincidingWithACubeTiesAsInTheReference) {
    const test::TempFolder scratch("vkray-mesh-tie");
    const std::filesystem::path& dir = scratch.path();
    std::ofstream(dir / "square.dat") << "4\n-1 -1\n1 -1\n1 1\n-1 1\n";
    const std::string prism = "push translate 0 0 -1 scale 1 1 2 extrude square.dat pop\n";
    std::string spheres;
    for (int i = 0; i < 9; ++i)
        spheres +=
            "push translate " + std::to_string(4 + 2 * i) + " 3 0 scale 0.5 0.5 0.5 sphere pop\n";
    const std::string camera = "camera eye 3 2.5 4 look 0 0 0 up 0 1 0 fov 50\n";
    for (const std::string& objects : {"cube\n" + prism, prism + "cube\n"}) {
        SCOPED_TRACE(objects);
        Scene scene = parseSdl(camera + objects + spheres, (dir / "tie.sdl").string(), {}, nullptr);
        loadSceneGeometry(scene, false, nullptr);
        ASSERT_TRUE(gpu::featuresOf(scene, {40, 30}, false).objectBvh);
        expectSceneAgrees(scene, {40, 30}, Precision::Robust);
    }
}

// A hollow glass ball around a glass core (the file's header says how): a
// boolean's surfaces bound the glass from the side their normals give, the
// subtracted ones turned once a difference.
TEST(AgreementRegressions, RaysThroughAHollowGlassBallChangeMediumAtEverySurface) {
    expectExplainedInRobustAndFp64("hollow_glass_ball.sdl", {80, 60});
}

}  // namespace
}  // namespace vkray
