// The binary as a user runs it: exit status, messages with their place, and
// no output file left behind by a failed run.
#include "image/exr_io.h"
#include "image/image_io.h"
#include "support/cli_fixture.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace {

using vkray::test::RunResult;
using vkray::test::vkray;
using Cli = vkray::test::CliTest;
namespace fs = std::filesystem;

const char* kGoodScene = "camera eye 0 0 5\nlight 5 5 5 1 1 1\nsphere\n";

TEST_F(Cli, RenderWritesImageAndAovsAndReportsTime) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png") +
                          " --aov " + path("aov") + " --size 64x48");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("device: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("Mrays/s"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("wrote " + path("out.png")), std::string::npos) << run.output;
    for (const char* file : {"out.png", "aov.depth.pfm", "aov.normal.pfm", "aov.id.pfm"})
        EXPECT_TRUE(fs::exists(dir / file)) << file;
    // Where the wall clock went, last: every stage a one-shot GPU render has.
    const size_t line = run.output.find("\ntime: scene ");
    ASSERT_NE(line, std::string::npos) << run.output;
    const std::string stages = run.output.substr(line);
    for (const char* stage : {"device set-up ", "shader ", "preparation and upload ", "trace ",
                              "its first tile ", "read-back ", "encode ", "other ", "; total "})
        EXPECT_NE(stages.find(stage), std::string::npos) << stage << "\n" << stages;
}

TEST_F(Cli, CpuRenderTellsPreparationFromTrace) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png") +
                          " --size 64x48 --cpu");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("cpu reference render: "), std::string::npos) << run.output;
    const size_t line = run.output.find("\ntime: scene ");
    ASSERT_NE(line, std::string::npos) << run.output;
    const std::string stages = run.output.substr(line);
    for (const char* stage : {"preparation (frame, BVH) ", "trace ", "encode ", "; total "})
        EXPECT_NE(stages.find(stage), std::string::npos) << stage << "\n" << stages;
    EXPECT_EQ(stages.find("device set-up"), std::string::npos) << stages;
}

// A scene with a mesh file tells the file's reading, and its BVH's build
// within it, apart from the rest of the scene's load.
TEST_F(Cli, RenderTellsTheMeshFilesAndTheirBvhsApart) {
    scene("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    RunResult run = vkray("render " + scene("m.sdl", "camera eye 0 0 5\nmesh quad.obj\n") + " -o " +
                          path("out.png") + " --size 32x24");
    ASSERT_EQ(run.status, 0) << run.output;
    const size_t line = run.output.find("\ntime: scene ");
    ASSERT_NE(line, std::string::npos) << run.output;
    const std::string stages = run.output.substr(line);
    EXPECT_NE(stages.find(" s (mesh files "), std::string::npos) << stages;
    EXPECT_NE(stages.find(" s, their BVHs "), std::string::npos) << stages;
}

