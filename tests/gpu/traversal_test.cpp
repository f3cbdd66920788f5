// The two traversals: the choice between vkray's own BVH walk and the
// driver's ray queries, and the ray-query walk's renders, which must be the
// own walk's bytes. The renders need a device with ray queries (lavapipe from
// Mesa 24.1: the suite's Mesa 25.0 stage); elsewhere they skip, saying so.
#include "support/frame_difference.h"
#include "support/gpu_fixture.h"

#include "gpu/traversal.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace vkray {
namespace {

namespace fs = std::filesystem;

std::string errorOf(gpu::Traversal asked, const gpu::DeviceInfo& device, const Scene& scene,
                    gpu::ShaderFeatures features) {
    try {
        gpu::chooseTraversal(asked, device, scene, features);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

Scene sceneOf(const std::string& sdl) {
    Scene scene = parseSdl(sdl, "traversal_test.sdl", {});
    loadSceneGeometry(scene, false, nullptr);
    return scene;
}

TEST(Traversal, ParsesItsThreeNamesAndRefusesOthers) {
    EXPECT_EQ(gpu::parseTraversal("--traversal", "own"), gpu::Traversal::Own);
    EXPECT_EQ(gpu::parseTraversal("--traversal", "rayquery"), gpu::Traversal::RayQuery);
    EXPECT_EQ(gpu::parseTraversal("--traversal", "auto"), gpu::Traversal::Auto);
    try {
        gpu::parseTraversal("--traversal", "embree");
        FAIL() << "embree accepted";
    } catch (const std::exception& e) {
        EXPECT_STREQ(e.what(), "--traversal 'embree': expected own, rayquery or auto");
    }
}

TEST(Traversal, RayQueriesAreRefusedWhereTheyCannotRunAndAutoSaysWhy) {
    const Scene spheres = sceneOf("sphere\ntranslate 2 0 0 sphere\n");
    const Scene planes = sceneOf("plane\n");
    const RenderSettings settings{32, 32, 1, 1};
    const gpu::ShaderFeatures features = gpu::featuresOf(spheres, settings, false);
    gpu::DeviceInfo without;
    without.index = 0;
    without.name = "a device";
    gpu::DeviceInfo with = without;
    with.rayQuery = true;

    EXPECT_NE(errorOf(gpu::Traversal::RayQuery, without, spheres, features)
                  .find("--traversal rayquery: the device 0 (a device) has no ray queries"),
              std::string::npos);
    EXPECT_NE(
        errorOf(gpu::Traversal::RayQuery, with, planes, gpu::featuresOf(planes, settings, false))
            .find("the scene has no bounded object"),
        std::string::npos);
    gpu::ShaderFeatures stress = features;
    stress.stressOutput = true;
    EXPECT_NE(errorOf(gpu::Traversal::RayQuery, with, spheres, stress).find("stress and debug"),
              std::string::npos);

    gpu::ShaderFeatures chosen = features;
    EXPECT_NE(gpu::chooseTraversal(gpu::Traversal::Auto, without, spheres, chosen)
                  .find("own walk (auto: the device 0 (a device) has no ray queries"),
              std::string::npos);
    EXPECT_FALSE(chosen.rayQuery);
    EXPECT_EQ(gpu::chooseTraversal(gpu::Traversal::Own, with, spheres, chosen),
              "own walk (--traversal own)");
    EXPECT_FALSE(chosen.rayQuery);
    gpu::chooseTraversal(gpu::Traversal::RayQuery, with, spheres, chosen);
    EXPECT_TRUE(chosen.rayQuery);
    EXPECT_TRUE(chosen.objectBvh) << "the structure's boxes are the BVH's entries";
    EXPECT_FALSE(gpu::hintsFeelers(chosen));
    EXPECT_FALSE(gpu::placesTrianglesInWorld(chosen));
    EXPECT_FALSE(gpu::meshNodesWithObjects(chosen));
}

#define VKRAY_NEED_RAY_QUERIES()                                                              \
    if (!test::gpuContext().device().rayQuery)                                                \
    GTEST_SKIP() << "the device (" << test::gpuContext().device().name                        \
                 << ") has no ray queries: the ray-query walk runs in the suite's Mesa 25.0 " \
                    "stage (lavapipe has them from Mesa 24.1)"

struct Case {
    std::string path;
    Precision precision;
};

void PrintTo(const Case& c, std::ostream* out) {
    *out << fs::path(c.path).filename().string() << " " << precisionName(c.precision);
}

class RayQueryWalk : public ::testing::TestWithParam<Case> {};

// The same bytes, not a tolerance: each object the driver's boxes let
// through is tested by the own walk's code (testObject), and a hit is
// chosen by the same rule (nearest, ties to the lower index), whatever the
// order the objects come in. The own walk here takes each mesh in its
// generic space, as the ray-query walk does (not its triangles in world
// space: other arithmetic). A box the driver culled that held a hit would
// show as a differing id.
TEST_P(RayQueryWalk, RendersTheOwnWalksBytes) {
    VKRAY_NEED_RAY_QUERIES();
    const Case& c = GetParam();
    const Scene scene = loadScene(c.path, {.lenient = true}, nullptr);
    const RenderSettings settings{128, 96, 1, 1};
    const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    const CameraBasis basis = makeCameraBasis(camera, settings.width, settings.height);
    const auto render = [&](gpu::Traversal traversal, gpu::GpuRenderStats& stats) {
        gpu::GpuTracer tracer(test::gpuContext(), {.shaderDirectory = test::kShaderDir,
                                                   .worldTriangles = false,
                                                   .precision = c.precision,
                                                   .traversal = traversal});
        return tracer.render(scene, basis, settings, &stats);
    };
    gpu::GpuRenderStats own, rayQuery;
    const Frame a = render(gpu::Traversal::Own, own);
    const Frame b = render(gpu::Traversal::RayQuery, rayQuery);
    EXPECT_EQ(own.variant.find("+ray-query"), std::string::npos) << own.variant;
    EXPECT_NE(rayQuery.variant.find("+ray-query"), std::string::npos) << rayQuery.variant;
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(test::differingValues(a.color, b.color), 0u) << "colour bits differ";
    EXPECT_EQ(test::differingValues(a.depth, b.depth), 0u);
    EXPECT_EQ(test::differingValues(a.normal, b.normal), 0u);
    EXPECT_GT(std::count_if(a.id.begin(), a.id.end(), [](int id) { return id >= 0; }), 50);
}

std::vector<Case> cases() {
    std::vector<Case> result;
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(test::kSourceDir + "/scenes"))
        if (entry.path().extension() == ".sdl") files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
    for (const std::string& file : files) result.push_back({file, Precision::Robust});
    for (const char* name : {"shadow_hints.sdl", "world_triangles.sdl", "gallery.dat"})
        result.push_back({test::kDataDir + "/" + name, Precision::Robust});
    // The other modes' arithmetic in the same tests, and the hollow glass
    // ball's surfaces met from inside.
    result.push_back({test::kSourceDir + "/scenes/whitted.sdl", Precision::Fp64});
    result.push_back({test::kSourceDir + "/scenes/csg.sdl", Precision::Fp64});
    result.push_back({test::kSourceDir + "/scenes/quadrics.sdl", Precision::Naive});
    result.push_back({test::kDataDir + "/difftest/hollow_glass_ball.sdl", Precision::Robust});
    return result;
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string name = fs::path(info.param.path).stem().string();
    for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return name + "_" + precisionName(info.param.precision);
}

INSTANTIATE_TEST_SUITE_P(Scenes, RayQueryWalk, ::testing::ValuesIn(cases()), caseName);

// A device without ray queries (VKRAY_FAULT=no-ray-query on one with them,
// or Mesa 22.3's lavapipe) refuses --traversal rayquery with what to do.
TEST(RayQueryWalk, IsRefusedOnADeviceWithoutThem) {
    if (test::gpuContext().device().rayQuery) GTEST_SKIP() << "this device has ray queries";
    const Scene scene = sceneOf("sphere\n");
    gpu::GpuTracer tracer(test::gpuContext(), {.shaderDirectory = test::kShaderDir,
                                               .traversal = gpu::Traversal::RayQuery});
    try {
        tracer.render(scene, makeCameraBasis(autoCamera(scene), 8, 8), {8, 8, 1, 1});
        FAIL() << "rendered without ray queries";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("has no ray queries"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("render with --traversal own"), std::string::npos);
    }
}

}  // namespace
}  // namespace vkray
