#include "app/options.h"
#include "util/error.h"

#include <gtest/gtest.h>

namespace vkray {
namespace {

Options parse(std::vector<std::string> args) { return parseOptions(args); }

std::string errorOf(std::vector<std::string> args) {
    try {
        parseOptions(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(Options, RenderWithEveryFlag) {
    Options o = parse({"render", "s.sdl", "-o", "x.png", "--size", "320x200", "--device=1",
                       "--block", "4", "--aov", "out/a", "--lenient", "--eye", "1,2,3",
                       "--look=0,0,-1.5", "--up", "0,0,1", "--fov", "45", "--threads", "2"});
    EXPECT_EQ(o.command, Command::Render);
    EXPECT_EQ(o.scenePath, "s.sdl");
    EXPECT_EQ(o.outputPath, "x.png");
    EXPECT_EQ(o.width, 320);
    EXPECT_EQ(o.height, 200);
    EXPECT_EQ(o.device, 1);
    EXPECT_EQ(o.block, 4);
    EXPECT_EQ(o.aovPrefix, "out/a");
    EXPECT_TRUE(o.lenient);
    EXPECT_EQ(*o.eye, glm::dvec3(1, 2, 3));
    EXPECT_EQ(*o.look, glm::dvec3(0, 0, -1.5));
    EXPECT_EQ(*o.up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(*o.fov, 45);
    EXPECT_EQ(o.threads, 2);
}

TEST(Options, CheckAndCompareTolerances) {
    Options check = parse({"render", "s.sdl", "--check", "--diff", "d.png", "--fail", "0.1",
                           "--failpercent", "2"});
    EXPECT_TRUE(check.check);
    EXPECT_EQ(check.diffPath, "d.png");
    EXPECT_EQ(*check.failThreshold, 0.1);
    EXPECT_EQ(*check.failPercent, 2);
    Options compare = parse({"compare", "a.png", "b.pfm", "--ids", "a.id.pfm", "b.id.pfm"});
    EXPECT_EQ(compare.command, Command::Compare);
    EXPECT_EQ(compare.imageB, "b.pfm");
    EXPECT_EQ(compare.idsB, "b.id.pfm");
}

TEST(Options, BadUsageNamesTheFlag) {
    EXPECT_NE(errorOf({"render", "s.sdl", "--size", "0x10"}).find("--size"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--size", "100000x100000"}).find("out of range"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--size", "16384x16384"}).find("more than the limit"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--size", "abc"}).find("WIDTHxHEIGHT"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--bogus"}).find("unknown option '--bogus'"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--eye", "1,2"}).find("three numbers"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--block"}).find("expects a value"), std::string::npos);
    EXPECT_NE(errorOf({"render"}).find("one scene file"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--cpu", "--check"}).find("--check"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--diff", "d.png"}).find("--check"), std::string::npos);
    EXPECT_NE(errorOf({"compare", "a.png", "--block", "2", "b.png"}).find("unknown option"),
              std::string::npos);
    EXPECT_NE(errorOf({"frobnicate"}).find("unknown command"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--fov", "180"}).find("--fov"), std::string::npos);
}

// Tolerances apply to --check's comparison: without it they are errors, as --diff is.
TEST(Options, FailAndFailPercentNeedCheckAsDiffDoes) {
    EXPECT_EQ(errorOf({"render", "s.sdl", "--diff", "d.png"}),
              "--diff needs --check (or use `vkray compare`)");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--fail", "0.1"}),
              "--fail needs --check (or use `vkray compare`)");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--failpercent=2"}),
              "--failpercent needs --check (or use `vkray compare`)");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--cpu", "--fail", "0"}),
              "--fail needs --check (or use `vkray compare`)");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--check", "--fail", "0", "--failpercent", "100"}), "");
    EXPECT_EQ(errorOf({"compare", "a.png", "b.png", "--fail", "0.1", "--failpercent", "1"}), "");
}

TEST(Options, SamplesPerPixelAndSeed) {
    const Options defaults = parse({"render", "s.sdl"});
    EXPECT_EQ(defaults.spp, 1);
    EXPECT_EQ(defaults.seed, 0u);
    const Options o = parse({"render", "s.sdl", "--spp", "16", "--seed=4294967295"});
    EXPECT_EQ(o.spp, 16);
    EXPECT_EQ(o.seed, 4294967295u);
    EXPECT_EQ(parse({"render", "s.sdl", "--cpu", "--spp", "4096"}).spp, 4096);
    EXPECT_EQ(parse({"render", "s.sdl", "--check", "--seed", "7"}).seed, 7u);
}

TEST(Options, BadSamplesOrSeedNameTheFlag) {
    EXPECT_NE(errorOf({"render", "s.sdl", "--spp", "0"}).find("--spp: 0 is out of range (1 .. 4096)"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--spp", "4097"}).find("out of range"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--spp", "2.5"}).find("--spp: '2.5' is not a whole number"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--seed", "-1"}).find("--seed: '-1' is not a whole number"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--seed", "4294967296"}).find("0 to 4294967295"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--seed", "x"}).find("--seed"), std::string::npos);
    // `pixel` traces the one ray through the pixel's centre.
    EXPECT_NE(errorOf({"pixel", "s.sdl", "1", "1", "--spp", "4"}).find("unknown option '--spp'"),
              std::string::npos);
}

TEST(Options, ViewDefaultsAndItsOwnFlags) {
    const Options o = parse({"view", "s.sdl", "--frames", "5", "--screenshot", "a.png", "--events", "e.txt",
                             "--fail", "0.1", "--eye", "1,2,3"});
    EXPECT_EQ(o.command, Command::View);
    EXPECT_EQ(o.scenePath, "s.sdl");
    EXPECT_EQ(o.width, 960);
    EXPECT_EQ(o.height, 540);
    EXPECT_EQ(o.spp, 16);
    EXPECT_EQ(o.frames, 5);
    EXPECT_EQ(o.screenshotPath, "a.png");
    EXPECT_EQ(o.eventsPath, "e.txt");
    EXPECT_EQ(*o.failThreshold, 0.1);
    EXPECT_EQ(parse({"view", "s.sdl", "--size", "64x48", "--spp", "2"}).width, 64);
    EXPECT_EQ(parse({"view", "s.sdl", "--size", "64x48", "--spp", "2"}).spp, 2);
}

TEST(Options, ViewRefusesWhatItDoesNotDo) {
    EXPECT_NE(errorOf({"view", "s.sdl", "--screenshot", "a.png"}).find("--screenshot needs --frames N"),
              std::string::npos);
    EXPECT_NE(errorOf({"view", "s.sdl", "--frames", "2", "--screenshot", "a.jpg"}).find("is a .png file"),
              std::string::npos);
    for (const char* flag : {"--block", "-o", "--aov", "--check"})
        EXPECT_NE(errorOf({"view", "s.sdl", flag, "4"}).find("unknown option '" + std::string(flag) + "' for `vkray view`"),
                  std::string::npos) << flag;
    EXPECT_NE(errorOf({"view", "s.sdl", "--cpu"}).find("unknown option '--cpu'"), std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--frames", "2"}).find("unknown option '--frames'"), std::string::npos);
    EXPECT_NE(errorOf({"view"}).find("view: expected one scene file"), std::string::npos);
    EXPECT_NE(errorOf({"view", "s.sdl", "--frames", "0"}).find("--frames: 0 is out of range"), std::string::npos);
}

}  // namespace
}  // namespace vkray
