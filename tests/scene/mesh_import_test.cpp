// Mesh files through Assimp: tests/data/meshes' own small files (written by
// hand, so every count, bound and normal below is worked out from the file),
// the real models of Debian's assimp-testmodels (skipped, with the reason,
// where that package is not installed), and every way a file can be refused,
// with the path, the SDL place that named it and Assimp's own message.
#include "scene/mesh_import.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <string>

#include "scene/scene_geometry.h"
#include "support/error_of.h"
#include "support/scene_checks.h"
#include "support/temp_folder.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;

const std::string kMeshes = test::kTestData + "meshes/";
const std::string kModels = "/usr/share/assimp/models/";

#define VKRAY_NEED_TESTMODELS()                                                           \
    do {                                                                                  \
        if (!fs::is_directory(kModels))                                                   \
            GTEST_SKIP() << kModels << " is missing: install Debian's assimp-testmodels " \
                         << "(scripts/install-deps.sh does)";                             \
    } while (0)

glm::dvec3 faceNormal(const TriangleMesh& mesh, const TriangleMesh::Triangle& t) {
    const glm::dvec3 a = mesh.positions[t.position[0]];
    return glm::normalize(
        glm::cross(mesh.positions[t.position[1]] - a, mesh.positions[t.position[2]] - a));
}

void writeFile(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

TEST(MeshImport, ChoosesTheReaderByTheNamesExtension) {
    EXPECT_TRUE(is3vnPath("pawn.3vn"));
    EXPECT_TRUE(is3vnPath("dir.obj/PAWN.3VN"));
    EXPECT_FALSE(is3vnPath("pawn.obj"));
    EXPECT_FALSE(is3vnPath("3vn"));
    EXPECT_FALSE(is3vnPath("model.3vn.glb"));
}

// Six quads without normals: twelve triangles, each with its own face normal
// (all three corners alike, pointing out of the cube), eight welded corners.
TEST(MeshImport, ObjQuadsAreSplitAndGetFaceNormals) {
    const TriangleMesh mesh = loadMeshFile(kMeshes + "cube.obj");
    EXPECT_EQ(mesh.name, "cube.obj");
    ASSERT_EQ(mesh.triangles.size(), 12u);
    EXPECT_EQ(mesh.positions.size(), 8u);
    EXPECT_TRUE(mesh.closed);
    test::expectNear(mesh.bounds.lo, glm::dvec3(-1));
    test::expectNear(mesh.bounds.hi, glm::dvec3(1));
    for (const TriangleMesh::Triangle& t : mesh.triangles) {
        const glm::dvec3 n = mesh.normals[t.normal[0]];
        EXPECT_EQ(t.normal[1], t.normal[0]);
        EXPECT_EQ(t.normal[2], t.normal[0]);
        test::expectNear(n, faceNormal(mesh, t));
        const glm::dvec3 centre = (mesh.positions[t.position[0]] + mesh.positions[t.position[1]] +
                                   mesh.positions[t.position[2]]) /
                                  3.0;
        EXPECT_GT(glm::dot(n, centre), 0.5) << "a face normal points into the cube";
        // Axis-aligned: one component is +-1.
        EXPECT_NEAR(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.0, 1e-12);
    }
}

// The file's vertex normals, normalised, one per corner.
TEST(MeshImport, PlyVertexNormalsAreKeptPerCorner) {
    const TriangleMesh mesh = loadMeshFile(kMeshes + "triangle_normals.ply");
    ASSERT_EQ(mesh.triangles.size(), 1u);
    EXPECT_FALSE(mesh.closed);
    const TriangleMesh::Triangle& t = mesh.triangles[0];
    const glm::dvec3 expected[3] = {{0, 0, 1},
                                    {1 / std::sqrt(2.0), 0, 1 / std::sqrt(2.0)},
                                    {0, 1 / std::sqrt(2.0), 1 / std::sqrt(2.0)}};
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 p = mesh.positions[t.position[k]];
        // Match corners by position: Assimp may keep or reorder them.
        const int corner = p.x == 1 ? 1 : p.y == 1 ? 2 : 0;
        const glm::dvec3 n = mesh.normals[t.normal[k]];
        EXPECT_NEAR(n.x, expected[corner].x, 1e-7) << "corner " << k;
        EXPECT_NEAR(n.y, expected[corner].y, 1e-7) << "corner " << k;
        EXPECT_NEAR(n.z, expected[corner].z, 1e-7) << "corner " << k;
    }
}

