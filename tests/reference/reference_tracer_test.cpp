// Known-answer images from the CPU reference: scenes small enough that every
// pixel's ray, hit and Hill shading can be worked out by hand.
#include "reference/reference_tracer.h"

#include "reference/reference_test_util.h"
#include "util/error.h"
#include "util/stopwatch.h"

#include <gtest/gtest.h>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace vkray::reference {
namespace {

using test::makeObject;
using test::scaling;
using test::translation;

constexpr float kInf = std::numeric_limits<float>::infinity();

CameraBasis camera(const glm::dvec3& eye, double fovDegrees, int width, int height) {
    Camera c;
    c.eye = eye;
    c.look = {0, 0, 0};
    c.up = {0, 1, 0};
    c.fovDegrees = fovDegrees;
    return makeCameraBasis(c, width, height);
}

// One unit sphere at the origin lit from (0,0,10) by a white light; diffuse
// 0.8, ambient 0.1 (global 0.1), specular 1 with exponent 2.
Scene litSphere() {
    Scene scene;
    scene.background = {0, 0, 0.6};
    scene.globalAmbient = {0.1, 0.1, 0.1};
    SceneObject sphere = makeObject(ShapeType::Sphere);
    sphere.material.ambient = {0.1, 0.1, 0.1};
    sphere.material.diffuse = {0.8, 0.8, 0.8};
    sphere.material.specular = {1, 1, 1};
    sphere.material.specularExponent = 2;
    scene.objects.push_back(sphere);
    scene.lights.push_back({{0, 0, 10}, {1, 1, 1}, {}});
    return scene;
}

void expectColor(const glm::vec3& actual, const glm::dvec3& expected, double tol = 1e-6) {
    EXPECT_NEAR(actual.r, expected.r, tol);
    EXPECT_NEAR(actual.g, expected.g, tol);
    EXPECT_NEAR(actual.b, expected.b, tol);
}

void expectSameFrames(const Frame& a, const Frame& b) {
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    for (size_t i = 0; i < a.pixelCount(); ++i) {
        ASSERT_EQ(a.color[i], b.color[i]) << "pixel " << i;
        ASSERT_EQ(a.depth[i], b.depth[i]) << "pixel " << i;
        ASSERT_EQ(a.normal[i], b.normal[i]) << "pixel " << i;
        ASSERT_EQ(a.id[i], b.id[i]) << "pixel " << i;
    }
}

TEST(ReferenceTracer, CentrePixelOfATinySphere) {
    // 3 x 3 pixels, 60 degrees: the centre pixel's ray is exactly -z and meets
    // the sphere at (0,0,1), t = 4. There n = s = v = h = +z, so every dot
    // product is 1: colour = 0.1 * 0.1 + 0.8 * 1 + 1 * 1^2 = 1.81.
    const Scene scene = litSphere();
    const Frame frame = render(scene, camera({0, 0, 5}, 60, 3, 3), {3, 3, 1});
    ASSERT_EQ(frame.width, 3);
    ASSERT_EQ(frame.height, 3);
    const size_t centre = frame.index(1, 1);
    EXPECT_EQ(frame.id[centre], 0);
    EXPECT_NEAR(frame.depth[centre], 4, 1e-6);
    EXPECT_EQ(frame.normal[centre], glm::vec3(0, 0, 1));
    expectColor(frame.color[centre], {1.81, 1.81, 1.81});
}

TEST(ReferenceTracer, StatsTellPreparationFromTrace) {
    // Both stages are timed on every render that asks; the rays take CPU
    // time, and neither stage takes longer than the render around them.
    const Scene scene = litSphere();
    ReferenceStats stats;
    ReferenceOptions options;
    options.threads = 1;
    options.stats = &stats;
    const Stopwatch around;
    render(scene, camera({0, 0, 5}, 60, 64, 48), {64, 48, 1}, options);
    const double wall = around.seconds();
    EXPECT_GE(stats.prepare.wall, 0);
    EXPECT_GT(stats.trace.wall, 0);
    EXPECT_GT(stats.trace.cpu, 0);
    EXPECT_LE(stats.prepare.wall + stats.trace.wall, wall);
}

TEST(ReferenceTracer, PixelsThatMissShowTheBackground) {
    // The other eight rays leave the eye at least atan(tan 30° * 2/3) ≈ 21°
    // off the axis; the sphere subtends only asin(1/5) ≈ 11.5°.
    const Scene scene = litSphere();
    const Frame frame = render(scene, camera({0, 0, 5}, 60, 3, 3), {3, 3, 1});
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 3; ++x) {
            if (x == 1 && y == 1) continue;
            const size_t i = frame.index(x, y);
            EXPECT_EQ(frame.id[i], -1) << x << "," << y;
            EXPECT_EQ(frame.depth[i], kInf) << x << "," << y;
            EXPECT_EQ(frame.normal[i], glm::vec3(0)) << x << "," << y;
            EXPECT_EQ(frame.color[i], glm::vec3(0, 0, 0.6f)) << x << "," << y;
        }
    }
}

