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

// The bounds this project states (docs/gpu-vs-reference.md):
constexpr double kMinIdAgreement = 0.999;        // object ids agree on >= 99.9 % of pixels
constexpr double kMaxColorRmse = 0.01;           // colour RMSE over all pixels
constexpr double kMaxAgreeingColorError = 1e-3;  // colour error where the ids agree ...
// ... on all but this fraction of the pixels. Whitted shading follows shadow
// feelers and reflected and refracted rays from every hit: one that grazes
// an edge or lands on a texture's cell border can go the other way in float
// than in double, however close the two primary hits are, and refraction
// magnifies the difference. whitted.sdl, the worst scene here, has 0.094 % of
// such pixels at 160x120 (block 1 and 3; 0.33 % with --spp 4, where each
// pixel has four chances); the others at most 0.05 %. Such pixels are
// isolated, so RMSE stays far below its bound. The largest error there is
// printed, not bounded (0.26 on whitted.sdl); docs/gpu-vs-reference.md quotes the figures.
constexpr double kMaxDisagreeingFraction = 0.005;  // of all the image's pixels

// Depth where both hit the same object, float against double: 1e-4 of it,
// and more at grazing incidence, where t = distance / cos(incidence) moves by
// about u / |cos| of itself for a float direction rounded by u (16 u: a few
// roundings of the direction, whose normalize Vulkan lets a device compute
// 2 ulp off; lavapipe stays within the 1e-4, an NVIDIA H200 did not).
void expectDepthsAgree(const Frame& gpu, const Frame& cpu, const CameraBasis& camera,
                       const RenderSettings& settings) {
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x) {
            const size_t i = gpu.index(x, y);
            if (gpu.id[i] != cpu.id[i] || gpu.id[i] < 0) continue;
            const glm::dvec3 d =
                primaryDirection(camera, settings, jitteredSample(x, y, settings, 0));
            const double cosine = std::abs(glm::dot(d, glm::dvec3(cpu.normal[i])));
            const double bound =
                cpu.depth[i] * (1e-4 + 16 * 0x1p-24 / std::max(cosine, 1e-12)) + 1e-5;
            ASSERT_NEAR(gpu.depth[i], cpu.depth[i], bound) << x << "," << y;
        }
}

struct Agreement {
    double idAgreement, rmse, maxErrorWhereIdsAgree;
    double
        disagreeingFraction;  // pixels with the same id and an error above kMaxAgreeingColorError
};

Agreement compareFrames(const Frame& gpu, const Frame& cpu) {
    const CompareResult color = compareImages(colorImage(gpu), colorImage(cpu), {});
    size_t same = 0, disagreeing = 0;
    double maxAgreeing = 0;
    for (size_t i = 0; i < gpu.pixelCount(); ++i) {
        if (gpu.id[i] != cpu.id[i]) continue;
        ++same;
        double error = 0;
        for (int c = 0; c < 3; ++c)
            error = std::max<double>(error, std::abs(std::clamp(gpu.color[i][c], 0.f, 1.f) -
                                                     std::clamp(cpu.color[i][c], 0.f, 1.f)));
        maxAgreeing = std::max(maxAgreeing, error);
        if (error > kMaxAgreeingColorError) ++disagreeing;
    }
    const double pixels = double(gpu.pixelCount());
    return {double(same) / pixels, color.rmse, maxAgreeing, double(disagreeing) / pixels};
}

void expectAgreement(const Agreement& a) {
    EXPECT_GE(a.idAgreement, kMinIdAgreement);
    EXPECT_LE(a.rmse, kMaxColorRmse);
    EXPECT_LE(a.disagreeingFraction, kMaxDisagreeingFraction)
        << "largest error where the ids agree: " << a.maxErrorWhereIdsAgree;
}

void printAgreement(const std::string& what, const Agreement& a) {
    std::printf(
        "%-36s ids agree %.4f %%, colour RMSE %.2e, max error where ids agree %.2e "
        "(%.3f %% of pixels above %.0e)\n",
        what.c_str(), 100 * a.idAgreement, a.rmse, a.maxErrorWhereIdsAgree,
        100 * a.disagreeingFraction, kMaxAgreeingColorError);
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
        const Agreement a = compareFrames(gpu, cpu);
        printAgreement(fs::path(path).filename().string() + " block " + std::to_string(block) + ":",
                       a);
        expectAgreement(a);
        expectDepthsAgree(gpu, cpu, basis, settings);
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
        const Agreement a = compareFrames(gpu, cpu);
        printAgreement("whitted.sdl --spp 4 block " + std::to_string(block) + ":", a);
        expectAgreement(a);
        expectDepthsAgree(gpu, cpu, basis, settings);
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
