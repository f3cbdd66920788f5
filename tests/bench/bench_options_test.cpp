// vkray_bench's command line: bad values are errors naming the flag, never
// clamped or read as 0 (atoi's `--repeat abc` was 1).
#include "bench/bench_options.h"
#include "util/error.h"

#include <gtest/gtest.h>

namespace vkray::bench {
namespace {

const std::vector<std::string> kKnown = {"spheres1", "mesh", "castle"};

BenchOptions defaults() {
    BenchOptions d;
    d.sceneNames = {"spheres1", "mesh"};
    d.tile = 256;
    d.shaderDirectory = "build/shaders";
    return d;
}

BenchOptions parse(std::vector<std::string> args) {
    return parseBenchOptions(args, defaults(), kKnown);
}

std::string errorOf(std::vector<std::string> args) {
    try {
        parse(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(BenchOptions, DefaultsAndEveryFlag) {
    const BenchOptions d = parse({});
    EXPECT_EQ(d.sceneNames, (std::vector<std::string>{"spheres1", "mesh"}));
    EXPECT_EQ(d.width, 1920);
    EXPECT_EQ(d.repeat, 2);
    EXPECT_EQ(d.tile, 256);
    EXPECT_EQ(d.allWidth, 1920);  // --all-size defaults to --size
    EXPECT_TRUE(d.all && d.cpu && d.embree && d.fma);
    const BenchOptions o =
        parse({"--scenes", "mesh,castle", "--size", "64x48", "--repeat=5", "--threads", "3",
               "--tile", "32", "--all-size", "16x8", "--no-all", "--no-cpu", "--no-embree",
               "--no-fma", "--shaded", "--only-experiments", "--shader-dir", "s"});
    EXPECT_EQ(o.sceneNames, (std::vector<std::string>{"mesh", "castle"}));
    EXPECT_EQ(o.width, 64);
    EXPECT_EQ(o.height, 48);
    EXPECT_EQ(o.repeat, 5);
    EXPECT_EQ(o.threads, 3);
    EXPECT_EQ(o.tile, 32);
    EXPECT_EQ(o.allWidth, 16);
    EXPECT_EQ(o.allHeight, 8);
    EXPECT_FALSE(o.all || o.cpu || o.embree || o.fma);
    EXPECT_TRUE(o.shaded && o.experiments && o.onlyExperiments);
    EXPECT_EQ(o.shaderDirectory, "s");
}

TEST(BenchOptions, AgainstIsTheTuningTableAloneOverTwoShaderFolders) {
    const std::string folder = ::testing::TempDir();
    const BenchOptions o = parse({"--against", folder});
    EXPECT_EQ(o.againstDirectory, folder);
    EXPECT_TRUE(o.experiments && o.onlyExperiments);
    EXPECT_FALSE(parse({}).onlyExperiments);
    const std::string missing = errorOf({"--against", "no/such/folder"});
    EXPECT_NE(missing.find("--against"), std::string::npos) << missing;
    EXPECT_NE(missing.find("no/such/folder"), std::string::npos) << missing;
}

TEST(BenchOptions, SceneFilesAloneReplaceTheDefaultList) {
    const BenchOptions files = parse({"--scene", "a.sdl", "--scene", "b.sdl"});
    EXPECT_TRUE(files.sceneNames.empty());
    EXPECT_EQ(files.sceneFiles, (std::vector<std::string>{"a.sdl", "b.sdl"}));
    EXPECT_EQ(parse({"--scene", "a.sdl", "--scenes", "mesh"}).sceneNames,
              (std::vector<std::string>{"mesh"}));
}

TEST(BenchOptions, RandomScenesAloneReplaceTheDefaultListAndTakeASeed) {
    const BenchOptions random = parse({"--random", "40", "--seed", "4294967295"});
    EXPECT_EQ(random.randomScenes, 40);
    EXPECT_TRUE(random.sceneNames.empty());
    ASSERT_TRUE(random.seed.has_value());
    EXPECT_EQ(*random.seed, 4294967295u);                     // difftest's seeds are 32 bits
    EXPECT_FALSE(parse({"--random", "3"}).seed.has_value());  // the harness draws a fresh one
    EXPECT_EQ(parse({"--random", "3", "--scenes", "mesh"}).sceneNames,
              (std::vector<std::string>{"mesh"}));
    EXPECT_EQ(parse({}).randomScenes, 0);
    EXPECT_NE(errorOf({"--random", "0"}).find("--random"), std::string::npos);
    EXPECT_NE(errorOf({"--random", "x"}).find("--random"), std::string::npos);
    EXPECT_NE(errorOf({"--random", "2", "--seed", "-1"}).find("--seed"), std::string::npos);
    EXPECT_NE(errorOf({"--random", "2", "--seed", "4294967296"}).find("--seed"), std::string::npos);
    const std::string alone = errorOf({"--seed", "7"});
    EXPECT_NE(alone.find("--random"), std::string::npos) << alone;
}

TEST(BenchOptions, BadValuesAreErrorsNamingTheFlag) {
    const std::string notANumber = errorOf({"--repeat", "abc"});
    EXPECT_NE(notANumber.find("--repeat"), std::string::npos) << notANumber;
    EXPECT_NE(notANumber.find("abc"), std::string::npos) << notANumber;
    EXPECT_NE(errorOf({"--repeat", "0"}).find("--repeat"), std::string::npos);
    EXPECT_NE(errorOf({"--repeat", "101"}).find("--repeat"), std::string::npos);
    EXPECT_NE(errorOf({"--tile", "4"}).find("--tile"), std::string::npos);
    EXPECT_NE(errorOf({"--threads", "2x"}).find("--threads"), std::string::npos);
    EXPECT_NE(errorOf({"--size", "64x"}).find("--size: expected WxH"), std::string::npos);
    EXPECT_NE(errorOf({"--all-size", "0x4"}).find("--all-size"), std::string::npos);
    EXPECT_NE(errorOf({"--scenes", "mesh,nope"}).find("unknown scene 'nope'"), std::string::npos);
    EXPECT_NE(errorOf({"--bogus"}).find("--bogus"), std::string::npos);
    EXPECT_NE(errorOf({"--repeat"}).find("--repeat"), std::string::npos);
}

TEST(BenchOptions, HelpListsTheFlagsAndScenes) {
    const BenchOptions help = parse({"--help"});
    for (const char* text : {"--repeat", "--scenes", "--all-size", "--only-experiments", "castle",
                             "default list: spheres1,mesh"})
        EXPECT_NE(help.helpText.find(text), std::string::npos) << text << "\n" << help.helpText;
}

}  // namespace
}  // namespace vkray::bench
