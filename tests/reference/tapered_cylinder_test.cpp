// Hill's generic tapered cylinder (axis z from 0 to 1, radius 1 at z = 0 and
// s at z = 1): hits worked out by hand on walls, caps, rims and the apex, the
// degenerate quadratics of docs/numerics-background.md, "Tapered cylinder",
// and a seeded property test
// that the spans are exactly where the ray is inside.
#include "reference/shapes.h"

#include "reference_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vkray::reference {
namespace {

using test::expectNear;
using test::expectSameDirection;

constexpr double kTol = 1e-12;

TEST(TaperedCylinder, CylinderWall) {
    // x^2 + y^2 = 1 at z = 0.5: the ray from x = 2 reaches x = 1 at t = 1.
    const auto hit = intersectTaperedCylinder({{2, 0, 0.5}, {-1, 0, 0}}, 1, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTol);
    expectSameDirection(hit->normal, {1, 0, 0}, kTol);
}

TEST(TaperedCylinder, ConeWallWithHalfTaper) {
    // s = 0.5: rho(z) = 1 - z/2 = 0.75 at z = 0.5, so x = 0.75, t = 1.25. The
    // normal (x, y, -k rho) = (0.75, 0, 0.375) is along (2, 0, 1).
    const auto hit = intersectTaperedCylinder({{2, 0, 0.5}, {-1, 0, 0}}, 0.5, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1.25, kTol);
    expectSameDirection(hit->normal, {2, 0, 1}, kTol);
}

TEST(TaperedCylinder, CapsFromAboveAndBelow) {
    auto hit = intersectTaperedCylinder({{0.2, 0.3, 5}, {0, 0, -1}}, 1, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4, kTol);
    expectSameDirection(hit->normal, {0, 0, 1}, kTol);

    hit = intersectTaperedCylinder({{0.2, 0.3, -5}, {0, 0, 1}}, 1, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5, kTol);
    expectSameDirection(hit->normal, {0, 0, -1}, kTol);

    // s = 0.5: the top disk has radius 0.5. r = 0.42 is on it...
    hit = intersectTaperedCylinder({{0.3, 0.3, 5}, {0, 0, -1}}, 0.5, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4, kTol);
    expectSameDirection(hit->normal, {0, 0, 1}, kTol);
    // ... r = 0.6 is not: the wall, where rho(z) = 1 - z/2 = 0.6, z = 0.8.
    hit = intersectTaperedCylinder({{0.6, 0, 5}, {0, 0, -1}}, 0.5, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4.2, kTol);
    expectSameDirection(hit->normal, {2, 0, 1}, kTol);
}

TEST(TaperedCylinder, RimBelongsToTheSolid) {
    // (2, 0, 2) - (1, 0, 1) t reaches the rim (1, 0, 1) at t = 1 and goes on
    // inside to the bottom disk at (0, 0, 0), t = 2. Wall and cap meet the
    // ray at the same t; the cap names the surface on a tie.
    const SpanPair spans = taperedCylinderSpans({{2, 0, 2}, {-1, 0, -1}}, 1);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 1, kTol);
    expectSameDirection(spans[0].enter.normal, {0, 0, 1}, kTol);
    EXPECT_NEAR(spans[0].exit.t, 2, kTol);
    expectSameDirection(spans[0].exit.normal, {0, 0, -1}, kTol);

    // Grazing the rim from outside, along a tangent of the top circle.
    const auto hit = intersectTaperedCylinder({{1, -3, 1}, {0, 1, 0}}, 1, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 3, kTol);
}

TEST(TaperedCylinder, AxisParallelRayMeetsOnlyTheCaps) {
    // NUMERICS stress case 13: A = B' = 0 (q = 0): no wall root at all.
    const SpanPair spans = taperedCylinderSpans({{0.5, 0, -1}, {0, 0, 1}}, 1);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_EQ(spans[0].enter.t, 1);
    expectSameDirection(spans[0].enter.normal, {0, 0, -1}, kTol);
    EXPECT_EQ(spans[0].exit.t, 2);
    expectSameDirection(spans[0].exit.normal, {0, 0, 1}, kTol);
    // Outside the wall, parallel to it: never inside.
    EXPECT_TRUE(taperedCylinderSpans({{1.5, 0, -1}, {0, 0, 1}}, 1).empty());
}

