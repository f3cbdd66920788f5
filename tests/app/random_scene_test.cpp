// The differential tester's scene generator: the same seed draws the same
// scene, every scene it draws is valid, and together they cover the whole
// language and every render setting.
#include "app/random_scene.h"

#include "scene/scene_geometry.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace vkray {
namespace {

namespace fs = std::filesystem;

TEST(RandomScene, TheSameSeedDrawsTheSameScene) {
    const RandomScene a = randomScene(7), b = randomScene(7), c = randomScene(8);
    EXPECT_EQ(a.sdl, b.sdl);
    EXPECT_EQ(a.spp, b.spp);
    EXPECT_EQ(a.sampleSeed, b.sampleSeed);
    EXPECT_EQ(a.precision, b.precision);
    EXPECT_NE(a.sdl, c.sdl);
    const Precision fp64 = Precision::Fp64, naive = Precision::Naive;
    EXPECT_EQ(randomScene(7, &fp64).precision, Precision::Fp64);
    EXPECT_EQ(randomScene(7, &naive).precision, Precision::Naive);
}

TEST(RandomScene, EverySceneLoadsAndTogetherTheyCoverTheLanguage) {
    const fs::path dir = fs::temp_directory_path() / "vkray-random-scene-test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::set<std::string> words;
    std::set<Precision> modes;
    bool bvh = false, antialiased = false, blocks = false, inside = false;
    const char* const keywords[] = {
        "sphere", "cube", "cylinder", "cone", "torus", "tetrahedron", "octahedron",
        "dodecahedron", "icosahedron", "buckyball", "teapot", "square", "plane", "mesh",
        "taperedCylinder -1", "taperedCylinder -0.5", "taperedCylinder 0 ", "taperedCylinder 2",
        "union", "intersection", "difference", "texture 1", "texture 2", "emissive 0.",
        "speedOfLight", "specularExponent", "rotate"};
    for (std::uint64_t seed = 0; seed < 300; ++seed) {
        const RandomScene r = randomScene(seed);
        const fs::path path = dir / "scene.sdl";
        std::ofstream(path) << r.sdl;
        if (!r.meshFile.empty()) std::ofstream(dir / r.meshFile) << r.meshText;
        Scene scene;
        ASSERT_NO_THROW(scene = loadScene(path.string(), {}, nullptr)) << "seed " << seed << ":\n"
                                                                       << r.sdl;
        ASSERT_TRUE(scene.camera.has_value()) << seed;
        EXPECT_FALSE(scene.objects.empty()) << seed;
        EXPECT_FALSE(scene.lights.empty()) << seed;
        for (const char* word : keywords)
            if (r.sdl.find(word) != std::string::npos) words.insert(word);
        modes.insert(r.precision);
        bvh |= scene.objects.size() > 8;
        antialiased |= r.spp > 1;
        blocks |= r.block > 1;
        // The eye at an object's centre: the camera line repeats a translate.
        const std::string eye = r.sdl.substr(11, r.sdl.find(" look") - 11);
        inside |= r.sdl.find("translate " + eye) != std::string::npos;
    }
    for (const char* word : keywords) EXPECT_TRUE(words.count(word)) << word << " never drawn";
    EXPECT_EQ(modes, (std::set<Precision>{Precision::Robust, Precision::Fp64}));
    EXPECT_TRUE(bvh);
    EXPECT_TRUE(antialiased);
    EXPECT_TRUE(blocks);
    EXPECT_TRUE(inside);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace vkray