// glTF 2.0 with its buffer in a data URI: the node's translation (2, 0, 0)
// places the tetrahedron, whose four faces make a closed surface.
TEST(MeshImport, GltfNodesPlaceTheirMeshes) {
    const TriangleMesh mesh = loadMeshFile(kMeshes + "tetrahedron_moved.gltf");
    ASSERT_EQ(mesh.triangles.size(), 4u);
    EXPECT_TRUE(mesh.closed);
    test::expectNear(mesh.bounds.lo, {2, 0, 0});
    test::expectNear(mesh.bounds.hi, {3, 1, 1});
}

TEST(MeshImport, BytesInMemoryReadAsTheHintSays) {
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const TriangleMesh mesh = importMeshBytes(triangle, "obj", "memory.obj");
    ASSERT_EQ(mesh.triangles.size(), 1u);
    test::expectNear(mesh.normals[mesh.triangles[0].normal[0]], {0, 0, 1});
}

TEST(MeshImport, RefusesWhatItCannotUseWithThePathAndTheReason) {
    const std::string missing = errorOf([] { importMeshFile("no/such/model.obj"); });
    EXPECT_NE(missing.find("no/such/model.obj: error: cannot read mesh file: No such file"),
              std::string::npos)
        << missing;

    const std::string folder = errorOf([] { importMeshFile(kMeshes); });
    EXPECT_NE(folder.find("not a regular file"), std::string::npos) << folder;

    const std::string points = errorOf([] { importMeshFile(kMeshes + "points.obj"); });
    EXPECT_NE(points.find("points.obj: error: the mesh file holds no triangles"), std::string::npos)
        << points;

    test::TempFolder temp("mesh-import");
    const fs::path garbage = temp.path() / "garbage.glb";
    writeFile(garbage, "glTF this is not a binary glTF file at all");
    const std::string bad = errorOf([&] { importMeshFile(garbage.string()); });
    EXPECT_NE(bad.find(garbage.string() + ": error: Assimp cannot read the mesh file: "),
              std::string::npos)
        << bad;
    EXPECT_GT(bad.size(), garbage.string().size() + 45) << "Assimp's own message is missing";

    const fs::path empty = temp.path() / "empty.ply";
    writeFile(empty, "");
    EXPECT_NE(errorOf([&] { importMeshFile(empty.string()); }).find(": error: "),
              std::string::npos);
}

// In a scene: `mesh FILE` of any format Assimp reads, the object placed by its
// transform; a broken file fails at the `mesh` word with the importer's
// message under it, and --lenient leaves the object out with a warning.
TEST(MeshImport, SceneMeshWordReadsEveryFormat) {
    test::TempFolder temp("mesh-import-scene");
    fs::copy_file(kMeshes + "cube.obj", temp.path() / "cube.obj");
    fs::copy_file(kMeshes + "tetrahedron_moved.gltf", temp.path() / "tetra.gltf");
    writeFile(temp.path() / "broken.glb", "not a model");
    writeFile(temp.path() / "scene.sdl",
              "translate 5 0 0 mesh cube.obj\n"
              "identityAffine mesh tetra.gltf\n");
    Scene scene = loadScene((temp.path() / "scene.sdl").string(), {}, nullptr);
    ASSERT_EQ(scene.objects.size(), 2u);
    ASSERT_EQ(scene.meshes.size(), 2u);
    const Aabb cube = worldBounds(scene.objects[0], scene);
    test::expectNear(cube.lo, {4, -1, -1});
    test::expectNear(cube.hi, {6, 1, 1});

    writeFile(temp.path() / "broken.sdl", "sphere\n  mesh broken.glb\n");
    const std::string path = (temp.path() / "broken.sdl").string();
    const std::string error = errorOf([&] { loadScene(path, {}, nullptr); });
    EXPECT_NE(error.find(path + ":2:3: error: cannot load mesh 'broken.glb'"), std::string::npos)
        << error;
    EXPECT_NE(error.find("Assimp cannot read the mesh file: "), std::string::npos) << error;

    std::vector<std::string> warnings;
    const Scene lenient = loadScene(path, {true}, &warnings);
    EXPECT_EQ(lenient.objects.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find(":2:3: warning: cannot load mesh 'broken.glb'; left out"),
              std::string::npos)
        << warnings[0];
}

