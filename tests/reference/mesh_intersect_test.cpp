// Watertight triangles and meshes: hand-worked hits and barycentrics, the
// shared-edge and needle cases of docs/numerics-background.md (hand-worked rays 16 and 17), rays
// exactly through edges and vertices, interpolated normals, and the mesh BVH
// against brute force on a closed sphere of 11 880 triangles.
#include "reference/mesh_intersect.h"

#include "reference_test_util.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <cmath>
#include <limits>

namespace vkray::reference {
namespace {

using test::expectNear;
using test::expectSameDirection;

constexpr double kTol = 1e-12;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::optional<TriangleHit> hitTriangle(const Ray& ray, const glm::dvec3& p0, const glm::dvec3& p1,
                                       const glm::dvec3& p2) {
    return intersectTriangle(WatertightRay(ray), p0, p1, p2, 0, kInf);
}

TEST(MeshTriangle, HitWithBarycentrics) {
    // (0.2, 0.3) in the triangle (0,0,0), (1,0,0), (0,1,0) has weights 0.5, 0.2, 0.3.
    const glm::dvec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
    auto hit = hitTriangle({{0.2, 0.3, 1}, {0, 0, -1}}, p0, p1, p2);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTol);
    EXPECT_NEAR(hit->b0, 0.5, kTol);
    EXPECT_NEAR(hit->b1, 0.2, kTol);
    EXPECT_NEAR(hit->b2, 0.3, kTol);
    EXPECT_TRUE(hit->entering);  // against the normal (0, 0, 1)

    hit = hitTriangle({{0.2, 0.3, -2}, {0, 0, 4}}, p0, p1, p2);  // from below, non-unit
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 0.5, kTol);
    EXPECT_FALSE(hit->entering);

    EXPECT_FALSE(hitTriangle({{0.8, 0.8, 1}, {0, 0, -1}}, p0, p1, p2));  // beside it
    EXPECT_FALSE(hitTriangle({{0.2, 0.3, 1}, {0, 0, 1}}, p0, p1, p2));   // behind
    EXPECT_FALSE(hitTriangle({{-1, 0.2, 0}, {1, 0, 0}}, p0, p1, p2));    // in its plane
    EXPECT_FALSE(hitTriangle({{0.2, 0.3, 1}, {0, 0, 0}}, p0, p1, p2));   // no direction
    // tMin and tMax are open.
    EXPECT_FALSE(intersectTriangle(WatertightRay({{0.2, 0.3, 1}, {0, 0, -1}}), p0, p1, p2, 1, 2));
    EXPECT_FALSE(intersectTriangle(WatertightRay({{0.2, 0.3, 1}, {0, 0, -1}}), p0, p1, p2, 0, 1));
}

TEST(MeshTriangle, EnteringMeansAgainstTheRightHandedNormal) {
    test::Random random(3);
    int checked = 0;
    for (int i = 0; i < 5000; ++i) {
        const glm::dvec3 p0 = random.inBox(glm::dvec3(-1), glm::dvec3(1));
        const glm::dvec3 p1 = random.inBox(glm::dvec3(-1), glm::dvec3(1));
        const glm::dvec3 p2 = random.inBox(glm::dvec3(-1), glm::dvec3(1));
        const glm::dvec3 target = (p0 + p1 + p2) / 3.0;
        const glm::dvec3 d = random.direction();
        const glm::dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
        if (std::abs(glm::dot(n, d)) < 1e-6) continue;
        const auto hit = hitTriangle({target - 3.0 * d, d}, p0, p1, p2);
        ASSERT_TRUE(hit) << i;
        EXPECT_NEAR(hit->t, 3, 1e-9) << i;
        EXPECT_EQ(hit->entering, glm::dot(n, d) < 0) << i;
        ++checked;
    }
    EXPECT_GT(checked, 4900);
}

// A rotation from three random angles (the columns are orthonormal).
glm::dmat3 randomRotation(test::Random& random) {
    const glm::dvec3 a = random.direction();
    glm::dvec3 b = glm::normalize(glm::cross(a, random.direction()));
    return glm::dmat3(a, b, glm::cross(a, b));
}

