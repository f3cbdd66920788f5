// The shader developer's tools as a user runs them: `vkray pixel`,
// `vkray shaders check`, -D, --dump-spirv, --validation and --watch.
#include "support/cli_fixture.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>
#include <chrono>
#include <csignal>
#include <regex>
#include <sstream>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;
using vkray::test::RunResult;
using vkray::test::vkray;
using ShaderDev = vkray::test::CliTest;

// A plane z = 0 seen head-on from (0, 0, 5): the centre pixel of a 3x3 image
// looks straight down -z and meets the plane at t = 5, point (0, 0, 0).
const char* kPlaneScene =
    "camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 60\n"
    "light 0 0 10 1 1 1\n"
    "diffuse 0.5 0.5 0.5 specular 0.2 0.2 0.2 specularExponent 4\n"
    "plane\n";

// The values of the row starting with `label`: "GPU CPU diff" as text.
std::string rowOf(const std::string& output, const std::string& label) {
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind(label + " ", 0) == 0) return line.substr(label.size());
    return "";
}

TEST_F(ShaderDev, PixelTracesTheAnalyticRayOnBothSides) {
    RunResult run = vkray("pixel " + scene("p.sdl", kPlaneScene) + " 1 1 --size 3x3");
    ASSERT_EQ(run.status, 0) << run.output;
    // t = 5 exactly on both sides (the ray is (0,0,5) + (0,0,-1) t).
    std::istringstream t(rowOf(run.output, "t"));
    double gpuT = 0, cpuT = 0;
    t >> gpuT >> cpuT;
    EXPECT_DOUBLE_EQ(gpuT, 5.0) << run.output;
    EXPECT_DOUBLE_EQ(cpuT, 5.0) << run.output;
    EXPECT_NE(rowOf(run.output, "closest hit").find("same"), std::string::npos) << run.output;
    EXPECT_NE(rowOf(run.output, "ray direction").find("(0, 0, -1)"), std::string::npos)
        << run.output;
    // Shading terms: m.s = 1, diffuse 0.5, m.h = 1, specular 0.2.
    EXPECT_NE(rowOf(run.output, "light 0 diffuse").find("(0.5, 0.5, 0.5)"), std::string::npos)
        << run.output;
    // Each side at its own precision: the GPU's float 0.2 to 9 digits, the
    // CPU's double 0.2 to 17.
    EXPECT_NE(rowOf(run.output, "light 0 specular").find("(0.200000003, 0.200000003, 0.200000003)"),
              std::string::npos)
        << run.output;
    EXPECT_NE(rowOf(run.output, "light 0 specular").find("(0.20000000000000001, "),
              std::string::npos)
        << run.output;
}

// `pixel` traces in the mode `render` would: auto's choice from the scene
// (a sphere seen from 1e5 of its radii is past robust's 1.6e4), or the
// mode asked for.
TEST_F(ShaderDev, PixelTracesInTheModeRenderWould) {
    const std::string far = scene("far.sdl",
                                  "camera eye 0 0 100000 look 0 0 0 up 0 1 0 fov 0.002\n"
                                  "light 0 10 100000 1 1 1\nsphere\n");
    RunResult run = vkray("pixel " + far + " 1 1 --size 3x3");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("precision: auto chose fp64: the 'sphere' at "), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("GPU (t and normal in double)"), std::string::npos) << run.output;
    run = vkray("pixel " + far + " 1 1 --size 3x3 --precision robust");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("GPU (float)"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("warning: the 'sphere'"), std::string::npos) << run.output;
}

TEST_F(ShaderDev, PixelOutsideTheImageIsAnError) {
    RunResult run = vkray("pixel " + scene("p.sdl", kPlaneScene) + " 3 1 --size 3x3");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("outside the 3x3 image"), std::string::npos) << run.output;
}

TEST_F(ShaderDev, ShadersCheckCompilesEveryVariant) {
    RunResult run = vkray("shaders check");
    EXPECT_EQ(run.status, 0) << run.output;
    // Every variant the check lists compiled: "N of N variants compiled".
    std::smatch counts;
    ASSERT_TRUE(
        std::regex_search(run.output, counts, std::regex(R"((\d+) of (\d+) variants compiled)")))
        << run.output;
    EXPECT_EQ(counts[1], counts[2]) << run.output;
    EXPECT_GT(std::stoi(counts[1]), 100) << "every pair of shapes, with and without the BVH";
}

// A copy of the shaders with one shape file broken at a known line.
fs::path brokenShaderCopy(const fs::path& dir) {
    const fs::path copy = dir / "shaders";
    fs::copy(VKRAY_SOURCE_DIR "/shaders", copy, fs::copy_options::recursive);
    std::ofstream(copy / "shapes" / "cube.glsl", std::ios::app) << "\nthis is not glsl;\n";
    return copy;
}

