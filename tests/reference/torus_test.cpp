// The generic torus (axis z, R = 1, r = 0.25) and its quartic solver: roots
// on chosen rays worked out by hand (docs/numerics-background.md, hand-worked rays 7 to 10), and
// seeded random rays from afar whose roots are certified by a sign change of
// F evaluated in long double.
#include "reference/quartic.h"
#include "reference/shapes.h"

#include "reference_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace vkray::reference {
namespace {

using test::expectSameDirection;

constexpr double kTol = 1e-12;

// ---- polynomial roots --------------------------------------------------------

std::vector<double> roots(std::vector<double> coeffs, double lo, double hi) {
    std::vector<double> out(coeffs.size());
    out.resize(std::size_t(polynomialRoots(coeffs, lo, hi, out.data())));
    return out;
}

TEST(Quartic, FourSimpleRoots) {
    // (x-1)(x-2)(x-3)(x-4) = x^4 - 10x^3 + 35x^2 - 50x + 24
    const std::vector<double> r = roots({24, -50, 35, -10, 1}, -10, 10);
    ASSERT_EQ(r.size(), 4u);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(r[std::size_t(i)], i + 1, kTol);
    // Only those inside the interval, which is closed.
    EXPECT_EQ(roots({24, -50, 35, -10, 1}, 2, 3.5), (std::vector<double>{2, 3}));
}

TEST(Quartic, DoubleRootIsReportedOnce) {
    // (x-1)^2 (x+1)(x-3) = x^4 - 4x^3 + 2x^2 + 4x - 3
    const std::vector<double> r = roots({-3, 4, 2, -4, 1}, -5, 5);
    ASSERT_EQ(r.size(), 3u);
    EXPECT_NEAR(r[0], -1, kTol);
    EXPECT_NEAR(r[1], 1, 1e-7);  // a double root is only as good as sqrt(eps)
    EXPECT_NEAR(r[2], 3, kTol);
}

TEST(Quartic, NoRealRootsAndLowerDegrees) {
    EXPECT_TRUE(roots({1, 0, 0, 0, 1}, -10, 10).empty());                   // x^4 + 1
    EXPECT_EQ(roots({-2, 1, 0, 0, 0}, -10, 10), (std::vector<double>{2}));  // leading zeros
    const std::vector<double> r = roots({2, -3, 1}, -10, 10);               // (x-1)(x-2)
    ASSERT_EQ(r.size(), 2u);
    EXPECT_NEAR(r[0], 1, kTol);
    EXPECT_NEAR(r[1], 2, kTol);
    EXPECT_TRUE(roots({5}, -1, 1).empty());
}

TEST(Quartic, CloseRootsAreSeparated) {
    // (x-1)(x-1.000001)(x+2)(x-5): two roots 1e-6 apart.
    const double a = 1, b = 1.000001, c = -2, d = 5;
    const std::vector<double> coeffs = {
        a * b * c * d, -(a * b * c + a * b * d + a * c * d + b * c * d),
        a * b + a * c + a * d + b * c + b * d + c * d, -(a + b + c + d), 1};
    const std::vector<double> r = roots(coeffs, -10, 10);
    ASSERT_EQ(r.size(), 4u);
    EXPECT_NEAR(r[0], -2, 1e-12);
    EXPECT_NEAR(r[1], 1, 1e-9);
    EXPECT_NEAR(r[2], 1.000001, 1e-9);
    EXPECT_NEAR(r[3], 5, 1e-12);
}

// ---- the torus -----------------------------------------------------------------

TEST(Torus, RayAlongXThroughBothTubes) {
    // z = 0, y = 0: the tube's cross-sections are |x| in [0.75, 1.25], so from
    // x = -3 the roots are t = 3 -+ 1.25, 3 -+ 0.75.
    const Ray ray{{-3, 0, 0}, {1, 0, 0}};
    const TorusRoots r = torusRoots(ray);
    ASSERT_EQ(r.count, 4);
    const double expected[4] = {1.75, 2.25, 3.75, 4.25};
    // grad F = 4(|p|^2 + R^2 - r^2) p - 8 R^2 (x, y, 0) points out of the tube.
    const glm::dvec3 normals[4] = {{-1, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {1, 0, 0}};
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(r.hits[i].t, expected[i], kTol) << i;
        expectSameDirection(r.hits[i].normal, normals[i], kTol);
    }
    // At (-1.25, 0, 0): 4 * 2.5 * -1.25 + 8 * 1.25 = -2.5.
    EXPECT_NEAR(r.hits[0].normal.x, -2.5, kTol);

    const SpanPair spans = torusSpans(ray);
    ASSERT_EQ(spans.size(), 2u);
    EXPECT_NEAR(spans[0].enter.t, 1.75, kTol);
    EXPECT_NEAR(spans[0].exit.t, 2.25, kTol);
    EXPECT_NEAR(spans[1].enter.t, 3.75, kTol);
    EXPECT_NEAR(spans[1].exit.t, 4.25, kTol);

    for (const auto& [tMin, t] : {std::pair{0.0, 1.75}, {1.75, 2.25}, {3.0, 3.75}, {4.0, 4.25}}) {
        const auto hit = intersectTorus(ray, tMin);
        ASSERT_TRUE(hit) << tMin;
        EXPECT_NEAR(hit->t, t, kTol) << tMin;
    }
    EXPECT_FALSE(intersectTorus(ray, 4.25));
}

TEST(Torus, TopOfTheTube) {
    // Straight down onto (1, 0, 0.25): normal (0, 0, 2) there; out at z = -0.25.
    const auto hit = intersectTorus({{1, 0, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4.75, kTol);
    EXPECT_NEAR(hit->normal.x, 0, kTol);
    EXPECT_NEAR(hit->normal.z, 2, kTol);
    const SpanPair spans = torusSpans({{1, 0, 5}, {0, 0, -1}});
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].exit.t, 5.25, kTol);
}

TEST(Torus, DownTheAxisMissesThroughTheHole) {
    // NUMERICS stress case 9: min F along the axis is (R^2 - r^2)^2 > 0.
    EXPECT_EQ(torusRoots({{0, 0, 5}, {0, 0, -1}}).count, 0);
    EXPECT_FALSE(intersectTorus({{0, 0, 5}, {0, 0, -1}}, 0));
    EXPECT_TRUE(torusSpans({{0, 0, 5}, {0, 0, -1}}).empty());
    // Beside the torus, and with no direction.
    EXPECT_FALSE(intersectTorus({{0, 2, 5}, {0, 0, -1}}, 0));
    EXPECT_FALSE(intersectTorus({{-3, 0, 0}, {0, 0, 0}}, 0));
}

TEST(Torus, GrazingTheOuterEquator) {
    // y = R + r: F along the line is x^2 (x^2 + 1), a double root at x = 0:
    // one touching hit, normal +y, and no span (the ray never gets inside).
    const Ray ray{{-3, 1.25, 0}, {1, 0, 0}};
    const auto hit = intersectTorus(ray, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 3, 1e-7);
    expectSameDirection(hit->normal, {0, 1, 0}, 1e-7);
    EXPECT_TRUE(torusSpans(ray).empty());
    EXPECT_FALSE(intersectTorus({{-3, 1.2500001, 0}, {1, 0, 0}}, 0));
}

TEST(Torus, TangentToTheTopOfTheTube) {
    // NUMERICS stress case 8: z = r touches the tube's top circle at x = -+1,
    // double roots at t = 2 and 4.
    const auto hit = intersectTorus({{-3, 0, 0.25}, {1, 0, 0}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2, 1e-7);
    // Just below, the circle (rho - 1)^2 + z^2 = r^2 gives rho = 1 -+ w,
    // w = sqrt(r^2 - z^2), four simple roots 3 -+ (1 +- w).
    const double z = 0.2499, w = std::sqrt(0.0625 - z * z);
    const TorusRoots r = torusRoots({{-3, 0, z}, {1, 0, 0}});
    ASSERT_EQ(r.count, 4);
    EXPECT_NEAR(r.hits[0].t, 2 - w, kTol);
    EXPECT_NEAR(r.hits[1].t, 2 + w, kTol);
    EXPECT_NEAR(r.hits[2].t, 4 - w, kTol);
    EXPECT_NEAR(r.hits[3].t, 4 + w, kTol);
    EXPECT_NEAR(r.hits[0].t, 1.992930, 1e-6);
    EXPECT_NEAR(r.hits[1].t, 2.007070, 1e-6);
}

TEST(Torus, InternalTangencyKeepsOneSpan) {
    // NUMERICS stress case 10: x = R - r touches the inner equator from inside
    // the tube: roots 2, 3 (double), 4; inside all along [2, 4].
    const Ray ray{{0.75, -3, 0}, {0, 1, 0}};
    const auto hit = intersectTorus(ray, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2, kTol);
    const SpanPair spans = torusSpans(ray);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 2, kTol);
    EXPECT_NEAR(spans[0].exit.t, 4, kTol);
}

TEST(Torus, FromFarAway) {
    // NUMERICS stress case 7: D = 1000; the shift makes these exact.
    const TorusRoots r = torusRoots({{-1000, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(r.count, 4);
    const double expected[4] = {998.75, 999.25, 1000.75, 1001.25};
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(r.hits[i].t, expected[i], 1e-9 * expected[i]);
    // The same from D = 1e6, with a non-unit direction (t halves).
    const TorusRoots far = torusRoots({{-1e6, 0, 0}, {2, 0, 0}});
    ASSERT_EQ(far.count, 4);
    EXPECT_NEAR(far.hits[0].t, (1e6 - 1.25) / 2, 1e-9 * 5e5);
    EXPECT_NEAR(far.hits[3].t, (1e6 + 1.25) / 2, 1e-9 * 5e5);
}

TEST(Torus, FromInsideTheTube) {
    // At (1, 0, 0), the tube's centre, going +x: out at x = 1.25.
    const auto hit = intersectTorus({{1, 0, 0}, {1, 0, 0}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 0.25, kTol);
    expectSameDirection(hit->normal, {1, 0, 0}, kTol);
}

// F in long double, at o + t d with o and d taken as exact.
long double torusF(const Ray& ray, long double t) {
    const long double x = ray.origin.x + t * ray.direction.x;
    const long double y = ray.origin.y + t * ray.direction.y;
    const long double z = ray.origin.z + t * ray.direction.z;
    const long double k = x * x + y * y + z * z + (1.0L - 0.0625L);
    return k * k - 4.0L * (x * x + y * y);
}

TEST(Torus, RandomFarRaysHaveCertifiedRoots) {
    // Seeded rays from distance D aimed at points near the torus. Each simple
    // root (not within 1e-4 of another) must have F changing sign across
    // t (1 -+ 1e-10); the normal must be the tube's, (p - c) for c the
    // nearest point of the centre circle.
    test::Random random(7);
    int certified = 0;
    for (const double distance : {10.0, 1e3, 1e5}) {
        for (int i = 0; i < 2000; ++i) {
            const glm::dvec3 target = random.inBox({-1.3, -1.3, -0.3}, {1.3, 1.3, 0.3});
            const glm::dvec3 direction = random.direction();
            const Ray ray{target - distance * direction, direction};
            const TorusRoots r = torusRoots(ray);
            for (int k = 0; k < r.count; ++k) {
                const double t = r.hits[k].t;
                if (k > 0) {
                    ASSERT_LE(r.hits[k - 1].t, t);
                }
                const bool isolated = (k == 0 || t - r.hits[k - 1].t > 1e-4) &&
                                      (k + 1 == r.count || r.hits[k + 1].t - t > 1e-4);
                if (!isolated) continue;
                const long double delta = 1e-10L * t;
                EXPECT_LT(torusF(ray, t - delta) * torusF(ray, t + delta), 0)
                    << "D " << distance << " ray " << i << " root " << k << " t " << t;
                const glm::dvec3 p = ray.origin + t * ray.direction;
                const glm::dvec3 c = glm::normalize(glm::dvec3(p.x, p.y, 0));
                expectSameDirection(r.hits[k].normal, p - c, 1e-6);
                ++certified;
            }
        }
    }
    EXPECT_GT(certified, 4000);
}

}  // namespace
}  // namespace vkray::reference
