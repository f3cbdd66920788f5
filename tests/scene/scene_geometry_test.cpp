// Scene geometry: meshes loaded once and shared, missing meshes reported at
// the `mesh` word (strict) or left out with a warning (lenient), world
// bounds worked out by hand, and the object BVH.
#include "scene/scene_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>

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

const std::string& kData = test::kTestData;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string corpus(const std::string& name) {
    return test::corpusFile(name);
}

Scene corpusScene(const char* name, bool lenient, std::vector<std::string>* warnings) {
    SdlOptions options;
    options.lenient = lenient;
    return loadSdlFile(corpus(name), options, warnings);
}

// SDL text as if it were a file in tests/data (so mesh paths find the meshes
// there), with its geometry loaded.
Scene sceneOf(const std::string& text, bool lenient = false,
              std::vector<std::string>* warnings = nullptr) {
    Scene scene = parseSdl(text, kData + "test.sdl", SdlOptions{}, warnings);
    loadSceneGeometry(scene, lenient, warnings);
    return scene;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

void expectBox(const Aabb& box, glm::dvec3 lo, glm::dvec3 hi, double tolerance = 1e-14) {
    for (int axis = 0; axis < 3; ++axis) {
        // Conservative: never inside the exact box, and only rounding-wide beyond it.
        EXPECT_LE(box.lo[axis], lo[axis]) << "axis " << axis;
        EXPECT_GE(box.hi[axis], hi[axis]) << "axis " << axis;
        EXPECT_NEAR(box.lo[axis], lo[axis], tolerance) << "axis " << axis;
        EXPECT_NEAR(box.hi[axis], hi[axis], tolerance) << "axis " << axis;
    }
}

// ---- meshes in corpus scenes (skipped without VKRAY_SDL_CORPUS) -------------------

TEST(SceneGeometry, CorpusHillSceneLenientLeavesOutItsMissingMeshesByName) {
    VKRAY_NEED_CORPUS();
    std::vector<std::string> warnings;
    Scene scene = corpusScene("hlScene1.dat", true, &warnings);
    ASSERT_EQ(scene.objects.size(), 25u);  // 20 shapes and 5 meshes (corpus tests)
    warnings.clear();
    loadSceneGeometry(scene, true, &warnings);
    EXPECT_EQ(scene.objects.size(), 20u);
    EXPECT_TRUE(scene.meshes.empty());
    const char* expected[][2] = {{"44:64", "pawn.3vn"},
                                 {"45:35", "bucky.3vn"},
                                 {"46:32", "diamond.3vn"},
                                 {"48:32", "icosa.3vn"},
                                 {"49:31", "barnsimp.3vn"}};
    ASSERT_EQ(warnings.size(), 5u);
    for (int i = 0; i < 5; ++i) {
        const std::string firstLine = corpus("hlScene1.dat:") + expected[i][0] +
                                      ": warning: cannot load mesh '" + expected[i][1] +
                                      "'; left out\n";
        EXPECT_EQ(warnings[i].substr(0, firstLine.size()), firstLine);
        // The reader's message follows as a note naming the missing file.
        EXPECT_TRUE(contains(warnings[i], std::string(expected[i][1]) +
                                              ": note: cannot read mesh file: No such file"))
            << warnings[i];
    }
    for (const SceneObject& object : scene.objects) EXPECT_NE(object.type, ShapeType::Mesh);
}

TEST(SceneGeometry, CorpusStrictMissingMeshNamesTheMeshWordAndThePath) {
    VKRAY_NEED_CORPUS();
    Scene scene = corpusScene("hlScene1.dat", false, nullptr);
    const std::string message = errorOf([&] { loadSceneGeometry(scene, false, nullptr); });
    const std::string firstLine =
        corpus("hlScene1.dat:44:64: error: cannot load mesh 'pawn.3vn'\n");
    EXPECT_EQ(message.substr(0, firstLine.size()), firstLine);
    EXPECT_TRUE(contains(message, corpus("pawn.3vn: error: cannot read mesh file: No such file")))
        << message;
}

TEST(SceneGeometry, CorpusBookSceneTeapotIsTheBuiltInOne) {
    VKRAY_NEED_CORPUS();
    std::vector<std::string> warnings;
    Scene scene = corpusScene("bookScene.dat", true, &warnings);
    const std::size_t objects = scene.objects.size();
    warnings.clear();
    loadSceneGeometry(scene, true, &warnings);
    EXPECT_TRUE(warnings.empty());
    EXPECT_EQ(scene.objects.size(), objects);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0]->name, "built-in teapot");
    int teapots = 0;
    for (const SceneObject& object : scene.objects) {
        if (object.type != ShapeType::Teapot) continue;
        EXPECT_EQ(object.mesh, 0);
        ++teapots;
    }
    EXPECT_EQ(teapots, 1);
}

