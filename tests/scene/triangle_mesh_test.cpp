// Triangle meshes: the corpus 3VN files (skipped without VKRAY_SDL_CORPUS),
// extruded outlines and the built-in solids, checked against counts, bounds
// and volumes worked out by hand.
#include "scene/triangle_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <ctime>
#include <functional>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>
#include <set>
#include <string>

#include "support/corpus.h"
#include "support/error_of.h"
#include "util/error.h"

#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray {
namespace {

// CPU time of this thread: timings that other processes (ctest -j) do not skew.
double threadSeconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

std::string corpus(const std::string& name) {
    return test::corpusFile(name);
}
const double kSqrt2 = std::numbers::sqrt2, kSqrt3 = std::numbers::sqrt3;
const double kSqrt5 = std::sqrt(5.0);

// The divergence theorem: sum over triangles of p0 . (p1 x p2) / 6; positive
// for a closed surface whose triangles are counter-clockwise seen from outside.
double signedVolume(const TriangleMesh& mesh) {
    double sixTimes = 0;
    for (const TriangleMesh::Triangle& t : mesh.triangles) {
        sixTimes +=
            glm::dot(mesh.positions[t.position[0]],
                     glm::cross(mesh.positions[t.position[1]], mesh.positions[t.position[2]]));
    }
    return sixTimes / 6;
}

glm::dvec3 geometricNormal(const TriangleMesh& mesh, const TriangleMesh::Triangle& t) {
    const glm::dvec3 a = mesh.positions[t.position[0]];
    return glm::normalize(
        glm::cross(mesh.positions[t.position[1]] - a, mesh.positions[t.position[2]] - a));
}

void expectBounds(const Aabb& bounds, glm::dvec3 lo, glm::dvec3 hi, double tolerance = 0) {
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(bounds.lo[axis], lo[axis], tolerance) << "axis " << axis;
        EXPECT_NEAR(bounds.hi[axis], hi[axis], tolerance) << "axis " << axis;
    }
}

// Every normal unit length; the BVH covers each triangle once; bounds agree.
void expectWellFormed(const TriangleMesh& mesh) {
    for (const glm::dvec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1, 1e-12);
    for (const TriangleMesh::Triangle& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            ASSERT_LT(t.position[k], mesh.positions.size());
            ASSERT_LT(t.normal[k], mesh.normals.size());
        }
    }
    ASSERT_EQ(mesh.bvh.order.size(), mesh.triangles.size());
    std::vector<int> seen(mesh.triangles.size(), 0);
    for (const std::uint32_t t : mesh.bvh.order) ++seen.at(t);
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
    ASSERT_FALSE(mesh.bvh.nodes.empty());
    EXPECT_EQ(mesh.bvh.nodes[0].bounds.lo, mesh.bounds.lo);
    EXPECT_EQ(mesh.bvh.nodes[0].bounds.hi, mesh.bounds.hi);
    EXPECT_LE(mesh.bvh.depth, kMaxBvhDepth);
}

// ---- 3VN -----------------------------------------------------------------------

TEST(TriangleMesh3vn, CorpusDodecahedron) {
    VKRAY_NEED_CORPUS();
    // 12 pentagons: 12 * (5 - 2) = 36 triangles. Its vertices are the
    // dodecahedron (+-1,+-1,+-1), (0, +-1/phi, +-phi) scaled by 1/phi (to 6
    // digits): within [-1, 1]^3, edge a = 2 / phi^2, volume (15 + 7 sqrt 5) / 4 a^3.
    const TriangleMesh mesh = meshFrom3vn(load3vn(corpus("Dodeca.3vn")));
    EXPECT_EQ(mesh.name, "Dodeca.3vn");
    EXPECT_EQ(mesh.positions.size(), 20u);
    EXPECT_EQ(mesh.triangles.size(), 36u);
    expectBounds(mesh.bounds, glm::dvec3(-1), glm::dvec3(1));
    expectWellFormed(mesh);
    EXPECT_TRUE(mesh.closed);
    const double edge = 2 / (std::numbers::phi * std::numbers::phi);
    EXPECT_NEAR(std::abs(signedVolume(mesh)), (15 + 7 * kSqrt5) / 4 * edge * edge * edge, 1e-4);
}

