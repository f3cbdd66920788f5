// The GPU (float) against the CPU reference (double) on every scene in
// scenes/ and tests/data, and on the corpus scenes when VKRAY_SDL_CORPUS names
// the corpus (lenient: missing meshes are left out). Silhouette pixels may
// pick different objects in float and double, and secondary rays that graze
// an edge may take different paths; everywhere else the two must agree to
// float accuracy.
#include "support/gpu_fixture.h"

#include "image/aov_images.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "numerics/agreement.h"
#include "reference/reference_tracer.h"
#include "scene/scene_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>

namespace vkray {
namespace {

namespace fs = std::filesystem;

// The margin rule (numerics/agreement.h, docs/gpu-vs-reference.md): every
// pixel whose colour (above 0.02, unclamped), id, depth or normal differs
// must be one the robust mode's error bound explains; the rest fail.
void expectAgreement(const std::string& what, const Scene& scene, const CameraBasis& camera,
                     const RenderSettings& settings, const Frame& gpu, const Frame& cpu) {
    const Agreement a = judgeAgreement(scene, camera, settings, Precision::Robust, gpu, cpu, {});
    std::printf("%-36s %zu pixels differ, %zu set aside (%.3f %%), %zu unexplained; largest %.2e\n",
                what.c_str(), a.differing, a.setAside,
                100.0 * double(a.setAside) / double(a.pixels), a.unexplained, a.largest);
    EXPECT_EQ(a.unexplained, 0u) << formatAgreement(a, {});
}

struct SceneFile {
    std::string path;  // for a corpus scene, its name in the corpus
    bool inCorpus = false;
    bool readsTestmodels = false;  // names files of Debian's assimp-testmodels
};

const char* const kTestmodels = "/usr/share/assimp/models";

// gtest's name for a case in its messages (else it prints the struct's bytes).
void PrintTo(const SceneFile& file, std::ostream* out) {
    *out << file.path;
}

class GpuVsReference : public ::testing::TestWithParam<SceneFile> {};

TEST_P(GpuVsReference, AgreeWithinStatedBounds) {
    if (GetParam().inCorpus) VKRAY_NEED_CORPUS();
    if (GetParam().readsTestmodels && !fs::is_directory(kTestmodels))
        GTEST_SKIP() << kTestmodels << " is missing: install Debian's assimp-testmodels "
                     << "(scripts/install-deps.sh does)";
    const std::string path =
        GetParam().inCorpus ? test::corpusFile(GetParam().path) : GetParam().path;
    std::vector<std::string> warnings;
    Scene scene = loadScene(path, {true}, &warnings);
    ASSERT_FALSE(scene.objects.empty());
    const Camera camera = scene.camera ? *scene.camera : autoCamera(scene);
    for (int block : {1, 3}) {
        const RenderSettings settings{160, 120, block};
        const CameraBasis basis = makeCameraBasis(camera, settings.width, settings.height);
        const Frame gpu = test::renderOnGpu(scene, basis, settings);
        const Frame cpu = reference::render(scene, basis, settings);
        expectAgreement(
            fs::path(path).filename().string() + " block " + std::to_string(block) + ":", scene,
            basis, settings, gpu, cpu);
    }
}

// Anti-aliasing: both renderers place the samples with shaders/sampling.h,
// so with the same seed they trace the same rays; the pixel is their mean
// and the AOVs are sample 0's.
TEST(GpuVsReferenceSampling, WhittedSceneWithFourSamples) {
    Scene scene = loadScene(test::kSourceDir + "/scenes/whitted.sdl", {}, nullptr);
    for (int block : {1, 2}) {
        const RenderSettings settings{160, 120, block, 4, 7};
        const CameraBasis basis = makeCameraBasis(*scene.camera, settings.width, settings.height);
        const Frame gpu = test::renderOnGpu(scene, basis, settings);
        const Frame cpu = reference::render(scene, basis, settings);
        expectAgreement("whitted.sdl --spp 4 block " + std::to_string(block) + ":", scene, basis,
                        settings, gpu, cpu);
    }
}

std::vector<SceneFile> projectScenes() {
    std::vector<SceneFile> files;
    for (const auto& entry : fs::directory_iterator(test::kSourceDir + "/scenes"))
        if (entry.path().extension() == ".sdl") files.push_back({entry.path().string()});
    std::sort(files.begin(), files.end(),
              [](const SceneFile& a, const SceneFile& b) { return a.path < b.path; });
    return files;
}

std::vector<SceneFile> dataScenes() {
    std::vector<SceneFile> files;
    for (const char* name : {"gallery.dat", "kitchen.dat", "tower.dat", "world_triangles.sdl"})
        files.push_back({test::kDataDir + "/" + name});
    // OBJ and glTF files by others, through Assimp.
    files.push_back({test::kDataDir + "/real_models.sdl", false, true});
    return files;
}

// By name: the list of tests must not depend on whether the corpus is there.
std::vector<SceneFile> corpusScenes() {
    std::vector<SceneFile> files;
    for (const char* name : {"bookScene.dat", "castle.dat", "hlScene1.dat"})
        files.push_back({name, true});
    return files;
}

std::string sceneName(const ::testing::TestParamInfo<SceneFile>& info) {
    std::string name = fs::path(info.param.path).stem().string();
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, GpuVsReference, ::testing::ValuesIn(projectScenes()), sceneName);
INSTANTIATE_TEST_SUITE_P(TestData, GpuVsReference, ::testing::ValuesIn(dataScenes()), sceneName);
// Skipped without VKRAY_SDL_CORPUS.
INSTANTIATE_TEST_SUITE_P(Corpus, GpuVsReference, ::testing::ValuesIn(corpusScenes()), sceneName);

}  // namespace
}  // namespace vkray
