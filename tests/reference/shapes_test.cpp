// Known answers for the CPU reference's generic shapes, worked out by hand
// from each implicit equation, and for the world-space wrapper (transformed
// rays, inverse-transpose normals, facing, closest hit).
#include "reference/shapes.h"

#include "reference/object_intersect.h"
#include "reference/reference_test_util.h"
#include "reference/scene_intersector.h"
#include "util/error.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <string>

namespace vkray::reference {
namespace {

using test::makeObject;
using test::scaling;
using test::translation;

constexpr double kTol = 1e-12;

const Scene kNoMeshes;  // intersectObject's scene, for objects that need no mesh

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tol = kTol) {
    EXPECT_NEAR(actual.x, expected.x, tol);
    EXPECT_NEAR(actual.y, expected.y, tol);
    EXPECT_NEAR(actual.z, expected.z, tol);
}

// Affine matrices written out entry by entry (glm is column-major: m[column][row]),
// so that the inverses below are exact and do not lean on glm::rotate's cos(90°).
// 90 degrees about +z: (x, y, z) -> (-y, x, z).
glm::dmat4 rotationZ90() {
    glm::dmat4 m(0.0);
    m[0] = {0, 1, 0, 0};   // image of x: +y
    m[1] = {-1, 0, 0, 0};  // image of y: -x
    m[2] = {0, 0, 1, 0};
    m[3] = {0, 0, 0, 1};
    return m;
}

// Its inverse, -90 degrees about +z: (x, y, z) -> (y, -x, z).
glm::dmat4 rotationZMinus90() {
    glm::dmat4 m(0.0);
    m[0] = {0, -1, 0, 0};
    m[1] = {1, 0, 0, 0};
    m[2] = {0, 0, 1, 0};
    m[3] = {0, 0, 0, 1};
    return m;
}

// ---- sphere ------------------------------------------------------------

TEST(Sphere, HitFromOutside) {
    // (0,0,5) - t z meets |P| = 1 at t = 4 (and 6): P = (0,0,1), normal = P.
    const auto hit = intersectSphere({{0, 0, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4, kTol);
    expectNear(hit->normal, {0, 0, 1});
}

TEST(Sphere, Miss) {
    EXPECT_FALSE(intersectSphere({{2, 0, 5}, {0, 0, -1}}, 0));
    EXPECT_FALSE(intersectSphere({{1.0000001, 0, 5}, {0, 0, -1}}, 0));
}

TEST(Sphere, TangentRayCountsAsAHit) {
    // x = 1 touches the sphere at (1,0,0): the double root t = 5.
    const auto hit = intersectSphere({{1, 0, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5, kTol);
    expectNear(hit->normal, {1, 0, 0});
}

TEST(Sphere, FromInsideReturnsTheFarRoot) {
    // Roots -1 and 1; -1 is behind the origin.
    const auto hit = intersectSphere({{0, 0, 0}, {0, 0, 1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTol);
    expectNear(hit->normal, {0, 0, 1});
}

TEST(Sphere, BehindTheRayIsAMiss) {
    EXPECT_FALSE(intersectSphere({{0, 0, 5}, {0, 0, 1}}, 0));
}

TEST(Sphere, NonUnitDirectionScalesT) {
    // The same line with c twice as long reaches (0,0,1) at t = 2.
    const auto hit = intersectSphere({{0, 0, 5}, {0, 0, -2}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2, kTol);
    expectNear(hit->normal, {0, 0, 1});
}

TEST(Sphere, ZeroDirectionIsNoRay) {
    EXPECT_FALSE(intersectSphere({{0, 0, 5}, {0, 0, 0}}, 0));
}

TEST(Sphere, TMinIsOpen) {
    const Ray ray{{0, 0, 5}, {0, 0, -1}};
    // A root exactly at tMin is excluded: the far root is next.
    const auto far = intersectSphere(ray, 4);
    ASSERT_TRUE(far);
    EXPECT_NEAR(far->t, 6, kTol);
    EXPECT_FALSE(intersectSphere(ray, 6));
    const auto near = intersectSphere(ray, std::nextafter(4.0, 0.0));
    ASSERT_TRUE(near);
    EXPECT_EQ(near->t, 4);
}

TEST(Sphere, StiffFarOrigin) {
    // C = 1e12 - 1 and q = 1e6 + 1 are exact, so t = C / q = 999999 exactly;
    // the textbook (-B - sqrt(disc)) / A would subtract 1e6 from 1e6.
    const auto hit = intersectSphere({{0, 0, 1e6}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1e6 - 1, 1e-15 * 1e6);
}

TEST(Sphere, StiffGrazingRayFromFarAway) {
    // docs/numerics-background.md, hand-worked rays 1 and 2: a unit sphere D away, the ray passing
    // 0.9995 from its centre. B^2 - AC subtracts two numbers near D^4 to get
    // ~1e-3 D^2: at D = 1e8 that is below double's resolution of D^4. The
    // expected t (in units of the non-unit direction) is from a 50-digit
    // solution with the double inputs taken as exact.
    struct Case {
        double distance, t;
    };
    for (const Case& k : {Case{1e4, 0.999996828111880918649680987189},
                          Case{1e8, 0.999999999683811665024729099222}}) {
        const auto hit = intersectSphere({{0, 0, -k.distance}, {0.9995, 0, k.distance}}, 0);
        ASSERT_TRUE(hit) << k.distance;
        EXPECT_NEAR(hit->t, k.t, 4e-16) << k.distance;
    }
}

// ---- plane and square ---------------------------------------------------

TEST(Plane, HillsWorkedExample) {
    // (4,1,3) + (-3,-5,-3) t: z = 3 - 3t = 0 at t = 1, P = (1,-4,0).
    const Ray ray{{4, 1, 3}, {-3, -5, -3}};
    const auto hit = intersectPlane(ray, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTol);
    expectNear(ray.origin + hit->t * ray.direction, {1, -4, 0});
    expectNear(hit->normal, {0, 0, 1});
}

TEST(Plane, FromBelowKeepsTheGenericNormal) {
    const auto hit = intersectPlane({{0, 0, -2}, {0, 0, 1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2, kTol);
    expectNear(hit->normal, {0, 0, 1});  // facing is the world wrapper's job
}

TEST(Plane, ParallelInsideAndBehindAreMisses) {
    EXPECT_FALSE(intersectPlane({{0, 0, 1}, {1, 0, 0}}, 0));  // parallel above
    EXPECT_FALSE(intersectPlane({{0, 0, 0}, {1, 1, 0}}, 0));  // lying in the plane
    EXPECT_FALSE(intersectPlane({{0, 0, 1}, {0, 0, 1}}, 0));  // moving away
}

TEST(Plane, TMinIsOpen) {
    const Ray ray{{0, 0, 1}, {0, 0, -1}};
    EXPECT_FALSE(intersectPlane(ray, 1));
    EXPECT_TRUE(intersectPlane(ray, std::nextafter(1.0, 0.0)));
}

TEST(Square, InsideHit) {
    const auto hit = intersectSquare({{0.5, -0.5, 2}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2, kTol);
    expectNear(hit->normal, {0, 0, 1});
}

TEST(Square, EdgesAreClosed) {
    // Straight down, so x and y are exact: x = 1 is on the edge, 1.0000001 is off it.
    EXPECT_TRUE(intersectSquare({{1, 0, 2}, {0, 0, -1}}, 0));
    EXPECT_TRUE(intersectSquare({{-1, -1, 2}, {0, 0, -1}}, 0));  // a corner
    EXPECT_FALSE(intersectSquare({{1.0000001, 0, 2}, {0, 0, -1}}, 0));
    EXPECT_FALSE(intersectSquare({{0, -1.0000001, 2}, {0, 0, -1}}, 0));
}

TEST(Square, SlantedRayLandsWhereThePlaneSays) {
    // Hill's ray lands at (1,-4,0): outside the square. Shifted by (0,4,0) it
    // lands on the edge point (1,0,0).
    EXPECT_FALSE(intersectSquare({{4, 1, 3}, {-3, -5, -3}}, 0));
    const auto hit = intersectSquare({{4, 5, 3}, {-3, -5, -3}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTol);
}

TEST(Square, ParallelIsAMiss) {
    EXPECT_FALSE(intersectSquare({{0, 0, 0}, {1, 0, 0}}, 0));
}

// ---- cube --------------------------------------------------------------

TEST(Cube, EachFaceFromOutside) {
    for (int axis = 0; axis < 3; ++axis) {
        for (double sign : {-1.0, 1.0}) {
            // Start 5 out along the face normal, off-centre on the face.
            glm::dvec3 origin(0), face(0);
            face[axis] = sign;
            origin[axis] = 5 * sign;
            origin[(axis + 1) % 3] = 0.25;
            origin[(axis + 2) % 3] = -0.5;
            const auto hit = intersectCube({origin, -face}, 0);
            ASSERT_TRUE(hit) << axis << " " << sign;
            EXPECT_NEAR(hit->t, 4, kTol) << axis << " " << sign;
            expectNear(hit->normal, face);
        }
    }
}

TEST(Cube, NonUnitDirection) {
    const auto hit = intersectCube({{5, 0, 0}, {-2, 0, 0}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 2, kTol);
    expectNear(hit->normal, {1, 0, 0});
}

TEST(Cube, RayInAFacePlaneWithZeroDirectionComponents) {
    // docs/numerics-background.md, hand-worked ray 15: y = 1 is the top face's
    // plane, c.y = c.z = 0.
    // A naive slab test computes (1 - 1) * inf = NaN here.
    auto hit = intersectCube({{-5, 1, 0}, {1, 0, 0}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4, kTol);
    expectNear(hit->normal, {-1, 0, 0});
    // Along an edge (y = z = 1).
    hit = intersectCube({{-5, 1, 1}, {1, 0, 0}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4, kTol);
    expectNear(hit->normal, {-1, 0, 0});
    // Just outside the face plane.
    EXPECT_FALSE(intersectCube({{-5, 1.0000001, 0}, {1, 0, 0}}, 0));
    EXPECT_FALSE(intersectCube({{-5, 0, -1.0000001}, {1, 0, 0}}, 0));
}

TEST(Cube, FromInsideLeavesThroughTheFarFace) {
    // The generic normal stays outward (+x); the world wrapper turns it.
    const auto hit = intersectCube({{0.5, 0, 0}, {1, 0, 0}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 0.5, kTol);
    expectNear(hit->normal, {1, 0, 0});
    // Slanted: leaves through y = -1 at t = 1 (x = 0.25, z = 0.5 there).
    const auto slanted = intersectCube({{0, 0, 0}, {0.25, -1, 0.5}}, 0);
    ASSERT_TRUE(slanted);
    EXPECT_NEAR(slanted->t, 1, kTol);
    expectNear(slanted->normal, {0, -1, 0});
}

TEST(Cube, MissesAndBehind) {
    EXPECT_FALSE(intersectCube({{5, 0, 0}, {1, 0, 0}}, 0));     // moving away
    EXPECT_FALSE(intersectCube({{-5, 2, 0}, {1, 0.1, 0}}, 0));  // passes above
    EXPECT_FALSE(intersectCube({{-5, 0, 0}, {1, 1, 0}}, 0));    // x and y slabs do not overlap
    EXPECT_FALSE(intersectCube({{0, 0, 0}, {0, 0, 0}}, 0));     // no direction
}

TEST(Cube, DiagonalIntoACorner) {
    const auto hit = intersectCube({{2, 2, 2}, {-1, -1, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 1, kTol);
    EXPECT_NEAR(glm::length(hit->normal), 1, kTol);  // one of the three faces
}

TEST(Cube, TMinIsOpen) {
    const Ray ray{{5, 0, 0}, {-1, 0, 0}};
    const auto exit = intersectCube(ray, 4);  // entry at exactly tMin: excluded
    ASSERT_TRUE(exit);
    EXPECT_NEAR(exit->t, 6, kTol);
    expectNear(exit->normal, {-1, 0, 0});
    EXPECT_FALSE(intersectCube(ray, 6));
}

// ---- world space ---------------------------------------------------------

TEST(Object, IdentitySphereInWorld) {
    const SceneObject sphere = makeObject(ShapeType::Sphere);
    const auto hit = intersectObject(kNoMeshes, sphere, 7, {{0, 0, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, 7);
    EXPECT_NEAR(hit->t, 4, kTol);
    expectNear(hit->point, {0, 0, 1});
    expectNear(hit->normal, {0, 0, 1});
}

TEST(Object, TranslatedRotatedScaledSphere) {
    // M = T(1,2,3) R_z(90°) S(2,1,1): an ellipsoid with semi-axes 1, 2, 1 along
    // world x, y, z, centred at (1,2,3), i.e. (X-1)^2 + ((Y-2)/2)^2 + (Z-3)^2 = 1.
    // The generic point g = (0.36, 0.48, 0.8) goes to M g = (0.52, 2.72, 3.8);
    // its normal (M^-1)^T g = R S^-1 g = R (0.18, 0.48, 0.8) = (-0.48, 0.18, 0.8),
    // which matches the ellipsoid's gradient (2(X-1), (Y-2)/2, 2(Z-3)) / 2.
    const glm::dmat4 M = translation({1, 2, 3}) * rotationZ90() * scaling({2, 1, 1});
    const glm::dmat4 inverse =
        scaling({0.5, 1, 1}) * rotationZMinus90() * translation({-1, -2, -3});
    const SceneObject sphere = makeObject(ShapeType::Sphere, M, inverse);

    const glm::dvec3 point(0.52, 2.72, 3.8);
    const glm::dvec3 normal = glm::dvec3(-0.48, 0.18, 0.8) / std::sqrt(0.9028);
    // Come in along the normal from 5 out: a convex body lies behind its
    // tangent plane, so the first hit is the point itself, at t = 5.
    const Ray ray{point + 5.0 * normal, -normal};
    const auto hit = intersectObject(kNoMeshes, sphere, 0, ray, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5, kTol);
    expectNear(hit->point, point);
    expectNear(hit->normal, normal);
}

TEST(Object, NonUniformScaleUsesTheInverseTranspose) {
    // docs/numerics-background.md, hand-worked ray 18: scale (1e3, 1, 1e-3). The generic point
    // (0, 1/√2, 1/√2) is the world point (0, 1/√2, 1e-3/√2) with normal
    // S^-1 (0, 1, 1)/√2 ∝ (0, 1, 1e3); M itself would give (0, 1, 1e-3).
    const SceneObject ellipsoid =
        makeObject(ShapeType::Sphere, scaling({1e3, 1, 1e-3}), scaling({1e-3, 1, 1e3}));
    const double r = 1 / std::sqrt(2.0);
    const auto hit = intersectObject(kNoMeshes, ellipsoid, 0, {{0, r, 10}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 10 - 1e-3 * r, kTol);
    expectNear(hit->point, {0, r, 1e-3 * r});
    expectNear(hit->normal, glm::dvec3(0, 1, 1e3) / std::sqrt(1 + 1e6));
}

TEST(Object, NormalFacesTheRay) {
    const SceneObject plane = makeObject(ShapeType::Plane);
    const auto below = intersectObject(kNoMeshes, plane, 0, {{0, 0, -2}, {0, 0, 1}}, 0);
    ASSERT_TRUE(below);
    expectNear(below->normal, {0, 0, -1});
    const auto above = intersectObject(kNoMeshes, plane, 0, {{0, 0, 2}, {0.5, 0, -1}}, 0);
    ASSERT_TRUE(above);
    expectNear(above->normal, {0, 0, 1});
    // Inside a cube the outward exit normal is turned back toward the eye.
    const auto inside =
        intersectObject(kNoMeshes, makeObject(ShapeType::Cube), 0, {{0.5, 0, 0}, {1, 0, 0}}, 0);
    ASSERT_TRUE(inside);
    expectNear(inside->normal, {-1, 0, 0});
}

TEST(Object, RotatedSquareStandsUpright) {
    // M = T(0,0,-3) R_z(90°) S(2,1,1): the square lies in z = -3 with its long
    // side turned onto y, spanning |x| <= 1, |y| <= 2.
    const glm::dmat4 M = translation({0, 0, -3}) * rotationZ90() * scaling({2, 1, 1});
    const glm::dmat4 inverse = scaling({0.5, 1, 1}) * rotationZMinus90() * translation({0, 0, 3});
    const SceneObject square = makeObject(ShapeType::Square, M, inverse);
    const auto hit = intersectObject(kNoMeshes, square, 0, {{0.5, 1.9, 0}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 3, kTol);
    expectNear(hit->point, {0.5, 1.9, -3});
    expectNear(hit->normal, {0, 0, 1});
    EXPECT_FALSE(intersectObject(kNoMeshes, square, 0, {{1.1, 0, 0}, {0, 0, -1}}, 0));
}

TEST(Object, MeshWithoutGeometryNamesItself) {
    SceneObject mesh = makeObject(ShapeType::Mesh);
    mesh.loc = {std::make_shared<const std::string>("scene.sdl"), 12, 5};
    try {
        intersectObject(kNoMeshes, mesh, 0, {{0, 0, 5}, {0, 0, -1}}, 0);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "scene.sdl:12:5: error: 'mesh' has no geometry loaded (call loadSceneGeometry)");
    }
    // A boolean needs its two operands (the reader always gives them).
    EXPECT_THROW(
        intersectObject(kNoMeshes, makeObject(ShapeType::Union), 0, {{0, 0, 5}, {0, 0, -1}}, 0),
        Error);
}

// ---- closest hit -----------------------------------------------------------

TEST(ClosestHit, PicksTheNearerObject) {
    Scene scene;
    // The farther sphere first, so that scene order cannot be the answer.
    scene.objects.push_back(
        makeObject(ShapeType::Sphere, translation({0, 0, -3}), translation({0, 0, 3})));
    scene.objects.push_back(makeObject(ShapeType::Sphere));
    const auto hit = closestHit(scene, {{0, 0, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, 1);
    EXPECT_NEAR(hit->t, 4, kTol);
}

TEST(ClosestHit, TiesGoToTheLowerIndex) {
    Scene scene;
    scene.objects.push_back(makeObject(ShapeType::Plane));
    scene.objects.push_back(makeObject(ShapeType::Square));  // the same z = 0 where they overlap
    scene.objects.push_back(makeObject(ShapeType::Sphere));
    auto hit = closestHit(scene, {{0, 0, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, 2);  // the sphere's top at z = 1 is nearer
    // Beside the sphere (0.9^2 + 0.5^2 > 1) but on the square: plane and square
    // meet the ray at the same t, and the earlier object wins.
    hit = closestHit(scene, {{0.9, 0.5, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, 0);
    EXPECT_NEAR(hit->t, 5, kTol);
}

TEST(ClosestHit, EmptySceneAndAllMisses) {
    Scene scene;
    EXPECT_FALSE(closestHit(scene, {{0, 0, 5}, {0, 0, -1}}, 0));
    scene.objects.push_back(makeObject(ShapeType::Sphere));
    EXPECT_FALSE(closestHit(scene, {{0, 0, 5}, {0, 0, 1}}, 0));
}

}  // namespace
}  // namespace vkray::reference