TEST(TriangleMesh3vn, CorpusArchAndPillar) {
    VKRAY_NEED_CORPUS();
    // arch.3vn: 160 quads -> 320 triangles; pillar.3vn: 1110 quads -> 2220
    // (bounds as the mesh_file tests read them off the files).
    const TriangleMesh arch = meshFrom3vn(load3vn(corpus("arch.3vn")));
    EXPECT_EQ(arch.triangles.size(), 320u);
    expectBounds(arch.bounds, {-15, 0, 0}, {15, 50, 10});
    expectWellFormed(arch);
    const TriangleMesh pillar = meshFrom3vn(load3vn(corpus("pillar.3vn")));
    EXPECT_EQ(pillar.triangles.size(), 2220u);
    expectBounds(pillar.bounds, {-8, 0, -7.956175}, {8, 60, 7.956175});
    expectWellFormed(pillar);
}

// A unit cube [0, 1]^3 as six quads, each face with its own four vertices
// (as many 3VN files do), counter-clockwise from outside, normal per face.
std::string cube3vn(bool dropLastFace = false, bool flipFirstFace = false,
                    bool zeroNormals = false) {
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    const char* const normals[6] = {"0 0 -1", "0 0 2", "0 -1 0", "0 1 0", "-1 0 0", "1 0 0"};
    const int faceCount = dropLastFace ? 5 : 6;
    std::string text = "24 6 " + std::to_string(faceCount) + "\n";
    for (int f = 0; f < 6; ++f) {
        for (const int corner : faces[f]) {
            text += std::to_string(corner & 1) + " " + std::to_string((corner >> 1) & 1) + " " +
                    std::to_string((corner >> 2) & 1) + "\n";
        }
    }
    for (const char* n : normals) text += std::string(zeroNormals ? "0 0 0" : n) + "\n";
    for (int f = 0; f < faceCount; ++f) {
        text += "4";
        for (int k = 0; k < 4; ++k) {
            const int corner = flipFirstFace && f == 0 ? 3 - k : k;
            text += " " + std::to_string(4 * f + corner);
        }
        for (int k = 0; k < 4; ++k) text += " " + std::to_string(f);
        text += "\n";
    }
    return text;
}

TEST(TriangleMesh3vn, ClosedComparesPositionsNotIndices) {
    const TriangleMesh cube = meshFrom3vn(parse3vn(cube3vn(), "cube.3vn"));
    EXPECT_EQ(cube.triangles.size(), 12u);
    EXPECT_TRUE(cube.closed);
    EXPECT_NEAR(signedVolume(cube), 1, 1e-15);
    EXPECT_FALSE(meshFrom3vn(parse3vn(cube3vn(true), "open.3vn")).closed);
    EXPECT_FALSE(meshFrom3vn(parse3vn(cube3vn(false, true), "flipped.3vn")).closed);
}

TEST(TriangleMesh3vn, NormalsAreNormalisedAndZeroOnesBecomeTheFacesNormal) {
    const TriangleMesh cube = meshFrom3vn(parse3vn(cube3vn(), "cube.3vn"));
    // The file's "0 0 2" (face 1, triangles 2 and 3) arrives as (0, 0, 1).
    EXPECT_EQ(cube.normals[cube.triangles[2].normal[0]], glm::dvec3(0, 0, 1));
    const TriangleMesh zero = meshFrom3vn(parse3vn(cube3vn(false, false, true), "zero.3vn"));
    expectWellFormed(zero);
    EXPECT_EQ(zero.normals.size(), 6u);  // one geometric normal per face
    for (const TriangleMesh::Triangle& t : zero.triangles) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(glm::dot(zero.normals[t.normal[k]], geometricNormal(zero, t)), 1, 1e-15);
        }
    }
}

// ---- extrude ---------------------------------------------------------------------

Outline outlineOf(std::vector<glm::dvec2> points, std::string path = "outline.dat") {
    return Outline{std::move(points), std::move(path)};
}