TEST(SceneGeometry, CorpusCastleExtrudesItsArchOnceForBothUses) {
    VKRAY_NEED_CORPUS();
    Scene scene = corpusScene("castle.dat", false, nullptr);
    loadSceneGeometry(scene, false, nullptr);  // strict: everything loads
    ASSERT_EQ(scene.meshes.size(), 1u);
    const TriangleMesh& arch = *scene.meshes[0];
    EXPECT_EQ(arch.name, "hlArch.dat");
    EXPECT_TRUE(arch.closed);
    EXPECT_EQ(arch.triangles.size(), 140u);
    int extrudes = 0;
    for (const SceneObject& object : scene.objects) {
        const bool extruded = object.type == ShapeType::Extrude;
        EXPECT_EQ(object.mesh, extruded ? 0 : -1);
        extrudes += extruded ? 1 : 0;
    }
    EXPECT_EQ(extrudes, 2);
    // The first arch (object 19): translate 26 -4 -1.5, scale 1 1.2 1; the
    // outline's box [-5, 5] x [0, 7] x [0, 1] lands on [21, 31] x [-4, 4.4] x [-1.5, -0.5].
    expectBox(worldBounds(scene.objects[19], scene), {21, -4, -1.5}, {31, 4.4, -0.5}, 1e-13);
}

TEST(SceneGeometry, EachFileLoadsOnceHoweverItIsSpelled) {
    const Scene scene = sceneOf(
        "mesh wedge.3vn translate 3 0 0 mesh ./wedge.3vn mesh ../data/wedge.3vn "
        "mesh pyramid.3vn dodecahedron tetrahedron dodecahedron");
    ASSERT_EQ(scene.objects.size(), 7u);
    ASSERT_EQ(scene.meshes.size(), 4u);  // wedge.3vn, pyramid.3vn, 2 built-ins
    EXPECT_EQ(scene.objects[0].mesh, 0);
    EXPECT_EQ(scene.objects[1].mesh, 0);
    EXPECT_EQ(scene.objects[2].mesh, 0);
    EXPECT_EQ(scene.objects[3].mesh, 1);
    EXPECT_EQ(scene.objects[4].mesh, 2);
    EXPECT_EQ(scene.objects[5].mesh, 3);
    EXPECT_EQ(scene.objects[6].mesh, 2);
    EXPECT_EQ(scene.meshes[0]->name, "wedge.3vn");
    EXPECT_EQ(scene.meshes[0]->triangles.size(), 8u);  // 2 triangles and 3 quads
    EXPECT_EQ(scene.meshes[1]->name, "pyramid.3vn");
    EXPECT_EQ(scene.meshes[2]->name, "built-in dodecahedron");
    EXPECT_EQ(scene.meshes[3]->name, "built-in tetrahedron");
}

TEST(SceneGeometry, MeshesInsideBooleans) {
    // Operands get their meshes; a missing one is an error at its own word...
    const Scene good = sceneOf("union dodecahedron difference sphere mesh wedge.3vn");
    ASSERT_EQ(good.objects.size(), 1u);
    EXPECT_EQ(good.objects[0].operands[0].mesh, 0);
    EXPECT_EQ(good.objects[0].operands[1].operands[1].mesh, 1);
    EXPECT_EQ(good.meshes.size(), 2u);
    EXPECT_EQ(errorOf([] {
                  sceneOf("sphere\nunion sphere\n  difference cube mesh gone.3vn");
              }).substr(0, 200),
              (kData + "test.sdl:3:19: error: cannot load mesh 'gone.3vn'\n" + kData +
               "gone.3vn: error: cannot read mesh file: No such file or directory")
                  .substr(0, 200));
    // ... and lenient leaves out the whole top-level boolean, with the meshes
    // only it used (the tetrahedron here), and says which boolean went.
    std::vector<std::string> warnings;
    const Scene lenient =
        sceneOf("sphere\nunion tetrahedron\n  difference cube mesh gone.3vn\ncube dodecahedron",
                true, &warnings);
    ASSERT_EQ(lenient.objects.size(), 3u);
    EXPECT_EQ(lenient.objects[0].type, ShapeType::Sphere);
    EXPECT_EQ(lenient.objects[1].type, ShapeType::Cube);
    EXPECT_EQ(lenient.objects[2].type, ShapeType::Dodecahedron);
    ASSERT_EQ(lenient.meshes.size(), 1u);
    EXPECT_EQ(lenient.meshes[0]->name, "built-in dodecahedron");
    EXPECT_EQ(lenient.objects[2].mesh, 0);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(contains(warnings[0], kData +
                                          "test.sdl:3:19: warning: cannot load mesh "
                                          "'gone.3vn'; the 'union' at " +
                                          kData + "test.sdl:2:1 that holds it is left out\n"))
        << warnings[0];
}