TEST(ReferenceTracer, WithoutAovsDepthAndNormalStayAsFrameMadeThem) {
    // As the GPU leaves them (RenderSettings::aovs): the colour and the id
    // are those of a render with AOVs.
    const Scene scene = litSphere();
    const CameraBasis basis = camera({0, 0, 5}, 60, 3, 3);
    RenderSettings settings{3, 3, 1};
    const Frame with = render(scene, basis, settings);
    settings.aovs = false;
    const Frame without = render(scene, basis, settings);
    const Frame untouched(3, 3);
    EXPECT_EQ(without.color, with.color);
    EXPECT_EQ(without.id, with.id);
    EXPECT_EQ(without.id[without.index(1, 1)], 0);
    EXPECT_EQ(without.depth, untouched.depth);
    EXPECT_EQ(without.normal, untouched.normal);
    EXPECT_NE(with.depth, untouched.depth);
}

TEST(ReferenceTracer, OneBlockFillsAllItsPixelsWithTheCentreRay) {
    const Scene scene = litSphere();
    const CameraBasis basis = camera({0, 0, 5}, 60, 3, 3);
    const Frame single = render(scene, basis, {3, 3, 1});
    const Frame block = render(scene, basis, {3, 3, 3});
    const size_t centre = single.index(1, 1);
    for (size_t i = 0; i < block.pixelCount(); ++i) {
        EXPECT_EQ(block.color[i], single.color[centre]) << i;
        EXPECT_EQ(block.depth[i], single.depth[centre]) << i;
        EXPECT_EQ(block.normal[i], single.normal[centre]) << i;
        EXPECT_EQ(block.id[i], 0) << i;
    }
}

TEST(ReferenceTracer, RaysFollowTheImageAxesAndAspect) {
    // 90 degrees (tan 45° = 1), 4 x 2 pixels, aspect 2, looking down -z at the
    // plane z = 0 from 5 up. Pixel (0,0) samples (0.5, 0.5): sx = -0.75,
    // sy = 0.5, so the ray runs along (-0.75 * 2, 0.5, -1) and reaches z = 0
    // at (-7.5, 2.5, 0), 5 |(-1.5, 0.5, -1)| = 5 sqrt(3.5) from the eye.
    Scene scene;
    scene.objects.push_back(makeObject(ShapeType::Plane));
    const Frame frame = render(scene, camera({0, 0, 5}, 90, 4, 2), {4, 2, 1});
    const size_t topLeft = frame.index(0, 0);
    EXPECT_EQ(frame.id[topLeft], 0);
    EXPECT_NEAR(frame.depth[topLeft], 5 * std::sqrt(3.5), 1e-5);
    EXPECT_EQ(frame.normal[topLeft], glm::vec3(0, 0, 1));
    // Pixel (3,1) mirrors it through the centre: sx = 0.75, sy = -0.5.
    EXPECT_EQ(frame.depth[frame.index(3, 1)], frame.depth[topLeft]);
}

TEST(ReferenceTracer, HillShadingWithASideLightAndEmission) {
    // Looking straight down at the plane z = 0: the centre ray hits (0,0,0)
    // with m = v = +z. A light at (3,0,4) gives s = (0.6, 0, 0.8), m.s = 0.8;
    // h = normalize(s + v) = (0.6, 0, 1.8) / sqrt(3.6), m.h = 1.8 / sqrt(3.6),
    // and m.h^2 = 3.24 / 3.6 = 0.9. With light colour (1, 0.5, 0), emissive
    // (0.2, 0, 0), ambient 0.1 * global 0.1, diffuse 0.8, specular 1:
    //     colour = (0.2, 0, 0) + 0.01 + (0.8 * 0.8 + 0.9) * (1, 0.5, 0).
    // A second light straight below adds nothing: m.s = -1, and s + v = 0
    // leaves no halfway vector.
    Scene scene;
    SceneObject plane = makeObject(ShapeType::Plane);
    plane.material.emissive = {0.2, 0, 0};
    plane.material.specular = {1, 1, 1};
    plane.material.specularExponent = 2;
    scene.objects.push_back(plane);
    scene.lights.push_back({{3, 0, 4}, {1, 0.5, 0}, {}});
    scene.lights.push_back({{0, 0, -4}, {1, 1, 1}, {}});
    const Frame frame = render(scene, camera({0, 0, 5}, 60, 3, 3), {3, 3, 1});
    const size_t centre = frame.index(1, 1);
    EXPECT_NEAR(frame.depth[centre], 5, 1e-6);
    expectColor(frame.color[centre], {0.2 + 0.01 + 1.54, 0.01 + 0.77, 0.01});
}

TEST(ReferenceTracer, ColourIsNotClamped) {
    const Scene scene = litSphere();
    const Frame frame = render(scene, camera({0, 0, 5}, 60, 3, 3), {3, 3, 1});
    EXPECT_GT(frame.color[frame.index(1, 1)].r, 1.0f);
}