// Closed, outward, the prism's volume, sides and caps with their flat normals.
void expectPrism(const TriangleMesh& mesh, double area) {
    expectWellFormed(mesh);
    EXPECT_TRUE(mesh.closed);
    EXPECT_TRUE(isClosedSurface(mesh.positions, mesh.triangles));
    EXPECT_NEAR(signedVolume(mesh), area, 1e-12 * std::max(1.0, area));
    for (const TriangleMesh::Triangle& t : mesh.triangles) {
        const glm::dvec3 n = mesh.normals[t.normal[0]];
        EXPECT_EQ(n, mesh.normals[t.normal[1]]);  // flat: sharp edges
        EXPECT_EQ(n, mesh.normals[t.normal[2]]);
        const glm::dvec3 a = mesh.positions[t.position[0]], b = mesh.positions[t.position[1]],
                         c = mesh.positions[t.position[2]];
        const glm::dvec3 cross = glm::cross(b - a, c - a);
        if (glm::length(cross) > 1e-12) {
            EXPECT_NEAR(glm::dot(glm::normalize(cross), n), 1, 1e-12);
        }
    }
    EXPECT_EQ(mesh.bounds.lo.z, 0);
    EXPECT_EQ(mesh.bounds.hi.z, 1);
}

TEST(TriangleMeshExtrude, CorpusHillsArchIsReadAsAQuadStrip) {
    VKRAY_NEED_CORPUS();
    // hlArch.dat's 36 points pair up as rungs (-3,0)-(-5,0), (-3,1)-(-5,1), ...:
    // Hill's quad strip. Its outline: the block [-5, 5] x [0, 7] (area 70)
    // less the opening under the inner points; by trapezoids over x on the
    // left half, 0.3 + 0.5 + 1.05 + 1.275 + 2.375 + 2.625 + 4.6 = 12.725, twice
    // that plus the 0.4-wide middle at height 6 (2.4) is 27.85. Area 42.15;
    // the prism (height 1) has that volume. 36 outline points: 72 side
    // triangles, 2 * 34 cap triangles.
    const Outline arch = loadOutline(corpus("hlArch.dat"));
    const TriangleMesh mesh = extrudeOutline(arch);
    EXPECT_EQ(mesh.name, "hlArch.dat");
    EXPECT_EQ(mesh.positions.size(), 72u);
    EXPECT_EQ(mesh.triangles.size(), 140u);
    expectPrism(mesh, 42.15);
    expectBounds(mesh.bounds, {-5, 0, 0}, {5, 7, 1});
    // The same area as the strip's 17 quads summed one by one (shoelace each).
    double quads = 0;
    for (std::size_t k = 0; k + 3 < arch.points.size(); k += 2) {
        const glm::dvec2 q[4] = {arch.points[k], arch.points[k + 1], arch.points[k + 3],
                                 arch.points[k + 2]};
        for (int i = 0; i < 4; ++i)
            quads += (q[i].x * q[(i + 1) % 4].y - q[(i + 1) % 4].x * q[i].y) / 2;
    }
    EXPECT_NEAR(std::abs(quads), 42.15, 1e-12);
}

TEST(TriangleMeshExtrude, EitherWindingGivesTheSameOutwardPrism) {
    const std::vector<glm::dvec2> square = {{0, 0}, {2, 0}, {2, 3}, {0, 3}};
    expectPrism(extrudeOutline(outlineOf(square)), 6);
    expectPrism(extrudeOutline(outlineOf({square.rbegin(), square.rend()})), 6);
    // 4 sides * 2 + 2 caps * 2 = 12 triangles.
    EXPECT_EQ(extrudeOutline(outlineOf(square)).triangles.size(), 12u);
}

