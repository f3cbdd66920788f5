// 3VN meshes and extrude outlines: the corpus files (skipped without
// VKRAY_SDL_CORPUS; tests/data's own meshes are checked in sdl_quirks_test.cpp)
// load with the counts and bounds read off the files by hand (awk over the
// tokens, not this reader),
// and every malformed input is refused with its place and a message that says
// what is wrong.
#include "scene/mesh_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

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

const std::string& kData = test::kTestData;

std::string corpus(const std::string& name) {
    return test::corpusFile(name);
}

std::string meshError(const std::string& text) {
    return errorOf([&] { parse3vn(text, "m.3vn"); });
}

std::string outlineError(const std::string& text) {
    return errorOf([&] { parseOutline(text, "o.dat"); });
}

// A unit square in z = 0 as one quad, all corners with normal +z.
const char* const kSquare =
    "4 1 1\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
    "0 0 1\n"
    "4\n0 1 2 3\n0 0 0 0\n";

void expectBounds(const PolygonMesh& mesh, glm::dvec3 lo, glm::dvec3 hi) {
    const MeshBounds bounds = boundsOf(mesh);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_DOUBLE_EQ(bounds.lo[axis], lo[axis]) << mesh.path << " axis " << axis;
        EXPECT_DOUBLE_EQ(bounds.hi[axis], hi[axis]) << mesh.path << " axis " << axis;
    }
}

// ---- the corpus (skipped without VKRAY_SDL_CORPUS) -------------------------------

TEST(Mesh3vn, CorpusDodecahedronWithCrlfAndTinyExponents) {
    VKRAY_NEED_CORPUS();
    // Header "20 12 12"; twelve pentagons; vertices within [-1, 1]^3 (the
    // vertex "1 0 0.381966" and its mirror images reach the faces of the cube).
    const PolygonMesh mesh = load3vn(corpus("Dodeca.3vn"));
    EXPECT_EQ(mesh.path, corpus("Dodeca.3vn"));
    EXPECT_EQ(mesh.vertices.size(), 20u);
    EXPECT_EQ(mesh.normals.size(), 12u);
    ASSERT_EQ(mesh.faces.size(), 12u);
    for (const PolygonMesh::Face& face : mesh.faces) EXPECT_EQ(face.cornerCount, 5);
    EXPECT_EQ(triangleCount(mesh), 36u);
    expectBounds(mesh, {-1, -1, -1}, {1, 1, 1});
    // Line 22, the first normal: "-4.75071e-009 0.850651 0.525731".
    EXPECT_DOUBLE_EQ(mesh.normals[0].x, -4.75071e-9);
    EXPECT_DOUBLE_EQ(mesh.normals[0].y, 0.850651);
    // Lines 34-36: "5", "0 7 8 15 4", "0 0 0 0 0".
    EXPECT_EQ(mesh.faces[0].line, 34);
    const std::span<const int> corners = mesh.vertexIndicesOf(mesh.faces[0]);
    EXPECT_EQ(std::vector<int>(corners.begin(), corners.end()), (std::vector<int>{0, 7, 8, 15, 4}));
    // The last face (lines 67-69): "18 14 19 16 13" with normal 11 throughout.
    EXPECT_EQ(mesh.faces[11].line, 67);
    EXPECT_EQ(mesh.vertexIndicesOf(mesh.faces[11])[4], 13);
    EXPECT_EQ(mesh.normalIndicesOf(mesh.faces[11])[0], 11);
}

TEST(Mesh3vn, CorpusArchHasOneLineFaces) {
    VKRAY_NEED_CORPUS();
    // Header "164 44 160"; every face is "4 a b c d i j k l" on one line.
    const PolygonMesh mesh = load3vn(corpus("arch.3vn"));
    EXPECT_EQ(mesh.vertices.size(), 164u);
    EXPECT_EQ(mesh.normals.size(), 44u);
    EXPECT_EQ(mesh.faces.size(), 160u);
    EXPECT_EQ(triangleCount(mesh), 320u);
    expectBounds(mesh, {-15, 0, 0}, {15, 50, 10});
    EXPECT_EQ(mesh.vertices[0], glm::dvec3(10, 0, 0));  // line 2
    EXPECT_EQ(mesh.faces.back().line, 369);
}

