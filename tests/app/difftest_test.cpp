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

TEST_F(Difftest, TheFixedSeedsAgreeOrAreNotComparable) {
    // Seeds 100..107: five open scenes (auto chose robust for two, fp64 for
    // three) and three drawn for a mode (two robust, one fp64); seed 100 is
    // open and past fp64's
    // envelope too (a cylinder squashed between rotations, |M^-1 eye| ~1e11):
    // not comparable, said with its reason, kept and counted neither way.
    RunResult run = vkray("difftest --scenes 8 --seed 100 --out " + path("found"));
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("not comparable seed 100: the 'cylinder' at "), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("beyond fp64's 4.3e+10, past every mode's envelope"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("auto (fp64) 2 of 2 agreed; auto (robust) 2 of 2 agreed; fp64 1 of "
                              "1 agreed; robust 2 of 2 agreed; 1 not comparable; 0 refused"),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("difftest: 7 passed, 0 failed"), std::string::npos) << run.output;
    EXPECT_EQ(scenesLeftIn(dir / "found"), 1u) << run.output;  // agreeing scenes are not kept
    EXPECT_TRUE(fs::exists(dir / "found" / "seed-100.sdl"));
}

// The ray-query walk (--traversal rayquery) on the same seeds: the same
// verdicts. Only where the device has ray queries (the Mesa 25.0 stage).
TEST_F(Difftest, TheRayQueryWalkAgreesOnTheFixedSeeds) {
    const RunResult devices = vkray("devices");
    if (devices.output.find("ray queries yes") == std::string::npos)
        GTEST_SKIP() << "the device has no ray queries (lavapipe has them from Mesa 24.1)";
    RunResult run =
        vkray("difftest --scenes 8 --seed 100 --traversal rayquery --out " + path("found"));
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("difftest: 7 passed, 0 failed"), std::string::npos) << run.output;
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
    // ... with the command that traces the pixel on both sides.
    EXPECT_NE(run.output.find("vkray pixel " + path("found") +
                              "/seed-101.sdl 20 15 --size 40x30 --block 1 --precision robust\n"),
              std::string::npos)
        << run.output;
}

TEST_F(Difftest, AGpuThatDrawsSomethingElseIsCaught) {
    // The shaders as built, but every light term and the background at 90 %
    // of their strength: a GPU that is only a little wrong.
    shadersWith(
        dir, "shade.glsl",
        {{"    return diffuse + specular;\n", "    return 0.9 * (diffuse + specular);\n"},
         {"task.weight * frame.background.rgb", "task.weight * 0.9 * frame.background.rgb"}});

    // Scenes drawn for robust (an open scene may be too dark for 10 % to
    // pass 0.02: open seed 102 is, its eye behind a tilted plane).
    RunResult run = vkray("difftest --scenes 3 --seed 100 --precision robust --shader-dir " +
                          path("shaders") + " --out " + path("found"));
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