TEST(TriangleMeshExtrude, NonConvexOutlinesAreEarClipped) {
    // An L: the 3 x 3 square less its 2 x 2 upper-right corner: area 5.
    expectPrism(extrudeOutline(outlineOf({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}})), 5);
    // A comb with 20 teeth, each 1 wide and 5 tall, 1 apart, on a 39 x 1 base:
    // 39 + 20 * 5 = 139.
    std::vector<glm::dvec2> comb = {{0, 0}, {39, 0}};
    for (int tooth = 19; tooth >= 0; --tooth) {
        const double x = 2.0 * tooth;
        comb.insert(comb.end(), {{x + 1, 1}, {x + 1, 6}, {x, 6}, {x, 1}});
    }
    expectPrism(extrudeOutline(outlineOf(comb)), 139);
    // A star with 50 points (radius 1 and 0.4 alternating) is non-convex all round.
    std::vector<glm::dvec2> star;
    for (int k = 0; k < 100; ++k) {
        const double angle = k * std::numbers::pi / 50, radius = k % 2 ? 0.4 : 1;
        star.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
    }
    double starArea = 0;
    for (std::size_t i = 0; i < star.size(); ++i) {
        const glm::dvec2 p = star[i], q = star[(i + 1) % star.size()];
        starArea += (p.x * q.y - q.x * p.y) / 2;
    }
    // Each of the 100 triangles (centre, p_k, p_k+1) has area 1 * 0.4 * sin(pi/50) / 2.
    EXPECT_NEAR(starArea, 100 * 0.4 * std::sin(std::numbers::pi / 50) / 2, 1e-14);
    expectPrism(extrudeOutline(outlineOf(star)), starArea);
}

TEST(TriangleMeshExtrude, RepeatedAndCollinearPointsAreFine) {
    // A 2 x 2 square with its edge midpoints, the first corner repeated, and
    // the first point again at the end: still area 4 and closed.
    expectPrism(
        extrudeOutline(outlineOf(
            {{0, 0}, {0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}, {0, 0}})),
        4);
}

