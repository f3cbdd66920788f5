// Where primary rays may meet an object: projections worked out by hand, and
// the one property that matters, checked on random scenes and cameras: no
// sample whose exact ray meets a box or a plane is left out of the cover.
#include "render/primary_cover.h"

#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace vkray {
namespace {

CameraBasis lookFrom(glm::dvec3 eye, glm::dvec3 look, double fov, int w, int h) {
    Camera camera;
    camera.eye = eye;
    camera.look = look;
    camera.up = {0, 1, 0};
    camera.fovDegrees = fov;
    return makeCameraBasis(camera, w, h);
}

Aabb box(glm::dvec3 lo, glm::dvec3 hi) {
    Aabb b;
    b.grow(lo);
    b.grow(hi);
    return b;
}

TEST(PrimaryCover, ACubeAheadCoversItsProjectionAndNothingFarFromIt) {
    // Eye (0, 0, 10) toward the origin, 90 degrees (tan 45 = 1), 100 x 100:
    // the cube [-1, 1]^3's nearest face, at depth 9, spans x, y in +-1/9 of
    // the half image, pixels 44.4 to 55.6; its far corners at depth 11 lie
    // within that. With a pixel's margin and cells of 4 pixels, the cover is
    // cells 10 to 14 a side, pixels 40 to 59.
    const RenderSettings settings{100, 100, 1};
    const PrimaryCover cover({{box({-1, -1, -1}, {1, 1, 1})}, {}, false},
                             lookFrom({0, 0, 10}, {0, 0, 0}, 90, 100, 100), settings);
    EXPECT_TRUE(cover.mayHit(49, 49, 51, 51));
    EXPECT_TRUE(cover.mayHit(44, 44, 45, 45));
    EXPECT_TRUE(cover.mayHit(40, 50, 41, 51));
    EXPECT_TRUE(cover.mayHit(59, 59, 60, 60));
    EXPECT_FALSE(cover.mayHit(0, 0, 40, 100));
    EXPECT_FALSE(cover.mayHit(60, 0, 100, 100));
    EXPECT_FALSE(cover.mayHit(0, 0, 100, 40));
    EXPECT_FALSE(cover.mayHit(0, 60, 100, 100));
    EXPECT_NEAR(cover.share(), 25.0 / 625.0, 1e-12);  // 5 x 5 of 25 x 25 cells
    EXPECT_FALSE(cover.mayHit(50, 50, 50, 60));       // an empty range
}

TEST(PrimaryCover, BoxesBehindTheEyeCoverNothingAndBoxesAroundItEverything) {
    const RenderSettings settings{64, 48, 1};
    const CameraBasis camera = lookFrom({0, 0, 10}, {0, 0, 0}, 60, 64, 48);
    const PrimaryCover behind({{box({-1, -1, 11}, {1, 1, 13})}, {}, false}, camera, settings);
    EXPECT_EQ(behind.share(), 0.0);
    EXPECT_FALSE(behind.mayHit(0, 0, 64, 48));
    // A room around the eye reaches its plane: every ray may meet it.
    const PrimaryCover around({{box({-20, -20, -20}, {20, 20, 20})}, {}, false}, camera, settings);
    EXPECT_EQ(around.share(), 1.0);
    // An object without a finite box, or a pile of planes: the whole image.
    EXPECT_EQ(PrimaryCover({{}, {}, true}, camera, settings).share(), 1.0);
    const std::vector<WorldPlane> planes(PrimaryCover::kMostPlanes + 1, WorldPlane{{0, 1, 0}, 50});
    EXPECT_EQ(PrimaryCover({{}, planes, false}, camera, settings).share(), 1.0);
    EXPECT_EQ(PrimaryCover(settings).share(), 1.0);
}

TEST(PrimaryCover, AFloorCoversTheImageBelowTheHorizonOnly) {
    // Eye 1 above the floor y = 0, looking level along -z, 90 degrees, 100 x
    // 100: rays below the middle row go down and meet the floor, rays above
    // go up and never do. The rows next to the horizon stay in (margin).
    const RenderSettings settings{100, 100, 1};
    const PrimaryCover floor({{}, {WorldPlane{{0, 1, 0}, 0}}, false},
                             lookFrom({0, 1, 0}, {0, 1, -1}, 90, 100, 100), settings);
    EXPECT_FALSE(floor.mayHit(0, 0, 100, 44));
    EXPECT_TRUE(floor.mayHit(0, 52, 1, 53));
    EXPECT_TRUE(floor.mayHit(99, 99, 100, 100));
    EXPECT_TRUE(floor.mayHit(50, 48, 51, 50));
    // Seen from below, the same floor covers the upper half.
    const PrimaryCover ceiling({{}, {WorldPlane{{0, 1, 0}, 0}}, false},
                               lookFrom({0, -1, 0}, {0, -1, -1}, 90, 100, 100), settings);
    EXPECT_TRUE(ceiling.mayHit(0, 0, 1, 1));
    EXPECT_FALSE(ceiling.mayHit(0, 56, 100, 100));
}

TEST(PrimaryCover, BlocksAtTheEdgeLookBeyondTheImage) {
    // 10 x 10 pixels in blocks of 4: the last block's ray looks through x =
    // 10, beyond the image; the cover reaches the whole blocks (12 pixels).
    RenderSettings settings{10, 10, 4};
    const CameraBasis camera = lookFrom({0, 0, 10}, {0, 0, 0}, 90, 10, 10);
    // A thin box seen at image x 10.5 to 11.5 only.
    const double depth = 10, scale = 2.0 / 10;  // tangent units a pixel at tan 45 = 1
    const double x0 = (10.5 * scale - 1) * depth, x1 = (11.5 * scale - 1) * depth;
    const PrimaryCover cover({{box({x0, -0.1, 0}, {x1, 0.1, 0})}, {}, false}, camera, settings);
    EXPECT_TRUE(cover.mayHit(8, 4, 12, 8));
    EXPECT_FALSE(cover.mayHit(0, 0, 4, 12));
}

TEST(PrimaryCover, TheShapesOfAScene) {
    Scene scene = parseSdl(
        "push translate 5 0 0 sphere pop push translate -5 0 0 cube pop push rotate -90 1 0 0 "
        "plane pop union sphere plane",
        "shapes.sdl", {});
    CoverShapes shapes = coverShapesOf(scene, nullptr);
    EXPECT_EQ(shapes.boxes.size(), 2u);
    ASSERT_EQ(shapes.planes.size(), 1u);
    // The floor: the generic z = 0 turned to y = 0, normal along y.
    EXPECT_NEAR(std::abs(shapes.planes[0].normal.y), 1, 1e-12);
    EXPECT_NEAR(shapes.planes[0].normal.x, 0, 1e-12);
    EXPECT_NEAR(shapes.planes[0].offset, 0, 1e-12);
    EXPECT_TRUE(shapes.unbounded);  // the union of a sphere and a plane
}

TEST(PrimaryCover, ABvhCutHoldsEveryObjectWithinItsBoxes) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> at(-50, 50);
    std::string sdl;
    for (int i = 0; i < 300; ++i)
        sdl += "push translate " + std::to_string(at(random)) + " " + std::to_string(at(random)) +
               " " + std::to_string(at(random)) + " sphere pop\n";
    const Scene scene = parseSdl(sdl, "many.sdl", {});
    const ObjectBvh objects = buildObjectBvh(scene);
    const CoverShapes cut = coverShapesOf(scene, &objects.bvh, 16);
    EXPECT_LE(cut.boxes.size(), 16u);
    EXPECT_GT(cut.boxes.size(), 8u);
    for (const SceneObject& object : scene.objects) {
        const Aabb b = worldBounds(object, scene);
        EXPECT_TRUE(std::any_of(cut.boxes.begin(), cut.boxes.end(), [&](const Aabb& c) {
            return c.lo.x <= b.lo.x && c.lo.y <= b.lo.y && c.lo.z <= b.lo.z && b.hi.x <= c.hi.x &&
                   b.hi.y <= c.hi.y && b.hi.z <= c.hi.z;
        }));
    }
    EXPECT_EQ(coverShapesOf(scene, &objects.bvh).boxes.size(), 300u);  // few enough: each object
}

