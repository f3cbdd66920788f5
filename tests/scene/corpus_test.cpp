// The real SDL files of the corpus (the folder VKRAY_SDL_CORPUS names; the
// tests skip without it), read as users will bring them. tests/data holds
// scenes of our own with the same quirks (sdl_quirks_test.cpp).
// Every expected number here was counted by reading the files (see the
// comments); none was copied from the reader's output.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <glm/vec4.hpp>
#include <string>
#include <vector>

#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"
#include "scene/triangle_mesh.h"
#include "support/corpus.h"
#include "support/error_of.h"
#include "support/scene_checks.h"
#include "util/error.h"

#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray {
namespace {

namespace fs = std::filesystem;

std::string corpus(const std::string& name) {
    return test::corpusFile(name);
}

Scene load(const char* name, bool lenient, std::vector<std::string>* warnings = nullptr) {
    SdlOptions options;
    options.lenient = lenient;
    return loadSdlFile(corpus(name), options, warnings);
}

using test::countOf;
using test::expectNear;
using test::worldPoint;

bool samePath(const std::string& a, const std::string& b) {
    return fs::path(a).lexically_normal() == fs::path(b).lexically_normal();
}

// ---- bookScene.dat: CRLF, a Latin-1 byte, `}def`, and `exponent 50` on line 6

TEST(Corpus, BookSceneStrictStopsAtExponent) {
    VKRAY_NEED_CORPUS();
    const std::string message = errorOf([] { load("bookScene.dat", false); });
    EXPECT_NE(message.find("bookScene.dat:6:1: error:"), std::string::npos) << message;
    EXPECT_NE(message.find("'exponent'"), std::string::npos) << message;
}

TEST(Corpus, BookSceneLenientHasTheTableAndTheJack) {
    VKRAY_NEED_CORPUS();
    std::vector<std::string> warnings;
    const Scene scene = load("bookScene.dat", true, &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("bookScene.dat:6:1: warning: unknown keyword 'exponent' skipped"),
              std::string::npos)
        << warnings[0];
    EXPECT_EQ(scene.path, corpus("bookScene.dat"));

    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].position, glm::dvec3(20, 60, 30));
    EXPECT_EQ(scene.lights[0].color, glm::dvec3(0.7, 0.7, 0.7));

    // jack = 3 x jackPart (3 spheres) = 9 spheres; 1 sphere; 1 teapot;
    // table = top + 4 legs = 5 cubes; 3 walls = 3 cubes.
    ASSERT_EQ(scene.objects.size(), 19u);
    for (int i = 0; i < 10; ++i) EXPECT_EQ(scene.objects[i].type, ShapeType::Sphere) << i;
    EXPECT_EQ(scene.objects[10].type, ShapeType::Teapot);
    for (int i = 11; i < 19; ++i) EXPECT_EQ(scene.objects[i].type, ShapeType::Cube) << i;

    EXPECT_EQ(scene.objects[0].loc.line, 7);  // written in def jackPart
    EXPECT_EQ(scene.objects[10].loc.str(), corpus("bookScene.dat:27:60"));
    // The material of lines 3-5; `exponent` set nothing, so the exponent is 1.
    for (const SceneObject& o : scene.objects) {
        EXPECT_EQ(o.material.ambient, glm::dvec3(0.7));
        EXPECT_EQ(o.material.diffuse, glm::dvec3(0.6));
        EXPECT_EQ(o.material.specular, glm::dvec3(1));
        EXPECT_EQ(o.material.specularExponent, 1);
    }
    // Transforms worked out by hand from lines 7, 14, 17, 25 and 26.
    expectNear(worldPoint(scene.objects[0], {0, 0, 1}), {0.4, 0.4, 0.68});
    expectNear(worldPoint(scene.objects[9], {1, 0, 0}), {0.35, 0.42, 0.35});
    expectNear(worldPoint(scene.objects[11], {0, 0, 0}), {0.4, 0.3, 0.4});
    expectNear(worldPoint(scene.objects[16], {0, 0, 0}), {1, 0.01, 1});
}

TEST(Corpus, BookSceneRendersEverythingItMakes) {
    VKRAY_NEED_CORPUS();
    // Strict stops at `exponent` (line 6); lenient skips it and builds the
    // teapot (line 27) as vkray's built-in one.
    EXPECT_NE(errorOf([&] {
                  loadScene(corpus("bookScene.dat"), {}, nullptr);
              }).find("bookScene.dat:6:1: error"),
              std::string::npos);
    std::vector<std::string> warnings;
    const Scene scene = loadScene(corpus("bookScene.dat"), {true}, &warnings);
    EXPECT_EQ(scene.objects.size(), 19u);
    EXPECT_EQ(countOf(scene, ShapeType::Teapot), 1);
    ASSERT_EQ(warnings.size(), 1u);  // only `exponent`
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0]->name, "built-in teapot");
}