// Real files written by others: counts read off the files by hand (the OBJ's
// and OFF's face lines, the PLY's header, the STL's facets).
TEST(MeshImport, RealModelsFromAssimpTestmodels) {
    VKRAY_NEED_TESTMODELS();
    struct Expected {
        const char* file;
        std::size_t triangles;
        bool closed;
    };
    // box.obj, Cube.off and cube.ply: six quads each; triangle.stl: one facet.
    for (const Expected& e :
         {Expected{"OBJ/box.obj", 12, true}, Expected{"OFF/Cube.off", 12, true},
          Expected{"PLY/cube.ply", 12, true}, Expected{"STL/triangle.stl", 1, false}}) {
        SCOPED_TRACE(e.file);
        const TriangleMesh mesh = loadMeshFile(kModels + e.file);
        EXPECT_EQ(mesh.triangles.size(), e.triangles);
        EXPECT_EQ(mesh.closed, e.closed);
    }
    for (const char* file : {"OBJ/spider.obj", "PLY/Wuson.ply", "STL/Spider_binary.stl",
                             "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"}) {
        SCOPED_TRACE(file);
        const TriangleMesh mesh = loadMeshFile(kModels + file);
        EXPECT_GT(mesh.triangles.size(), 10u);
        for (const glm::dvec3& n : mesh.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
    }
    // Broken files of the collection are refused, not read half.
    for (const char* file :
         {"glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf", "glTF2/MissingBin/BoxTextured.gltf"}) {
        SCOPED_TRACE(file);
        EXPECT_NE(errorOf([&] { loadMeshFile(kModels + file); }).find(": error: "),
                  std::string::npos);
    }
}

// What Assimp warns of reaches the user at the mesh word's place: a file
// with some faces out of range loads without them, and says so.
TEST(MeshImport, AssimpsWarningsAreShownAtTheMeshWord) {
    VKRAY_NEED_TESTMODELS();
    const std::string file = kModels + "glTF2/IndexOutOfRange/IndexOutOfRange.gltf";
    std::vector<std::string> warnings;
    const TriangleMesh mesh = importMeshFile(file, &warnings);
    EXPECT_GT(mesh.triangles.size(), 0u);
    ASSERT_FALSE(warnings.empty());
    EXPECT_EQ(warnings[0],
              "Assimp: Some faces had out-of-range indices. Those faces were dropped.");

    test::TempFolder temp("mesh-import-warnings");
    writeFile(temp.path() / "scene.sdl", "sphere\nmesh " + file + "\n");
    std::vector<std::string> shown;
    const Scene scene = loadScene((temp.path() / "scene.sdl").string(), {}, &shown);
    EXPECT_EQ(scene.objects.size(), 2u);
    ASSERT_FALSE(shown.empty());
    EXPECT_NE(shown[0].find("scene.sdl:2:1: warning: mesh '" + file +
                            "': Assimp: Some faces had out-of-range indices"),
              std::string::npos)
        << shown[0];
    // A good file warns of nothing.
    warnings.clear();
    importMeshFile(kMeshes + "cube.obj", &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
}

}  // namespace
}  // namespace vkray