TEST(TriangleMeshExtrude, SimpleQuadStripAndCrossingOutlines) {
    // Read as a polygon, (0,0) (0,1) (1,0) (1,1) is a bow tie; as a quad strip
    // it is the rung pair (0,0)-(0,1), (1,0)-(1,1): the unit square.
    expectPrism(extrudeOutline(outlineOf({{0, 0}, {0, 1}, {1, 0}, {1, 1}})), 1);
    // A bow tie both ways, and an odd count that crosses: refused with the path.
    const std::string expected =
        "bow.dat: error: the outline crosses or touches itself; extrude needs a simple polygon "
        "(or Hill's quad strip: pairs of points, each pair a rung)";
    EXPECT_EQ(errorOf([] {
                  extrudeOutline(outlineOf({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, "bow.dat"));
              }),
              expected);
    EXPECT_EQ(errorOf([] {
                  extrudeOutline(outlineOf({{0, 0}, {2, 2}, {2, 0}, {0, 2}, {-1, 1}}, "bow.dat"));
              }),
              expected);
    // Collinear only: no area.
    EXPECT_NE(errorOf([] { extrudeOutline(outlineOf({{0, 0}, {1, 0}, {2, 0}})); }), "(no error)");
}

// ---- built-in solids --------------------------------------------------------------

struct SolidFacts {
    ShapeType type;
    std::size_t vertices, triangles, faces;
    double volume;
};

std::vector<SolidFacts> platonicAndBuckyball() {
    // Edge a for circumradius 1, then the textbook volume in a.
    const double icosaEdge = 1 / std::sin(2 * std::numbers::pi / 5);  // R = a sin(2 pi / 5)
    const double dodecaEdge = 4 / (kSqrt3 * (1 + kSqrt5));            // R = a sqrt3 (1 + sqrt5) / 4
    const double buckyEdge = 4 / std::sqrt(58 + 18 * kSqrt5);  // R = a sqrt(58 + 18 sqrt5) / 4
    return {
        // Regular tetrahedron, R = 1: a = 4 / sqrt 6, V = a^3 / (6 sqrt 2) = 8 / (9 sqrt 3).
        {ShapeType::Tetrahedron, 4, 4, 4, 8 / (9 * kSqrt3)},
        // Two square pyramids of base 2 (diagonal 2) and height 1: 2 * (2 * 1 / 3) = 4/3.
        {ShapeType::Octahedron, 6, 8, 8, 4.0 / 3},
        {ShapeType::Icosahedron, 12, 20, 20, 5.0 / 12 * (3 + kSqrt5) * std::pow(icosaEdge, 3)},
        {ShapeType::Dodecahedron, 20, 36, 12, (15 + 7 * kSqrt5) / 4 * std::pow(dodecaEdge, 3)},
        {ShapeType::Buckyball, 60, 116, 32, (125 + 43 * kSqrt5) / 4 * std::pow(buckyEdge, 3)},
    };
}

TEST(TriangleMeshBuiltIn, PlatonicSolidsAndBuckyball) {
    for (const SolidFacts& facts : platonicAndBuckyball()) {
        SCOPED_TRACE(shapeKeyword(facts.type));
        ASSERT_TRUE(isBuiltInMesh(facts.type));
        const TriangleMesh mesh = builtInMesh(facts.type);
        EXPECT_EQ(mesh.name, std::string("built-in ") + shapeKeyword(facts.type));
        EXPECT_EQ(mesh.positions.size(), facts.vertices);
        EXPECT_EQ(mesh.triangles.size(), facts.triangles);
        EXPECT_EQ(mesh.normals.size(), facts.faces);  // one flat normal per face
        for (const glm::dvec3& p : mesh.positions) EXPECT_NEAR(glm::length(p), 1, 1e-15);
        EXPECT_TRUE(mesh.closed);
        EXPECT_NEAR(signedVolume(mesh), facts.volume, 1e-13);
        for (const TriangleMesh::Triangle& t : mesh.triangles) {
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(glm::dot(mesh.normals[t.normal[k]], geometricNormal(mesh, t)), 1,
                            1e-13);
        }
        expectWellFormed(mesh);
    }
}

TEST(TriangleMeshBuiltIn, BuckyballHasTwelvePentagonsAndTwentyHexagons) {
    const TriangleMesh mesh = builtInMesh(ShapeType::Buckyball);
    std::map<std::uint32_t, std::set<std::uint32_t>> cornersOfFace;
    for (const TriangleMesh::Triangle& t : mesh.triangles)
        cornersOfFace[t.normal[0]].insert(std::begin(t.position), std::end(t.position));
    int pentagons = 0, hexagons = 0;
    for (const auto& [face, corners] : cornersOfFace) {
        pentagons += corners.size() == 5 ? 1 : 0;
        hexagons += corners.size() == 6 ? 1 : 0;
    }
    EXPECT_EQ(pentagons, 12);
    EXPECT_EQ(hexagons, 20);
}

TEST(TriangleMeshBuiltIn, OctahedronAndTetrahedronOrientation) {
    // Octahedron: the axes' unit points; tetrahedron: alternate cube corners / sqrt 3.
    expectBounds(builtInMesh(ShapeType::Octahedron).bounds, glm::dvec3(-1), glm::dvec3(1));
    expectBounds(builtInMesh(ShapeType::Tetrahedron).bounds, glm::dvec3(-1 / kSqrt3),
                 glm::dvec3(1 / kSqrt3), 1e-15);
    // Icosahedron (0, +-1, +-phi) / |.|: reaches phi / sqrt(1 + phi^2) on every axis.
    const double phi = std::numbers::phi, reach = phi / std::sqrt(1 + phi * phi);
    expectBounds(builtInMesh(ShapeType::Icosahedron).bounds, glm::dvec3(-reach), glm::dvec3(reach),
                 1e-15);
}

TEST(TriangleMeshBuiltIn, DiamondIsAnOctagonalBrilliant) {
    const TriangleMesh mesh = builtInMesh(ShapeType::Diamond);
    EXPECT_EQ(mesh.positions.size(), 17u);  // 8 girdle, 8 table, 1 culet
    EXPECT_EQ(mesh.triangles.size(), 30u);  // crown 16, pavilion 8, table 6
    EXPECT_TRUE(mesh.closed);
    expectWellFormed(mesh);
    double radius = 0;
    for (const glm::dvec3& p : mesh.positions) radius = std::max(radius, glm::length(p));
    EXPECT_NEAR(radius, 1, 1e-15);  // the girdle
    // Girdle octagon radius 1 in y = 0 reaches x = +-1 and z = +-1; the table
    // at y = 0.3, the culet at y = -0.86.
    expectBounds(mesh.bounds, {-1, -0.86, -1}, {1, 0.3, 1}, 1e-15);
    // Volume: pavilion = a pyramid on the girdle octagon (area 2 sqrt2 R^2):
    // 2 sqrt2 * 0.86 / 3. Crown = a prismatoid (all corners in y = 0 and
    // y = 0.3): h / 6 (A_girdle + 4 A_middle + A_table), A_middle the 16-gon
    // through the midpoints of its 16 slanted edges (table corner k, at
    // 45k + 22.5 degrees, to girdle corners k and k + 1).
    const auto at = [](double radius, double degrees) {
        const double a = degrees * std::numbers::pi / 180;
        return glm::dvec2(radius * std::cos(a), radius * std::sin(a));
    };
    std::vector<glm::dvec2> middle;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec2 table = at(0.55, 45 * k + 22.5);
        middle.push_back((table + at(1, 45 * k)) / 2.0);
        middle.push_back((table + at(1, 45 * (k + 1))) / 2.0);
    }
    double middleArea = 0;
    for (std::size_t i = 0; i < middle.size(); ++i) {
        const glm::dvec2 p = middle[i], q = middle[(i + 1) % middle.size()];
        middleArea += (p.x * q.y - q.x * p.y) / 2;
    }
    const double octagon = 2 * kSqrt2;
    const double expected =
        octagon * 0.86 / 3 + 0.3 / 6 * (octagon + 4 * middleArea + octagon * 0.55 * 0.55);
    EXPECT_NEAR(std::abs(signedVolume(mesh)), expected, 1e-13);
    EXPECT_GT(signedVolume(mesh), 0);
    // The table faces up.
    int up = 0;
    for (const glm::dvec3& n : mesh.normals) up += n == glm::dvec3(0, 1, 0) ? 1 : 0;
    EXPECT_EQ(up, 1);
}