TEST_F(ShaderDev, ShadersCheckNamesTheBrokenFileAndLine) {
    const fs::path copy = brokenShaderCopy(dir);
    RunResult run = vkray("shaders check --shader-dir " + copy.string());
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("FAIL  cube"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("cube.glsl:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("ok    sphere"), std::string::npos) << run.output;
}

TEST_F(ShaderDev, DefinesChangeTheVariantAndDumpSpirvWritesIt) {
    const std::string s = scene("p.sdl", kPlaneScene);
    fs::create_directories(dir / "spv");
    RunResult plain =
        vkray("render " + s + " -o " + path("a.png") + " --size 8x8 --dump-spirv " + path("spv"));
    RunResult defined = vkray("render " + s + " -o " + path("b.png") +
                              " --size 8x8 -D VKRAY_EXAMPLE=2 --dump-spirv=" + path("spv"));
    ASSERT_EQ(plain.status, 0) << plain.output;
    ASSERT_EQ(defined.status, 0) << defined.output;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir / "spv")) files.push_back(entry.path());
    ASSERT_EQ(files.size(), 2u) << "a define must give its own variant";
    for (const fs::path& file : files) {
        std::ifstream in(file, std::ios::binary);
        std::uint32_t magic = 0;
        in.read(reinterpret_cast<char*>(&magic), sizeof magic);
        EXPECT_EQ(magic, 0x07230203u) << file;  // SPIR-V's magic number
    }
    RunResult bad = vkray("render " + s + " -o " + path("c.png") + " -D 1X=2");
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_NE(bad.output.find("-D"), std::string::npos) << bad.output;
}

TEST_F(ShaderDev, ValidationLayerSeesNothingOnEveryScene) {
    for (const auto& entry : fs::directory_iterator(VKRAY_SOURCE_DIR "/scenes")) {
        if (entry.path().extension() != ".sdl") continue;
        RunResult run = vkray("render " + entry.path().string() + " -o " + path("v.png") +
                              " --size 40x30 --block 2 --validation");
        EXPECT_EQ(run.status, 0) << entry.path() << "\n" << run.output;
        EXPECT_EQ(run.output.find("validation:"), std::string::npos) << run.output;
    }
    RunResult pixel =
        vkray("pixel " + scene("p.sdl", kPlaneScene) + " 1 1 --size 3x3 --validation");
    EXPECT_EQ(pixel.status, 0) << pixel.output;
}

TEST_F(ShaderDev, DevicesListsWhatAShaderDeveloperNeeds) {
    RunResult run = vkray("devices");
    ASSERT_EQ(run.status, 0) << run.output;
    for (const char* field :
         {"[render picks this]", "type ", "driver ", "Vulkan 1.", "shaderFloat64 ",
          "subgroup size ", "max storage buffer ", "max workgroup size "})
        EXPECT_NE(run.output.find(field), std::string::npos) << field << "\n" << run.output;
}

using WatchedRender = vkray::test::BackgroundVkray;

std::string readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

TEST_F(ShaderDev, WatchKeepsTheLastGoodImageAndReloads) {
    const fs::path shaders = dir / "shaders";
    fs::copy(VKRAY_SOURCE_DIR "/shaders", shaders, fs::copy_options::recursive);
    const std::string s = scene("p.sdl", kPlaneScene);
    const fs::path image = dir / "w.png";
    WatchedRender watch("render " + s + " -o " + image.string() + " --size 16x16 --watch " +
                            "--shader-dir " + shaders.string(),
                        dir / "watch.log");
    ASSERT_TRUE(watch.waitFor("watching", 1)) << watch.output();
    const std::string firstImage = readBytes(image);
    ASSERT_FALSE(firstImage.empty());

    // Break the shader: the error names the file and line, the image stays.
    const fs::path plane = shaders / "shapes" / "plane.glsl";
    const std::string original = readBytes(plane);
    std::ofstream(plane, std::ios::app) << "\nbroken here;\n";
    ASSERT_TRUE(watch.waitFor("watching", 2)) << watch.output();
    EXPECT_NE(watch.output().find("plane.glsl:"), std::string::npos) << watch.output();
    EXPECT_NE(watch.output().find("kept the last good image"), std::string::npos);
    EXPECT_EQ(readBytes(image), firstImage);

    // Fix it so that the plane is never hit: a new image, and the reload time.
    std::string fixed = original;
    const std::string hitTest = "return t > tMin && t < tMax;";
    ASSERT_NE(fixed.find(hitTest), std::string::npos);
    std::ofstream(plane, std::ios::trunc)
        << fixed.replace(fixed.find(hitTest), hitTest.size(), "return false;");
    ASSERT_TRUE(watch.waitFor("watching", 3)) << watch.output();
    EXPECT_NE(watch.output().find("reloaded in"), std::string::npos) << watch.output();
    EXPECT_NE(readBytes(image), firstImage);

    EXPECT_EQ(watch.stop(), 0) << watch.output();
    EXPECT_NE(watch.output().find("stopped"), std::string::npos) << watch.output();
}

}  // namespace