TEST(Mesh3vn, CorpusPillarLoads) {
    VKRAY_NEED_CORPUS();
    // Header "1140 1140 1110", all quads; z reaches +-7.956175 (line 296 and
    // its mirror).
    const PolygonMesh mesh = load3vn(corpus("pillar.3vn"));
    EXPECT_EQ(mesh.vertices.size(), 1140u);
    EXPECT_EQ(mesh.normals.size(), 1140u);
    EXPECT_EQ(mesh.faces.size(), 1110u);
    EXPECT_EQ(triangleCount(mesh), 2220u);
    expectBounds(mesh, {-8, 0, -7.956175}, {8, 60, 7.956175});
}

TEST(Mesh3vn, FanTrianglesKeepEachCornersNormal) {
    const char* const text =
        "5 5 1\n"
        "0 0 0\n1 0 0\n1 1 0\n0.5 2 0\n0 1 0\n"
        "1 0 0\n0 1 0\n0 0 1\n1 1 0\n0 1 1\n"
        "5 0 1 2 3 4 4 3 2 1 0\n";
    const PolygonMesh mesh = parse3vn(text, "fan.3vn");
    const std::vector<MeshTriangle> triangles = fanTriangles(mesh);
    ASSERT_EQ(triangles.size(), 3u);
    // Fan around corner 0: (0 1 2), (0 2 3), (0 3 4), normals paired by corner.
    const int expectedVertices[3][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
    const int expectedNormals[3][3] = {{4, 3, 2}, {4, 2, 1}, {4, 1, 0}};
    for (int t = 0; t < 3; ++t) {
        EXPECT_EQ(triangles[t].face, 0);
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(triangles[t].vertex[k], expectedVertices[t][k]) << t << "," << k;
            EXPECT_EQ(triangles[t].normal[k], expectedNormals[t][k]) << t << "," << k;
        }
    }
}

TEST(Mesh3vn, BoundsCountOnlyUsedVertices) {
    const PolygonMesh mesh =
        parse3vn("4 1 1\n0 0 0\n1 0 0\n0 1 0\n100 100 100\n0 0 1\n3 0 1 2 0 0 0\n", "unused.3vn");
    expectBounds(mesh, {0, 0, 0}, {1, 1, 0});
}

TEST(Mesh3vn, AnyWhitespaceAndSignedOrTinyNumbers) {
    // Tabs, CRLF, blank lines, a leading '+', an exponent below double range
    // (reads as 0) and a subnormal.
    const PolygonMesh mesh = parse3vn(
        "3\t1 1\r\n\r\n+1 0 0\r\n0 1e-400 0\r\n0 0 4.9e-324\r\n0 0 1\r\n3 0 1 2\t0 0 0", "ws.3vn");
    EXPECT_EQ(mesh.vertices[0], glm::dvec3(1, 0, 0));
    EXPECT_EQ(mesh.vertices[1].y, 0.0);
    EXPECT_GT(mesh.vertices[2].z, 0.0);
    EXPECT_EQ(mesh.faces.size(), 1u);
}

TEST(Mesh3vn, EmptyMeshIsAllowed) {
    const PolygonMesh mesh = parse3vn("0 0 0\n", "empty.3vn");
    EXPECT_TRUE(mesh.faces.empty());
    EXPECT_EQ(triangleCount(mesh), 0u);
    EXPECT_GT(boundsOf(mesh).lo.x, boundsOf(mesh).hi.x);
}

// ---- malformed meshes: each with its place ---------------------------------------

TEST(Mesh3vnErrors, EmptyFile) {
    EXPECT_EQ(meshError(""), "m.3vn:1:1: error: the file ends where the vertex count should be");
    EXPECT_EQ(meshError("\n\n  "),
              "m.3vn:3:3: error: the file ends where the vertex count should be");
}

TEST(Mesh3vnErrors, MalformedOrNegativeCounts) {
    EXPECT_EQ(meshError("4 x 1"),
              "m.3vn:1:3: error: expected the normal count (a whole number), found 'x'");
    EXPECT_EQ(meshError("4.5 1 1"),
              "m.3vn:1:1: error: expected the vertex count (a whole number), found '4.5'");
    EXPECT_EQ(meshError("4 1 -2"), "m.3vn:1:5: error: the face count '-2' is negative");
}

