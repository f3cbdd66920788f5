// The float128 oracle on scenes whose answers are known in closed form (its
// shapes alone: exact_shapes_test.cpp), its set-aside and conditioning, and
// the metrics computed against it.
#include "numerics/oracle.h"
#include "numerics/stress_suite.h"
#include "scene/sdl_reader.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vkray::numerics {
namespace {

OracleRay ray(const glm::dvec3& origin, const glm::dvec3& direction) {
    return exactRay(origin, glm::normalize(direction));
}

Scene sceneOf(const std::string& text) {
    return parseSdl(text, "test.sdl", {});
}

TEST(Oracle, SphereAMillionAwayInTheWorld) {
    // A unit sphere at (1e6, 0, 0) seen from the origin straight on: t = 1e6 - 1,
    // certified to 1e-28 of it, normal -x.
    const Scene scene = sceneOf("push translate 1e6 0 0 sphere pop");
    const OracleHit hit = closestHit(scene, ray({0, 0, 0}, {1, 0, 0}));
    ASSERT_EQ(hit.id, 0);
    EXPECT_LE(abs(hit.t - Quad(999999)), hit.tBound);
    EXPECT_LT(double(hit.tBound / hit.t), 1e-28);
    EXPECT_FALSE(hit.uncertain);
    EXPECT_TRUE(hit.entering);
    EXPECT_LT(angleBetween(toDvec3(hit.normal), {-1, 0, 0}), 1e-25);
}

TEST(Oracle, EllipsoidNormalUsesInverseTranspose) {
    // Stress case 18: scale (1e3, 1, 1e-3); generic (0, 1/sqrt 2, 1/sqrt 2) is the
    // world point (0, 0.7071, 7.071e-4), whose normal is (0, 0.0010000, 0.9999995).
    const Scene scene = sceneOf("scale 1e3 1 1e-3 sphere");
    const double s = 1 / std::sqrt(2.0);
    const OracleHit hit = closestHit(scene, ray({0, s, 1}, {0, 0, -1}));
    ASSERT_EQ(hit.id, 0);
    EXPECT_NEAR(double(hit.t), 1 - s * 1e-3, 1e-15);
    const glm::dvec3 expected = glm::normalize(glm::dvec3(0, 1e-3, 1));
    EXPECT_LT(angleBetween(toDvec3(hit.normal), expected), 1e-12);
    EXPECT_NEAR(double(hit.normal.y), 0.0010000, 1e-7);
}

TEST(Oracle, TiesGoToTheLowerIndexAndNormalsFaceTheRay) {
    const Scene scene =
        sceneOf("plane push rotate 37 0 0 1 plane pop push translate 0 0 -1 sphere pop");
    const OracleHit hit = closestHit(scene, ray({0.2, 0.1, 3}, {0, 0, -1}));
    EXPECT_EQ(hit.id, 0);
    EXPECT_EQ(double(hit.t), 3);
    const OracleHit below = closestHit(scene, ray({0.2, 0.1, -3}, {0, 0, 1}));
    EXPECT_EQ(below.id, 2);  // the sphere (centre z = -1) comes before the planes
    EXPECT_LT(double(below.normal.z), 0);
}

TEST(Oracle, RefusesMeshesAndBooleans) {
    const Scene scene = sceneOf("sphere\nunion sphere cube\n");
    try {
        requireOracleScene(scene);
        FAIL() << "a boolean was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("test.sdl:2:1"), std::string::npos) << e.what();
    }
}

TEST(Oracle, SetAsideOnlyWhereTheFootprintStraddlesAnEdge) {
    // A unit sphere filling part of a small image: pixels well inside or
    // outside are never set aside; a pixel is set aside only beside an id
    // change, and only where its footprint (a few float roundings of its
    // ray) meets the rim.
    const Scene scene = sceneOf("camera eye 0 0 5 look 0 0 0 fov 30\nsphere\n");
    const RenderSettings settings{40, 30, 1};
    const CameraBasis camera = makeCameraBasis(*scene.camera, 40, 30);
    const std::vector<OraclePixel> pixels = renderOracle(scene, camera, settings, 2);
    const OraclePixel& centre = pixels[15 * 40 + 20];
    EXPECT_EQ(centre.hit.id, 0);
    EXPECT_FALSE(centre.setAside[0] || centre.besideEdge);
    EXPECT_EQ(pixels[0].hit.id, -1);
    size_t beside = 0, setAside = 0;
    for (const OraclePixel& p : pixels) {
        beside += p.besideEdge;
        setAside += p.setAside[0];
        EXPECT_TRUE(!p.setAside[0] || p.besideEdge);
    }
    EXPECT_GT(beside, 40u);
    EXPECT_LT(setAside, beside / 10);  // 32 u of a pixel 1.3e-2 rad wide: rare
    // A ray 1e-7 rad inside the rim hits; turned by the float footprint
    // (8 u (2 + e / |o| + alphaD / |d|) = 8 u (2 + 1/5 + 1) = 1.5e-6 rad), it misses.
    const double rim = std::asin(0.2);  // angular radius from 5
    const glm::dvec3 inside{std::sin(rim - 1e-7), 0, -std::cos(rim - 1e-7)};
    EXPECT_EQ(closestHit(scene, ray({0, 0, 5}, inside)).id, 0);
    EXPECT_EQ(closestHit(scene, ray({0, 0, 5}, inside + 1.5e-6 * glm::dvec3(1, 0, 0))).id, -1);
}

TEST(Oracle, ConditionOfAHeadOnSphere) {
    // A unit sphere straight ahead at distance 5 (t = 4): |o| = 5, |d| = 1,
    // alphaD = 1, n.d = 1, e = 1, alphaO = 5: t = (5 + 4 (1 + 1) + 1) / 4 = 3.5,
    // tWorld = 5 / 4; normal = J (1 + k t |d| (1 + cos) t) with J = sqrt 3,
    // k = 1: sqrt 3 (1 + 8 t); normalWorld = sqrt 3 8 tWorld.
    const Scene scene = sceneOf("camera eye 0 0 5 look 0 0 0 fov 30\nsphere\n");
    const RenderSettings settings{1, 1, 1};
    const CameraBasis camera = makeCameraBasis(*scene.camera, 1, 1);
    const OraclePixel p = renderOracle(scene, camera, settings, 1).at(0);
    ASSERT_EQ(p.hit.id, 0);
    EXPECT_NEAR(double(p.hit.t), 4, 1e-25);
    EXPECT_NEAR(p.conditioning.t, 3.5, 1e-12);
    EXPECT_NEAR(p.conditioning.tWorld, 1.25, 1e-12);
    EXPECT_NEAR(p.conditioning.normal, std::sqrt(3.0) * (1 + 8 * 3.5), 1e-9);
    EXPECT_NEAR(p.conditioning.normalWorld, std::sqrt(3.0) * 8 * 1.25, 1e-9);
}

TEST(Metrics, FlipsSetAsideAndErrorsAgainstTheAllowance) {
    std::vector<OraclePixel> oracle(5);
    for (OraclePixel& p : oracle) {
        p.hit.id = 0;
        p.hit.t = 10;
        p.hit.normal = {0, 0, 1};
        p.conditioning.t = 2;
        p.conditioning.normal = 4;
        p.conditioning.tWorld = 1e14;  // forgiven only as written
    }
    oracle[3].setAside[0] = true;
    const double inf = std::numeric_limits<double>::infinity(), u = 0x1p-24;
    const auto sample = [](double t, glm::dvec3 n, int object) {
        StressSample s;
        s.t = t;
        s.normal = n;
        s.object = object;
        return s;
    };
    std::vector<StressSample> samples{
        sample(10 * (1 + 6 * u), {0, 0, 1}, 0),  // 6 u: 3 u times its condition 2
        sample(inf, {0, 0, 0}, -1),              // a flip
        sample(10, {0, 1e-3, 1}, 1),             // another object
        sample(inf, {0, 0, 0}, -1),              // a flip set aside: not counted
        sample(10, {0, 8 * u, 1}, 0),            // a normal 8 u off: twice its condition 4
    };
    const ModeMetrics m = compareWithOracle(oracle, samples, kFloat);
    EXPECT_EQ(m.pixels, 5u);
    EXPECT_EQ(m.setAside, 1u);
    EXPECT_EQ(m.flips, 1u);
    EXPECT_EQ(m.wrongId, 1u);
    EXPECT_EQ(m.compared, 2u);
    EXPECT_NEAR(m.tErrMax, 6 * u, 1e-12);
    EXPECT_NEAR(m.tRatioMax, 3, 1e-6);
    EXPECT_NEAR(m.normalErrMax, 8 * u, 1e-12);
    EXPECT_NEAR(m.normalRatioMax, 2, 1e-6);
    EXPECT_EQ(m.tConditionMax, 2);
    EXPECT_FALSE(withinBounds(m));  // the flip and the wrong id fail it
    // In double as written the world term joins the allowance.
    EXPECT_LT(compareWithOracle(oracle, samples, kDoubleAsWritten).tRatioMax, 1e-3);
}

}  // namespace
}  // namespace vkray::numerics
