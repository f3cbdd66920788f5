// Texture colours at known generic points and (u, v): each texture code,
// the (u, v) of every shape, the nearest-texel lookup, and whole renders
// where the texture is all a pixel shows (ambient 1 x global 1, nothing
// else, so the colour is k itself).
#include "reference/textures.h"

#include "image/image_io.h"
#include "reference/reference_test_util.h"
#include "reference/shading.h"
#include "scene/pixmaps.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <string>

#ifndef VKRAY_SOURCE_DIR
#define VKRAY_SOURCE_DIR "."
#endif

namespace vkray::reference {
namespace {

using test::expectNear;

constexpr double kPi = std::numbers::pi;

// Text as if in scenes/, so data/texels.png is found. Only ambient light:
// a hit shows k * ambient (1) * globalAmbient (1).
Scene texturedScene(const std::string& shapes) {
    Scene scene = parseSdl(
        "background 0 0 0 globalAmbient 1 1 1 ambient 1 1 1 diffuse 0 0 0\n"
        "makePixmap 0 data/texels.png\n" +
            shapes,
        VKRAY_SOURCE_DIR "/scenes/textures.sdl", {});
    loadSceneGeometry(scene, false, nullptr);
    return scene;
}

glm::dvec3 seen(const Scene& scene, const glm::dvec3& from, const glm::dvec3& to) {
    const SceneIntersector intersector(scene);
    return WhittedShader(scene, intersector)
        .radiance({from, glm::normalize(to - from)}, 0, Medium{});
}

// The texel (x, y) of scenes/data/texels.png (tests/scene/pixmaps_test.cpp).
glm::dvec3 texel(int x, int y) {
    return {float(32 * x + 16) / 255.0f, float(64 * y + 32) / 255.0f,
            float((x + y) % 2 == 0 ? 128 : 255) / 255.0f};
}

// The centre of texel (x, y) of the 8 x 4 image as (u, v).
glm::dvec2 uvOfTexel(int x, int y) {
    return {(x + 0.5) / 8, 1 - (y + 0.5) / 4};
}

TEST(Textures, CheckerboardCellsShiftedByHalfACell) {
    const glm::dvec3 odd(0.2, 0.3, 0.4);
    // size 0.5: cell = floor(2x + 0.5) + floor(2y + 0.5) + floor(2z + 0.5).
    expectNear(checkerboard({0, 0, 0}, 0.5, odd), glm::dvec3(1), 0);        // 0: even
    expectNear(checkerboard({0.3, 0, 0}, 0.5, odd), odd, 0);                // 1: odd
    expectNear(checkerboard({1, 0.3, 0.3}, 0.5, odd), glm::dvec3(1), 0);    // 2 + 1 + 1
    expectNear(checkerboard({1, 0.3, 0.8}, 0.5, odd), odd, 0);              // 2 + 1 + 2
    expectNear(checkerboard({-0.3, 0, 0}, 0.5, odd), odd, 0);               // -1: odd
    expectNear(checkerboard({-0.3, -0.3, 0}, 0.5, odd), glm::dvec3(1), 0);  // -2: even
}

TEST(Textures, WoodRingsAboutTheZAxisShiftedByHalfARing) {
    // ring = floor(r / w + 1/2): ring 0 is the disk r < w/2, ring j the band
    // (j - 1/2) w <= r < (j + 1/2) w; odd rings take the colour.
    const glm::dvec3 odd(0.55, 0.35, 0.15);
    expectNear(woodRings({0.02, 0, 7}, 0.1, odd), glm::dvec3(1), 0);   // 0.2 + 0.5: ring 0
    expectNear(woodRings({0.06, 0, 0}, 0.1, odd), odd, 0);             // 0.6 + 0.5: ring 1
    expectNear(woodRings({0.09, 0.09, 0}, 0.1, odd), odd, 0);          // r = 0.127: ring 1
    expectNear(woodRings({0, -0.22, 0}, 0.1, odd), glm::dvec3(1), 0);  // 2.2 + 0.5: ring 2
    expectNear(woodRings({0.3, 0.4, 0}, 0.3, odd), glm::dvec3(1), 0);  // r = 0.5: ring 2 (2.17)
    expectNear(woodRings({0.3, 0.4, 0}, 0.4, odd), odd, 0);            // 1.25 + 0.5: ring 1
}

TEST(Textures, WoodRingBoundariesMissTheCylinderWall) {
    // For a width w = 1/k, radius 1 is ring k's middle (r / w + 1/2 = k + 1/2),
    // so the generic cylinder's wall and its neighbourhood are all one ring,
    // even (white) for k = 10 and 4, odd (the colour) for k = 3 and 5.
    const glm::dvec3 odd(0.55, 0.35, 0.15), white(1);
    for (const glm::dvec3& g : {glm::dvec3(1, 0, 0.5), glm::dvec3(0.6, -0.8, 0),
                                glm::dvec3(0.96, 0, 1), glm::dvec3(0, 1.04, 0)})
        expectNear(woodRings(g, 0.1, odd), white, 0);         // 9.6 .. 10.4, + 0.5: ring 10
    expectNear(woodRings({0.9, 0, 0}, 0.25, odd), white, 0);  // 3.6 + 0.5: ring 4
    expectNear(woodRings({-1, 0, 0}, 0.25, odd), white, 0);
    expectNear(woodRings({0, 1.1, 0}, 0.25, odd), white, 0);    // 4.4 + 0.5
    expectNear(woodRings({0, -1, 0.3}, 1.0 / 3, odd), odd, 0);  // 3 + 0.5: ring 3
    expectNear(woodRings({0.8, 0.6, 0}, 0.2, odd), odd, 0);     // 5 + 0.5: ring 5
    // The axis (a cone's apex) is in the middle of ring 0.
    expectNear(woodRings({0, 0, 1}, 0.1, odd), white, 0);
}

TEST(Textures, UvOfEveryShape) {
    const glm::dvec3 none(0);
    const auto expectUv = [](glm::dvec2 actual, glm::dvec2 expected) {
        EXPECT_NEAR(actual.x, expected.x, 1e-15);
        EXPECT_NEAR(actual.y, expected.y, 1e-15);
    };
    // Sphere: longitude about z from -x (u = 0), latitude from the south pole.
    expectUv(surfaceUv(ShapeType::Sphere, {1, 0, 0}, none), {0.5, 0.5});
    expectUv(surfaceUv(ShapeType::Sphere, {0, 1, 0}, none), {0.75, 0.5});
    expectUv(surfaceUv(ShapeType::Sphere, {0, 0, 1}, none), {0.5, 1});
    expectUv(surfaceUv(ShapeType::Sphere, {0, -std::sqrt(0.5), -std::sqrt(0.5)}, none),
             {0.25, 0.25});
    // Plane: a tile every 2 units; square: [-1, 1]^2 onto [0, 1]^2.
    expectUv(surfaceUv(ShapeType::Plane, {0.5, -0.5, 0}, none), {0.75, 0.25});
    expectUv(surfaceUv(ShapeType::Plane, {2.5, 3.5, 0}, none), {0.75, 0.25});
    expectUv(surfaceUv(ShapeType::Square, {0.5, -0.5, 0}, none), {0.75, 0.25});
    // Cylinder wall: around and up; caps: like the square.
    expectUv(surfaceUv(ShapeType::Cylinder, {-1, 0, 0.25}, {-1, 0, 0}), {1, 0.25});
    expectUv(surfaceUv(ShapeType::TaperedCylinder, {0, -0.5, 0.5}, {0, -0.5, 0.25}), {0.25, 0.5});
    expectUv(surfaceUv(ShapeType::Cylinder, {0.5, 0, 1}, {0, 0, 1}), {0.75, 0.5});
    expectUv(surfaceUv(ShapeType::Cone, {0, 0.5, 0}, {0, 0, -1}), {0.5, 0.75});
    // Cube: the face of the largest |g|, the other two coordinates in order.
    expectUv(surfaceUv(ShapeType::Cube, {1, 0.5, -0.5}, none), {0.75, 0.25});
    expectUv(surfaceUv(ShapeType::Cube, {0.5, -1, 0}, none), {0.75, 0.5});
    expectUv(surfaceUv(ShapeType::Cube, {0, 0.5, 1}, none), {0.5, 0.75});
    // Torus: around the axis, then around the tube from its outer equator.
    expectUv(surfaceUv(ShapeType::Torus, {1.25, 0, 0}, none), {0.5, 0.5});
    expectUv(surfaceUv(ShapeType::Torus, {0, 1, 0.25}, none), {0.75, 0.75});
    // Meshes: x and y onto [0, 1], wrapped.
    expectUv(surfaceUv(ShapeType::Teapot, {0.5, -0.5, 3}, none), {0.75, 0.25});
    expectUv(surfaceUv(ShapeType::Mesh, {2.5, 1.5, 0}, none), {0.75, 0.25});
}

TEST(Textures, NearestTexelWrapsUAndClampsV) {
    const Scene scene = texturedScene("");
    const Image& image = *findPixmap(scene, 0)->image;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            expectNear(nearestTexel(image, uvOfTexel(x, y)), texel(x, y), 0);
    expectNear(nearestTexel(image, {0, 1}), texel(0, 0), 0);        // top-left corner
    expectNear(nearestTexel(image, {1, 0}), texel(0, 3), 0);        // u = 1 wraps to 0
    expectNear(nearestTexel(image, {-0.01, 1.5}), texel(7, 0), 0);  // u wraps, v clamps
    expectNear(nearestTexel(image, {2.3, -4}), texel(2, 3), 0);
}

TEST(Textures, NoTextureIsWhite) {
    const Scene scene = texturedScene("sphere");
    expectNear(seen(scene, {5, 0, 0}, {0, 0, 0}), glm::dvec3(1), 0);
}

TEST(Textures, CheckerboardOnATransformedCube) {
    // The cube moved and stretched: the texture follows its generic space.
    // World (10 + 2 gx, gy, gz): the ray along -x meets the face gx = 1.
    const Scene scene =
        texturedScene("texture 1 parameters 4 0.5 0.2 0.3 0.4 translate 10 0 0 scale 2 1 1 cube");
    expectNear(seen(scene, {20, 0.3, 0.3}, {12, 0.3, 0.3}), glm::dvec3(1), 0);
    expectNear(seen(scene, {20, 0.3, 0.8}, {12, 0.3, 0.8}), glm::dvec3(0.2, 0.3, 0.4), 0);
}

TEST(Textures, WoodWithDefaultsOnACylinderCap) {
    // Default width 0.1 and colour (0.55, 0.35, 0.15). Looking down on the
    // top cap (z = 1): r = 0.27 is ring 3 (2.7 + 0.5), r = 0.18 ring 2.
    const Scene scene = texturedScene("texture 2 cylinder");
    expectNear(seen(scene, {0.27, 0, 5}, {0.27, 0, 0}), glm::dvec3(0.55, 0.35, 0.15), 1e-15);
    expectNear(seen(scene, {0, 0.18, 5}, {0, 0.18, 0}), glm::dvec3(1), 0);
}

TEST(Textures, ImageOnASphereAtAKnownUv) {
    // Texel (5, 2)'s centre: u = 5.5/8 (longitude 67.5 degrees), v = 1.5/4
    // (latitude -22.5 degrees), on a sphere of radius 2 at (0, 0, 3).
    const double longitude = (5.5 / 8 - 0.5) * 2 * kPi, latitude = (1.5 / 4 - 0.5) * kPi;
    const glm::dvec3 g(std::cos(latitude) * std::cos(longitude),
                       std::cos(latitude) * std::sin(longitude), std::sin(latitude));
    const Scene scene =
        texturedScene("texture 3 parameters 1 0 translate 0 0 3 scale 2 2 2 sphere");
    const glm::dvec3 p = glm::dvec3(0, 0, 3) + 2.0 * g;
    expectNear(seen(scene, p + 5.0 * g, p), texel(5, 2), 0);
}

TEST(Textures, ImageOnEachFaceOfACube) {
    const Scene scene = texturedScene("texture 3 parameters 1 0 cube");
    // +x face: (u, v) = ((y + 1)/2, (z + 1)/2); texel (1, 3) has u = 1.5/8, v = 0.5/4.
    const glm::dvec2 uv = uvOfTexel(1, 3);
    const double a = 2 * uv.x - 1, b = 2 * uv.y - 1;
    expectNear(seen(scene, {5, a, b}, {0, a, b}), texel(1, 3), 0);
    // -y face: (x, z); +z face: (x, y).
    expectNear(seen(scene, {a, -5, b}, {a, 0, b}), texel(1, 3), 0);
    expectNear(seen(scene, {a, b, 5}, {a, b, 0}), texel(1, 3), 0);
}

TEST(Textures, ImageFollowsTheOperandHitInCsg) {
    // A textured sphere cut by an untextured cube: where the sphere's surface
    // shows, its texture does; the cube's cut face stays white.
    const Scene scene =
        texturedScene("difference texture 3 parameters 1 0 sphere texture 0 translate 0 0 1 cube");
    // The cut face z = 0 seen from above: the cube's (subtracted) surface.
    expectNear(seen(scene, {0.1, 0.1, 5}, {0.1, 0.1, 0}), glm::dvec3(1), 0);
    // The sphere's lower half from below, next to the south pole (v near 0:
    // the bottom row) at longitude 67.5 degrees (u = 5.5/8: column 5).
    const double x = 1e-4 * std::cos(3 * kPi / 8), y = 1e-4 * std::sin(3 * kPi / 8);
    expectNear(seen(scene, {x, y, -5}, {x, y, 0}), texel(5, 3), 0);
}

}  // namespace
}  // namespace vkray::reference
