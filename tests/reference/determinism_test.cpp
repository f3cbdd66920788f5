// Determinism: the same scene and options give the same bytes, run after run
// and whatever the thread count, from the CPU reference through the writers.
// (Frame equality across thread counts is in reference_tracer_test.cpp; this
// checks the files a user gets.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "image/aov_images.h"
#include "image/image_io.h"
#include "reference/reference_tracer.h"
#include "render/camera.h"
#include "scene/sdl_reader.h"
#include "support/temp_folder.h"

#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray {
namespace {

namespace fs = std::filesystem;

class Determinism : public ::testing::Test {
protected:
    std::string bytesOf(const std::string& name) const {
        std::ifstream in(dir / name, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }

    // Every file `render -o x.png --aov x` writes, concatenated.
    std::string filesFor(const Frame& frame, const std::string& name) const {
        const std::string prefix = (dir / name).string();
        writeImage(prefix + ".png", colorImage(frame));
        writeAovs(prefix, frame, {});
        return bytesOf(name + ".png") + bytesOf(name + ".depth.pfm") +
               bytesOf(name + ".normal.pfm") + bytesOf(name + ".id.pfm");
    }

    test::TempFolder scratch_{"vkray-determinism"};
    const fs::path dir = scratch_.path();
};

TEST_F(Determinism, CpuReferenceGivesTheSameFilesRunAfterRunWithAnyThreadCount) {
    Scene scene = loadSdlFile(VKRAY_SOURCE_DIR "/scenes/default.sdl", SdlOptions{});
    for (const int block : {1, 3}) {
        const RenderSettings settings{96, 72, block};
        const CameraBasis camera =
            makeCameraBasis(scene.camera.value_or(autoCamera(scene)), 96, 72);
        std::string first;
        for (const int threads : {1, 2, 3, 7, 1, 2, 3, 7}) {
            const Frame frame = reference::render(scene, camera, settings, {threads});
            const std::string files = filesFor(frame, "run");
            if (first.empty()) {
                first = files;
                ASSERT_GT(first.size(), 96u * 72 * 4 * 5);  // 5 floats per pixel in the PFMs
            }
            ASSERT_EQ(files, first) << "block " << block << ", " << threads << " threads";
        }
    }
}

TEST_F(Determinism, WritingTheSameFrameTwiceGivesIdenticalBytes) {
    // Values whose encoding could wobble if it depended on anything but the
    // value: NaN, infinities, -0, values beyond [0, 1], an odd size.
    Frame frame(7, 5);
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (size_t i = 0; i < frame.pixelCount(); ++i) {
        const float f = float(i);
        frame.color[i] = {f / 17, i % 3 ? -0.0f : 2.5f, i % 5 ? nan : inf};
        frame.depth[i] = i % 4 ? f * 0.1f : inf;
        frame.normal[i] = {0, i % 2 ? 1.0f : -1.0f, -0.0f};
        frame.id[i] = i % 6 ? int(i) : -1;
    }
    const std::string once = filesFor(frame, "a");
    EXPECT_EQ(filesFor(frame, "b"), once);
    EXPECT_EQ(filesFor(frame, "a"), once);  // replacing a file gives the same bytes too
}

}  // namespace
}  // namespace vkray