TEST(TaperedCylinder, RayParallelToAGenerator) {
    // NUMERICS stress case 12: s = 0, d = (1, 0, -1)/sqrt 2 is parallel to the
    // generator from the apex (0,0,1) to (1,0,0), so A = 0 and the quadratic
    // is linear. Entry at (-0.75, 0, 0.25), t = 1.75 sqrt 2; the normal there
    // (x, y, rho) = (-0.75, 0, 0.75); exit through the base at (-0.5, 0, 0).
    const double h = 1 / std::sqrt(2.0);
    const SpanPair spans = taperedCylinderSpans({{-2.5, 0, 2}, {h, 0, -h}}, 0);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 1.75 * std::sqrt(2.0), kTol);
    EXPECT_NEAR(spans[0].enter.t, 2.4748737, 1e-7);
    expectSameDirection(spans[0].enter.normal, {-1, 0, 1}, kTol);
    EXPECT_NEAR(spans[0].exit.t, 2 * std::sqrt(2.0), kTol);
    expectSameDirection(spans[0].exit.normal, {0, 0, -1}, kTol);
}

TEST(TaperedCylinder, ConeApexHasTheAxisAsNormal) {
    // NUMERICS stress case 11: down the axis onto the apex (0, 0, 1): a double
    // root at t = 2 where the gradient vanishes; the axis stands in.
    const SpanPair spans = taperedCylinderSpans({{0, 0, 3}, {0, 0, -1}}, 0);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 2, kTol);
    expectSameDirection(spans[0].enter.normal, {0, 0, 1}, kTol);
    EXPECT_NEAR(spans[0].exit.t, 3, kTol);
    expectSameDirection(spans[0].exit.normal, {0, 0, -1}, kTol);
    // A cone has no top disk: beside the apex, the wall.
    const auto hit = intersectTaperedCylinder({{0.5, 0, 3}, {0, 0, -1}}, 0, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2.5, kTol);  // rho(z) = 1 - z = 0.5 at z = 0.5
    expectSameDirection(hit->normal, {1, 0, 1}, kTol);
}

TEST(TaperedCylinder, FromInside) {
    auto hit = intersectTaperedCylinder({{0, 0, 0.5}, {1, 0, 0}}, 1, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTol);
    expectSameDirection(hit->normal, {1, 0, 0}, kTol);
    hit = intersectTaperedCylinder({{0, 0, 0.5}, {0, 0, 2}}, 1, 0);  // non-unit direction
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 0.25, kTol);
    expectSameDirection(hit->normal, {0, 0, 1}, kTol);
}

TEST(TaperedCylinder, Misses) {
    EXPECT_FALSE(intersectTaperedCylinder({{0, 0, 1.5}, {1, 0, 0}}, 1, 0));    // above z = 1
    EXPECT_FALSE(intersectTaperedCylinder({{-2, 0, -0.1}, {1, 0, 0}}, 1, 0));  // below z = 0
    EXPECT_FALSE(intersectTaperedCylinder({{2, 0, 0.5}, {0, 1, 0}}, 1, 0));    // beside
    EXPECT_FALSE(intersectTaperedCylinder({{2, 0, 0.5}, {1, 0, 0}}, 1, 0));    // behind
    EXPECT_FALSE(intersectTaperedCylinder({{0.9, 0, 0.5}, {0, 1, 0}}, 0, 0));  // beside a cone
    // The mirror nappe of a cone (z > 1) is not part of it.
    EXPECT_FALSE(intersectTaperedCylinder({{-5, 0, 1.5}, {1, 0, 0}}, 0, 0));
    EXPECT_FALSE(intersectTaperedCylinder({{0, 0, 5}, {0, 0, 0}}, 1, 0));  // no direction
}

TEST(TaperedCylinder, TMinIsOpen) {
    const Ray ray{{2, 0, 0.5}, {-1, 0, 0}};
    const auto exit = intersectTaperedCylinder(ray, 1, 1);
    ASSERT_TRUE(exit);
    EXPECT_NEAR(exit->t, 3, kTol);
    expectSameDirection(exit->normal, {-1, 0, 0}, kTol);
    EXPECT_FALSE(intersectTaperedCylinder(ray, 1, 3));
}

TEST(TaperedCylinder, NearTangentRay) {
    // NUMERICS stress case 14: the line y = y0, z = 0.5 cuts the circle
    // x^2 + y^2 = 1 at x = +-sqrt(1 - y0^2) = +-sqrt((1 - y0)(1 + y0)), both
    // factors exact. For y0 = 1 - 2^-23 (the float 0.99999988) that is
    // 2 -+ 4.8828e-4: NUMERICS's 1.99951172 and 2.00048828.
    for (const double y0 : {1 - std::ldexp(1.0, -23), 0.99999988}) {
        const double half = std::sqrt((1 - y0) * (1 + y0));
        const SpanPair spans = taperedCylinderSpans({{-2, y0, 0.5}, {1, 0, 0}}, 1);
        ASSERT_EQ(spans.size(), 1u) << y0;
        EXPECT_NEAR(spans[0].enter.t, 2 - half, kTol) << y0;
        EXPECT_NEAR(spans[0].exit.t, 2 + half, kTol) << y0;
    }
    const SpanPair spans =
        taperedCylinderSpans({{-2, 1 - std::ldexp(1.0, -23), 0.5}, {1, 0, 0}}, 1);
    EXPECT_NEAR(spans[0].enter.t, 1.99951172, 1e-8);
    EXPECT_NEAR(spans[0].exit.t, 2.00048828, 1e-8);
}

