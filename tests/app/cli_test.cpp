// The binary as a user runs it: exit status, messages with their place, and
// no output file left behind by a failed run.
#include "support/cli_fixture.h"

#include <gtest/gtest.h>

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
    ASSERT_EQ(vkray("render " + s + " -o " + path("b.png") + " --size 64x48 --eye 0,0.5,5").status, 0);
    RunResult run = vkray("compare " + path("a.png") + " " + path("b.png"));
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("FAIL"), std::string::npos) << run.output;
}

TEST_F(Cli, CheckRendersBothAndReportsIds) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png") +
                    " --size 64x48 --check --diff " + path("diff.png"));
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("object ids"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("RMSE"), std::string::npos) << run.output;
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
    expectRenderError("sphere\n mesh missing.3vn\n", "bad.sdl:2:2: error: cannot load mesh 'missing.3vn'");
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
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("no/such/dir/out.png"));
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
    const std::string s = scene("s.sdl", "camera eye 0 0 5\nlight 5 5 5 1 1 1\ntexture -1\nsphere\n");
    RunResult run = vkray("render " + s + " --lenient -o " + path("out.png") + " --size 32x24");
    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("s.sdl:3:1: warning: texture -1 is not one of 0 none, 1 checkerboard, "
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

TEST_F(Cli, NoVulkanDriverGivesAdviceAndExitsOne) {
    RunResult run = vkray("render " + scene("s.sdl", kGoodScene) + " -o " + path("out.png"),
                    "VK_ICD_FILENAMES=" + path("none.json"));
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("--cpu"), std::string::npos) << run.output;
    expectNoOutputs();
}

}  // namespace