TEST(MeshTriangle, SharedEdgeIsHitExactlyOnce) {
    // NUMERICS stress case 16: two triangles folded along a shared edge, in a
    // random position, and rays aimed at points of that edge from within 30
    // degrees of the fold's mean normal, which sees the two on either side of
    // the edge: every ray must hit exactly one of them.
    test::Random random(16);
    for (int pair = 0; pair < 200; ++pair) {
        const glm::dmat3 rotation = randomRotation(random);
        const glm::dvec3 shift = random.inBox(glm::dvec3(-10), glm::dvec3(10));
        const auto place = [&](const glm::dvec3& p) { return rotation * p + shift; };
        const glm::dvec3 a = place({0, random.uniform(-0.2, 0.2), 0});
        const glm::dvec3 b = place({0, 1 + random.uniform(-0.2, 0.2), random.uniform(-0.1, 0.1)});
        const glm::dvec3 left = place({-1, random.uniform(0, 1), random.uniform(-0.3, 0.3)});
        const glm::dvec3 right = place({1, random.uniform(0, 1), random.uniform(-0.3, 0.3)});
        // (left, a, b) and (b, a, right): the edge a-b walked both ways.
        for (int i = 0; i < 100; ++i) {
            const double s = random.uniform(0, 1);
            const glm::dvec3 target = a + s * (b - a);
            glm::dvec3 tilt(random.uniform(-0.5, 0.5), random.uniform(-0.5, 0.5), -1);
            const glm::dvec3 d = rotation * glm::normalize(tilt);
            const WatertightRay ray({target - random.uniform(0.5, 100) * d, d});
            const int hits = int(bool(intersectTriangle(ray, left, a, b, 0, kInf))) +
                             int(bool(intersectTriangle(ray, b, a, right, 0, kInf)));
            ASSERT_EQ(hits, 1) << "pair " << pair << " ray " << i;
        }
    }
}

TEST(MeshTriangle, RayExactlyThroughAnEdgeOrAVertex) {
    // Coordinates where the edge functions are exactly 0: the tie is broken
    // the same way for both triangles, so exactly one takes the ray. The
    // square [0, 1]^2 split along its diagonal, and a fan of four around the
    // origin.
    const glm::dvec3 o(0, 0, 0), x(1, 0, 0), xy(1, 1, 0), y(0, 1, 0);
    for (const glm::dvec3& p : {glm::dvec3(0.5, 0.5, 0), glm::dvec3(0.25, 0.25, 0)}) {
        for (const glm::dvec3& d :
             {glm::dvec3(0, 0, -1), glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(1, 2, -3))}) {
            const WatertightRay ray({p - 2.0 * d, d});
            const int hits = int(bool(intersectTriangle(ray, o, x, xy, 0, kInf))) +
                             int(bool(intersectTriangle(ray, o, xy, y, 0, kInf)));
            EXPECT_EQ(hits, 1) << p.x << " " << d.z;
        }
    }
    const glm::dvec3 fan[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    for (const glm::dvec3& d :
         {glm::dvec3(0, 0, -1), glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(0, 1, -1))}) {
        const WatertightRay ray({-2.0 * d, d});
        int hits = 0;
        for (int k = 0; k < 4; ++k)
            hits += int(bool(intersectTriangle(ray, o, fan[k], fan[(k + 1) % 4], 0, kInf)));
        EXPECT_EQ(hits, 1) << d.y << " " << d.z;
    }
}

TEST(MeshTriangle, NeedleTriangleIsHit) {
    // NUMERICS stress case 17: an area of 5e-8; an epsilon on det would reject it.
    const auto hit =
        hitTriangle({{0.5, 0.5e-7, 1}, {0, 0, -1}}, {0, 0, 0}, {1, 0, 0}, {0.5, 1e-7, 0});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTol);
    EXPECT_NEAR(hit->b2, 0.5, 1e-9);
    EXPECT_FALSE(hitTriangle({{0.5, 1.5e-7, 1}, {0, 0, -1}}, {0, 0, 0}, {1, 0, 0}, {0.5, 1e-7, 0}));
}

TriangleMesh oneTriangle() {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.normals = {
        {0, 0, 1}, glm::normalize(glm::dvec3(1, 0, 1)), glm::normalize(glm::dvec3(0, 1, 1))};
    mesh.triangles = {{{0, 1, 2}, {0, 1, 2}}};
    finishMesh(mesh);
    return mesh;
}

