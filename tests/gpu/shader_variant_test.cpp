// Shader variants: a scene's specialised variant (only the shapes it uses)
// renders exactly the image of the all-features variant, for every scene
// here and the corpus; and each variant declares exactly the bindings the
// host uploads (bindingsFor).
#include "support/gpu_fixture.h"

#include "gpu/spirv_cache.h"
#include "scene/scene_geometry.h"
#include "shaders/layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <set>

namespace vkray {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> scenesToRender() {
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(test::kSourceDir + "/scenes"))
        if (entry.path().extension() == ".sdl") files.push_back(entry.path().string());
    for (const char* corpus : {"hlScene1.dat", "bookScene.dat", "castle.dat"})
        files.push_back(test::kCorpusDir + "/" + corpus);
    std::sort(files.begin(), files.end());
    return files;
}

// Bit patterns, so that -0 against +0 or two NaNs count as what they are.
template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

class SpecializedVsAllFeatures : public ::testing::TestWithParam<std::string> {};

// Same bytes, not a tolerance: the variants differ only in which `case`s of
// intersectObject (and which shape files) are compiled in; the code each
// object runs, and so lavapipe's arithmetic for it, is the same.
TEST_P(SpecializedVsAllFeatures, RenderTheSameBytes) {
    const Scene scene = loadScene(GetParam(), {true}, nullptr);
    ASSERT_FALSE(scene.objects.empty());
    const gpu::ShaderFeatures specialised = gpu::featuresOf(scene, false);
    const gpu::ShaderFeatures all = gpu::featuresOf(scene, true);
    ASSERT_NE(specialised, all) << "no scene here uses every shape kind";
    std::printf("%-16s %-40s vs %s\n", fs::path(GetParam()).filename().c_str(),
                gpu::describe(specialised).c_str(), gpu::describe(all).c_str());
    const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    for (int block : {1, 3}) {
        const RenderSettings settings{160, 120, block};
        const CameraBasis basis = makeCameraBasis(camera, settings.width, settings.height);
        gpu::GpuRenderStats statsScene, statsAll;
        const Frame a = test::renderOnGpu(scene, basis, settings, &statsScene, false);
        const Frame b = test::renderOnGpu(scene, basis, settings, &statsAll, true);
        ASSERT_EQ(statsScene.variant, gpu::describe(specialised));
        ASSERT_EQ(statsAll.variant, gpu::describe(all));
        size_t differing = 0;
        for (size_t i = 0; i < a.pixelCount(); ++i)
            differing += std::memcmp(&a.color[i], &b.color[i], sizeof a.color[i]) != 0 ? 1 : 0;
        EXPECT_EQ(differing, 0u) << "block " << block << ": colour bits differ";
        EXPECT_TRUE(sameBits(a.depth, b.depth)) << "block " << block;
        EXPECT_TRUE(sameBits(a.normal, b.normal)) << "block " << block;
        EXPECT_EQ(a.id, b.id) << "block " << block;
        // Not an empty picture: the comparison covers hits.
        EXPECT_GT(std::count_if(a.id.begin(), a.id.end(), [](int id) { return id >= 0; }), 100);
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SpecializedVsAllFeatures, ::testing::ValuesIn(scenesToRender()),
                         [](const auto& info) {
                             std::string name = fs::path(info.param).stem().string();
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

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

TEST(ShaderVariant, BindingsMatchTheSpirv) {
    // Each kind alone, with and without the object BVH and the debug record,
    // and all of them: every #if around a binding is on in one and off in another.
    std::vector<gpu::ShaderFeatures> variants;
    for (size_t kind = 0; kind <= gpu::kGpuKinds.size(); ++kind)
        for (bool bvh : {false, true})
            for (bool debug : {false, true}) {
                gpu::ShaderFeatures f;
                if (kind < gpu::kGpuKinds.size()) f.kinds[kind] = true;
                else f.kinds.fill(true);
                f.objectBvh = bvh;
                f.debugPixel = debug;
                variants.push_back(f);
            }
    for (const gpu::ShaderFeatures& f : variants) {
        const gpu::CompiledShader shader =
            gpu::loadOrCompile({test::kShaderDir, "trace.comp", gpu::definesFor(f)});
        std::set<std::uint32_t> expected;
        for (const gpu::ShaderBinding& b : gpu::bindingsFor(f)) expected.insert(b.binding);
        EXPECT_EQ(spirvBindings(shader.spirv), expected) << gpu::describe(f);
    }
}

TEST(ShaderVariant, FeaturesFollowTheScene) {
    const Scene csg = loadScene(test::kSourceDir + "/scenes/csg.sdl", {}, nullptr);
    const gpu::ShaderFeatures f = gpu::featuresOf(csg, false);
    EXPECT_TRUE(f.kinds[gpu::KIND_BOOLEAN]);
    EXPECT_FALSE(f.kinds[gpu::KIND_TORUS]);
    // Every shape in csg.sdl is an operand of a boolean: the spheres and
    // cubes inside them still need their code.
    EXPECT_TRUE(f.kinds[gpu::KIND_SPHERE]);
    EXPECT_TRUE(f.kinds[gpu::KIND_CUBE]);
    // The object BVH follows the number of bounded objects, in both variants.
    Scene nine;
    for (int i = 0; i < 9; ++i) nine.objects.push_back(SceneObject{});
    EXPECT_TRUE(gpu::featuresOf(nine, false).objectBvh);
    EXPECT_TRUE(gpu::featuresOf(nine, true).objectBvh);
    nine.objects.pop_back();
    EXPECT_FALSE(gpu::featuresOf(nine, false).objectBvh);
    EXPECT_EQ(gpu::describe(gpu::featuresOf(nine, false)), "sphere");
    EXPECT_EQ(gpu::describe(gpu::featuresOf(nine, true)), "all shapes");
}

}  // namespace
}  // namespace vkray