// The EXR's layers hold what the PFM set and a float image of the same
// render hold (GPU renders repeat bit for bit), and P lies on the unit sphere.
TEST_F(Cli, ExrAovsHoldThePfmLayersAndTheHitPoints) {
    const std::string s = scene("s.sdl", kGoodScene);
    RunResult pfm =
        vkray("render " + s + " -o " + path("a.pfm") + " --aov " + path("a") + " --size 32x24");
    ASSERT_EQ(pfm.status, 0) << pfm.output;
    RunResult exr =
        vkray("render " + s + " -o " + path("b.png") + " --aov " + path("b.exr") + " --size 32x24");
    ASSERT_EQ(exr.status, 0) << exr.output;
    EXPECT_NE(exr.output.find("wrote " + path("b.exr") +
                              " (R, G, B, Z, N.X, N.Y, N.Z, id, P.X, P.Y, P.Z)"),
              std::string::npos)
        << exr.output;
    std::ifstream in(path("b.exr"), std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const vkray::ExrImage layers = vkray::decodeExr(bytes, "b.exr", {});
    ASSERT_EQ(layers.channels.size(), 11u);
    const auto channel = [&](const char* name) { return layers.find(name)->values; };
    const auto plane = [](const vkray::Image& image, int c) {
        std::vector<float> values;
        for (size_t i = size_t(c); i < image.pixels.size(); i += size_t(image.channels))
            values.push_back(image.pixels[i]);
        return values;
    };
    const vkray::Image colour = vkray::readImage(path("a.pfm")),
                       normal = vkray::readImage(path("a.normal.pfm"));
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(channel(std::array{"R", "G", "B"}[c]), plane(colour, c)) << c;
        EXPECT_EQ(channel(std::array{"N.X", "N.Y", "N.Z"}[c]), plane(normal, c)) << c;
    }
    EXPECT_EQ(channel("Z"), vkray::readImage(path("a.depth.pfm")).pixels);
    EXPECT_EQ(channel("id"), vkray::readImage(path("a.id.pfm")).pixels);
    size_t hits = 0;
    for (size_t i = 0; i < channel("id").size(); ++i) {
        const glm::vec3 p(channel("P.X")[i], channel("P.Y")[i], channel("P.Z")[i]);
        if (channel("id")[i] < 0) {
            EXPECT_EQ(p, glm::vec3(0)) << i;
            continue;
        }
        ++hits;
        EXPECT_NEAR(glm::length(p), 1.0f, 1e-5f) << i;  // on the unit sphere
        EXPECT_GT(p.z, 0) << i;                         // the side facing the eye at z = 5
    }
    EXPECT_GT(hits, 50u);

    // With blocks and jittered samples P follows sample 0's ray, the one the
    // other layers hold: it still lies on the sphere.
    RunResult jittered = vkray("render " + s + " -o " + path("c.png") + " --aov " + path("c.exr") +
                               " --size 32x24 --spp 4 --block 2 --seed 7");
    ASSERT_EQ(jittered.status, 0) << jittered.output;
    std::ifstream jin(path("c.exr"), std::ios::binary);
    const vkray::ExrImage sampled = vkray::decodeExr(
        std::string{std::istreambuf_iterator<char>(jin), std::istreambuf_iterator<char>()}, "c.exr",
        {"id", "P.X", "P.Y", "P.Z"});
    size_t sampledHits = 0;
    for (size_t i = 0; i < sampled.channels[0].values.size(); ++i) {
        if (sampled.channels[0].values[i] < 0) continue;
        ++sampledHits;
        const glm::vec3 p(sampled.channels[1].values[i], sampled.channels[2].values[i],
                          sampled.channels[3].values[i]);
        EXPECT_NEAR(glm::length(p), 1.0f, 1e-5f) << i;
    }
    EXPECT_GT(sampledHits, 50u);
}

TEST_F(Cli, ExrImageIsLinearAndOneFileHoldsImageAndAovs) {
    const std::string s =
        scene("s.sdl", "camera eye 0 0 5\nlight 5 5 5 4 4 4\nsphere\n");  // bright: above 1
    RunResult image = vkray("render " + s + " -o " + path("x.exr") + " --size 32x24");
    ASSERT_EQ(image.status, 0) << image.output;
    const vkray::Image linear = vkray::readImage(path("x.exr"));
    EXPECT_GT(*std::max_element(linear.pixels.begin(), linear.pixels.end()), 1.0f);  // unclamped
    RunResult both =
        vkray("render " + s + " -o " + path("y.exr") + " --aov " + path("y.exr") + " --size 32x24");
    ASSERT_EQ(both.status, 0) << both.output;
    EXPECT_EQ(both.output.find("wrote " + path("y.exr") + "\n"), std::string::npos) << both.output;
    EXPECT_NE(both.output.find("wrote " + path("y.exr") + " (R, G, B,"), std::string::npos)
        << both.output;
    EXPECT_EQ(vkray::readImage(path("y.exr")).pixels, linear.pixels);
    EXPECT_TRUE(vkray::hasIdChannel(path("y.exr")));
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(dir))
        files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files, (std::vector<std::string>{"s.sdl", "x.exr", "y.exr"}));  // no temporaries
}

// compare reads EXR like PNG, and finds ids in an EXR's id channel: the
// image's own, one beside a PNG, or named with --ids.
TEST_F(Cli, CompareReadsExrAndItsIdChannel) {
    const std::string s = scene("s.sdl", kGoodScene);
    ASSERT_EQ(
        vkray("render " + s + " -o " + path("a.exr") + " --aov " + path("a.exr") + " --size 32x24")
            .status,
        0);
    ASSERT_EQ(
        vkray("render " + s + " -o " + path("b.png") + " --aov " + path("b.exr") + " --size 32x24")
            .status,
        0);
    ASSERT_EQ(vkray("render " + s + " -o " + path("moved.png") + " --aov " + path("moved.exr") +
                    " --size 32x24 --look 1,0,0")
                  .status,
              0);
    RunResult same = vkray("compare " + path("a.exr") + " " + path("a.exr"));
    EXPECT_EQ(same.status, 0) << same.output;
    EXPECT_NE(same.output.find("object ids from " + path("a.exr") + " and " + path("a.exr")),
              std::string::npos)
        << same.output;
    // The PNG is clamped and rounded to 8 bits: within 1/255 of the EXR's float.
    RunResult mixed = vkray("compare " + path("b.png") + " " + path("a.exr") + " --fail 0.0021");
    EXPECT_EQ(mixed.status, 0) << mixed.output;
    EXPECT_NE(mixed.output.find("object ids from " + path("b.exr") + " and " + path("a.exr")),
              std::string::npos)
        << mixed.output;
    RunResult moved = vkray("compare " + path("a.exr") + " " + path("moved.png") + " --ids " +
                            path("a.exr") + " " + path("moved.exr") + " --fail 1 --failpercent 1");
    EXPECT_EQ(moved.status, 2) << moved.output;  // colour within --fail 1, ids far apart
    EXPECT_NE(moved.output.find("object ids      "), std::string::npos) << moved.output;
}