// ---- hlScene1.dat: Hill's own test scene, every word in the grammar ----------

TEST(Corpus, HillSceneLoadsStrictly) {
    VKRAY_NEED_CORPUS();
    std::vector<std::string> warnings;
    const Scene scene = load("hlScene1.dat", false, &warnings);
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(scene.background, glm::dvec3(0.1));
    EXPECT_EQ(scene.maxRecursionDepth, 6);
    EXPECT_EQ(scene.minTransparency, 0.8);
    EXPECT_EQ(scene.minReflectivity, 0.7);
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].position, glm::dvec3(10));

    // taperedCylinder (36), cone (40), 2 jacks x 3 bars x 3 spheres (42, 43),
    // 5 meshes (44-49; 38 and 51 are comments).
    ASSERT_EQ(scene.objects.size(), 25u);
    EXPECT_EQ(scene.objects[0].type, ShapeType::TaperedCylinder);
    EXPECT_EQ(scene.objects[0].taper, 0.3);
    EXPECT_EQ(scene.objects[0].loc.str(), corpus("hlScene1.dat:36:22"));
    EXPECT_EQ(scene.objects[1].type, ShapeType::Cone);
    EXPECT_EQ(scene.objects[1].taper, 0);
    for (int i = 2; i < 20; ++i) EXPECT_EQ(scene.objects[i].type, ShapeType::Sphere) << i;
    const char* meshes[] = {"pawn.3vn", "bucky.3vn", "diamond.3vn", "icosa.3vn", "barnsimp.3vn"};
    for (int i = 0; i < 5; ++i) {
        const SceneObject& mesh = scene.objects[20 + i];
        EXPECT_EQ(mesh.type, ShapeType::Mesh);
        EXPECT_TRUE(samePath(mesh.file, corpus(meshes[i]))) << mesh.file;
    }
    EXPECT_EQ(scene.objects[20].loc.str(), corpus("hlScene1.dat:44:64"));

    // `use red` (line 16) before line 36; the bar's first sphere is green.
    EXPECT_EQ(scene.objects[0].material.diffuse, glm::dvec3(0.8, 0, 0.7));
    EXPECT_EQ(scene.objects[0].material.ambient, glm::dvec3(0.2, 0, 0));
    EXPECT_EQ(scene.objects[0].material.specular, glm::dvec3(0.8));
    EXPECT_EQ(scene.objects[0].material.specularExponent, 30);
    EXPECT_EQ(scene.objects[2].material.diffuse, glm::dvec3(0, 0.8, 0));
    EXPECT_EQ(scene.objects[3].material.diffuse, glm::dvec3(0.8, 0, 0.7));
    EXPECT_EQ(scene.objects[20].material.diffuse, glm::dvec3(0, 0.8, 0.8));  // cyan pawn
    EXPECT_EQ(scene.objects[21].material.diffuse, glm::dvec3(0.9, 0.9, 0));  // yellow bucky

    // Lenient reads it the same way.
    EXPECT_EQ(load("hlScene1.dat", true).objects.size(), 25u);
}

TEST(Corpus, HillSceneReportsItsMissingMeshesByNameAndPlace) {
    VKRAY_NEED_CORPUS();
    // pawn.3vn, bucky.3vn, diamond.3vn, icosa.3vn and barnsimp.3vn are not
    // in the corpus: strict stops at the first, lenient leaves each out.
    EXPECT_NE(errorOf([&] {
                  loadScene(corpus("hlScene1.dat"), {}, nullptr);
              }).find("hlScene1.dat:44:64: error: cannot load mesh 'pawn.3vn'"),
              std::string::npos);
    std::vector<std::string> warnings;
    const Scene scene = loadScene(corpus("hlScene1.dat"), {true}, &warnings);
    EXPECT_EQ(scene.objects.size(), 20u);
    EXPECT_EQ(countOf(scene, ShapeType::Sphere), 18);
    EXPECT_EQ(countOf(scene, ShapeType::Cone), 1);
    EXPECT_EQ(countOf(scene, ShapeType::TaperedCylinder), 1);
    ASSERT_EQ(warnings.size(), 5u);
    EXPECT_NE(warnings[0].find("hlScene1.dat:44:64: warning: cannot load mesh 'pawn.3vn'"),
              std::string::npos);
    EXPECT_NE(warnings[4].find("hlScene1.dat:49:31: warning: cannot load mesh 'barnsimp.3vn'"),
              std::string::npos);
}

