// Determinism on the GPU: the same scene and options give the same bits on the
// same device, run after run, with a fresh Vulkan context (device, pipeline,
// buffers) each time, and whatever the tile size. Every pixel's value depends
// only on its own ray, so nothing but a bug (a race, uninitialised memory, a
// read past a buffer) can make two runs differ.
#include "support/gpu_fixture.h"

#include "scene/scene_geometry.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

namespace vkray {
namespace {

namespace fs = std::filesystem;

// Bitwise, so that -0 vs 0 or two NaN payloads would count as different.
template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expectIdentical(const Frame& a, const Frame& b, const std::string& what) {
    EXPECT_TRUE(sameBits(a.color, b.color)) << what << ": colour";
    EXPECT_TRUE(sameBits(a.depth, b.depth)) << what << ": depth";
    EXPECT_TRUE(sameBits(a.normal, b.normal)) << what << ": normal";
    EXPECT_TRUE(sameBits(a.id, b.id)) << what << ": id";
}

// Renders `scene` with block 1 and block 3 on a context of its own.
std::vector<Frame> renderWithFreshContext(const Scene& scene, int tileSize) {
    gpu::Context context;
    gpu::GpuTracer tracer(context, {.shaderDirectory = test::kShaderDir, .tileSize = tileSize});
    std::vector<Frame> frames;
    for (const int block : {1, 3}) {
        const RenderSettings settings{120, 90, block};
        const CameraBasis camera = makeCameraBasis(scene.camera.value_or(autoCamera(scene)),
                                                   settings.width, settings.height);
        frames.push_back(tracer.render(scene, camera, settings));
    }
    return frames;
}

TEST(GpuDeterminism, EverySceneGivesTheSameBitsRunAfterRun) {
    int scenes = 0;
    for (const auto& entry : fs::directory_iterator(test::kSourceDir + "/scenes")) {
        if (entry.path().extension() != ".sdl") continue;
        ++scenes;
        const Scene scene = loadScene(entry.path().string(), {}, nullptr);
        const std::string name = entry.path().filename().string();
        // A second run on a fresh context, in tiles of 48 pixels (a multiple of
        // both blocks): 6 dispatches instead of one, the same bits.
        const std::vector<Frame> first = renderWithFreshContext(scene, 256);
        const std::vector<Frame> again = renderWithFreshContext(scene, 48);
        for (size_t i = 0; i < first.size(); ++i)
            expectIdentical(again[i], first[i], name + (i ? ", block 3" : ", block 1"));
    }
    EXPECT_GE(scenes, 8);
}

}  // namespace
}  // namespace vkray
