// The long-double oracle on rays whose answers are known in closed form
// (docs/numerics-background.md, hand-worked rays 1, 7 to 15 and 18), its silhouette
// band, the metrics computed against it, and the float replay's RTG6 offset.
#include "numerics/feelers.h"
#include "numerics/oracle.h"
#include "numerics/stress_suite.h"
#include "scene/error.h"
#include "scene/sdl_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vkray::numerics {
namespace {

RVec v(Real x, Real y, Real z) { return {x, y, z}; }

Scene sceneOf(const std::string& text) { return parseSdl(text, "test.sdl", {}); }

Crossings<Real> crossingsOf(const std::string& text, RVec o, RVec d) {
    const Scene scene = sceneOf(text);
    return objectCrossings(scene.objects.at(0), {o, d});
}

TEST(Oracle, FarSphereSilhouetteRay) {
    // Stress case 1: unit sphere at (0, 0, 1e4), the ray through (0.9995, 0, 1e4).
    const Crossings<Real> c =
        crossingsOf("push translate 0 0 1e4 sphere pop", v(0, 0, 0), normalize(v(0.9995L, 0, 1e4L)));
    ASSERT_EQ(c.count, 2);
    EXPECT_NEAR(double(c.at[0].t), 9999.968331, 1e-6);
}

TEST(Oracle, TorusFromAfarHasFourRoots) {
    // Stress case 7: o = (-1000, 0, 0), d = +x; roots 998.75, 999.25, 1000.75, 1001.25.
    const Crossings<Real> c = torusCrossings(v(-1000, 0, 0), v(1, 0, 0), Real(1), Real(0.25));
    ASSERT_EQ(c.count, 4);
    const double expected[4] = {998.75, 999.25, 1000.75, 1001.25};
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(double(c.at[size_t(i)].t), expected[i], 1e-12);
}

TEST(Oracle, TorusNearItsTopTangent) {
    // Stress case 8 at z = 0.2499: the tube's section there is 1 +- sqrt(0.0625 - 0.2499^2).
    const Crossings<Real> c = torusCrossings(v(-3, 0, 0.2499L), v(1, 0, 0), Real(1), Real(0.25));
    ASSERT_EQ(c.count, 4);
    const Real half = std::sqrt(Real(0.0625) - Real(0.2499L) * Real(0.2499L));
    EXPECT_NEAR(double(c.at[0].t), double(3 - (1 + half)), 1e-12);  // 1.99292964
    EXPECT_NEAR(double(c.at[1].t), double(3 - (1 - half)), 1e-12);  // 2.00707036
}

TEST(Oracle, TorusHoleAndInternalTangency) {
    // Stress case 9: straight down the hole misses, even for a fat tube.
    EXPECT_EQ(torusCrossings(v(0, 0, 5), v(0, 0, -1), Real(1), Real(0.25)).count, 0);
    EXPECT_EQ(torusCrossings(v(0, 0, 5), v(0, 0, -1), Real(1), Real(0.999999L)).count, 0);
    // Stress case 10: x = 0.75 touches the inner equator at t = 3 (a tangent, not a
    // crossing) and crosses at t = 2 and 4.
    const Crossings<Real> c = torusCrossings(v(0.75L, -3, 0), v(0, 1, 0), Real(1), Real(0.25));
    ASSERT_EQ(c.count, 2);
    EXPECT_NEAR(double(c.at[0].t), 2, 1e-12);
    EXPECT_NEAR(double(c.at[1].t), 4, 1e-12);
}

TEST(Oracle, ConeApexAndGeneratorParallelRay) {
    // Stress case 11: down the axis onto the apex at t = 2, normal the axis.
    Crossings<Real> c = taperedCylinderCrossings(v(0, 0, 3), v(0, 0, -1), Real(0));
    ASSERT_GE(c.count, 2);
    EXPECT_NEAR(double(c.at[0].t), 2, 1e-15);
    EXPECT_EQ(c.at[0].normal.z, 1);
    EXPECT_NEAR(double(c.at[c.count - 1].t), 3, 1e-15);  // the base
    // Stress case 12: along a generator's direction, one wall root.
    c = taperedCylinderCrossings(v(-2.5L, 0, 2), normalize(v(1, 0, -1)), Real(0));
    ASSERT_GE(c.count, 1);
    EXPECT_NEAR(double(c.at[0].t), 2.4748737, 1e-7);
    EXPECT_NEAR(double(-2.5L + c.at[0].t / std::sqrt(Real(2))), -0.75, 1e-12);
}

TEST(Oracle, CylinderAxisParallelAndNearTangent) {
    // Stress case 13: parallel to the axis, in through the bottom cap, out of the top.
    Crossings<Real> c = taperedCylinderCrossings(v(0.5L, 0, -1), v(0, 0, 1), Real(1));
    ASSERT_EQ(c.count, 2);
    EXPECT_NEAR(double(c.at[0].t), 1, 1e-15);
    EXPECT_NEAR(double(c.at[1].t), 2, 1e-15);
    // Stress case 14 with y = 0.99999988f: roots 2 -+ sqrt(1 - y^2).
    const Real y = Real(0.99999988f);
    c = taperedCylinderCrossings(v(-2, y, 0.5L), v(1, 0, 0), Real(1));
    ASSERT_EQ(c.count, 2);
    EXPECT_NEAR(double(c.at[0].t), 1.99951172, 1e-8);
    EXPECT_NEAR(double(c.at[1].t), 2.00048828, 1e-8);
}

TEST(Oracle, CubeFaceAndEdgeGraze) {
    // Stress case 15: along a face (y = 1) and along an edge (y = z = 1).
    for (Real z : {Real(0), Real(1)}) {
        const Crossings<Real> c = cubeCrossings(v(-5, 1, z), v(1, 0, 0));
        ASSERT_EQ(c.count, 2);
        EXPECT_EQ(c.at[0].t, 4);
        EXPECT_EQ(c.at[1].t, 6);
    }
}

TEST(Oracle, EllipsoidNormalUsesInverseTranspose) {
    // Stress case 18: scale (1e3, 1, 1e-3); generic (0, 1/sqrt 2, 1/sqrt 2) is the
    // world point (0, 0.7071, 7.071e-4), whose normal is (0, 0.0010000, 0.9999995).
    const Scene scene = sceneOf("scale 1e3 1 1e-3 sphere");
    const Real s = 1 / std::sqrt(Real(2));
    const OracleHit hit = closestHit(scene, {v(0, s, 1), v(0, 0, -1)});
    ASSERT_EQ(hit.id, 0);
    EXPECT_NEAR(double(hit.t), double(1 - s * Real(1e-3)), 1e-15);
    const glm::dvec3 expected = glm::normalize(glm::dvec3(0, 1e-3, 1));
    EXPECT_LT(angleBetween(toDvec3(hit.normal), expected), 1e-12);
    EXPECT_NEAR(double(hit.normal.y), 0.0010000, 1e-7);
}

TEST(Oracle, TiesGoToTheLowerIndexAndNormalsFaceTheRay) {
    const Scene scene = sceneOf("plane push rotate 37 0 0 1 plane pop push translate 0 0 -1 sphere pop");
    const OracleHit hit = closestHit(scene, {v(0.2L, 0.1L, 3), v(0, 0, -1)});
    EXPECT_EQ(hit.id, 0);
    EXPECT_EQ(double(hit.t), 3);
    const OracleHit below = closestHit(scene, {v(0.2L, 0.1L, -3), v(0, 0, 1)});
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

TEST(Oracle, SilhouetteBandAndSpread) {
    // A unit sphere filling part of a small image: pixels near the rim are in
    // the float band, those well inside are not, and t moves little there.
    const Scene scene = sceneOf("camera eye 0 0 5 look 0 0 0 fov 30\nsphere\n");
    const RenderSettings settings{40, 30, 1};
    const CameraBasis camera = makeCameraBasis(*scene.camera, 40, 30);
    const std::vector<OraclePixel> pixels = renderOracle(scene, camera, settings, 2);
    const OraclePixel& centre = pixels[15 * 40 + 20];
    EXPECT_EQ(centre.hit.id, 0);
    EXPECT_FALSE(centre.silhouette[0]);
    EXPECT_LT(centre.tSpread[0], 1e-6);
    EXPECT_LT(centre.tSpread[1], 1e-14);
    EXPECT_EQ(pixels[0].hit.id, -1);
    // Near-tangent rays: a ray 1e-7 rad inside the rim is in the float band.
    const Real rim = std::asin(Real(0.2));  // angular radius from 5
    const RVec inside{std::sin(rim - Real(1e-7)), 0, -std::cos(rim - Real(1e-7))};
    EXPECT_EQ(closestHit(scene, {v(0, 0, 5), inside}).id, 0);
    EXPECT_EQ(closestHit(scene, {v(0, 0, 5), normalize(inside + Real(kBandAngle[0]) * v(1, 0, 0))}).id, -1);
}

TEST(Metrics, FlipsSilhouetteAndErrorBeyondTheBand) {
    std::vector<OraclePixel> oracle(4);
    for (OraclePixel& p : oracle) {
        p.hit.id = 0;
        p.hit.t = 10;
        p.hit.normal = v(0, 0, 1);
        p.tSpread[0] = 1e-6;
    }
    oracle[3].silhouette[0] = true;
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<ModeSample> samples{
        {10 + 1e-6 + 1e-5, {0, 0, 1}, 0},  // t error 1e-5 beyond the spread: 1e-6 relative
        {inf, {0, 0, 0}, -1},              // a flip
        {10, {0, 1e-3, 1}, 1},             // another object
        {inf, {0, 0, 0}, -1},              // a flip in the band: not counted
    };
    const ModeMetrics m = compareWithOracle(oracle, samples, 0);
    EXPECT_EQ(m.pixels, 4u);
    EXPECT_EQ(m.silhouette, 1u);
    EXPECT_EQ(m.flips, 1u);
    EXPECT_EQ(m.wrongId, 1u);
    EXPECT_EQ(m.compared, 1u);
    EXPECT_NEAR(m.tErrMax, 1e-6, 1e-12);
    EXPECT_NEAR(m.tErrRms, 1e-6, 1e-12);
    EXPECT_EQ(m.normalErrMax, 0);
    EXPECT_FALSE(withinBounds(m));  // the flip and the wrong id fail it
}

TEST(Feelers, RobustOffsetScalesWithTheLargestCoordinate) {
    // 2^-18 of the largest coordinate (32 to 64 of its float spacings) along
    // the normal, whichever coordinate that moves: at 1e5, 0.38 along y.
    // (Rays along the normal here: the step is all along it.)
    Vec3<float> p = offsetRayOriginRobust({1e5f, 1e-3f, -1e5f}, {0, 1, 0}, {0, 1, 0});
    EXPECT_EQ(p.x, 1e5f);
    EXPECT_EQ(p.y, 1e-3f + 1e5f / 262144.0f);
    EXPECT_EQ(p.z, -1e5f);
    // Near the origin (every coordinate within 1/32), a fixed 1/65536.
    EXPECT_EQ(offsetRayOriginRobust({1e-3f, 0, 0}, {-1, 0, 0}, {-1, 0, 0}).x, 1e-3f - 1.0f / 65536.0f);
    // A zero normal component leaves its coordinate alone.
    EXPECT_EQ(offsetRayOriginRobust({3.0f, 5.0f, 7.0f}, {0, 0, -1}, {0, 0, -1}).x, 3.0f);
}

TEST(Feelers, RobustOffsetStepsAlongTheRayItself) {
    // The step off the surface is taken along the new ray, so that it stays on
    // the exact ray's line: leaving the plane y = 0 at 60 degrees from its
    // normal (n . a = 1/2), the origin moves 2 steps along the ray, 1 step up.
    const float step = 4.0f / 262144.0f;  // 2^-18 of the largest coordinate, 4
    const float s = std::sqrt(3.0f) / 2;
    Vec3<float> p = offsetRayOriginRobust({4, 0, 1}, {0, 1, 0}, {2 * s, 1, 0});
    EXPECT_FLOAT_EQ(p.x, 4 + 2 * step * s);
    EXPECT_FLOAT_EQ(p.y, step);
    EXPECT_EQ(p.z, 1.0f);
    // A grazing ray (n . a = 0.01) goes at most OFFSET_MAX_FORWARD = 8 steps
    // along itself (0.08 steps up); the rest of the step is along the normal.
    const float c = 0.01f, sc = std::sqrt(1 - c * c);
    p = offsetRayOriginRobust({4, 0, 1}, {0, 1, 0}, {sc, c, 0});
    EXPECT_FLOAT_EQ(p.x, 4 + 8 * step * sc);
    EXPECT_FLOAT_EQ(p.y, step);
    // A ray on the other side of n than the normal (a mesh's interpolated
    // normal may send one there) moves along n alone, as before.
    p = offsetRayOriginRobust({4, 0, 1}, {0, 1, 0}, {1, -0.5f, 0});
    EXPECT_EQ(p.x, 4.0f);
    EXPECT_EQ(p.y, step);
}

}  // namespace
}  // namespace vkray::numerics