TEST(Mesh3vnErrors, CountsAboveTheLimitsAreRefusedBeforeReading) {
    EXPECT_EQ(meshError("20000001 0 0"),
              "m.3vn:1:1: error: the vertex count '20000001' is above vkray's limit of 20000000");
    EXPECT_EQ(meshError("0 0 99999999999999999999999"),
              "m.3vn:1:5: error: the face count '99999999999999999999999' is above vkray's "
              "limit of 20000000");
}

TEST(Mesh3vnErrors, HeaderPromisingMoreThanTheFileHoldsFailsFast) {
    // A 10-byte file that claims 19 million vertices is refused from its
    // header and size, before anything is allocated.
    EXPECT_EQ(meshError("19000000 0 0 1"),
              "m.3vn:1:1: error: the header promises 19000000 vertices, 0 normals and 0 faces, "
              "which need at least 114000000 bytes; the file has only 2 after the header "
              "(truncated, or not a 3VN file)");
}

TEST(Mesh3vnErrors, MalformedNaNInfiniteAndOverflowingCoordinates) {
    EXPECT_EQ(meshError("1 0 0\n0 0,5 0\n"),
              "m.3vn:2:3: error: expected a number for vertex 0 (y), found '0,5'");
    EXPECT_EQ(meshError("1 0 0\n0 nan 0\n"),
              "m.3vn:2:3: error: expected a finite number for vertex 0 (y), found 'nan'");
    EXPECT_EQ(meshError("1 1 0\n0 0 0\n-inf 0 0\n"),
              "m.3vn:3:1: error: expected a finite number for normal 0 (x), found '-inf'");
    EXPECT_EQ(meshError("1 0 0\n0 0 1e999\n"),
              "m.3vn:2:5: error: the number '1e999' for vertex 0 (z) is out of range");
}

TEST(Mesh3vnErrors, MissingData) {
    EXPECT_EQ(meshError("2 1 1\n0 0 0\n1 1 1\n0 0 1\n3 0 1 1 0 0 0 7\n"),
              "m.3vn:5:15: error: unexpected '7' after the last face (1 face in the header) "
              "(does the header's count match the data?)");
    // The header fits the file's size, but the data runs out inside face 0.
    EXPECT_EQ(meshError(std::string("3 1 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2 0 0") +
                        std::string(20, ' ')),
              "m.3vn:6:32: error: the file ends where face 0: normal index should be");
}

TEST(Mesh3vnErrors, FaceWithFewerThanThreeCorners) {
    EXPECT_EQ(meshError(std::string(kSquare).replace(36, 1, "2")),
              "m.3vn:7:1: error: face 0 has '2' corners; a face needs at least 3");
    EXPECT_EQ(meshError(std::string(kSquare).replace(36, 1, "q")),
              "m.3vn:7:1: error: expected the corner count of face 0 (a whole number), found 'q'");
}

TEST(Mesh3vnErrors, FaceWithMoreCornersThanTheFileCanHold) {
    EXPECT_EQ(meshError("3 1 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1000000 0 1 2 0 0 0\n"),
              "m.3vn:6:1: error: face 0 has '1000000' corners, more than the rest of the file "
              "can hold");
    EXPECT_EQ(meshError("3 1 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n60000001 0 1 2 0 0 0\n"),
              "m.3vn:6:1: error: face 0 with '60000001' corners takes the mesh above vkray's "
              "limit of 60000000 corners in all");
}

TEST(Mesh3vnErrors, IndexOutOfRange) {
    EXPECT_EQ(meshError(std::string(kSquare).replace(44, 1, "4")),
              "m.3vn:8:7: error: face 0: vertex index '4' is out of range (0..3: the mesh has 4 "
              "vertices)");
    EXPECT_EQ(meshError(std::string(kSquare).replace(44, 1, "-1")),
              "m.3vn:8:7: error: face 0: vertex index '-1' is out of range (0..3: the mesh has 4 "
              "vertices)");
    EXPECT_EQ(meshError(std::string(kSquare).replace(46, 1, "1")),
              "m.3vn:9:1: error: face 0: normal index '1' is out of range (0..0: the mesh has 1 "
              "normal)");
    EXPECT_EQ(meshError("3 0 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0 0 0\n"),
              "m.3vn:5:9: error: face 0: normal index '0' is out of range (the mesh has no "
              "normals)");
    EXPECT_EQ(meshError(std::string(kSquare).replace(44, 1, "x")),
              "m.3vn:8:7: error: expected face 0: vertex index (a whole number), found 'x'");
}