TEST(TriangleMeshBuiltIn, TeapotHasGlutsSizeAndOrientation) {
    // glutSolidTeapot(1): Newell's (x, y, z) -> (x, z - 1.5, -y) / 2. Newell's
    // surface spans x in [-3, 3.43408] (the handle's back column is
    // -1.5, -2.5, -3, -3: least at its end; the spout lip's column 3.3,
    // 3.525, 3.45, 3.2 peaks at v = (0.6 - sqrt(0.2475)) / 0.25), y in [-2, 2]
    // (the body's radius-2 row at z = 0.9) and z in [0, 3.15] (flat bottom,
    // flat knob top). So x in [-1.5, 1.71704], y in [-0.75, 0.825],
    // z in [-1, 1]. The spout's peak lies between samples: 1e-3 slack there.
    const double v = (0.6 - std::sqrt(0.2475)) / 0.25, s = 1 - v;
    const double spoutX =
        3.3 * s * s * s + 3 * 3.525 * v * s * s + 3 * 3.45 * v * v * s + 3.2 * v * v * v;
    EXPECT_NEAR(spoutX / 2, 1.71704, 1e-5);
    const TriangleMesh mesh = builtInMesh(ShapeType::Teapot);
    EXPECT_EQ(mesh.name, "built-in teapot");
    EXPECT_FALSE(mesh.closed);
    // 32 patches * 16 * 16 quads * 2, less one triangle per quad at the poles
    // of the 4 lid-top and 4 bottom patches (8 * 16).
    EXPECT_EQ(mesh.triangles.size(), 32u * 16 * 16 * 2 - 8 * 16);
    expectWellFormed(mesh);
    EXPECT_EQ(mesh.bounds.lo.x, -1.5);
    EXPECT_LE(mesh.bounds.hi.x, spoutX / 2);
    EXPECT_NEAR(mesh.bounds.hi.x, spoutX / 2, 1e-3);
    EXPECT_EQ(mesh.bounds.lo.y, -0.75);
    EXPECT_EQ(mesh.bounds.hi.y, 0.825);
    EXPECT_EQ(mesh.bounds.lo.z, -1);
    EXPECT_EQ(mesh.bounds.hi.z, 1);
    // Normals: straight up at the knob's top, down at the bottom's middle,
    // out along +-z where the body is widest (Newell's y = -+2).
    int checked = 0;
    const auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::distance(a, b) < 1e-12; };
    for (const TriangleMesh::Triangle& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p = mesh.positions[t.position[k]], n = mesh.normals[t.normal[k]];
            const std::pair<glm::dvec3, glm::dvec3> expected[] = {{{0, 0.825, 0}, {0, 1, 0}},
                                                                  {{0, -0.75, 0}, {0, -1, 0}},
                                                                  {{0, -0.3, 1}, {0, 0, 1}},
                                                                  {{0, -0.3, -1}, {0, 0, -1}}};
            for (const auto& [where, normal] : expected) {
                if (!near(p, where)) continue;
                EXPECT_NEAR(glm::dot(n, normal), 1, 1e-9) << where.x << " " << where.y;
                ++checked;
            }
        }
    }
    // Each pole is a corner of 4 patches * 16 triangles; each body point of 4.
    EXPECT_GE(checked, 2 * 64 + 2 * 4);
}

