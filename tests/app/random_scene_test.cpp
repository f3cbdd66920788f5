// The differential tester's scene generator: the same seed draws the same
// scene, every scene it draws is valid, and together they cover the whole
// language and every render setting.
#include "app/random_scene.h"

#include "numerics/envelope.h"
#include "reference/shading.h"
#include "scene/scene_geometry.h"
#include "support/temp_folder.h"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

namespace vkray {
namespace {

namespace fs = std::filesystem;

// The scene as `scene.sdl` in `dir`, with the files it names beside it.
fs::path writeScene(const fs::path& dir, const RandomScene& r) {
    const fs::path path = dir / "scene.sdl";
    std::ofstream(path) << r.sdl;
    for (const SideFile& file : r.files)
        std::ofstream(dir / file.name, std::ios::binary) << file.bytes;
    return path;
}

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
    const test::TempFolder scratch("vkray-random-scene-test");
    const fs::path& dir = scratch.path();
    std::set<std::string> words;
    std::set<Precision> modes;
    bool bvh = false, antialiased = false, blocks = false, inside = false, near = false;
    const char* const keywords[] = {"sphere",
                                    "cube",
                                    "cylinder",
                                    "cone",
                                    "torus",
                                    "tetrahedron",
                                    "octahedron",
                                    "dodecahedron",
                                    "icosahedron",
                                    "buckyball",
                                    "teapot",
                                    "square",
                                    "plane",
                                    "mesh",
                                    "taperedCylinder -1",
                                    "taperedCylinder -0.5",
                                    "taperedCylinder 0 ",
                                    "taperedCylinder 2",
                                    "union",
                                    "intersection",
                                    "difference",
                                    "texture 1",
                                    "texture 2",
                                    "emissive 0.",
                                    "speedOfLight",
                                    "specularExponent",
                                    "rotate"};
    for (std::uint64_t seed = 0; seed < 300; ++seed) {
        const RandomScene r = randomScene(seed);
        const fs::path path = writeScene(dir, r);
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
        near |= r.reach.nearRatio > 0;
        // The generator's |M^-1 eye| of each object is the scene reader's.
        ASSERT_EQ(r.genericEye.size(), scene.objects.size()) << seed;
        for (size_t i = 0; i < scene.objects.size(); ++i) {
            const glm::dvec3 generic(scene.objects[i].objectFromWorld *
                                     glm::dvec4(scene.camera->eye, 1));
            EXPECT_NEAR(r.genericEye[i], glm::length(generic),
                        1e-9 * std::max(1.0, glm::length(generic)))
                << "seed " << seed << ", object " << i;
        }
    }
    for (const char* word : keywords) EXPECT_TRUE(words.count(word)) << word << " never drawn";
    EXPECT_EQ(modes, (std::set<Precision>{Precision::Robust, Precision::Fp64}));
    EXPECT_TRUE(bvh);
    EXPECT_TRUE(antialiased);
    EXPECT_TRUE(blocks);
    EXPECT_TRUE(inside);
    EXPECT_TRUE(near);
}

// Each mode's scenes reach every figure of their envelope (docs/numerics.md,
// "Envelope"), each family its own, and none goes beyond: the distance in
// object sizes, |M^-1 eye| of a squashed object, |M^-1 eye| per texture
// cell, the squashes between and before rotations, a huge object's R / H
// from close above it, a refracting solid's thickness per distance.
// Reached: within a factor of 2 (4 for the squashes; 8 where three of ten
// draws are not aimed at the figure's last factor of two).
TEST(RandomScene, EachModesScenesCoverTheirWholeEnvelopeAndStayInside) {
    for (const Precision mode : {Precision::Robust, Precision::Fp64}) {
        const SceneEnvelope envelope = envelopeOf(mode);
        SceneReach most[2];
        int drawn[2] = {0, 0};
        for (std::uint64_t seed = 0; seed < 600; ++seed) {
            const RandomScene r = randomScene(seed, &mode);
            const SceneReach& reach = r.reach;
            const EnvelopeLimits& env = r.lone ? envelope.lone : envelope.scenes;
            const std::string where = std::string(precisionName(mode)) + (r.lone ? " lone" : "") +
                                      " seed " + std::to_string(seed);
            EXPECT_LE(reach.eye, env.farthestEye) << where;
            EXPECT_LE(reach.generic, env.farthestGeneric) << where;
            EXPECT_LE(reach.perCell, env.farthestPerCell) << where;
            EXPECT_LE(reach.worldEye, env.farthestWorldEye) << where;
            EXPECT_GE(reach.squash, env.smallestSquash * (1 - 1e-5)) << where;
            EXPECT_GE(reach.innerSquash, env.smallestInnerSquash * (1 - 1e-5)) << where;
            EXPECT_LE(reach.nearRatio, env.largestNearRatio) << where;
            EXPECT_GE(reach.thinPerDistance, env.thinnestPerDistance) << where;
            SceneReach& m = most[r.lone];
            ++drawn[r.lone];
            m.eye = std::max(m.eye, reach.eye);
            m.generic = std::max(m.generic, reach.generic);
            m.perCell = std::max(m.perCell, reach.perCell);
            m.squash = std::min(m.squash, reach.squash);
            m.innerSquash = std::min(m.innerSquash, reach.innerSquash);
            m.nearRatio = std::max(m.nearRatio, reach.nearRatio);
            m.thinPerDistance = std::min(m.thinPerDistance, reach.thinPerDistance);
        }
        for (const bool lone : {false, true}) {
            const EnvelopeLimits& env = lone ? envelope.lone : envelope.scenes;
            const SceneReach& m = most[lone];
            const std::string name =
                std::string(precisionName(mode)) + (lone ? " lone" : " scenes");
            EXPECT_GT(drawn[lone], 100) << name;
            EXPECT_GE(m.eye, env.farthestEye / 2) << name;
            EXPECT_GE(m.perCell, env.farthestPerCell / 2) << name;
            EXPECT_LE(m.squash, env.smallestSquash * 4) << name;
            EXPECT_LE(m.innerSquash, env.smallestInnerSquash * 4) << name;
            EXPECT_GE(m.nearRatio, env.largestNearRatio / 2) << name;
            if (!lone) {
                EXPECT_GE(m.generic, env.farthestGeneric / 8) << name;
                EXPECT_LE(m.thinPerDistance, env.thinnestPerDistance * 2) << name;
            }
        }
    }
}

// Glass among several objects is held to 5e3 times the offset of the
// refracted rays of both renderers compared: the GPU mode's (robust: 2^-18
// of the distance) and the CPU reference's. fp64's figure was once set from
// its shader's 2^-47 alone, and the CPU reference's refracted rays leaked
// through a tetrahedron squashed to 1.3e-8 (difftest seed 60213, 0.46 % of
// the pixels).
TEST(RandomScene, GlassIsThickerThanEitherRenderersOffset) {
    for (const Precision precision : {Precision::Robust, Precision::Fp64}) {
        const double glass = envelopeOf(precision).scenes.thinnestPerDistance;
        EXPECT_GE(glass, 5e3 * reference::kSecondaryRayOffset) << precisionName(precision);
        if (precision == Precision::Robust) {
            EXPECT_GE(glass, 5e3 * 0x1p-18);
        }
    }
}

// A plane's hits near its horizon lie arbitrarily far, where neither GPU
// mode places them to a texture cell (difftest seed 73245, a wood floor:
// 1.95 % of the pixels at 32x24, all on the horizon's row): drawn for a
// mode, planes are untextured (robust's envelope leaves a textured horizon
// out; open scenes texture them, and auto runs fp64 there).
TEST(RandomScene, APlaneDrawnForAModeIsNeverTextured) {
    int planes = 0;
    for (const Precision mode : {Precision::Naive, Precision::Robust, Precision::Fp64}) {
        for (std::uint64_t seed = 0; seed < 600; ++seed) {
            const std::string sdl = randomScene(seed, &mode).sdl;
            for (std::size_t at = sdl.find(" plane pop"); at != std::string::npos;
                 at = sdl.find(" plane pop", at + 1)) {
                // The material line before the plane's placement line.
                const std::size_t placement = sdl.rfind('\n', at);
                const std::size_t material = sdl.rfind('\n', placement - 1);
                const std::string line = sdl.substr(material + 1, placement - material - 1);
                EXPECT_TRUE(line.find(" texture ") == std::string::npos ||
                            line.ends_with(" texture 0"))
                    << precisionName(mode) << " seed " << seed << ": " << line;
                ++planes;
            }
        }
    }
    EXPECT_GT(planes, 30);
}

// Open scenes (half the seeds drawn for no mode) go where the scenes drawn
// for a mode do not: several planes, tilted and textured (a pixmap too),
// booleans nested in booleans with tori, hourglasses and the mesh among
// their solids, squashes past robust's figures, floors seen to their
// horizon; and `--precision auto` has something to choose: some are inside
// robust's envelope, some need fp64, some pass fp64's too.
TEST(RandomScene, OpenScenesGoPastTheEnvelopesAndAutoChooses) {
    const test::TempFolder scratch("vkray-random-scene-open");
    const fs::path& dir = scratch.path();
    int open = 0, severalPlanes = 0, tilted = 0, texturedPlanes = 0, pixmaps = 0, nested = 0,
        squashedPast = 0, horizon = 0;
    std::map<std::string, int> chosen;
    std::set<std::string> operands;
    for (std::uint64_t seed = 0; seed < 300; ++seed) {
        const RandomScene r = randomScene(seed);
        if (!r.open) continue;
        ++open;
        const fs::path path = writeScene(dir, r);
        Scene scene;
        ASSERT_NO_THROW(scene = loadScene(path.string(), {}, nullptr)) << "seed " << seed << ":\n"
                                                                       << r.sdl;
        ASSERT_EQ(r.genericEye.size(), scene.objects.size()) << seed;
        int planes = 0;
        for (const SceneObject& o : scene.objects) {
            if (o.type == ShapeType::Plane) {
                ++planes;
                texturedPlanes += o.material.texture != 0;
                const glm::dvec3 normal = glm::normalize(glm::dvec3(
                    glm::transpose(glm::dmat3(o.objectFromWorld)) * glm::dvec3(0, 0, 1)));
                tilted += std::abs(normal.y) < 0.999;
            }
            pixmaps += o.material.texture == 3;
            // M's columns' lengths: its scales, whatever the rotations.
            const glm::dmat3 m(o.worldFromObject);
            const double a = glm::length(m[0]), b = glm::length(m[1]), c = glm::length(m[2]);
            const double squash = std::min({a, b, c}) / std::max({a, b, c});
            squashedPast += squash < envelopeOf(Precision::Robust).scenes.smallestSquash;
        }
        severalPlanes += planes > 1;
        for (std::size_t at = r.sdl.find("\n  push"); at != std::string::npos;
             at = r.sdl.find("\n  push", at + 1)) {
            const std::string line = r.sdl.substr(at + 1, r.sdl.find('\n', at + 1) - at - 1);
            for (const char* op : {" union", " intersection", " difference"})
                nested += line.ends_with(op);
            for (const char* solid : {" torus", " taperedCylinder -1", " mesh pyramid.3vn"})
                if (line.ends_with(solid)) operands.insert(solid);
        }
        const Camera camera = *scene.camera;
        const CameraBasis basis = makeCameraBasis(camera, r.width, r.height);
        const PrecisionChoice choice = choosePrecision(scene, basis);
        for (const EnvelopeExcess& e : choice.outside)
            horizon += e.what.ends_with("a textured plane with its horizon in view");
        ++chosen[!choice.beyondEvery.empty() ? "not comparable" : precisionName(choice.precision)];
    }
    EXPECT_GT(open, 100);
    EXPECT_GT(severalPlanes, 5);
    EXPECT_GT(tilted, 10);
    EXPECT_GT(texturedPlanes, 10);
    EXPECT_GT(pixmaps, 5);
    EXPECT_GT(nested, 10);
    EXPECT_GT(squashedPast, 5);
    EXPECT_GT(horizon, 5);
    EXPECT_EQ(operands.size(), 3u);
    for (const char* mode : {"robust", "fp64", "not comparable"})
        EXPECT_GT(chosen[mode], 10) << mode;
}

// fp64 goes further than robust on every figure.
TEST(RandomScene, Fp64sEnvelopeIsWiderThanRobusts) {
    const SceneEnvelope robust = envelopeOf(Precision::Robust), fp64 = envelopeOf(Precision::Fp64);
    for (const auto& [r, f] :
         {std::pair{robust.scenes, fp64.scenes}, std::pair{robust.lone, fp64.lone}}) {
        EXPECT_GT(f.farthestEye, r.farthestEye);
        EXPECT_GT(f.farthestGeneric, r.farthestGeneric);
        EXPECT_GT(f.farthestPerCell, r.farthestPerCell);
        EXPECT_LT(f.smallestSquash, r.smallestSquash);
        EXPECT_LE(f.smallestInnerSquash, r.smallestInnerSquash);
        EXPECT_GT(f.largestNearRatio, r.largestNearRatio);
        EXPECT_LE(f.thinnestPerDistance, r.thinnestPerDistance);
    }
}

}  // namespace
}  // namespace vkray
