// Whitted shading on the GPU against answers computed by hand: a 1x1
// image's one ray goes exactly from the eye through the look point, so the
// shader's colour for a chosen ray can be checked (shadows, transparent
// occluders, mirrors, the recursion bound, Snell's law and total internal
// reflection, textures), and a whole frame for determinism of --seed.
#include "support/gpu_fixture.h"

#include "render/camera.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

namespace vkray {
namespace {

// The colour of the ray eye -> look in the scene `sdl` (text as if written
// in scenes/, so data/texels.png is found).
Frame traceOne(const std::string& sdl, glm::dvec3 eye, glm::dvec3 look, glm::dvec3 up = {0, 1, 0}) {
    return test::traceOneRay(sdl, test::kSourceDir + "/scenes/t.sdl", eye, look, up);
}

void expectColor(const Frame& f, glm::dvec3 expected, double tolerance = 2e-6) {
    EXPECT_NEAR(f.color[0].r, expected.r, tolerance);
    EXPECT_NEAR(f.color[0].g, expected.g, tolerance);
    EXPECT_NEAR(f.color[0].b, expected.b, tolerance);
}

// A floor z = 0 lit from (0, 0, 10) with ambient 1 x globalAmbient 0.2 and
// diffuse 0.5; `occluders` between the light and the floor's origin.
std::string floorScene(const std::string& occluders) {
    return "background 0 0 0 globalAmbient 0.2 0.2 0.2\n"
           "light 0 0 10 1 1 1\n"
           "ambient 1 1 1 diffuse 0.5 0.5 0.5 specular 0 0 0 plane\n" +
           occluders;
}

// The floor's origin seen from (4, 0, 4): the view misses the occluders,
// which stay within distance 1 of the z axis above z = 4.
Frame floorOrigin(const std::string& occluders) {
    return traceOne(floorScene(occluders), {4, 0, 4}, {0, 0, 0});
}

TEST(GpuShading, AShadowedPointHasOnlyTheAmbientTerm) {
    const std::string sphere = "push translate 0 0 5 sphere pop\n";
    expectColor(floorOrigin(sphere), glm::dvec3(0.2));
    // (3, 0, 0)'s feeler to the light passes 1.44 from the sphere's centre:
    // lit, diffuse 0.5 * m.s with s = (-3, 0, 10) / sqrt(109).
    const Frame lit = traceOne(floorScene(sphere), {7, 0, 4}, {3, 0, 0});
    expectColor(lit, glm::dvec3(0.2 + 0.5 * 10 / std::sqrt(109.0)));
    // Without the sphere the origin is lit straight from above.
    expectColor(floorOrigin(""), glm::dvec3(0.2 + 0.5));
}

TEST(GpuShading, TransparentOccludersPassTheirTransparencyOncePerObject) {
    // The feeler crosses both surfaces of the sphere: still one factor 0.5.
    expectColor(floorOrigin("transparency 0.5 push translate 0 0 5 sphere pop\n"),
                glm::dvec3(0.2 + 0.5 * 0.5));
    // Two spheres: 0.5 * 0.25.
    expectColor(floorOrigin("transparency 0.5 push translate 0 0 5 sphere pop\n"
                            "transparency 0.25 push translate 0 0 7.5 sphere pop\n"),
                glm::dvec3(0.2 + 0.5 * 0.5 * 0.25));
    // A boolean is one object, with the transparency of the operand met
    // first (the lower sphere's 0.9; not 0.9 * 0.5).
    expectColor(floorOrigin("union\n"
                            "  transparency 0.9 push translate 0 0 5 sphere pop\n"
                            "  transparency 0.5 push translate 0 0 7.5 sphere pop\n"),
                glm::dvec3(0.2 + 0.5 * 0.9));
    // A light behind the surface is blocked by the surface itself.
    expectColor(traceOne(floorScene(""), {4, 0, -4}, {0, 0, 0}), glm::dvec3(0.2));
}

TEST(GpuShading, ObjectBvhFeelersFindTheSameOccluders) {
    // Twelve small spheres (an object BVH) far from the feeler, and one on it.
    std::string spheres;
    for (int i = 0; i < 12; ++i)
        spheres +=
            "push translate " + std::to_string(-20 - 3 * i) + " 5 5 scale 0.5 0.5 0.5 sphere pop\n";
    expectColor(floorOrigin(spheres), glm::dvec3(0.7));
    expectColor(floorOrigin(spheres + "transparency 0.5 push translate 0 0 5 sphere pop\n"),
                glm::dvec3(0.2 + 0.5 * 0.5));
}

TEST(GpuShading, ObjectBvhFeelersPassEachMeshsTransparencyOnce) {
    // Meshes met by an object BVH's walk are walked in it (their triangles
    // in its leaves): a feeler crossing a closed mesh meets two triangles
    // and passes its transparency once, 0.5 * 0.25 for the two octahedra.
    std::string spheres;
    for (int i = 0; i < 12; ++i)
        spheres +=
            "push translate " + std::to_string(-20 - 3 * i) + " 5 5 scale 0.5 0.5 0.5 sphere pop\n";
    const std::string octahedra =
        "transparency 0.5 push translate 0.2 0.1 5 octahedron pop\n"
        "transparency 0.25 push translate 0.1 0.2 7.5 octahedron pop\n";
    expectColor(floorOrigin(spheres + octahedra), glm::dvec3(0.2 + 0.5 * 0.5 * 0.25));
    // An opaque one stops it.
    expectColor(floorOrigin(spheres + "push translate 0.2 0.1 5 octahedron pop\n"),
                glm::dvec3(0.2));
}

// A mirror square z = 0 (no colour of its own) under a wall square z = 10
// with emissive (0.5, 0.25, 1); the eye between them looks down.
std::string mirrorUnderWall(const std::string& settings) {
    return "background 0 0 0 minReflectivity 0.3 " + settings +
           "\nambient 0 0 0 diffuse 0 0 0 reflectivity 0.8 square\n"
           "reflectivity 0 emissive 0.5 0.25 1 push translate 0 0 10 square pop\n";
}

TEST(GpuShading, AMirrorShowsTheWallTimesItsReflectivity) {
    const Frame f = traceOne(mirrorUnderWall(""), {0, 0, 5}, {0, 0, 0});
    expectColor(f, 0.8 * glm::dvec3(0.5, 0.25, 1));
    // The AOVs are the mirror's own.
    EXPECT_EQ(f.id[0], 0);
    EXPECT_NEAR(f.depth[0], 5, 1e-5);
    // Reflectivity at or below minReflectivity, or no recursion: no reflection.
    expectColor(traceOne(mirrorUnderWall("maxRecursionDepth 0"), {0, 0, 5}, {0, 0, 0}),
                glm::dvec3(0));
    expectColor(traceOne(mirrorUnderWall("minReflectivity 0.8"), {0, 0, 5}, {0, 0, 0}),
                glm::dvec3(0));
}

TEST(GpuShading, FacingMirrorsStopAtMaxRecursionDepth) {
    // Mirrors z = 0 and z = 10, each emissive 0.4 and reflectivity 0.5: the
    // ray bounces between them, level i adding 0.4 * 0.5^i, down to level D.
    for (int depth : {0, 1, 3, 8}) {
        const std::string sdl =
            "maxRecursionDepth " + std::to_string(depth) +
            " minReflectivity 0.3 background 1 1 1\n"
            "ambient 0 0 0 diffuse 0 0 0 emissive 0.4 0.4 0.4 reflectivity 0.5\n"
            "square push translate 0 0 10 square pop\n";
        double expected = 0;
        for (int level = 0; level <= depth; ++level) expected += 0.4 * std::pow(0.5, level);
        SCOPED_TRACE("maxRecursionDepth " + std::to_string(depth));
        expectColor(traceOne(sdl, {0, 0, 5}, {0, 0, 0}), glm::dvec3(expected));
    }
}

// A plane z = planeZ seen by ambient light only (k times 1 x 1), with a
// checkerboard of 0.1 cells: white where floor(x / 0.1 + 0.5) is even, at
// y = 0. A ray landing within 0.05 of x = n 0.1 (n even) sees white, and
// black if it lands a cell off.
std::string checkeredPlane(double planeZ) {
    return "globalAmbient 1 1 1 background 0 0 0\n"
           "push translate 0 0 " +
           std::to_string(planeZ) +
           " ambient 1 1 1 diffuse 0 0 0 texture 1 parameters 4 0.1 0 0 0 plane pop texture 0\n";
}

// Glass with no colour of its own that lets everything through, light
// slower by half in it (index 2: critical angle 30 degrees).
const std::string kGlass = "ambient 0 0 0 diffuse 0 0 0 transparency 1 speedOfLight 0.5\n";

TEST(GpuShading, RefractionThroughASlabFollowsSnell) {
    // A slab -0.5 <= z <= 0.5 met at 45 degrees: inside, sin(theta2) =
    // 0.5 sin 45, so tan(theta2) = 0.377964; it leaves parallel to the
    // incoming ray. From (x0, 0, 3.5) along (1, 0, -1): the plane z = -2 is
    // reached at x0 + 3 + 0.377964 + 1.5 (unbent: x0 + 5.5, a cell further
    // than the 0.05 the test allows).
    const double x0 = -(3 + 0.377964 + 1.5);
    const std::string sdl =
        checkeredPlane(-2) + "maxRecursionDepth 3\n" + kGlass + "push scale 20 20 0.5 cube pop\n";
    expectColor(traceOne(sdl, {x0, 0, 3.5}, {x0 + 1, 0, 2.5}), glm::dvec3(1), 1e-6);
    // Landing 0.1 further along sees a black cell: the test can fail.
    expectColor(traceOne(sdl, {x0 + 0.1, 0, 3.5}, {x0 + 1.1, 0, 2.5}), glm::dvec3(0), 1e-6);
}

TEST(GpuShading, TotalInternalReflectionInsideACube) {
    // Into the top of the cube [-1, 1]^3 at 45 degrees at x = xe: inside at
    // 20.7 degrees from -z, the ray meets the face x = 1 at 69.3 degrees,
    // beyond the critical 30: it is mirrored, leaves through the bottom at
    // x = 1.24407 - xe and reaches z = -3 at x = -0.75593 - xe.
    const double xe = 0.44407;  // lands at x = -1.2, the middle of a white cell
    const std::string sdl = checkeredPlane(-3) + "maxRecursionDepth 4\n" + kGlass + "cube\n";
    expectColor(traceOne(sdl, {xe - 3, 0, 4}, {xe, 0, 1}), glm::dvec3(1), 1e-6);
    // One level short, the last refraction is not followed: black.
    const std::string shallow = checkeredPlane(-3) + "maxRecursionDepth 2\n" + kGlass + "cube\n";
    expectColor(traceOne(shallow, {xe - 3, 0, 4}, {xe, 0, 1}), glm::dvec3(0), 1e-6);
}

// Only ambient light, ambient 1: the colour is the texture's k.
std::string textured(const std::string& texture, const std::string& shape) {
    return "globalAmbient 1 1 1 ambient 1 1 1 diffuse 0 0 0\n"
           "makePixmap 0 data/texels.png\n" +
           texture + " " + shape + "\n";
}

// scenes/data/texels.png, 8 x 4: texel (x, y), y = 0 the top row, is
// ((32x + 16) / 255, (64y + 32) / 255, (x + y even ? 128 : 255) / 255).
glm::dvec3 texel(int x, int y) {
    return glm::dvec3(32 * x + 16, 64 * y + 32, (x + y) % 2 == 0 ? 128 : 255) / 255.0;
}

// The generic sphere's point with texture coordinates (u, v), from the
// spec's u = 0.5 + atan2(y, x) / 2 pi, v = 0.5 + asin(z) / pi.
glm::dvec3 spherePoint(double u, double v) {
    const double longitude = (u - 0.5) * 2 * std::numbers::pi;
    const double latitude = (v - 0.5) * std::numbers::pi;
    return {std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
            std::sin(latitude)};
}

TEST(GpuShading, TextureColourAtKnownPoints) {
    // Image on a sphere, at the centres of texels (4, 2) and (6, 1): u =
    // (x + 0.5) / 8, v = 1 - (y + 0.5) / 4 (v = 1 is the top row), seen
    // along the normal.
    const std::string sphere = textured("texture 3 parameters 1 0", "sphere");
    const glm::dvec3 a = spherePoint(4.5 / 8, 1 - 2.5 / 4), b = spherePoint(6.5 / 8, 1 - 1.5 / 4);
    expectColor(traceOne(sphere, 5.0 * a, {0, 0, 0}, {0, 0, 1}), texel(4, 2));
    expectColor(traceOne(sphere, 5.0 * b, {0, 0, 0}, {0, 0, 1}), texel(6, 1));
    // Square at generic (-0.9, 0.9): u = 0.05, v = 0.95 -> the top-left texel.
    expectColor(
        traceOne(textured("texture 3 parameters 1 0", "square"), {-0.9, 0.9, 5}, {-0.9, 0.9, 0}),
        texel(0, 0));
    // Cube face z = 1 at (0.3, -0.2): u = 0.65, v = 0.4 -> texel (5, 2).
    expectColor(
        traceOne(textured("texture 3 parameters 1 0", "cube"), {0.3, -0.2, 5}, {0.3, -0.2, 0}),
        texel(5, 2));
    // Checkerboard of size 0.5 on the cube's face z = 1: at x = 0 the cells
    // add up to 0 + 0 + 2 (even: white), at x = 0.6 to 1 + 0 + 2 (odd: the colour).
    const std::string checker = textured("texture 1 parameters 4 0.5 0.9 0.2 0.1", "cube");
    expectColor(traceOne(checker, {0, 0, 5}, {0, 0, 0}), glm::dvec3(1));
    expectColor(traceOne(checker, {0.6, 0, 5}, {0.6, 0, 0}), glm::dvec3(0.9, 0.2, 0.1));
    // Wood rings 0.25 wide about z on a sphere seen from above: 0.3 from the
    // axis is ring 1 (the colour), 0.1 is ring 0 (white).
    const std::string wood = textured("texture 2 parameters 4 0.25 0.5 0.3 0.1", "sphere");
    expectColor(traceOne(wood, {0.3, 0, 5}, {0.3, 0, 0}), glm::dvec3(0.5, 0.3, 0.1));
    expectColor(traceOne(wood, {0.1, 0, 5}, {0.1, 0, 0}), glm::dvec3(1));
}

bool sameBytes(const Frame& a, const Frame& b) {
    const auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
    return a.color.size() == b.color.size() &&
           std::memcmp(a.color.data(), b.color.data(), bytes(a.color)) == 0 &&
           std::memcmp(a.depth.data(), b.depth.data(), bytes(a.depth)) == 0 &&
           std::memcmp(a.normal.data(), b.normal.data(), bytes(a.normal)) == 0 &&
           std::memcmp(a.id.data(), b.id.data(), bytes(a.id)) == 0;
}

TEST(GpuShading, TheSameSeedGivesTheSameBytes) {
    const Scene scene = loadScene(test::kSourceDir + "/scenes/whitted.sdl", {}, nullptr);
    const CameraBasis camera = makeCameraBasis(*scene.camera, 64, 48);
    const Frame first = test::renderOnGpu(scene, camera, {64, 48, 1, 4, 11});
    const Frame second = test::renderOnGpu(scene, camera, {64, 48, 1, 4, 11});
    EXPECT_TRUE(sameBytes(first, second));
    // Another seed moves the samples: some pixel changes.
    EXPECT_FALSE(sameBytes(first, test::renderOnGpu(scene, camera, {64, 48, 1, 4, 12})));
}

}  // namespace
}  // namespace vkray