// How long the build takes is the benchmark's to say (its time is printed
// here, not asserted: a sanitizer build on a loaded machine takes several
// times longer); what is asserted is the tree that keeps every walk short.
TEST(TriangleMeshBvh, AMillionTrianglesMakeABalancedTree) {
    // A unit sphere as a 1000 x 500 latitude-longitude grid, 2 triangles a cell.
    constexpr int kAround = 1000, kDown = 500;
    TriangleMesh mesh;
    for (int j = 0; j <= kDown; ++j) {
        for (int i = 0; i <= kAround; ++i) {
            const double theta = std::numbers::pi * j / kDown,
                         phi = 2 * std::numbers::pi * i / kAround;
            mesh.positions.emplace_back(std::sin(theta) * std::cos(phi),
                                        std::sin(theta) * std::sin(phi), std::cos(theta));
        }
    }
    mesh.normals = {{0, 0, 1}};
    for (std::uint32_t j = 0; j < kDown; ++j) {
        for (std::uint32_t i = 0; i < kAround; ++i) {
            const std::uint32_t a = j * (kAround + 1) + i, b = a + 1, c = b + kAround + 1,
                                d = a + kAround + 1;
            mesh.triangles.push_back({{a, b, c}, {0, 0, 0}});
            mesh.triangles.push_back({{a, c, d}, {0, 0, 0}});
        }
    }
    ASSERT_EQ(mesh.triangles.size(), 1'000'000u);
    const double start = threadSeconds();
    finishMesh(mesh);
    const double seconds = threadSeconds() - start;
    std::printf("[ timing   ] BVH over %zu triangles: %.3f s (CPU), %zu nodes, depth %d\n",
                mesh.triangles.size(), seconds, mesh.bvh.nodes.size(), mesh.bvh.depth);
    // Split in the middle, a million triangles in leaves of a few need about
    // log2(1e6 / 2) = 19 levels; 24 were built. Well short of the GPU's
    // stack (kMaxBvhDepth), and fewer nodes than triangles.
    EXPECT_LE(mesh.bvh.depth, 30);
    EXPECT_LT(mesh.bvh.nodes.size(), mesh.triangles.size());
    expectWellFormed(mesh);
    expectBounds(mesh.bounds, glm::dvec3(-1), glm::dvec3(1), 1e-6);
}

TEST(TriangleMeshBuiltIn, OthersAreNotBuiltIn) {
    for (const ShapeType type : {ShapeType::Sphere, ShapeType::Mesh, ShapeType::Extrude,
                                 ShapeType::Union, ShapeType::Torus})
        EXPECT_FALSE(isBuiltInMesh(type)) << shapeKeyword(type);
}

}  // namespace
}  // namespace vkray