TEST(SceneGeometry, MissingOutlineIsReportedAtTheExtrudeWord) {
    std::vector<std::string> warnings;
    const Scene scene = sceneOf("extrude missing.dat sphere", true, &warnings);
    EXPECT_EQ(scene.objects.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].substr(0, warnings[0].find('\n')),
              kData + "test.sdl:1:1: warning: cannot extrude 'missing.dat'; left out");
}

TEST(SceneGeometry, CorpusLoadSceneLoadsMeshes) {
    VKRAY_NEED_CORPUS();
    std::vector<std::string> warnings;
    const Scene scene = loadScene(corpus("hlScene1.dat"), SdlOptions{.lenient = true}, &warnings);
    int meshWarnings = 0;
    for (const std::string& w : warnings) meshWarnings += contains(w, "cannot load mesh") ? 1 : 0;
    EXPECT_EQ(meshWarnings, 5);
    for (const SceneObject& object : scene.objects) {
        if (object.type == ShapeType::Mesh) {
            EXPECT_GE(object.mesh, 0);
        }
    }
}

// ---- world bounds ------------------------------------------------------------------

Aabb boundsOf(const std::string& text) {
    const Scene scene = sceneOf(text);
    EXPECT_EQ(scene.objects.size(), 1u);
    return worldBounds(scene.objects.at(0), scene);
}

TEST(SceneGeometry, WorldBoundsOfTransformedShapes) {
    // M = T(1, 2, 3) S(2, 3, 4): the unit sphere's box becomes centre (1, 2, 3)
    // with half sizes (2, 3, 4).
    expectBox(boundsOf("translate 1 2 3 scale 2 3 4 sphere"), {-1, -1, -1}, {3, 5, 7});
    // A cube turned 30 degrees about z: its square's corners reach
    // cos 30 + sin 30 = 1.3660... in x and y; z stays [-1, 1].
    const double reach = std::cos(std::numbers::pi / 6) + 0.5;
    expectBox(boundsOf("rotate 30 0 0 1 cube"), {-reach, -reach, -1}, {reach, reach, 1});
    // 45 degrees about x, then moved: y and z reach sqrt 2 about (0, 0, 10).
    const double r2 = std::numbers::sqrt2;
    expectBox(boundsOf("translate 0 0 10 rotate 45 1 0 0 cube"), {-1, -r2, 10 - r2},
              {1, r2, 10 + r2}, 1e-13);
    // Generic extents: square z = 0; tapered cylinder radius max(1, s); torus R + r, r.
    expectBox(boundsOf("translate 0 0 5 square"), {-1, -1, 5}, {1, 1, 5});
    expectBox(boundsOf("taperedCylinder 2"), {-2, -2, 0}, {2, 2, 1});
    expectBox(boundsOf("taperedCylinder 0.5"), {-1, -1, 0}, {1, 1, 1});
    expectBox(boundsOf("cone"), {-1, -1, 0}, {1, 1, 1});
    expectBox(boundsOf("scale 1 1 3 cylinder"), {-1, -1, 0}, {1, 1, 3});
    expectBox(boundsOf("torus"), {-1.25, -1.25, -0.25}, {1.25, 1.25, 0.25});
    // The built-in octahedron (vertices on the axes) scaled by 2.
    expectBox(boundsOf("scale 2 2 2 octahedron"), glm::dvec3(-2), glm::dvec3(2));
    EXPECT_FALSE(boundsOf("rotate 10 1 1 0 plane").finite());
}

TEST(SceneGeometry, FlatBoundsAreHitByRays) {
    const Aabb square = boundsOf("translate 0 0 5 square");
    EXPECT_LT(square.hi.z - square.lo.z, 1e-14);
    double t = -1;
    EXPECT_TRUE(intersectAabb(square, {0.5, 0.5, 0}, 1.0 / glm::dvec3(0, 0, 1), 0, kInf, &t));
    EXPECT_NEAR(t, 5, 1e-14);
    EXPECT_TRUE(intersectAabb(square, {-3, 0, 5}, 1.0 / glm::dvec3(1, 0, 0), 0, kInf, &t));
    EXPECT_NEAR(t, 2, 1e-14);
}