TEST_F(Cli, CompareRefusesABrokenExr) {
    const std::string s = scene("s.sdl", kGoodScene);
    ASSERT_EQ(vkray("render " + s + " -o " + path("good.exr") + " --size 32x24").status, 0);
    std::ifstream in(path("good.exr"), std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::ofstream(path("cut.exr"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    std::ofstream(path("junk.exr"), std::ios::binary) << "GIF89a, not an OpenEXR file";
    for (const char* bad : {"cut.exr", "junk.exr"}) {
        RunResult run =
            vkray("compare " + path("good.exr") + " " + path(bad) + " --diff " + path("diff.png"));
        EXPECT_EQ(run.status, 1) << run.output;
        EXPECT_NE(run.output.find("vkray: error: " + path(bad) + ": not a readable OpenEXR file ("),
                  std::string::npos)
            << run.output;
        EXPECT_FALSE(fs::exists(dir / "diff.png"));
    }
}

TEST_F(Cli, CpuAndGpuImagesCompareWithinTolerance) {
    const std::string s = scene("s.sdl", kGoodScene);
    ASSERT_EQ(vkray("render " + s + " -o " + path("gpu.png") + " --size 64x48").status, 0);
    RunResult cpu = vkray("render " + s + " --cpu -o " + path("cpu.png") + " --size 64x48");
    ASSERT_EQ(cpu.status, 0) << cpu.output;
    EXPECT_NE(cpu.output.find("cpu reference"), std::string::npos);
    RunResult same = vkray("compare " + path("gpu.png") + " " + path("gpu.png"));
    EXPECT_EQ(same.status, 0) << same.output;
    EXPECT_NE(same.output.find("PSNR"), std::string::npos) << same.output;
    RunResult loose = vkray("compare " + path("gpu.png") + " " + path("cpu.png") +
                            " --fail 0.02 --failpercent 1 --diff " + path("diff.png"));
    EXPECT_EQ(loose.status, 0) << loose.output;
    EXPECT_TRUE(fs::exists(dir / "diff.png"));
}

TEST_F(Cli, CompareBeyondToleranceExitsTwo) {
    const std::string s = scene("s.sdl", kGoodScene);
    ASSERT_EQ(vkray("render " + s + " -o " + path("a.png") + " --size 64x48").status, 0);
    ASSERT_EQ(vkray("render " + s + " -o " + path("b.png") + " --size 64x48 --eye 0,0.5,5").status,
              0);
    RunResult run = vkray("compare " + path("a.png") + " " + path("b.png"));
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("FAIL"), std::string::npos) << run.output;
}

TEST_F(Cli, CheckRendersBothAndJudgesByTheMarginRule) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png") +
                          " --size 64x48 --check --diff " + path("diff.png"));
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("of 3072 pixels"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("ids "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("unexplained     0 pixels"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("result          PASS"), std::string::npos) << run.output;
    EXPECT_TRUE(fs::exists(dir / "diff.png"));
}

TEST_F(Cli, MalformedNumber) {
    expectRenderError("sphere\ntranslate 1 abc 2\n", "bad.sdl:2:");
}

TEST_F(Cli, UnknownKeywordInStrictMode) {
    expectRenderError("sphere\n  frobnicate 1 2\n", "bad.sdl:2:3");
}

TEST_F(Cli, UnbalancedBraces) {
    expectRenderError("def a { sphere\n", "bad.sdl:1:");
}

TEST_F(Cli, UseOfUndefinedName) {
    expectRenderError("sphere use nothing\n", "nothing");
}

TEST_F(Cli, RecursiveDef) {
    expectRenderError("def a { use b } def b { use a } use a\n", "recursive");
}

TEST_F(Cli, MissingMeshNamesItsPlace) {
    expectRenderError("sphere\n mesh missing.3vn\n",
                      "bad.sdl:2:2: error: cannot load mesh 'missing.3vn'");
}

TEST_F(Cli, EveryErrorOfASceneIsReportedAndNothingIsWritten) {
    const std::string scene = VKRAY_SOURCE_DIR "/tests/data/three_errors.sdl";
    RunResult run = vkray("render " + scene + " -o " + path("out.png"));
    EXPECT_EQ(run.status, 1) << run.output;
    for (const char* place : {"three_errors.sdl:3:15: error: ", "three_errors.sdl:5:1: error: ",
                              "three_errors.sdl:6:1: error: "})
        EXPECT_NE(run.output.find(place), std::string::npos) << place << "\n" << run.output;
    expectNoOutputs();
}

TEST_F(Cli, MissingSceneFile) {
    RunResult run = vkray("render " + path("nope.sdl") + " -o " + path("out.png"));
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find("nope.sdl"), std::string::npos) << run.output;
    expectNoOutputs();
}

TEST_F(Cli, AbsurdSize) {
    expectRenderError(kGoodScene, "--size", "--size 100000x100000");
    expectRenderError(kGoodScene, "--size", "--size 0x10");
}

TEST_F(Cli, UnwritableOutputPath) {
    RunResult run =
        vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("no/such/dir/out.png"));
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("no/such/dir"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir / "no"));
}

