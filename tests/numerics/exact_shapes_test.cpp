// The oracle's shapes on rays whose answers are known in closed form
// (docs/numerics-background.md, "Hand-worked rays"): each t within its
// certified bracket, the bracket far narrower than any renderer's error, and
// tangents and edges classified.
#include "numerics/exact_shapes.h"

#include <gtest/gtest.h>

namespace vkray::numerics {
namespace {

BVec v(const Quad& x, const Quad& y, const Quad& z) {
    return {Bounded(x), Bounded(y), Bounded(z)};
}

// t is within the crossing's certified bracket (give or take the rounding
// of the test's own closed form, a few float128 units), which is at most
// 1e-28 of it.
void expectCrossing(const ExactCrossing& c, const Quad& t,
                    CrossingKind kind = CrossingKind::Crossing) {
    EXPECT_LE(abs(c.t - t), c.tBound + 64 * kQuadUnit * abs(t))
        << double(c.t) << " against " << double(t);
    EXPECT_LE(double(c.tBound), 1e-28 * double(abs(t) + 1));
    EXPECT_EQ(c.kind, kind) << double(c.t);
}

const double R = 1, r = 0.25;

TEST(ExactShapes, FarSphereSilhouetteRay) {
    // Hand-worked ray 1: unit sphere at (0, 0, 1e4), the ray from the origin
    // through (0.9995, 0, 1e4), in generic space o = (0, 0, -1e4).
    const QVec d = normalize(QVec{Quad(0.9995), 0, Quad(1e4)});
    const ExactCrossings c = sphereCrossings(v(0, 0, -1e4), v(d.x, d.y, d.z));
    ASSERT_EQ(c.count, 2);
    // t = D cos - sqrt(1 - D^2 sin^2), D = 1e4, sin = 0.9995 / |(0.9995, 0, 1e4)|.
    const Quad D = 1e4, sine = d.x, cosine = d.z;
    expectCrossing(c.at[0], D * cosine - sqrt(1 - D * D * sine * sine));
    EXPECT_NEAR(double(c.at[0].t), 9999.968331, 1e-6);
}

TEST(ExactShapes, SphereAMillionAway) {
    // A unit sphere 1e6 away along x, the ray through (1e6, 0.6, 0): the line
    // has t = along -+ sqrt(1 - miss^2).
    const Quad y = Quad(0.6), L = sqrt(Quad(1e12) + y * y);
    const QVec d{Quad(1e6) / L, y / L, 0};
    const ExactCrossings c = sphereCrossings(v(-1e6, 0, 0), v(d.x, d.y, d.z));
    ASSERT_EQ(c.count, 2);
    // The line passes 1e6 y / L from the centre, which lies 1e12 / L along it.
    const Quad along = Quad(1e12) / L, miss2 = Quad(1e12) * y * y / (L * L);
    expectCrossing(c.at[0], along - sqrt(1 - miss2));
    expectCrossing(c.at[1], along + sqrt(1 - miss2));
    // The normal at the near hit is the point on the sphere.
    const QVec p = QVec{-1e6, 0, 0} + c.at[0].t * d;
    EXPECT_LT(double(length(valueOf(c.at[0].normal) - p)), 1e-25);
}

TEST(ExactShapes, FarPlaneAndAThinSlab) {
    // Hand-worked ray 5: the plane z = 0 seen from 2 above along
    // (0.1, 0.2, -1): t = 2 sqrt(1.05), the origin 1e5 away in x.
    const QVec w{Quad(0.1), Quad(0.2), -1};
    const QVec d = w / length(w);
    const ExactCrossings c = planeCrossings(v(1e5, -3e4, 2), v(d.x, d.y, d.z), false);
    ASSERT_EQ(c.count, 1);
    expectCrossing(c.at[0], 2 * length(w));  // t = 2 / |d_z|
    // Hand-worked ray 6: from a plane at 1e3 to one 1e-3 above it, at 30
    // degrees from the normal: t = 1e-3 / cos 30.
    const Quad cos30 = sqrt(Quad(3)) / 2;
    const ExactCrossings slab = planeCrossings(v(1e3, 0, -1e-3), v(Quad(0.5), 0, cos30), false);
    ASSERT_EQ(slab.count, 1);
    expectCrossing(slab.at[0], Quad(1e-3) / cos30);
}

TEST(ExactShapes, TorusFromAfarHasFourRoots) {
    // Hand-worked ray 7: o = (-1000, 0, 0), d = +x; roots 998.75, 999.25, 1000.75, 1001.25.
    const ExactCrossings c = torusCrossings(v(-1000, 0, 0), v(1, 0, 0), R, r);
    ASSERT_EQ(c.count, 4);
    const double expected[4] = {998.75, 999.25, 1000.75, 1001.25};
    for (int i = 0; i < 4; ++i) expectCrossing(c.at[size_t(i)], Quad(expected[i]));
}

TEST(ExactShapes, TorusHitAlongItsAxis) {
    // Parallel to the axis through the tube's centre circle: in at the top
    // (z = r) at t = 4.75, out at the bottom at 5.25, normals +-z.
    const ExactCrossings c = torusCrossings(v(1, 0, 5), v(0, 0, -1), R, r);
    ASSERT_EQ(c.count, 2);
    expectCrossing(c.at[0], Quad(4.75));
    expectCrossing(c.at[1], Quad(5.25));
    EXPECT_GT(double(c.at[0].normal.z.v), 0);
    EXPECT_LT(double(abs(c.at[0].normal.x.v) / abs(c.at[0].normal.z.v)), 1e-28);
    // Hand-worked ray 9: down the axis itself, through the hole: no crossing,
    // even for a tube almost filling the hole.
    EXPECT_EQ(torusCrossings(v(0, 0, 5), v(0, 0, -1), R, r).count, 0);
    EXPECT_EQ(torusCrossings(v(0, 0, 5), v(0, 0, -1), R, 0.999999).count, 0);
}

TEST(ExactShapes, TorusTangentRaysAreFoundAndClassified) {
    // Hand-worked ray 8: along the top of the tube, z = r: double roots at
    // t = 2 and 4, touching; at z = 0.2499, four crossings 1 +- sqrt(r^2 - z^2) from x = 0.
    ExactCrossings c = torusCrossings(v(-3, 0, 0.25), v(1, 0, 0), R, r);
    ASSERT_EQ(c.count, 2);
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(c.at[size_t(i)].kind, CrossingKind::Tangent);
        EXPECT_NEAR(double(c.at[size_t(i)].t), 2.0 + 2 * i, 1e-12);
    }
    const Quad z = Quad(0.2499), half = sqrt(Quad(0.0625) - z * z);
    c = torusCrossings(v(-3, 0, z), v(1, 0, 0), R, r);
    ASSERT_EQ(c.count, 4);
    expectCrossing(c.at[0], 3 - (1 + half));
    expectCrossing(c.at[1], 3 - (1 - half));
    // Hand-worked ray 10: x = 0.75 crosses at t = 2 and 4 and touches the
    // inner equator at t = 3.
    c = torusCrossings(v(0.75, -3, 0), v(0, 1, 0), R, r);
    ASSERT_EQ(c.count, 3);
    expectCrossing(c.at[0], 2);
    EXPECT_EQ(c.at[1].kind, CrossingKind::Tangent);
    EXPECT_NEAR(double(c.at[1].t), 3, 1e-12);
    expectCrossing(c.at[2], 4);
}

TEST(ExactShapes, ConeApexAndGeneratorParallelRay) {
    // Hand-worked ray 11: down the axis onto the apex at t = 2 (on the rim:
    // the oracle cannot tell wall from top there), out through the base at t = 3.
    ExactCrossings c = taperedCylinderCrossings(v(0, 0, 3), v(0, 0, -1), 0);
    ASSERT_EQ(c.count, 2);
    EXPECT_NEAR(double(c.at[0].t), 2, 1e-25);
    EXPECT_EQ(c.at[0].kind, CrossingKind::Edge);
    expectCrossing(c.at[1], 3);
    // Hand-worked ray 12: parallel to a generator, one wall root at
    // (-0.75, 0, 0.25): t = 1.75 sqrt 2.
    const Quad s2 = sqrt(Quad(2));
    c = taperedCylinderCrossings(v(-2.5, 0, 2), v(1 / s2, 0, -1 / s2), 0);
    ASSERT_GE(c.count, 1);
    expectCrossing(c.at[0], Quad(1.75) * s2);
}

TEST(ExactShapes, CylinderAxisParallelAndNearTangent) {
    // Hand-worked ray 13: parallel to the axis, in through the bottom cap at
    // t = 1, out of the top at t = 2.
    ExactCrossings c = taperedCylinderCrossings(v(0.5, 0, -1), v(0, 0, 1), 1);
    ASSERT_EQ(c.count, 2);
    expectCrossing(c.at[0], 1);
    expectCrossing(c.at[1], 2);
    // Hand-worked ray 14, y the float 1 - 2^-23: roots 2 -+ sqrt(1 - y^2).
    const Quad y = Quad(0.99999988f);
    c = taperedCylinderCrossings(v(-2, y, 0.5), v(1, 0, 0), 1);
    ASSERT_EQ(c.count, 2);
    expectCrossing(c.at[0], 2 - sqrt(1 - y * y));
    expectCrossing(c.at[1], 2 + sqrt(1 - y * y));
}

TEST(ExactShapes, HourglassHasBothNappes) {
    // s = -1: radius |1 - 2z|, the apex at z = 1/2. Across at z = 1/4 (lower
    // nappe) and z = 3/4 (upper), radius 1/2 both: in at t = 2.5, out at 3.5.
    for (double z : {0.25, 0.75}) {
        const ExactCrossings c = taperedCylinderCrossings(v(-3, 0, z), v(1, 0, 0), -1);
        ASSERT_EQ(c.count, 2) << z;
        expectCrossing(c.at[0], Quad(2.5));
        expectCrossing(c.at[1], Quad(3.5));
    }
    // Up at x = 3/4: in through the bottom cap (t = 1), out of the lower
    // nappe where |1 - 2z| = 3/4 (z = 1/8), in again through the upper one
    // (z = 7/8), out of the top cap (radius |s| = 1) at t = 2.
    const ExactCrossings c = taperedCylinderCrossings(v(0.75, 0, -1), v(0, 0, 1), -1);
    ASSERT_EQ(c.count, 4);
    expectCrossing(c.at[0], 1);
    expectCrossing(c.at[1], Quad(1.125));
    expectCrossing(c.at[2], Quad(1.875));
    expectCrossing(c.at[3], 2);
}

TEST(ExactShapes, CubeFacesAndTheirEdges) {
    // Through the middle of two faces: t = 4 and 6.
    ExactCrossings c = cubeCrossings(v(-5, 0.5, 0.25), v(1, 0, 0));
    ASSERT_EQ(c.count, 2);
    expectCrossing(c.at[0], 4);
    expectCrossing(c.at[1], 6);
    EXPECT_EQ(double(c.at[0].normal.x.v), -1);
    // Hand-worked ray 15: in a face's plane (y = 1) and along an edge: the
    // crossings are there, and the oracle says it cannot tell the side.
    for (double z : {0.0, 1.0}) {
        c = cubeCrossings(v(-5, 1, z), v(1, 0, 0));
        ASSERT_EQ(c.count, 2) << z;
        EXPECT_NEAR(double(c.at[0].t), 4, 1e-25);
        EXPECT_NEAR(double(c.at[1].t), 6, 1e-25);
        EXPECT_EQ(c.at[0].kind, CrossingKind::Edge);
    }
}

TEST(ExactShapes, SquareKeepsItsFace) {
    EXPECT_EQ(planeCrossings(v(0.5, 0.5, 1), v(0, 0, -1), true).count, 1);
    EXPECT_EQ(planeCrossings(v(1.5, 0.5, 1), v(0, 0, -1), true).count, 0);
    const ExactCrossings edge = planeCrossings(v(1, 0.5, 1), v(0, 0, -1), true);
    ASSERT_EQ(edge.count, 1);
    EXPECT_EQ(edge.at[0].kind, CrossingKind::Edge);
}

}  // namespace
}  // namespace vkray::numerics