TEST(Mesh, InterpolatedNormalAndGeometricNormal) {
    const TriangleMesh mesh = oneTriangle();
    const auto hit = intersectMesh(mesh, {{0.2, 0.3, 1}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->triangle, 0u);
    const GenericHit surface = meshSurface(mesh, *hit);
    EXPECT_NEAR(surface.t, 1, kTol);
    expectNear(surface.normal,
               0.5 * mesh.normals[0] + 0.2 * mesh.normals[1] + 0.3 * mesh.normals[2], kTol);
    expectSameDirection(surface.geometricNormal, {0, 0, 1}, kTol);
}

TEST(Mesh, BvhMatchesBruteForce) {
    // 10 000 seeded rays at a closed sphere of 11 880 triangles, from outside
    // and inside, some missing: the same triangle and bit-identical t.
    const TriangleMesh mesh = test::tessellatedSphere(100, 60);
    ASSERT_EQ(mesh.triangles.size(), 11880u);
    ASSERT_GT(mesh.bvh.nodes.size(), 1u);
    test::Random random(10000);
    int hits = 0;
    for (int i = 0; i < 10000; ++i) {
        const bool inside = i % 4 == 0;
        const glm::dvec3 origin =
            inside ? random.inBox(glm::dvec3(-0.5), glm::dvec3(0.5)) : 3.0 * random.direction();
        const glm::dvec3 target = random.inBox(glm::dvec3(-1.2), glm::dvec3(1.2));
        const Ray ray{origin, (target - origin) * random.uniform(0.1, 10)};
        const double tMin = i % 3 == 0 ? 0.3 : 0;
        const auto fast = intersectMesh(mesh, ray, tMin);
        const auto slow = intersectMeshBruteForce(mesh, ray, tMin);
        ASSERT_EQ(bool(fast), bool(slow)) << "ray " << i;
        if (!fast) continue;
        ++hits;
        ASSERT_EQ(fast->triangle, slow->triangle) << "ray " << i;
        ASSERT_EQ(fast->t, slow->t) << "ray " << i;
    }
    EXPECT_GT(hits, 4000);  // about half the rays hit
}

TEST(Mesh, ClosedMeshCrossingsComeInPairs) {
    // Rays aimed exactly at the sphere mesh's vertices and edge midpoints, the
    // cases that leak through non-watertight tests: a convex closed surface is
    // crossed 0 or 2 times, and twice by a ray that goes in through the point
    // along its normal.
    const TriangleMesh mesh = test::tessellatedSphere(12, 16);
    test::Random random(12);
    for (const TriangleMesh::Triangle& triangle : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 a = mesh.positions[triangle.position[k]];
            const glm::dvec3 b = mesh.positions[triangle.position[(k + 1) % 3]];
            for (const glm::dvec3& point : {a, 0.5 * (a + b)}) {
                const glm::dvec3 d = random.direction();
                const auto any = meshCrossings(mesh, {point - 3.0 * d, d});
                EXPECT_TRUE(any.size() == 0 || any.size() == 2) << any.size();
                const auto inward = meshCrossings(mesh, {3.0 * point, -point});
                ASSERT_EQ(inward.size(), 2u);
                EXPECT_TRUE(inward[0].crossing.entering);
                EXPECT_FALSE(inward[1].crossing.entering);
                EXPECT_EQ(meshSpans(mesh, {3.0 * point, -point}).size(), 1u);
            }
        }
    }
}

TEST(Mesh, SpansOfAClosedMesh) {
    // Along the z axis through the poles (vertices of the mesh): in at z = 1,
    // out at z = -1.
    const TriangleMesh mesh = test::tessellatedSphere(12, 16);
    const std::vector<GenericSpan> spans = meshSpans(mesh, {{0, 0, 5}, {0, 0, -1}});
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 4, kTol);
    EXPECT_NEAR(spans[0].exit.t, 6, kTol);
    expectSameDirection(spans[0].enter.normal, {0, 0, 1}, 1e-9);
    expectSameDirection(spans[0].exit.normal, {0, 0, -1}, 1e-9);
}

}  // namespace
}  // namespace vkray::reference