TEST(SceneGeometry, WorldBoundsOfBooleans) {
    // Spheres at x = -3 and x = 3: union [-4, 4] x [-1, 1]^2.
    expectBox(boundsOf("union push translate -3 0 0 sphere pop push translate 3 0 0 sphere pop"),
              {-4, -1, -1}, {4, 1, 1});
    // Sphere at 0 and cube at x = 1.5 ([0.5, 2.5] in x): they overlap in [0.5, 1].
    expectBox(boundsOf("intersection sphere push translate 1.5 0 0 cube pop"), {0.5, -1, -1},
              {1, 1, 1});
    // difference: the first operand's box.
    expectBox(boundsOf("difference push translate 0 4 0 sphere pop cube"), {-1, 3, -1}, {1, 5, 1});
    // A plane cut by a sphere is bounded; a plane joined to one is not.
    expectBox(boundsOf("intersection push rotate 20 1 0 0 plane pop sphere"), glm::dvec3(-1),
              glm::dvec3(1));
    EXPECT_FALSE(boundsOf("union plane sphere").finite());
    // Apart: nothing is left of an intersection.
    EXPECT_TRUE(boundsOf("intersection sphere push translate 5 0 0 sphere pop").empty());
    // Nested: (sphere at -3 union sphere at 3) intersected with the cube at 0.
    expectBox(boundsOf("intersection union push translate -3 0 0 sphere pop push translate 3 0 0 "
                       "sphere pop scale 2 2 2 cube"),
              {-2, -1, -1}, {2, 1, 1});
}

TEST(SceneGeometry, MeshObjectsWithoutTheirMeshAreUnbounded) {
    Scene scene = parseSdl("dodecahedron", "t.sdl", SdlOptions{});
    EXPECT_FALSE(worldBounds(scene.objects[0], scene).finite());  // mesh == -1: not loaded yet
    loadSceneGeometry(scene, false, nullptr);
    // Dodecahedron with circumradius 1: (+-1, +-1, +-1) / sqrt3 and (0, 1/phi, phi) / sqrt3
    // reach phi / sqrt 3 on each axis.
    const double reach = std::numbers::phi / std::numbers::sqrt3;
    expectBox(worldBounds(scene.objects[0], scene), glm::dvec3(-reach), glm::dvec3(reach), 1e-15);
}

// ---- object BVH ---------------------------------------------------------------------

TEST(SceneGeometry, ObjectBvhHoldsBoundedObjectsAndListsTheRest) {
    const Scene scene = sceneOf(
        "sphere plane push translate 5 0 0 cube pop "
        "intersection sphere push translate 5 0 0 sphere pop "
        "union plane cube translate 0 9 0 teapot");
    ASSERT_EQ(scene.objects.size(), 6u);
    const ObjectBvh objects = buildObjectBvh(scene);
    // Bounded: sphere (0), cube (2), teapot (5); unbounded: plane (1), union with a plane (4);
    // the empty intersection (3) in neither.
    std::vector<std::uint32_t> order = objects.bvh.order;
    std::sort(order.begin(), order.end());
    EXPECT_EQ(order, (std::vector<std::uint32_t>{0, 2, 5}));
    EXPECT_EQ(objects.unbounded, (std::vector<std::uint32_t>{1, 4}));
    ASSERT_FALSE(objects.bvh.nodes.empty());
    // The root holds the sphere, the cube at x = 5 and the teapot around y = 9.
    expectBox(objects.bvh.nodes[0].bounds, {-1.5, -1, -1}, {6, 9.825, 1});
}

TEST(SceneGeometry, ObjectBvhOverManySpheresFindsEachOne) {
    std::string text;
    for (int i = 0; i < 1000; ++i) {
        text += "push translate " + std::to_string(i % 10 * 3) + " " +
                std::to_string(i / 10 % 10 * 3) + " " + std::to_string(i / 100 * 3) +
                " sphere pop\n";
    }
    const Scene scene = sceneOf(text);
    const ObjectBvh objects = buildObjectBvh(scene);
    EXPECT_TRUE(objects.unbounded.empty());
    std::vector<std::uint32_t> order = objects.bvh.order;
    std::sort(order.begin(), order.end());
    for (std::uint32_t i = 0; i < 1000; ++i) ASSERT_EQ(order[i], i);
    // Sphere i's centre: a ray down z through it finds it in some leaf the ray reaches.
    for (std::uint32_t i = 0; i < 1000; i += 37) {
        const glm::dvec3 centre(i % 10 * 3, i / 10 % 10 * 3, i / 100 * 3);
        const glm::dvec3 origin = centre - glm::dvec3(0, 0, 50);
        const glm::dvec3 inv = 1.0 / glm::dvec3(0, 0, 1);
        bool found = false;
        std::vector<std::uint32_t> stack{0};
        while (!stack.empty()) {
            const std::uint32_t index = stack.back();
            stack.pop_back();
            const BvhNode& node = objects.bvh.nodes[index];
            if (!intersectAabb(node.bounds, origin, inv, 0, kInf)) continue;
            if (node.leaf()) {
                for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                    found |= objects.bvh.order[k] == i;
            } else {
                stack.push_back(node.first);
                stack.push_back(index + 1);
            }
        }
        EXPECT_TRUE(found) << i;
    }
}

}  // namespace
}  // namespace vkray