TEST(TaperedCylinder, FarGrazingRay) {
    // The same tangent line seen from 1e8 away: the shifted origin keeps C
    // and B'^2 - AC free of the distance.
    const double y0 = 0.96, half = std::sqrt((1 - y0) * (1 + y0));  // 0.28
    const SpanPair spans = taperedCylinderSpans({{-1e8, y0, 0.5}, {1, 0, 0}}, 1);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 1e8 - half, 1e-8);
    EXPECT_NEAR(spans[0].exit.t, 1e8 + half, 1e-8);
}

TEST(TaperedCylinder, NegativeTaperIsAnHourglass) {
    // s = -1: rho(z) = 1 - 2z, |rho| = 1 at both ends and 0 at z = 0.5. A
    // vertical line at x = 0.25 is inside while |1 - 2z| >= 0.25: z <= 0.375
    // and z >= 0.625.
    const SpanPair spans = taperedCylinderSpans({{0.25, 0, -1}, {0, 0, 1}}, -1);
    ASSERT_EQ(spans.size(), 2u);
    EXPECT_NEAR(spans[0].enter.t, 1, kTol);
    EXPECT_NEAR(spans[0].exit.t, 1.375, kTol);
    expectSameDirection(spans[0].exit.normal, {0.25, 0, 0.5}, kTol);  // (x, y, 2 rho)
    EXPECT_NEAR(spans[1].enter.t, 1.625, kTol);
    expectSameDirection(spans[1].enter.normal, {0.25, 0, -0.5}, kTol);
    EXPECT_NEAR(spans[1].exit.t, 2, kTol);
}

// Whether p is in the solid, straight from its definition.
bool insideTapered(const glm::dvec3& p, double s) {
    const double rho = 1 + (s - 1) * p.z;
    return p.z >= 0 && p.z <= 1 && p.x * p.x + p.y * p.y <= rho * rho;
}

TEST(TaperedCylinder, SpansAreWhereTheRayIsInside) {
    // Seeded random rays through the solid's neighbourhood, for cylinders,
    // cones and frusta: points sampled along the ray are inside exactly when
    // they lie in a span, except within 1e-9 of a span's end.
    test::Random random(14);
    for (const double s : {1.0, 0.0, 0.5, 2.0, -0.5}) {
        for (int i = 0; i < 2000; ++i) {
            const glm::dvec3 target = random.inBox({-1.2, -1.2, -0.2}, {1.2, 1.2, 1.2});
            const glm::dvec3 direction = random.direction();
            const Ray ray{target - 4.0 * direction, direction};
            const SpanPair spans = taperedCylinderSpans(ray, s);
            for (const GenericSpan& span : spans) {
                ASSERT_TRUE(std::isfinite(span.enter.t) && std::isfinite(span.exit.t));
                ASSERT_LE(span.enter.t, span.exit.t);
            }
            for (int k = 0; k <= 400; ++k) {
                const double t = 0.02 * k;
                bool inSpan = false, nearEnd = false;
                for (const GenericSpan& span : spans) {
                    inSpan = inSpan || (t >= span.enter.t && t <= span.exit.t);
                    nearEnd = nearEnd || std::abs(t - span.enter.t) < 1e-9 ||
                              std::abs(t - span.exit.t) < 1e-9;
                }
                if (nearEnd) continue;
                ASSERT_EQ(inSpan, insideTapered(ray.origin + t * ray.direction, s))
                    << "s " << s << " ray " << i << " t " << t;
            }
            // Entering, the outward normal faces against the ray; leaving, along it.
            for (const GenericSpan& span : spans) {
                if (span.exit.t - span.enter.t < 1e-6) continue;
                EXPECT_LE(glm::dot(span.enter.normal, direction), 1e-12) << s << " " << i;
                EXPECT_GE(glm::dot(span.exit.normal, direction), -1e-12) << s << " " << i;
            }
        }
    }
}

}  // namespace
}  // namespace vkray::reference
