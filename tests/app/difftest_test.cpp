// `vkray difftest`: a fixed set of seeds draws scenes on which the GPU and
// the CPU reference agree, and a GPU that draws something else is caught,
// its scene kept with the command that shows it.
#include "support/cli_fixture.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

namespace {

using vkray::test::RunResult;
using vkray::test::vkray;
using Difftest = vkray::test::CliTest;
namespace fs = std::filesystem;

size_t scenesLeftIn(const fs::path& folder) {
    size_t n = 0;
    for (const auto& entry : fs::directory_iterator(folder))
        n += entry.path().extension() == ".sdl";
    return n;
}

TEST_F(Difftest, TheFixedSeedsAgree) {
    // Seeds 100..107 draw six robust and two fp64 scenes: a lone huge
    // object seen from close, a view close above a huge object, far views
    // (fp64's 2.8e5 object sizes away with a squash of 1.5e-6, robust's to
    // 1.1e3), booleans, polyhedra, meshes, tapers and textures among them.
    RunResult run = vkray("difftest --scenes 8 --seed 100 --out " + path("found"));
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("difftest: 8 passed, 0 failed"), std::string::npos) << run.output;
    EXPECT_EQ(scenesLeftIn(dir / "found"), 0u) << run.output;  // agreeing scenes are not kept
}

// The shaders as built, `from` replaced by `to` in the copy's file `name`
// (which must hold it), in the test's folder: a GPU that is wrong as the
// test wants it.
fs::path shadersWith(const fs::path& dir, const std::string& name,
                     const std::vector<std::pair<std::string, std::string>>& edits) {
    const fs::path shaders = fs::path(VKRAY_BINARY).parent_path() / "shaders";
    fs::copy(shaders, dir / "shaders", fs::copy_options::recursive);
    const fs::path file = dir / "shaders" / name;
    std::stringstream text;
    text << std::ifstream(file).rdbuf();
    std::string source = text.str();
    for (const auto& [from, to] : edits) {
        EXPECT_NE(source.find(from), std::string::npos) << from;
        if (source.find(from) != std::string::npos)
            source.replace(source.find(from), from.size(), to);
    }
    std::ofstream(file) << source;
    return dir / "shaders";
}

TEST_F(Difftest, AShaderWrongOnOnePixelFails) {
    // A GPU wrong on the one pixel right of the image's centre, on every
    // image: robust seed 101 is 40x30 at one sample. That pixel is inside an
    // object (no edge, cell border or shadow's edge within the mode's error
    // bound), so nothing explains it: the scene fails, whatever its size.
    const fs::path shaders = shadersWith(
        dir, "trace.comp",
        {{"void writePixels(uvec2 first, uint firstPixel, uvec2 tileSize, GpuPixel result) {\n",
          "void writePixels(uvec2 first, uint firstPixel, uvec2 tileSize, GpuPixel result) {\n"
          "    if (all(equal(rayPixel, frame.image.xy / 2u)))\n"
          "        result.color.rgb = step(result.color.rgb, vec3(0.5));\n"}});
    RunResult run = vkray("difftest --scenes 1 --seed 101 --precision robust --shader-dir " +
                          shaders.string() + " --out " + path("found"));
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("DISAGREE seed 101 (robust): 40x30: 1 of 1200 pixels differ, 0 set "
                              "aside, 1 unexplained"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("difftest: 0 passed, 1 failed"), std::string::npos) << run.output;
    EXPECT_TRUE(fs::exists(dir / "found" / "seed-101.sdl"));  // kept, to look at
}

TEST_F(Difftest, AGpuThatDrawsSomethingElseIsCaught) {
    // The shaders as built, but every light term and the background at 90 %
    // of their strength: a GPU that is only a little wrong.
    shadersWith(
        dir, "shade.glsl",
        {{"    return diffuse + specular;\n", "    return 0.9 * (diffuse + specular);\n"},
         {"task.weight * frame.background.rgb", "task.weight * 0.9 * frame.background.rgb"}});

    RunResult run = vkray("difftest --scenes 3 --seed 100 --shader-dir " + path("shaders") +
                          " --out " + path("found"));
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("difftest: 0 passed, 3 failed"), std::string::npos) << run.output;
    // Each disagreement is kept, with the command that shows it.
    for (int seed = 100; seed < 103; ++seed) {
        const std::string file = path("found") + "/seed-" + std::to_string(seed) + ".sdl";
        EXPECT_NE(run.output.find("DISAGREE seed " + std::to_string(seed) + " "), std::string::npos)
            << run.output;
        EXPECT_TRUE(fs::exists(file)) << file;
        EXPECT_NE(run.output.find("vkray render " + file + " --size "), std::string::npos)
            << run.output;
    }
}

}  // namespace
