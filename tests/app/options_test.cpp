#include "app/options.h"
#include "util/error.h"

#include <gtest/gtest.h>

namespace vkray {
namespace {

Options parse(std::vector<std::string> args) {
    return parseOptions(args);
}

std::string errorOf(std::vector<std::string> args) {
    try {
        parseOptions(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(Options, RenderWithEveryFlag) {
    Options o =
        parse({"render",          "s.sdl", "-o",    "x.png", "--size",    "320x200",   "--device=1",
               "--block",         "4",     "--aov", "out/a", "--lenient", "--eye",     "1,2,3",
               "--look=0,0,-1.5", "--up",  "0,0,1", "--fov", "45",        "--threads", "2"});
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
    Options check = parse(
        {"render", "s.sdl", "--check", "--diff", "d.png", "--fail", "0.1", "--failpercent", "2"});
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
    EXPECT_NE(errorOf({"render", "s.sdl", "--size", "abc"}).find("WIDTHxHEIGHT"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--bogus"}).find("unknown option '--bogus'"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--eye", "1,2"}).find("three numbers"),
              std::string::npos);
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
    EXPECT_NE(
        errorOf({"render", "s.sdl", "--spp", "0"}).find("--spp: 0 is out of range (1 .. 4096)"),
        std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--spp", "4097"}).find("out of range"),
              std::string::npos);
    EXPECT_NE(
        errorOf({"render", "s.sdl", "--spp", "2.5"}).find("--spp: '2.5' is not a whole number"),
        std::string::npos);
    EXPECT_NE(
        errorOf({"render", "s.sdl", "--seed", "-1"}).find("--seed: '-1' is not a whole number"),
        std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--seed", "4294967296"}).find("0 to 4294967295"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--seed", "x"}).find("--seed"), std::string::npos);
    // `pixel` traces one sample of the pixel's --spp: one of them.
    const Options o =
        parse({"pixel", "s.sdl", "1", "1", "--spp", "4", "--seed", "7", "--sample", "3"});
    EXPECT_EQ(o.spp, 4);
    EXPECT_EQ(o.seed, 7u);
    EXPECT_EQ(o.pixelSample, 3);
    EXPECT_NE(errorOf({"pixel", "s.sdl", "1", "1", "--spp", "4", "--sample", "4"})
                  .find("pixel: --sample 4 is not one of the 4 samples of --spp 4 (0 to 3)"),
              std::string::npos);
    EXPECT_NE(errorOf({"pixel", "s.sdl", "1", "1", "--sample", "1"}).find("--sample 1"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--sample", "1"}).find("unknown option '--sample'"),
              std::string::npos);
}

TEST(Options, ViewDefaultsAndItsOwnFlags) {
    const Options o = parse({"view", "s.sdl", "--frames", "5", "--screenshot", "a.png", "--events",
                             "e.txt", "--fail", "0.1", "--eye", "1,2,3"});
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
    EXPECT_NE(
        errorOf({"view", "s.sdl", "--screenshot", "a.png"}).find("--screenshot needs --frames N"),
        std::string::npos);
    EXPECT_NE(
        errorOf({"view", "s.sdl", "--frames", "2", "--screenshot", "a.jpg"}).find("is a .png file"),
        std::string::npos);
    for (const char* flag : {"--block", "-o", "--aov", "--check"})
        EXPECT_NE(errorOf({"view", "s.sdl", flag, "4"})
                      .find("unknown option '" + std::string(flag) + "' for `vkray view`"),
                  std::string::npos)
            << flag;
    EXPECT_NE(errorOf({"view", "s.sdl", "--cpu"}).find("unknown option '--cpu'"),
              std::string::npos);
    EXPECT_NE(errorOf({"render", "s.sdl", "--frames", "2"}).find("unknown option '--frames'"),
              std::string::npos);
    EXPECT_NE(errorOf({"view"}).find("view: expected one scene file"), std::string::npos);
    EXPECT_NE(errorOf({"view", "s.sdl", "--frames", "0"}).find("--frames: 0 is out of range"),
              std::string::npos);
}

// Each command's --help is its own, generated from the flags it takes.
TEST(Options, EveryCommandHasItsOwnHelp) {
    const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
        {{"render", "--help"},
         {"vkray render", "SCENE", "-o,--output", "--spp", "--check", "--fail", "--failpercent",
          "--aov", "-D", "--watch", "Needs: --check", "Ctrl-C"}},
        {{"pixel", "-h"}, {"vkray pixel", "SCENE", "X", "Y", "--block", "--precision"}},
        {{"compare", "--help"}, {"vkray compare", "--ids", "--diff", "--fail", "--failpercent"}},
        {{"stress", "--help"}, {"vkray stress", "--cases", "--cases-dir", "--out", "--size"}},
        {{"report", "--help"}, {"vkray report", "SCENE", "--out", "--fov", "--lenient"}},
        {{"features", "--help"}, {"vkray features", "--variant", "--spp", "-D"}},
        {{"difftest", "--help"}, {"vkray difftest", "--scenes", "--seed", "--variant", "--out"}},
        {{"view", "--help"},
         {"vkray view", "--frames", "--screenshot", "--events", "--fail", "keys:"}},
        {{"devices", "--help"}, {"vkray devices"}},
        {{"shaders", "check", "--help"},
         {"vkray shaders check", "--all", "--precision", "--shader-dir"}},
        {{"--help"},
         {"render", "pixel", "compare", "stress", "report", "features", "difftest", "view",
          "devices", "shaders", "--version", "COMMAND --help"}},
    };
    for (const auto& [args, texts] : cases) {
        const Options o = parse(args);
        EXPECT_EQ(o.command, Command::Help) << args[0];
        for (const std::string& text : texts)
            EXPECT_NE(o.helpText.find(text), std::string::npos) << text << " in\n" << o.helpText;
    }
    // Only the command's own flags.
    EXPECT_EQ(parse({"render", "--help"}).helpText.find("--frames"), std::string::npos);
    EXPECT_EQ(parse({"stress", "--help"}).helpText.find("--spp"), std::string::npos);
    EXPECT_EQ(parse({"compare", "--help"}).helpText.find("--block"), std::string::npos);
    EXPECT_EQ(parse({}).helpText, usageText());
    EXPECT_EQ(parse({"help"}).helpText, usageText());
}

TEST(Options, ValuesOutOfRangeNameTheFlag) {
    EXPECT_EQ(errorOf({"render", "s.sdl", "--threads", "0"}),
              "--threads: 0 is out of range (1 .. 1024)");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--block=2000"}),
              "--block: 2000 is out of range (1 .. 1024)");
    EXPECT_EQ(errorOf({"difftest", "--scenes", "0"}),
              "--scenes: 0 is out of range (1 .. 100000000)");
    EXPECT_EQ(errorOf({"stress", "--device", "x"}), "--device: 'x' is not a whole number");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--failpercent", "101", "--check"}),
              "--failpercent: must be between 0 and 100");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--cpu", "--validation"}),
              "--validation applies to the GPU; drop --cpu");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--cpu", "-DX=1"}),
              "-D and --dump-spirv apply to the GPU shader; drop --cpu");
    EXPECT_EQ(errorOf({"render", "s.sdl", "--precision", "fp64", "--cpu"}),
              "--precision applies to the GPU; --cpu always renders in double");
    EXPECT_EQ(errorOf({"render", "a.sdl", "b.sdl"}),
              "render: expected one scene file, e.g. `vkray render scenes/default.sdl -o out.png`");
    EXPECT_EQ(errorOf({"shaders"}), "shaders: expected `vkray shaders check`");
    EXPECT_EQ(errorOf({"devices", "x"}), "devices: takes no arguments");
    EXPECT_EQ(errorOf({"compare", "a.png", "b.png", "--ids", "a.id.pfm"}),
              "--ids: expected two files, A.id.pfm B.id.pfm (or A.exr B.exr)");
}

TEST(Options, DefinesRepeatAndNegativeNumbersAreValues) {
    const Options o =
        parse({"render", "s.sdl", "-D", "A=1", "-DB", "--eye", "-1,-2,-3", "-D", "C=x y"});
    ASSERT_EQ(o.defines.size(), 3u);
    EXPECT_EQ(o.defines[0], (std::pair<std::string, std::string>{"A", "1"}));
    EXPECT_EQ(o.defines[1], (std::pair<std::string, std::string>{"B", "1"}));
    EXPECT_EQ(o.defines[2], (std::pair<std::string, std::string>{"C", "x y"}));
    EXPECT_EQ(*o.eye, glm::dvec3(-1, -2, -3));
    EXPECT_EQ(o.scenePath, "s.sdl");
    EXPECT_EQ(parse({"render", "s.sdl", "--spp", "2", "--spp", "8"}).spp,
              8);  // the last one counts
    EXPECT_EQ(parse({"--version"}).command, Command::Version);
    const Options check = parse({"shaders", "check", "--all"});
    EXPECT_EQ(check.command, Command::ShadersCheck);
    EXPECT_TRUE(check.everyVariant);
}

}  // namespace
}  // namespace vkray