TEST_F(Cli, LenientModeWarnsAndRenders) {
    const std::string s = scene("s.sdl", "exponent 50\nsphere\nmesh gone.3vn\n");
    RunResult run = vkray("render " + s + " --lenient -o " + path("out.png") + " --size 32x24");
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("s.sdl:1:1: warning"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("s.sdl:3:1: warning: cannot load mesh 'gone.3vn'"), std::string::npos)
        << run.output;
    EXPECT_TRUE(fs::exists(dir / "out.png"));
}

TEST_F(Cli, LenientRenderReadsAnUnknownTextureCodeAsNone) {
    const std::string s =
        scene("s.sdl", "camera eye 0 0 5\nlight 5 5 5 1 1 1\ntexture -1\nsphere\n");
    RunResult run = vkray("render " + s + " --lenient -o " + path("out.png") + " --size 32x24");
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(
        run.output.find("s.sdl:3:1: warning: texture -1 is not one of 0 none, 1 checkerboard, "
                        "2 wood, 3 image; drawn without a texture"),
        std::string::npos)
        << run.output;
    EXPECT_TRUE(fs::exists(dir / "out.png"));
    // Strict: an error at the same place, and nothing written.
    fs::remove(dir / "out.png");
    RunResult strict = vkray("render " + s + " -o " + path("out.png") + " --size 32x24");
    EXPECT_EQ(strict.status, 1) << strict.output;
    EXPECT_NE(strict.output.find("s.sdl:3:1: error: texture -1 is not one of"), std::string::npos)
        << strict.output;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST_F(Cli, EveryCommandsHelpExitsZeroWithItsFlags) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"render", "--spp"},        {"pixel", "--block"},  {"compare", "--ids"},
        {"stress", "--cases"},      {"report", "--out"},   {"features", "--variant"},
        {"difftest", "--scenes"},   {"view", "--frames"},  {"devices", "vkray devices"},
        {"shaders check", "--all"}, {"", "COMMAND --help"}};
    for (const auto& [command, flag] : cases) {
        RunResult run = vkray(command + " --help");
        EXPECT_EQ(run.status, 0) << command << "\n" << run.output;
        EXPECT_NE(run.output.find(flag), std::string::npos) << command << "\n" << run.output;
    }
    RunResult bad = vkray("render " + scene("s.sdl", kGoodScene) + " --spp 0");
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_NE(bad.output.find("vkray: error: --spp: 0 is out of range (1 .. 4096)"),
              std::string::npos)
        << bad.output;
    RunResult unknown = vkray("report --bogus");
    EXPECT_EQ(unknown.status, 1) << unknown.output;
    EXPECT_NE(unknown.output.find(
                  "unknown option '--bogus' for `vkray report`; try `vkray report --help`"),
              std::string::npos)
        << unknown.output;
    expectNoOutputs();
}

TEST_F(Cli, NoVulkanDriverGivesAdviceAndExitsOne) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                          "VK_ICD_FILENAMES=" + path("none.json"));
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("--cpu"), std::string::npos) << run.output;
    expectNoOutputs();
}

}  // namespace
