// Whitted shading in the CPU reference against answers worked out by hand:
// shadows (opaque and transparent occluders), mirror reflection, refraction
// through a slab, a sphere and a prism (Snell from the angles), total
// internal reflection, and maxRecursionDepth between two mirrors.
#include "reference/shading.h"

#include "reference/reference_test_util.h"
#include "scene/scene_geometry.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <string>

namespace vkray::reference {
namespace {

using test::expectNear;

Scene sceneOf(const std::string& text) {
    Scene scene = parseSdl(text, "shading.sdl", {});
    loadSceneGeometry(scene, false, nullptr);
    return scene;
}

// What the ray from `from` toward `to` sees, through the object BVH and by
// brute force (they must agree).
glm::dvec3 seen(const Scene& scene, const glm::dvec3& from, const glm::dvec3& to) {
    const Ray ray{from, glm::normalize(to - from)};
    const SceneIntersector bvh(scene), bruteForce(scene, true);
    const glm::dvec3 color = WhittedShader(scene, bvh).radiance(ray, 0, Medium{});
    expectNear(WhittedShader(scene, bruteForce).radiance(ray, 0, Medium{}), color, 1e-15);
    return color;
}

double degrees(double d) {
    return d * std::numbers::pi / 180;
}

// ---- shadows -----------------------------------------------------------------

// The floor z = 0 (Hill's generic plane) under a unit sphere at (0, 0, 2),
// a white light at (0, 0, 10). Rays come in low from +x, so they meet the
// floor, never the sphere. Defaults: ambient 0.1 x global 0.1, diffuse 0.8.
const char* kFloorAndBall =
    "light 0 0 10 1 1 1 globalAmbient 0.1 0.1 0.1\n"
    "plane\n"
    "TRANSPARENCY translate 0 0 2 sphere\n";

Scene floorAndBall(double transparency) {
    std::string text = kFloorAndBall;
    text.replace(text.find("TRANSPARENCY"), 12, "transparency " + std::to_string(transparency));
    return sceneOf(text);
}

TEST(Shadows, APointUnderTheSphereGetsOnlyAmbient) {
    // Floor point (0.3, 0, 0): the feeler to (0, 0, 10) passes x = 0.24 at
    // z = 2, inside the sphere.
    const Scene scene = floorAndBall(0);
    expectNear(seen(scene, {10, 0, 1}, {0.3, 0, 0}), glm::dvec3(0.01), 1e-15);
}

TEST(Shadows, APointBesideTheSphereIsLit) {
    // Floor point (5, 0, 0): m = +z, s = (-5, 0, 10)/sqrt(125), m.s = 10/sqrt(125).
    const Scene scene = floorAndBall(0);
    expectNear(seen(scene, {10, 0, 1}, {5, 0, 0}), glm::dvec3(0.01 + 0.8 * 10 / std::sqrt(125.0)),
               1e-14);
}

TEST(Shadows, ATransparentOccluderLetsItsTransparencyThrough) {
    // The feeler crosses the sphere's surface twice; the sphere counts once.
    const Scene scene = floorAndBall(0.5);
    const double mDotS = 10 / std::sqrt(0.09 + 100);
    expectNear(seen(scene, {10, 0, 1}, {0.3, 0, 0}), glm::dvec3(0.01 + 0.5 * 0.8 * mDotS), 1e-14);
}

TEST(Shadows, TwoTransparentOccludersMultiply) {
    const Scene scene = sceneOf(
        "plane transparency 0.5 translate 0 0 2 sphere translate 0 0 3 sphere "
        "translate 0 0 5 defaultMaterials sphere");  // spheres at z = 2, 5 (both 0.5) and 10
    const SceneIntersector intersector(scene);
    const WhittedShader shader(scene, intersector);
    // lightThrough itself: from below the stack, toward points above each sphere.
    expectNear(shader.lightThrough({0, 0, 0.5}, {0, 0, 4}), glm::dvec3(0.5), 0);
    expectNear(shader.lightThrough({0, 0, 0.5}, {0, 0, 7}), glm::dvec3(0.25), 0);
    expectNear(shader.lightThrough({0, 0, 0.5}, {0, 0, 12}), glm::dvec3(0), 0);  // opaque third
    expectNear(shader.lightThrough({3, 0, 0.5}, {3, 0, 12}), glm::dvec3(1), 0);  // beside them
}

TEST(Shadows, ABooleanCountsAsOneObject) {
    // Two overlapping transparent spheres, as one union and as two objects.
    const std::string spheres = "transparency 0.5 translate 0 0 2 sphere translate 0 0 1 sphere";
    const Scene joined = sceneOf("union " + spheres);
    const Scene apart = sceneOf(spheres);
    const SceneIntersector joinedBvh(joined), apartBvh(apart);
    expectNear(WhittedShader(joined, joinedBvh).lightThrough({0, 0, 0}, {0, 0, 10}),
               glm::dvec3(0.5), 0);
    expectNear(WhittedShader(apart, apartBvh).lightThrough({0, 0, 0}, {0, 0, 10}), glm::dvec3(0.25),
               0);
}

TEST(Shadows, ALightBehindTheSurfaceAddsNothing) {
    // Seen from above, the floor's light is below it: no diffuse, no specular.
    const Scene scene = sceneOf("light 0 0 -10 1 1 1 specular 1 1 1 plane");
    expectNear(seen(scene, {0, 0, 5}, {0, 0, 0}), glm::dvec3(0.01), 1e-15);
}

TEST(Shadows, FeelersLeaveFarFromTheOriginWithoutHittingTheirOwnSurface) {
    // A lit sphere far from the origin: every hit seen from the light's side
    // must be lit (a feeler that hit its own surface would shadow it).
    const Scene scene =
        sceneOf("light 100000 0 100010 1 1 1 translate 100000 0 0 scale 3 3 3 sphere");
    for (int i = 0; i < 20; ++i) {
        const double x = 100000 - 1.5 + 0.15 * i;
        const glm::dvec3 color = seen(scene, {x, 0.1 * i, 100}, {x, 0.1 * i, 0});
        EXPECT_GT(color.r, 0.1) << "ray " << i;
    }
}

// A convex shape can never be met again by a ray that leaves its surface
// outward: the reflected ray of every hit, started by offsetRayOrigin, must
// miss it, at any scale and distance from the origin (self-hits show as
// shadow acne and speckled mirrors). Rays come from random directions at
// randomly placed, rotated and stretched shapes.
TEST(SecondaryRays, NeverMeetTheirOwnConvexSurfaceAgain) {
    test::Random random(20261123);
    const char* shapes[] = {"sphere",     "cube",        "cylinder", "cone", "taperedCylinder 0.5",
                            "octahedron", "dodecahedron"};
    int tested = 0;
    for (const char* shape : shapes) {
        for (const double distance : {0.0, 1e2, 1e4}) {
            for (int placement = 0; placement < 8; ++placement) {
                const glm::dvec3 centre = distance * random.direction();
                const glm::dvec3 axis = random.direction();
                const double scale = std::exp(random.uniform(-3, 3));
                const Scene scene = sceneOf(
                    "translate " + std::to_string(centre.x) + " " + std::to_string(centre.y) + " " +
                    std::to_string(centre.z) + " rotate " + std::to_string(random.uniform(0, 360)) +
                    " " + std::to_string(axis.x) + " " + std::to_string(axis.y) + " " +
                    std::to_string(axis.z) + " scale " + std::to_string(scale) + " " +
                    std::to_string(scale * random.uniform(0.3, 3)) + " " + std::to_string(scale) +
                    " " + shape);
                const SceneIntersector intersector(scene);
                for (int i = 0; i < 50; ++i) {
                    const glm::dvec3 from = centre + 10 * scale * random.direction();
                    const glm::dvec3 to =
                        centre + scale * random.inBox(glm::dvec3(-0.5), glm::dvec3(0.5));
                    const Ray ray{from, glm::normalize(to - from)};
                    const std::optional<WorldHit> hit = intersector.closestHit(ray, 0.0);
                    if (!hit) continue;
                    const glm::dvec3 r = reflectDirection(ray.direction, hit->normal);
                    if (glm::dot(r, hit->geometricNormal) <= 0)
                        continue;  // grazing: r along the face
                    const Ray reflected{offsetRayOrigin(hit->point, hit->geometricNormal, r), r};
                    const std::optional<WorldHit> again = intersector.closestHit(reflected, 0.0);
                    EXPECT_FALSE(again)
                        << shape << " at distance " << distance << ": hit again at t " << again->t;
                    ++tested;
                }
            }
        }
    }
    EXPECT_GT(tested, 5000);
}

// ---- reflection --------------------------------------------------------------

TEST(Reflection, AMirrorFacingAColouredWallShowsThatColourTimesReflectivity) {
    // Mirror: the floor z = 0, black but for reflectivity 0.8. Wall: the
    // plane x = 3 (z = 0 turned to face -x), emissive only. The ray from
    // (-1, 0, 1) meets the mirror at the origin and goes on to (3, 0, 3).
    const Scene scene = sceneOf(
        "background 0 0 0 ambient 0 0 0 diffuse 0 0 0 reflectivity 0.8 plane\n"
        "reflectivity 0 emissive 0.2 0.6 0.4 translate 3 0 0 rotate 90 0 1 0 plane");
    expectNear(seen(scene, {-1, 0, 1}, {0, 0, 0}), 0.8 * glm::dvec3(0.2, 0.6, 0.4), 1e-15);
    // Away from the wall the mirror shows the background.
    expectNear(seen(scene, {1, 0, 1}, {0, 0, 0}), glm::dvec3(0), 0);
}

TEST(Reflection, OnlyAboveMinReflectivity) {
    const Scene scene = sceneOf(
        "minReflectivity 0.8 background 0 0 0 ambient 0 0 0 diffuse 0 0 0 reflectivity 0.8 plane\n"
        "reflectivity 0 emissive 0.2 0.6 0.4 translate 3 0 0 rotate 90 0 1 0 plane");
    expectNear(seen(scene, {-1, 0, 1}, {0, 0, 0}), glm::dvec3(0), 0);  // 0.8 is not > 0.8
}

// Two facing mirrors, z = 0 and z = 2, each emissive 1 and reflectivity
// 0.5: a ray bouncing straight between them collects 1 + 1/2 + 1/4 + ...,
// one term per hit. D bounces (hits at levels 0..D) give 2 - 2^-D exactly.
TEST(Reflection, FacingMirrorsStopAtMaxRecursionDepth) {
    for (int depth = 0; depth <= kMaxRecursionDepth; ++depth) {
        const Scene scene = sceneOf("maxRecursionDepth " + std::to_string(depth) +
                                    " minReflectivity 0.1 ambient 0 0 0 diffuse 0 0 0 "
                                    "emissive 1 1 1 reflectivity 0.5 plane translate 0 0 2 plane");
        EXPECT_EQ(seen(scene, {0, 0, 1}, {0, 0, 0}).g, 2 - std::ldexp(1.0, -depth))
            << "maxRecursionDepth " << depth;
    }
}

// ---- refraction ----------------------------------------------------------------

TEST(Refraction, SnellAndTotalInternalReflectionForOneSurface) {
    // 45 degrees onto z = 0 from above, into glass with c2/c1 = 0.6:
    // sin(theta2) = 0.6 sin(45 deg).
    const glm::dvec3 d = glm::normalize(glm::dvec3(1, 0, -1));
    const glm::dvec3 m(0, 0, 1);
    const double sin2 = 0.6 * std::sin(degrees(45));
    const std::optional<glm::dvec3> t = refractDirection(d, m, 0.6);
    ASSERT_TRUE(t);
    expectNear(*t, {sin2, 0, -std::sqrt(1 - sin2 * sin2)}, 1e-15);
    // Leaving glass for air (eta = 1 / 0.5 = 2): the critical angle is 30 degrees.
    const auto at = [&](double incidence) {
        return refractDirection({std::sin(degrees(incidence)), 0, -std::cos(degrees(incidence))}, m,
                                2.0);
    };
    EXPECT_TRUE(at(29.9));
    EXPECT_FALSE(at(30.1));
    EXPECT_FALSE(at(60));
    // Straight through, whatever eta.
    expectNear(*refractDirection({0, 0, -1}, m, 0.6), {0, 0, -1}, 0);
}

// Between equal speeds (eta = 1) a ray goes straight on, grazing or not:
// summed as 1 - eta^2 (1 - cos1^2), cos1^2 below the rounding of 1 was lost
// and a ray 1e-9 rad off a plane left along it (in float: below 2.4e-4).
TEST(Refraction, AGrazingRayBetweenEqualSpeedsGoesStraightOn) {
    const glm::dvec3 m(0, 0, 1);
    for (const double grazing : {1e-3, 1e-5, 1e-9}) {
        SCOPED_TRACE(grazing);
        const glm::dvec3 d(std::cos(grazing), 0, -std::sin(grazing));
        const std::optional<glm::dvec3> t = refractDirection(d, m, 1.0);
        ASSERT_TRUE(t);
        EXPECT_NEAR(t->z, d.z, 1e-6 * grazing);
        EXPECT_NEAR(t->x, d.x, 1e-15);
    }
}

TEST(Refraction, TheMediumStackRemembersFourLevels) {
    const Medium air;
    EXPECT_EQ(air.speed(), 1);
    const Medium water = air.entered(0.75);
    const Medium glass = water.entered(0.6);
    EXPECT_EQ(glass.speed(), 0.6);
    EXPECT_EQ(glass.left().speed(), 0.75);
    EXPECT_EQ(glass.left().left().speed(), 1);
    EXPECT_EQ(air.left().speed(), 1);  // leaving with nothing entered: still air
    const Medium deep = glass.entered(0.5).entered(0.4).entered(0.3);  // a fifth level
    EXPECT_EQ(deep.depth, 5);
    EXPECT_EQ(deep.speed(), 0.4);  // the fourth's speed is kept
    EXPECT_EQ(deep.left().speed(), 0.4);
    EXPECT_EQ(deep.left().left().speed(), 0.5);
}

// A glass slab z in [-0.5, 0.5] (a flat cube), c = 0.6, transparency 0.9,
// black and unlit. The ray from (-2, 0, 2) at 45 degrees enters at
// (-0.5, 0, 0.5) and bends to theta2 = asin(0.6 sin 45 deg); it leaves the
// bottom parallel to where it came from, shifted sideways by
// thickness sin(theta1 - theta2) / cos(theta2). A small emissive marker far
// down that line is seen (through two surfaces: 0.9^2); one on the
// unrefracted line is not.
TEST(Refraction, ThroughAGlassSlabTheRayLeavesParallelAndShifted) {
    const double theta1 = degrees(45), theta2 = std::asin(0.6 * std::sin(theta1));
    const double shift = std::sin(theta1 - theta2) / std::cos(theta2);
    EXPECT_NEAR(shift, 0.375812, 1e-6);  // by hand: sin(19.8959 deg) / cos(25.1041 deg)
    const glm::dvec3 entry(-0.5, 0, 0.5), d = glm::normalize(glm::dvec3(1, 0, -1));
    const glm::dvec3 exit = entry + glm::dvec3(std::tan(theta2), 0, -1);  // 1 deep
    // The exit point lies `shift` off the unrefracted line.
    const glm::dvec3 offLine = (exit - entry) - glm::dot(exit - entry, d) * d;
    EXPECT_NEAR(glm::length(offLine), shift, 1e-12);
    const auto slabWithMarkerAt = [](const glm::dvec3& marker) {
        return sceneOf(
            "background 0 0 0 minTransparency 0.1 ambient 0 0 0 diffuse 0 0 0 "
            "transparency 0.9 speedOfLight 0.6 push scale 10 10 0.5 cube pop "
            "defaultMaterials ambient 0 0 0 diffuse 0 0 0 emissive 1 1 1 translate " +
            std::to_string(marker.x) + " 0 " + std::to_string(marker.z) +
            " scale 0.05 0.05 0.05 sphere");
    };
    const glm::dvec3 onRefracted = exit + 50.0 * d;
    const glm::dvec3 onStraight = entry + (50.0 + glm::dot(exit - entry, d)) * d;
    expectNear(seen(slabWithMarkerAt(onRefracted), {-2, 0, 2}, entry), glm::dvec3(0.81), 1e-12);
    expectNear(seen(slabWithMarkerAt(onStraight), {-2, 0, 2}, entry), glm::dvec3(0), 0);
}

// A glass unit sphere with c = 0.5 and a ray parallel to its axis at height
// 0.5: theta1 = 30 degrees, sin(theta2) = 0.5 sin(theta1). Each surface turns
// the ray by theta1 - theta2 toward the axis; it leaves turned twice that,
// from the far end of a chord 2 cos(theta2) long.
TEST(Refraction, ThroughAGlassSphereMatchesSnellByHand) {
    const double theta1 = degrees(30), theta2 = std::asin(0.5 * std::sin(theta1));
    const double turn = theta1 - theta2;
    const glm::dvec3 entry(0.5, 0, std::sqrt(0.75));
    const glm::dvec3 inside(-std::sin(turn), 0, -std::cos(turn));
    const glm::dvec3 exit = entry + 2 * std::cos(theta2) * inside;
    EXPECT_NEAR(glm::length(exit), 1, 1e-12);  // the chord ends on the sphere
    const glm::dvec3 out(-std::sin(2 * turn), 0, -std::cos(2 * turn));
    // The CPU's own first step agrees with the angles.
    expectNear(*refractDirection({0, 0, -1}, entry, 0.5), inside, 1e-15);
    const auto sphereWithMarkerAt = [](const glm::dvec3& marker) {
        return sceneOf(
            "background 0 0 0 minTransparency 0.1 ambient 0 0 0 diffuse 0 0 0 "
            "transparency 0.9 speedOfLight 0.5 sphere "
            "defaultMaterials ambient 0 0 0 diffuse 0 0 0 emissive 1 1 1 translate " +
            std::to_string(marker.x) + " 0 " + std::to_string(marker.z) +
            " scale 0.02 0.02 0.02 sphere");
    };
    const glm::dvec3 from(0.5, 0, 5);
    expectNear(seen(sphereWithMarkerAt(exit + 20.0 * out), from, entry), glm::dvec3(0.81), 1e-12);
    // Had it gone straight on (or bent the other way), the marker is missed.
    expectNear(seen(sphereWithMarkerAt({0.5, 0, -20}), from, entry), glm::dvec3(0), 0);
}

// A right-angle prism: the cube [-1, 1]^3 cut by the half-space x + z <= 0
// (a plane turned 45 degrees about y), glass, transparency 0.9. A ray up
// through the bottom face (no bend) meets the hypotenuse at 45 degrees.
// c = 0.5: critical angle asin(0.5) = 30 < 45 degrees: totally reflected to
// -x, out through the face x = -1 (no bend), to a marker at (-10, 0, 0.5),
// through three surfaces (0.9^3). c = 0.9: critical angle 64 degrees: it
// leaves through the hypotenuse at asin(sin 45 deg / 0.9) from its normal.
std::string prism(double speedOfLight, const glm::dvec3& marker) {
    return "background 0 0 0 minTransparency 0.1 ambient 0 0 0 diffuse 0 0 0 transparency 0.9 "
           "speedOfLight " +
           std::to_string(speedOfLight) +
           " intersection cube push rotate 45 0 1 0 plane pop "
           "defaultMaterials ambient 0 0 0 diffuse 0 0 0 emissive 1 1 1 translate " +
           std::to_string(marker.x) + " 0 " + std::to_string(marker.z) +
           " scale 0.1 0.1 0.1 sphere";
}

TEST(Refraction, TotalInternalReflectionPastTheCriticalAngle) {
    const glm::dvec3 from(-0.5, 0, -5), to(-0.5, 0, 0);
    const glm::dvec3 reflectedMarker(-10, 0, 0.5);
    expectNear(seen(sceneOf(prism(0.5, reflectedMarker)), from, to), glm::dvec3(0.729), 1e-12);
    // Below the critical angle the light leaves instead: the marker is dark.
    expectNear(seen(sceneOf(prism(0.9, reflectedMarker)), from, to), glm::dvec3(0), 0);
    // ... and is found where Snell says, from (-0.5, 0, 0.5).
    const glm::dvec3 n = glm::normalize(glm::dvec3(1, 0, 1));
    const glm::dvec3 along = glm::normalize(glm::dvec3(-1, 0, 1));  // the face, toward +z
    const double theta2 = std::asin(std::sin(degrees(45)) / 0.9);
    const glm::dvec3 out = std::cos(theta2) * n + std::sin(theta2) * along;
    const glm::dvec3 refractedMarker = glm::dvec3(-0.5, 0, 0.5) + 20.0 * out;
    expectNear(seen(sceneOf(prism(0.9, refractedMarker)), from, to), glm::dvec3(0.81), 1e-12);
}

TEST(Refraction, OnlyAboveMinTransparency) {
    const glm::dvec3 from(-0.5, 0, -5), to(-0.5, 0, 0);
    std::string text = prism(0.5, {-10, 0, 0.5});
    text.replace(text.find("minTransparency 0.1"), 19, "minTransparency 0.9");
    expectNear(seen(sceneOf(text), from, to), glm::dvec3(0), 0);
}

}  // namespace
}  // namespace vkray::reference