// Whether the exact ray e + t d, t > 0, meets the box (slabs in double).
bool rayMeetsBox(glm::dvec3 e, glm::dvec3 d, const Aabb& b) {
    double near = 0, far = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (e[a] < b.lo[a] || e[a] > b.hi[a]) return false;
            continue;
        }
        double t0 = (b.lo[a] - e[a]) / d[a], t1 = (b.hi[a] - e[a]) / d[a];
        if (t0 > t1) std::swap(t0, t1);
        near = std::max(near, t0);
        far = std::min(far, t1);
    }
    return near <= far;
}

TEST(PrimaryCover, NoSampleThatMeetsAShapeIsLeftOut) {
    // Random boxes and planes seen from random eyes: every sample point whose
    // exact primary ray meets a box or a plane lies in the cover, and some
    // of the image is left out (the cover is not everything by accident).
    std::mt19937 random(2026);
    std::uniform_real_distribution<double> unit(0, 1), coordinate(-20, 20);
    int leftOut = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const RenderSettings settings{97, 61, 1 + trial % 3};
        const glm::dvec3 eye(coordinate(random), coordinate(random), coordinate(random));
        const glm::dvec3 look(coordinate(random), coordinate(random), coordinate(random));
        if (glm::length(look - eye) < 1) continue;
        const CameraBasis camera =
            lookFrom(eye, look, 20 + 100 * unit(random), settings.width, settings.height);
        CoverShapes shapes;
        for (int i = 0; i < 4; ++i) {
            const glm::dvec3 c(coordinate(random), coordinate(random), coordinate(random));
            const glm::dvec3 half(3 * unit(random), 3 * unit(random), 0.01 + 3 * unit(random));
            shapes.boxes.push_back(box(c - half, c + half));
        }
        if (trial % 2 == 0)
            shapes.planes.push_back(
                {glm::normalize(glm::dvec3(unit(random) - 0.5, unit(random), unit(random) - 0.5)),
                 coordinate(random)});
        const PrimaryCover cover(shapes, camera, settings);
        const int extentX = (settings.width + settings.block - 1) / settings.block * settings.block;
        const int extentY =
            (settings.height + settings.block - 1) / settings.block * settings.block;
        for (int py = 0; py < extentY; ++py)
            for (int px = 0; px < extentX; ++px) {
                const double sx = 2 * (px + unit(random)) / settings.width - 1;
                const double sy = 1 - 2 * (py + unit(random)) / settings.height;
                const glm::dvec3 d = -camera.n + sx * camera.tanHalfFov * camera.aspect * camera.u +
                                     sy * camera.tanHalfFov * camera.v;
                bool meets = std::any_of(shapes.boxes.begin(), shapes.boxes.end(),
                                         [&](const Aabb& b) { return rayMeetsBox(eye, d, b); });
                for (const WorldPlane& p : shapes.planes)
                    meets =
                        meets || (glm::dot(p.normal, eye) + p.offset) * glm::dot(p.normal, d) < 0;
                if (meets) {
                    ASSERT_TRUE(cover.mayHit(px, py, px + 1, py + 1))
                        << "trial " << trial << ", pixel " << px << "," << py;
                }
                leftOut += cover.mayHit(px, py, px + 1, py + 1) ? 0 : 1;
            }
    }
    EXPECT_GT(leftOut, 10000);
}

}  // namespace
}  // namespace vkray