TEST(Mesh3vnErrors, BinaryGarbageIsQuotedShort) {
    const std::string message = meshError("3 1 1\n" + std::string(100, '\x01'));
    EXPECT_EQ(message, "m.3vn:2:1: error: expected a number for vertex 0 (x), found '" +
                           std::string(40, '\x01') + "...'");
}

// ---- outlines -------------------------------------------------------------------

TEST(Outline, CorpusHillsArch) {
    VKRAY_NEED_CORPUS();
    // hlArch.dat: "36", then 36 CRLF lines of "x y", from (-3, 0) to (5, 0).
    const Outline outline = loadOutline(corpus("hlArch.dat"));
    EXPECT_EQ(outline.path, corpus("hlArch.dat"));
    ASSERT_EQ(outline.points.size(), 36u);
    EXPECT_EQ(outline.points.front(), glm::dvec2(-3, 0));
    EXPECT_EQ(outline.points[2], glm::dvec2(-3, 1));
    EXPECT_EQ(outline.points.back(), glm::dvec2(5, 0));
}

TEST(OutlineErrors, EachWithItsPlace) {
    EXPECT_EQ(outlineError(""), "o.dat:1:1: error: the file ends where the point count should be");
    EXPECT_EQ(outlineError("2\n0 0\n1 1\n"),
              "o.dat:1:1: error: an outline needs at least 3 points; the count is 2");
    EXPECT_EQ(outlineError("-3\n"), "o.dat:1:1: error: the point count '-3' is negative");
    EXPECT_EQ(outlineError("1000001\n"),
              "o.dat:1:1: error: the point count '1000001' is above vkray's limit of 1000000");
    EXPECT_EQ(outlineError("900000\n0 0\n"),
              "o.dat:1:1: error: the count promises 900000 points, which need at least 3600000 "
              "bytes; the file has only 5 after the count");
    EXPECT_EQ(outlineError("3\n0 0\n1 x\n0 1\n"),
              "o.dat:3:3: error: expected a number for point 1 (y), found 'x'");
    EXPECT_EQ(outlineError("3\n0 0\n1 inf\n0 1\n"),
              "o.dat:3:3: error: expected a finite number for point 1 (y), found 'inf'");
    EXPECT_EQ(outlineError("3\n0 0\n1 0\n0 1\n7\n"),
              "o.dat:5:1: error: unexpected '7' after the last point (3 points in the count) "
              "(does the header's count match the data?)");
    EXPECT_EQ(outlineError("3\n0 0\n1 0\n0         \n"),
              "o.dat:5:1: error: the file ends where point 2 (y) should be");
}

// ---- files ------------------------------------------------------------------------

TEST(MeshFiles, MissingFileOrFolderIsAnErrorNamingIt) {
    EXPECT_EQ(errorOf([] { load3vn("no/such.3vn"); }),
              "no/such.3vn: error: cannot read mesh file: No such file or directory");
    EXPECT_EQ(errorOf([] { loadOutline(kData); }),
              kData + ": error: cannot read outline file: Is a directory");
}

TEST(MeshFiles, ErrorsInAFileNameItsPath) {
    const fs::path path =
        fs::path(::testing::TempDir()) / ("vkray-mesh-" + std::to_string(::getpid()) + ".3vn");
    std::ofstream(path) << "3 1 1\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n3 0 1 5 0 0 0\r\n";
    EXPECT_EQ(errorOf([&] { load3vn(path.string()); }),
              path.string() +
                  ":6:7: error: face 0: vertex index '5' is out of range (0..2: the "
                  "mesh has 3 vertices)");
    fs::remove(path);
}

}  // namespace
}  // namespace vkray