// A scene with every supported shape, transformed, for whole-image checks.
Scene mixedScene() {
    Scene scene = litSphere();
    // A wall x = -4: the plane turned by R_y(90°), which takes +z to +x. It
    // fills the left of the view; rays to the right miss everything.
    glm::dmat4 rotateY90(0.0), rotateYMinus90(0.0);
    rotateY90[0] = {0, 0, -1, 0};
    rotateY90[1] = {0, 1, 0, 0};
    rotateY90[2] = {1, 0, 0, 0};
    rotateY90[3] = {0, 0, 0, 1};
    rotateYMinus90 = glm::transpose(rotateY90);  // a rotation's inverse, exactly
    SceneObject wall = makeObject(ShapeType::Plane, translation({-4, 0, 0}) * rotateY90,
                                  rotateYMinus90 * translation({4, 0, 0}));
    wall.material.diffuse = {0.2, 0.7, 0.3};
    scene.objects.push_back(wall);
    scene.objects.push_back(makeObject(ShapeType::Cube,
                                       translation({2.5, 0, 0}) * scaling({0.5, 1, 0.75}),
                                       scaling({2, 1, 1 / 0.75}) * translation({-2.5, 0, 0})));
    scene.objects.push_back(
        makeObject(ShapeType::Square, translation({-2.5, 1, 0.5}), translation({2.5, -1, -0.5})));
    scene.lights.push_back({{-5, 5, 5}, {0.3, 0.3, 0.9}, {}});
    return scene;
}

TEST(ReferenceTracer, ThreadCountDoesNotChangeTheImage) {
    const Scene scene = mixedScene();
    for (int block : {1, 5}) {  // 5 divides neither 64 nor 48: edge blocks are clipped
        const RenderSettings settings{64, 48, block};
        const CameraBasis basis = camera({3, 4, 9}, 60, settings.width, settings.height);
        const Frame one = render(scene, basis, settings, {1});
        const Frame four = render(scene, basis, settings, {4});
        const Frame automatic = render(scene, basis, settings, {0});
        expectSameFrames(one, four);
        expectSameFrames(one, automatic);
        // Every object shows up, and something misses.
        for (int id = -1; id < int(scene.objects.size()); ++id)
            EXPECT_NE(std::count(one.id.begin(), one.id.end(), id), 0) << "id " << id;
    }
}

TEST(ReferenceTracer, BlocksAreUniform) {
    const Scene scene = mixedScene();
    const RenderSettings settings{64, 48, 5};
    const Frame frame = render(scene, camera({3, 4, 9}, 60, 64, 48), settings);
    for (int y = 0; y < frame.height; ++y) {
        for (int x = 0; x < frame.width; ++x) {
            const size_t first = frame.index(x - x % 5, y - y % 5);
            const size_t i = frame.index(x, y);
            ASSERT_EQ(frame.color[i], frame.color[first]) << x << "," << y;
            ASSERT_EQ(frame.id[i], frame.id[first]) << x << "," << y;
        }
    }
}

TEST(ReferenceTracer, MissingMeshIsRefusedBeforeRendering) {
    Scene scene = litSphere();
    SceneObject teapot = makeObject(ShapeType::Teapot);
    teapot.loc = {std::make_shared<const std::string>("scene.sdl"), 3, 1};
    scene.objects.push_back(teapot);
    try {
        render(scene, camera({0, 0, 5}, 60, 3, 3), {3, 3, 1});
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "scene.sdl:3:1: error: 'teapot' has no geometry loaded (call loadSceneGeometry)");
    }
}

TEST(ReferenceTracer, BooleanWithoutAnInsideIsRefusedBeforeRendering) {
    Scene scene = litSphere();
    SceneObject square = makeObject(ShapeType::Square);
    square.loc = {std::make_shared<const std::string>("scene.sdl"), 4, 9};
    SceneObject difference = makeObject(ShapeType::Difference);
    difference.operands = {makeObject(ShapeType::Sphere), square};
    scene.objects.push_back(difference);
    try {
        tracePixel(scene, camera({0, 0, 5}, 60, 3, 3), {3, 3, 1}, 1, 1);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "scene.sdl:4:9: error: 'square' has no inside and cannot be an operand of "
                  "'difference'");
    }
}

TEST(ReferenceTracer, EmptySceneIsAllBackground) {
    Scene scene;
    scene.background = {0.25, 0.5, 0.75};
    const Frame frame = render(scene, camera({0, 0, 5}, 60, 4, 3), {4, 3, 2});
    for (size_t i = 0; i < frame.pixelCount(); ++i) {
        EXPECT_EQ(frame.color[i], glm::vec3(0.25f, 0.5f, 0.75f));
        EXPECT_EQ(frame.depth[i], kInf);
        EXPECT_EQ(frame.id[i], -1);
    }
}

}  // namespace
}  // namespace vkray::reference
