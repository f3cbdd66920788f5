// Leaving code out changes nothing: every scene in scenes/, tests/data and
// the corpus (when VKRAY_SDL_CORPUS names it) renders the same bytes in its
// specialised variant (only its shapes and shading) and in the all-features
// variant; and each variant declares exactly the bindings the host uploads
// (bindingsFor).
#include "support/frame_difference.h"
#include "support/gpu_fixture.h"

#include "gpu/shader_variant.h"
#include "gpu/spirv_cache.h"
#include "scene/scene_geometry.h"
#include "shaders/layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <ostream>
#include <set>

namespace vkray {
namespace {

namespace fs = std::filesystem;

// The scenes rendered: scenes/*.sdl, tests/data's scenes and the corpus's.
// Lenient for all: the corpus and tests/data need it (words Hill's grammar
// lacks, missing meshes), and our scenes read the same either way.
std::vector<std::string> projectScenes() {
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(test::kSourceDir + "/scenes"))
        if (entry.path().extension() == ".sdl") files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

// tests/data's scenes that render (the others there are meshes and outlines).
const char* const kDataScenes[] = {"gallery.dat", "kitchen.dat", "shadow_hints.sdl", "tower.dat",
                                   "world_triangles.sdl"};
// The corpus's scenes, by name: the list of tests must not depend on whether
// the corpus is there (hlArch.dat is an outline that castle.dat extrudes).
const char* const kCorpusScenes[] = {"bookScene.dat", "castle.dat", "hlScene1.dat"};

struct Case {
    std::string path;  // for a corpus scene, its name in the corpus
    int spp;
    bool inCorpus = false;
};

// gtest's name for a case in its messages (else it prints the struct's bytes).
void PrintTo(const Case& c, std::ostream* out) {
    *out << fs::path(c.path).filename().string() << " --spp " << c.spp;
}

class SpecialisedVsAllFeatures : public ::testing::TestWithParam<Case> {};

// Same bytes, not a tolerance. A variant only drops code that cannot run for
// its scene: the `case`s of shapes it lacks, and shading whose run-time
// condition can never hold (a reflection test that is always false, a
// feeler that cannot meet anything). What remains is the same source, so
// lavapipe computes the same arithmetic, in the same order, for every ray.
// Small images (96x72) keep this cheap; spp 3 covers the antialiasing code.
// Where the specialised variant would place the mesh objects' triangles in
// world space (other arithmetic, not less code), it walks them in their
// generic space here, as the all-features variant does; the test below
// compares the two.
TEST_P(SpecialisedVsAllFeatures, RenderTheSameBytes) {
    const Case& c = GetParam();
    if (c.inCorpus) VKRAY_NEED_CORPUS();
    const std::string path = c.inCorpus ? test::corpusFile(c.path) : c.path;
    const Scene scene = loadScene(path, {.lenient = true}, nullptr);
    ASSERT_FALSE(scene.objects.empty());
    RenderSettings settings{96, 72, 1, c.spp};
    const gpu::ShaderFeatures specialised = gpu::featuresOf(scene, settings, false);
    const gpu::ShaderFeatures all = gpu::featuresOf(scene, settings, true);
    ASSERT_NE(specialised, all) << "no scene here uses every feature";
    std::printf("%-16s spp %d: %s vs %s\n", fs::path(c.path).filename().c_str(), c.spp,
                gpu::describe(specialised).c_str(), gpu::describe(all).c_str());
    const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    const CameraBasis basis = makeCameraBasis(camera, settings.width, settings.height);
    gpu::GpuRenderStats statsScene, statsAll;
    const Frame a = test::renderOnGpu(scene, basis, settings, &statsScene, false, false);
    const Frame b = test::renderOnGpu(scene, basis, settings, &statsAll, true);
    ASSERT_EQ(statsScene.variant, gpu::describe(specialised));
    ASSERT_EQ(statsAll.variant, gpu::describe(all));
    EXPECT_EQ(test::differingValues(a.color, b.color), 0u) << "colour bits differ";
    EXPECT_EQ(test::differingValues(a.depth, b.depth), 0u);
    EXPECT_EQ(test::differingValues(a.normal, b.normal), 0u);
    EXPECT_EQ(a.id, b.id);
    // Not an empty picture: the comparison covers hits.
    EXPECT_GT(std::count_if(a.id.begin(), a.id.end(), [](int id) { return id >= 0; }), 50);
}

std::vector<Case> sceneCases() {
    std::vector<Case> result;
    for (const std::string& path : projectScenes()) result.push_back({path, 1});
    for (const char* name : {"/scenes/textures.sdl", "/scenes/whitted.sdl"})
        result.push_back({test::kSourceDir + name, 3});
    return result;
}

std::vector<Case> dataCases() {
    std::vector<Case> result;
    for (const char* name : kDataScenes) result.push_back({test::kDataDir + "/" + name, 1});
    return result;
}

std::vector<Case> corpusCases() {
    std::vector<Case> result;
    for (const char* name : kCorpusScenes) result.push_back({name, 1, true});
    return result;
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
    std::string name = fs::path(info.param.path).stem().string();
    for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return name + "_spp" + std::to_string(info.param.spp);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SpecialisedVsAllFeatures, ::testing::ValuesIn(sceneCases()),
                         caseName);
INSTANTIATE_TEST_SUITE_P(TestData, SpecialisedVsAllFeatures, ::testing::ValuesIn(dataCases()),
                         caseName);
// Skipped without VKRAY_SDL_CORPUS.
INSTANTIATE_TEST_SUITE_P(Corpus, SpecialisedVsAllFeatures, ::testing::ValuesIn(corpusCases()),
                         caseName);

// A feeler's hint (VKRAY_FEELER_HINTS) changes how long its walk takes,
// never whether it gets through: the same bytes with every hint replaced by
// a number made from the pixel and the light (VKRAY_ARBITRARY_HINTS, a test
// hook), the entry of any object (the half-transparent cube's, whose
// transparency must not count twice, the torus's, which waits on the list
// of kept objects, the mesh's) or none. The scene's feelers meet all three.
TEST(FeelerHints, ThePictureDoesNotDependOnThem) {
    const Scene scene = loadScene(test::kDataDir + "/shadow_hints.sdl", {}, nullptr);
    const RenderSettings settings{192, 144, 1, 1};
    ASSERT_TRUE(gpu::hintsFeelers(gpu::featuresOf(scene, settings, false)));
    const CameraBasis basis = makeCameraBasis(*scene.camera, settings.width, settings.height);
    gpu::GpuTracer hinted(test::gpuContext(), {.shaderDirectory = test::kShaderDir});
    gpu::GpuTracer arbitrary(test::gpuContext(), {.shaderDirectory = test::kShaderDir,
                                                  .userDefines = {{"VKRAY_ARBITRARY_HINTS", "1"}}});
    const Frame a = hinted.render(scene, basis, settings);
    const Frame b = arbitrary.render(scene, basis, settings);
    EXPECT_EQ(test::differingValues(a.color, b.color), 0u) << "colour bits differ";
    EXPECT_EQ(a.id, b.id);
}

// Mesh objects' triangles placed in world space (VKRAY_WORLD_TRIANGLES) are
// other arithmetic than each mesh walked in its generic space: float rounds
// each corner's M p once instead of each ray's M^-1 (o + t d). The two differ
// only where a ray grazes a silhouette or a feeler an edge: within the
// bounds of the GPU against the CPU reference (gpu_vs_reference_test.cpp).
// castle.dat's extrusions are two objects of one mesh among 218 others.
TEST(WorldTriangles, AgreeWithTheMeshesWalkedInTheirGenericSpace) {
    std::vector<std::string> paths{test::kDataDir + "/world_triangles.sdl"};
    if (test::corpusDir()) paths.push_back(test::corpusFile("castle.dat"));
    for (const std::string& path : paths) {
        const Scene scene = loadScene(path, {.lenient = true}, nullptr);
        const RenderSettings settings{240, 180, 1, 1};
        const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
        const CameraBasis basis = makeCameraBasis(camera, settings.width, settings.height);
        gpu::GpuRenderStats world, generic;
        const Frame a = test::renderOnGpu(scene, basis, settings, &world, false, true);
        const Frame b = test::renderOnGpu(scene, basis, settings, &generic, false, false);
        EXPECT_NE(world.variant.find("+world-triangles"), std::string::npos) << world.variant;
        EXPECT_EQ(generic.variant.find("+world-triangles"), std::string::npos) << generic.variant;
        const test::FrameDifference d = test::frameDifference(a, b, 1e-3);
        const double pixels = double(a.pixelCount());
        std::printf("%s: ids differ on %zu pixels, colour by over 1e-3 on %zu (max %.3g)\n",
                    fs::path(path).filename().c_str(), d.ids, d.over, d.maxColor);
        EXPECT_LE(double(d.ids), 0.001 * pixels) << path;
        EXPECT_LE(double(d.over), 0.005 * pixels) << path;
    }
}

// The Binding decorations of a SPIR-V module (OpDecorate %id Binding n).
std::set<std::uint32_t> spirvBindings(const std::vector<std::uint32_t>& spirv) {
    constexpr std::uint32_t kOpDecorate = 71, kDecorationBinding = 33;
    std::set<std::uint32_t> bindings;
    for (size_t i = 5; i < spirv.size();) {
        const std::uint32_t words = spirv[i] >> 16, opcode = spirv[i] & 0xffffu;
        if (words == 0) break;
        if (opcode == kOpDecorate && words >= 4 && spirv[i + 2] == kDecorationBinding)
            bindings.insert(spirv[i + 3]);
        i += words;
    }
    return bindings;
}

// The host uploads a buffer for each of bindingsFor() and nothing else
// (GpuTracer checks that); here bindingsFor() is checked against what the
// compiled shader declares, so no variant binds a buffer it never reads.
TEST(ShaderVariant, BindingsMatchTheSpirv) {
    // Each kind alone, each shading feature alone, with and without the
    // object BVH and the debug record, and all: every #if around a binding
    // is on in one and off in another.
    std::vector<gpu::ShaderFeatures> variants;
    const size_t kinds = gpu::kGpuKinds.size(), shadings = gpu::kGpuShading.size();
    for (size_t feature = 0; feature <= kinds + shadings; ++feature)
        for (bool bvh : {false, true})
            for (bool debug : {false, true}) {
                gpu::ShaderFeatures f;
                f.kinds[gpu::KIND_SPHERE] = true;
                if (feature < kinds)
                    f.kinds[feature] = true;
                else if (feature < kinds + shadings)
                    f.shading[feature - kinds] = true;
                else {
                    f.kinds.fill(true);
                    f.shading.fill(true);
                }
                f.objectBvh = bvh;
                f.debugPixel = debug;
                variants.push_back(f);
            }
    for (const gpu::ShaderFeatures& f : variants) {
        const gpu::CompiledShader shader =
            gpu::loadOrCompile({test::kShaderDir, "trace.comp",
                                gpu::definesFor(f, precisionDefines(Precision::Robust))});
        std::set<std::uint32_t> expected;
        for (const gpu::ShaderBinding& b : gpu::bindingsFor(f)) expected.insert(b.binding);
        EXPECT_EQ(spirvBindings(shader.spirv), expected) << gpu::describe(f);
    }
}

}  // namespace
}  // namespace vkray