// ---- castle.dat: deep def nesting and the `extrude hlArch.dat` extension -----

TEST(Corpus, CastleParses) {
    VKRAY_NEED_CORPUS();
    const Scene scene = load("castle.dat", false);
    EXPECT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.background, glm::dvec3(0.9));
    // archWall (used twice) = 2 towers (2 cylinders + 1 taperedCylinder each)
    // + 2 longTallWalls (16 cubes each) + extrude + wallsection (4 cubes) = 43;
    // left and right walls 40 cubes each; ground and roof 2; roofTrim (13
    // cubes) used 4 times.
    EXPECT_EQ(scene.objects.size(), 220u);
    EXPECT_EQ(countOf(scene, ShapeType::Cube), 206);
    EXPECT_EQ(countOf(scene, ShapeType::Cylinder), 8);
    EXPECT_EQ(countOf(scene, ShapeType::TaperedCylinder), 4);
    EXPECT_EQ(countOf(scene, ShapeType::Extrude), 2);

    ASSERT_GE(scene.objects.size(), 20u);
    EXPECT_EQ(scene.objects[0].type, ShapeType::Cylinder);
    EXPECT_EQ(scene.objects[0].loc.str(), corpus("castle.dat:173:2"));
    EXPECT_EQ(scene.objects[2].type, ShapeType::TaperedCylinder);
    EXPECT_EQ(scene.objects[2].taper, 0.33);
    const SceneObject& arch = scene.objects[19];
    EXPECT_EQ(arch.type, ShapeType::Extrude);
    EXPECT_EQ(arch.loc.str(), corpus("castle.dat:206:2"));
    EXPECT_TRUE(samePath(arch.file, corpus("hlArch.dat"))) << arch.file;
    // Lines 200, 204, 205: translate 21 -4 -1.5, translate 5 0 0, scale 1 1.2 1.
    expectNear(worldPoint(arch, {0, 1, 0}), {26, -2.8, -1.5});
    for (const SceneObject& o : scene.objects) {
        EXPECT_EQ(o.material.emissive, glm::dvec3(0.6, 0, 0));
        EXPECT_EQ(o.material.reflectivity, 0.3);
    }
}

TEST(Corpus, CastleLoadsWithItsExtrudedArches) {
    VKRAY_NEED_CORPUS();
    const Scene scene = loadScene(corpus("castle.dat"), {}, nullptr);
    EXPECT_EQ(scene.objects.size(), 220u);
    ASSERT_EQ(scene.meshes.size(), 1u);  // both `extrude hlArch.dat` share one mesh
    for (const SceneObject& o : scene.objects) {
        if (o.type == ShapeType::Extrude) {
            EXPECT_EQ(o.mesh, 0);
        }
    }
}

// ---- scenes/*.sdl: the project's own scenes, in vkray's dialect ----------------

TEST(ProjectScenes, LoadStrictlyWithCameras) {
    int scenes = 0;
    for (const auto& entry : fs::directory_iterator(VKRAY_SOURCE_DIR "/scenes")) {
        if (entry.path().extension() != ".sdl") continue;
        ++scenes;
        std::vector<std::string> warnings;
        const Scene scene = loadScene(entry.path().string(), {}, &warnings);
        EXPECT_TRUE(warnings.empty()) << entry.path();
        EXPECT_TRUE(scene.camera.has_value()) << entry.path();
        EXPECT_FALSE(scene.objects.empty()) << entry.path();
    }
    EXPECT_GE(scenes, 1);
}

TEST(ProjectScenes, DefaultSceneAsWritten) {
    const Scene scene = loadSdlFile(VKRAY_SOURCE_DIR "/scenes/default.sdl", {});
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.camera->eye, glm::dvec3(14, 9, 16));
    EXPECT_EQ(scene.camera->look, glm::dvec3(0, 1, 0));
    EXPECT_EQ(scene.camera->fovDegrees, 40);
    EXPECT_EQ(scene.lights.size(), 3u);
    // floor plane, red sphere, blue cube, green ellipsoid, glowing square
    ASSERT_EQ(scene.objects.size(), 5u);
    EXPECT_EQ(scene.objects[0].type, ShapeType::Plane);
    EXPECT_EQ(scene.objects[4].type, ShapeType::Square);
    EXPECT_EQ(scene.objects[1].material.specularExponent, 60);  // use shiny
}

}  // namespace
}  // namespace vkray
