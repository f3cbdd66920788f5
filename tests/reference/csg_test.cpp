// CSG by ray intervals: booleans of spheres worked out by hand (union,
// lens, bite, hollow), nesting, the plane as a half-space, mesh and torus
// operands, csgMaxSpans, the refusal of operands without an inside, and a
// seeded property test against point membership.
#include "reference/csg.h"

#include "reference/scene_intersector.h"
#include "reference_test_util.h"
#include "util/error.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace vkray::reference {
namespace {

using test::boolean;
using test::expectSameDirection;
using test::makeObject;
using test::placed;

constexpr double kTol = 1e-12;

const Scene kNoMeshes;

TEST(Csg, UnionOfOverlappingSpheres) {
    // Unit spheres at x = -+0.5: along the x axis from x = -5, in at x = -1.5
    // (t = 3.5) and out at x = 1.5 (t = 6.5); the overlap inside is no boundary.
    const SceneObject both = boolean(ShapeType::Union, placed(ShapeType::Sphere, {-0.5, 0, 0}),
                                     placed(ShapeType::Sphere, {0.5, 0, 0}));
    const Ray ray{{-5, 0, 0}, {1, 0, 0}};
    const SpanList spans = objectSpans(kNoMeshes, both, ray);
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 3.5, kTol);
    expectSameDirection(spans[0].enter.normal, {-1, 0, 0}, kTol);
    EXPECT_EQ(spans[0].enter.surface, &both.operands[0]);
    EXPECT_NEAR(spans[0].exit.t, 6.5, kTol);
    expectSameDirection(spans[0].exit.normal, {1, 0, 0}, kTol);
    EXPECT_EQ(spans[0].exit.surface, &both.operands[1]);

    auto hit = intersectObject(kNoMeshes, both, 3, ray, 0);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, 3);
    EXPECT_NEAR(hit->t, 3.5, kTol);
    EXPECT_EQ(hit->surface, &both.operands[0]);
    hit = intersectObject(kNoMeshes, both, 3, ray, 4);  // from inside: the far side
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 6.5, kTol);
    expectSameDirection(hit->normal, {-1, 0, 0}, kTol);  // turned to face the ray

    // At y = 0.5 the first sphere's chord starts at x = -0.5 - sqrt(0.75).
    hit = intersectObject(kNoMeshes, both, 0, {{-5, 0.5, 0}, {1, 0, 0}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4.5 - std::sqrt(0.75), kTol);
}

TEST(Csg, IntersectionIsTheLens) {
    // The lens of the same two spheres: in through the second sphere's left
    // side (x = -0.5, t = 4.5), out through the first's right (x = 0.5).
    const SceneObject lens =
        boolean(ShapeType::Intersection, placed(ShapeType::Sphere, {-0.5, 0, 0}),
                placed(ShapeType::Sphere, {0.5, 0, 0}));
    const SpanList spans = objectSpans(kNoMeshes, lens, {{-5, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 4.5, kTol);
    EXPECT_EQ(spans[0].enter.surface, &lens.operands[1]);
    expectSameDirection(spans[0].enter.normal, {-1, 0, 0}, kTol);
    EXPECT_NEAR(spans[0].exit.t, 5.5, kTol);
    EXPECT_EQ(spans[0].exit.surface, &lens.operands[0]);
    // Beside the lens (|y| > sqrt(0.75)) both spheres are met, but not together.
    EXPECT_FALSE(intersectObject(kNoMeshes, lens, 0, {{-5, 0.9, 0}, {1, 0, 0}}, 0));
}

TEST(Csg, DifferenceShowsTheBiteWithTheNegatedNormal) {
    // Unit sphere minus the unit sphere at x = 1: from x = 5 going -x, the
    // first solid point is the bite's face at x = 0 (t = 5). It lies on the
    // second sphere, whose outward normal there, -x, is negated: +x, facing
    // the ray.
    const SceneObject bitten = boolean(ShapeType::Difference, placed(ShapeType::Sphere, {0, 0, 0}),
                                       placed(ShapeType::Sphere, {1, 0, 0}));
    const auto hit = intersectObject(kNoMeshes, bitten, 0, {{5, 0, 0}, {-1, 0, 0}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5, kTol);
    expectSameDirection(hit->normal, {1, 0, 0}, kTol);
    EXPECT_EQ(hit->surface, &bitten.operands[1]);
}

TEST(Csg, HollowSphereFromInsideTheShell) {
    // A radius-2 sphere minus the unit sphere: along x from -5 the shell is
    // [3, 4] and [6, 7]. The hollow's walls carry the inner sphere's normal
    // negated: pointing into the hollow, away from the solid.
    const SceneObject hollow =
        boolean(ShapeType::Difference, placed(ShapeType::Sphere, {0, 0, 0}, {2, 2, 2}),
                placed(ShapeType::Sphere, {0, 0, 0}));
    const Ray ray{{-5, 0, 0}, {1, 0, 0}};
    const SpanList spans = objectSpans(kNoMeshes, hollow, ray);
    ASSERT_EQ(spans.size(), 2u);
    EXPECT_NEAR(spans[0].exit.t, 4, kTol);
    expectSameDirection(spans[0].exit.normal, {1, 0, 0}, kTol);
    EXPECT_NEAR(spans[1].enter.t, 6, kTol);
    expectSameDirection(spans[1].enter.normal, {-1, 0, 0}, kTol);
    EXPECT_NEAR(spans[1].exit.t, 7, kTol);
    // Starting in the shell, the ray leaves the solid into the hollow at t = 4.
    const auto hit = intersectObject(kNoMeshes, hollow, 0, ray, 3.5);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4, kTol);
    expectSameDirection(hit->normal, {-1, 0, 0}, kTol);
    EXPECT_EQ(hit->surface, &hollow.operands[1]);
}

TEST(Csg, NestedBooleans) {
    // (spheres at x = -+0.5, united) minus a radius-0.5 sphere at x = 0.5:
    // [3.5, 6.5] minus [5, 6] along the x axis from -5.
    const SceneObject pair = boolean(ShapeType::Union, placed(ShapeType::Sphere, {-0.5, 0, 0}),
                                     placed(ShapeType::Sphere, {0.5, 0, 0}));
    const SceneObject carved = boolean(ShapeType::Difference, pair,
                                       placed(ShapeType::Sphere, {0.5, 0, 0}, glm::dvec3(0.5)));
    const SpanList spans = objectSpans(kNoMeshes, carved, {{-5, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(spans.size(), 2u);
    EXPECT_NEAR(spans[0].enter.t, 3.5, kTol);
    EXPECT_NEAR(spans[0].exit.t, 5, kTol);
    EXPECT_NEAR(spans[1].enter.t, 6, kTol);
    EXPECT_EQ(spans[1].enter.surface, &carved.operands[1]);
    EXPECT_NEAR(spans[1].exit.t, 6.5, kTol);
    EXPECT_EQ(spans[1].exit.surface, &carved.operands[0].operands[1]);
    // ... intersected with the half-space x <= 0.75 (a plane turned by
    // (x, y, z) -> (z, y, -x) and moved to x = 0.75): the last piece is cut.
    glm::dmat4 turn(0.0), back(0.0);
    turn[0] = {0, 0, -1, 0};  // generic x -> world -z
    turn[1] = {0, 1, 0, 0};
    turn[2] = {1, 0, 0, 0};  // generic z -> world x
    turn[3] = {0.75, 0, 0, 1};
    back[0] = {0, 0, 1, 0};
    back[1] = {0, 1, 0, 0};
    back[2] = {-1, 0, 0, 0};
    back[3] = {0, 0, -0.75, 1};
    const SceneObject cut =
        boolean(ShapeType::Intersection, carved, makeObject(ShapeType::Plane, turn, back));
    const SpanList cutSpans = objectSpans(kNoMeshes, cut, {{-5, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(cutSpans.size(), 1u);
    EXPECT_NEAR(cutSpans[0].exit.t, 5, kTol);
    EXPECT_EQ(csgMaxSpans(kNoMeshes, cut), 3 + 1 - 1);
}

TEST(Csg, PlaneIsAHalfSpace) {
    const SceneObject sphere = placed(ShapeType::Sphere, {0, 0, 0});
    const SceneObject plane = placed(ShapeType::Plane, {0, 0, 0});
    // The sphere minus z <= 0: the upper hemisphere. From below, the cut face
    // at t = 5, with the plane's normal negated (-z, facing the ray).
    const SceneObject upper = boolean(ShapeType::Difference, sphere, plane);
    auto hit = intersectObject(kNoMeshes, upper, 0, {{0, 0, -5}, {0, 0, 1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5, kTol);
    expectSameDirection(hit->normal, {0, 0, -1}, kTol);
    EXPECT_EQ(hit->surface, &upper.operands[1]);
    hit = intersectObject(kNoMeshes, upper, 0, {{0, 0, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4, kTol);
    // The sphere and z <= 0: the lower hemisphere, entered through the cut.
    const SceneObject lower = boolean(ShapeType::Intersection, sphere, plane);
    hit = intersectObject(kNoMeshes, lower, 0, {{0, 0, 5}, {0, 0, -1}}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 5, kTol);
    expectSameDirection(hit->normal, {0, 0, 1}, kTol);
    // The union reaches down forever: from below only the sphere's top is a
    // boundary; parallel to the plane, below it, never one.
    const SceneObject both = boolean(ShapeType::Union, sphere, plane);
    const SpanList spans = objectSpans(kNoMeshes, both, {{0, 0, -5}, {0, 0, 1}});
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_TRUE(std::isinf(spans[0].enter.t));
    EXPECT_NEAR(spans[0].exit.t, 6, kTol);
    EXPECT_FALSE(intersectObject(kNoMeshes, both, 0, {{-5, 0, -3}, {1, 0, 0}}, 0));
}

TEST(Csg, TouchingSpansMerge) {
    // Unit spheres at x = -+1 touch at the origin: one span along the x axis.
    const SceneObject both = boolean(ShapeType::Union, placed(ShapeType::Sphere, {-1, 0, 0}),
                                     placed(ShapeType::Sphere, {1, 0, 0}));
    const SpanList spans = objectSpans(kNoMeshes, both, {{-5, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 3, kTol);
    EXPECT_NEAR(spans[0].exit.t, 7, kTol);
    // A tangent span (length 0) of one operand changes nothing: the sphere
    // at y = 1 only touches the x axis.
    const SceneObject touched = boolean(ShapeType::Difference, placed(ShapeType::Cube, {0, 0, 0}),
                                        placed(ShapeType::Sphere, {0, 1, 0}));
    const SpanList cube = objectSpans(kNoMeshes, touched, {{-5, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(cube.size(), 1u);
    EXPECT_NEAR(cube[0].enter.t, 4, kTol);
    EXPECT_NEAR(cube[0].exit.t, 6, kTol);
}

TEST(Csg, AThinResultFarAwayIsNoSliver) {
    // Two cube slabs 6e-6 thick, side by side, seen face-on from 2.2e4 away: one span 6e-6
    // long, 2.7e-10 of t. Ends within 1e-9 of t were once taken as one, and the span removed as a
    // sliver (where the GPU drew the slab).
    const SceneObject slab =
        boolean(ShapeType::Union, placed(ShapeType::Cube, {0, 0, 0}, {1, 1, 3e-6}),
                placed(ShapeType::Cube, {0.5, 0, 0}, {1, 1, 3e-6}));
    const SpanList spans = objectSpans(kNoMeshes, slab, {{0.2, 0.1, 2.2e4}, {0, 0, -1}});
    ASSERT_EQ(spans.size(), 1u);
    EXPECT_NEAR(spans[0].enter.t, 2.2e4 - 3e-6, 1e-9);
    EXPECT_NEAR(spans[0].exit.t, 2.2e4 + 3e-6, 1e-9);
    // 3e-9 thick: 2.7e-13 of t, which ends within 1e-12 of t once took for a
    // sliver too (the corner of a cube in a union squashed to 2e-7).
    const SceneObject thinner =
        boolean(ShapeType::Union, placed(ShapeType::Cube, {0, 0, 0}, {1, 1, 3e-9}),
                placed(ShapeType::Cube, {0.5, 0, 0}, {1, 1, 3e-9}));
    const SpanList thin = objectSpans(kNoMeshes, thinner, {{0.2, 0.1, 2.2e4}, {0, 0, -1}});
    ASSERT_EQ(thin.size(), 1u);
    EXPECT_NEAR(thin[0].exit.t - thin[0].enter.t, 6e-9, 1e-11);
}

Scene sceneWithSphereMesh(bool closed) {
    Scene scene;
    auto mesh = std::make_shared<TriangleMesh>(test::tessellatedSphere(12, 16));
    mesh->closed = closed;
    mesh->name = "ball.3vn";
    scene.meshes.push_back(mesh);
    return scene;
}

TEST(Csg, ClosedMeshAndTorusOperands) {
    // A unit sphere minus the half-size sphere mesh, down the z axis through
    // the mesh's poles: [4, 6] minus [4.5, 5.5].
    const Scene scene = sceneWithSphereMesh(true);
    SceneObject ball = placed(ShapeType::Mesh, {0, 0, 0}, glm::dvec3(0.5));
    ball.mesh = 0;
    const SceneObject shell =
        boolean(ShapeType::Difference, placed(ShapeType::Sphere, {0, 0, 0}), ball);
    const SpanList spans = objectSpans(scene, shell, {{0, 0, 5}, {0, 0, -1}});
    ASSERT_EQ(spans.size(), 2u);
    EXPECT_NEAR(spans[0].exit.t, 4.5, kTol);
    EXPECT_NEAR(spans[1].enter.t, 5.5, kTol);
    EXPECT_EQ(csgMaxSpans(scene, shell), 1 + 176);  // 352 triangles

    // A torus united with a radius-0.5 sphere in its hole: three spans along x.
    const SceneObject ring = boolean(ShapeType::Union, placed(ShapeType::Torus, {0, 0, 0}),
                                     placed(ShapeType::Sphere, {0, 0, 0}, glm::dvec3(0.5)));
    const SpanList three = objectSpans(kNoMeshes, ring, {{-3, 0, 0}, {1, 0, 0}});
    ASSERT_EQ(three.size(), 3u);
    EXPECT_NEAR(three[0].enter.t, 1.75, kTol);
    EXPECT_NEAR(three[1].enter.t, 2.5, kTol);
    EXPECT_NEAR(three[2].exit.t, 4.25, kTol);
    EXPECT_EQ(csgMaxSpans(kNoMeshes, ring), 3);
}

TEST(Csg, MaxSpansPerShape) {
    const Scene scene = sceneWithSphereMesh(true);
    const auto spansOf = [&](ShapeType type, double taper = 1) {
        SceneObject o = makeObject(type);
        o.taper = taper;
        o.mesh = 0;
        return csgMaxSpans(scene, o);
    };
    EXPECT_EQ(spansOf(ShapeType::Sphere), 1);
    EXPECT_EQ(spansOf(ShapeType::Cube), 1);
    EXPECT_EQ(spansOf(ShapeType::Plane), 1);
    EXPECT_EQ(spansOf(ShapeType::Cylinder), 1);
    EXPECT_EQ(spansOf(ShapeType::Cone), 1);
    EXPECT_EQ(spansOf(ShapeType::TaperedCylinder, 0.5), 1);
    EXPECT_EQ(spansOf(ShapeType::TaperedCylinder, -1), 2);
    EXPECT_EQ(spansOf(ShapeType::Torus), 2);
    EXPECT_EQ(spansOf(ShapeType::Square), 0);
    EXPECT_EQ(spansOf(ShapeType::Mesh), 176);
    const SceneObject torus = makeObject(ShapeType::Torus);
    const SceneObject sphere = makeObject(ShapeType::Sphere);
    EXPECT_EQ(csgMaxSpans(scene, boolean(ShapeType::Union, torus, torus)), 4);
    EXPECT_EQ(csgMaxSpans(scene, boolean(ShapeType::Intersection, torus, torus)), 3);
    EXPECT_EQ(csgMaxSpans(scene, boolean(ShapeType::Difference, sphere, torus)), 3);
    EXPECT_EQ(csgMaxSpans(scene, boolean(ShapeType::Intersection, sphere, sphere)), 1);
}

std::string refusal(const Scene& scene, const SceneObject& object) {
    try {
        intersectObject(scene, object, 0, {{0, 0, 5}, {0, 0, -1}}, 0);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(Csg, OperandWithoutAnInsideIsRefusedAtItsPlace) {
    const auto file = std::make_shared<const std::string>("scene.sdl");
    SceneObject square = makeObject(ShapeType::Square);
    square.loc = {file, 7, 3};
    EXPECT_EQ(refusal(kNoMeshes, boolean(ShapeType::Union, makeObject(ShapeType::Sphere), square)),
              "scene.sdl:7:3: error: 'square' has no inside and cannot be an operand of 'union'");
    // Also nested, and for meshes that are not closed surfaces.
    const Scene scene = sceneWithSphereMesh(false);
    SceneObject open = makeObject(ShapeType::Mesh);
    open.mesh = 0;
    open.loc = {file, 9, 1};
    const SceneObject nested =
        boolean(ShapeType::Difference, makeObject(ShapeType::Sphere),
                boolean(ShapeType::Intersection, makeObject(ShapeType::Cube), open));
    EXPECT_EQ(refusal(scene, nested),
              "scene.sdl:9:1: error: 'mesh' has no inside and cannot be an operand of "
              "'intersection' (ball.3vn is not a closed surface)");
    EXPECT_THROW(requireReferenceScene(Scene{.objects = {nested}, .meshes = scene.meshes}), Error);
    EXPECT_THROW(csgMaxSpans(scene, nested), Error);
    // A mesh operand whose mesh was never loaded.
    SceneObject unloaded = makeObject(ShapeType::Teapot);
    unloaded.loc = {file, 2, 2};
    const SceneObject withTeapot =
        boolean(ShapeType::Union, makeObject(ShapeType::Sphere), unloaded);
    EXPECT_EQ(refusal(kNoMeshes, withTeapot),
              "scene.sdl:2:2: error: 'teapot' has no geometry loaded (call loadSceneGeometry)");
}

// ---- property: spans against point membership ---------------------------------

bool insideGeneric(ShapeType type, const glm::dvec3& p) {
    switch (type) {
    case ShapeType::Sphere: return glm::dot(p, p) <= 1;
    case ShapeType::Cube: return std::abs(p.x) <= 1 && std::abs(p.y) <= 1 && std::abs(p.z) <= 1;
    case ShapeType::Plane: return p.z <= 0;
    case ShapeType::Cylinder: return p.z >= 0 && p.z <= 1 && p.x * p.x + p.y * p.y <= 1;
    case ShapeType::Cone:
        return p.z >= 0 && p.z <= 1 && p.x * p.x + p.y * p.y <= (1 - p.z) * (1 - p.z);
    case ShapeType::Torus: {
        const double k = glm::dot(p, p) + 1 - 0.0625;
        return k * k - 4 * (p.x * p.x + p.y * p.y) <= 0;
    }
    default: return false;
    }
}

bool insideWorld(const SceneObject& object, const glm::dvec3& p) {
    if (isBoolean(object.type)) {
        const bool a = insideWorld(object.operands[0], p), b = insideWorld(object.operands[1], p);
        if (object.type == ShapeType::Union) return a || b;
        if (object.type == ShapeType::Intersection) return a && b;
        return a && !b;
    }
    return insideGeneric(object.type, glm::dvec3(object.objectFromWorld * glm::dvec4(p, 1)));
}

// Every span end of every primitive in the tree: near them, rounding decides.
void collectEnds(const SceneObject& object, const Ray& ray, std::vector<double>& ends) {
    if (isBoolean(object.type)) {
        for (const SceneObject& operand : object.operands) collectEnds(operand, ray, ends);
        return;
    }
    for (const Span& span : objectSpans(kNoMeshes, object, ray)) {
        ends.push_back(span.enter.t);
        ends.push_back(span.exit.t);
    }
}

SceneObject randomPrimitive(test::Random& random) {
    const ShapeType types[] = {ShapeType::Sphere, ShapeType::Cube,  ShapeType::Cylinder,
                               ShapeType::Cone,   ShapeType::Torus, ShapeType::Plane};
    const ShapeType type = types[random.index(random.uniform(0, 1) < 0.1 ? 6 : 5)];
    // M = T R S with R orthonormal, so M^-1 = S^-1 R^T T^-1.
    const glm::dvec3 a = random.direction();
    const glm::dvec3 b = glm::normalize(glm::cross(a, random.direction()));
    const glm::dmat3 rotation(a, b, glm::cross(a, b));
    const glm::dvec3 scale = random.inBox(glm::dvec3(0.5), glm::dvec3(1.5));
    const glm::dvec3 shift = random.inBox(glm::dvec3(-1), glm::dvec3(1));
    return makeObject(type, test::translation(shift) * glm::dmat4(rotation) * test::scaling(scale),
                      test::scaling(1.0 / scale) * glm::dmat4(glm::transpose(rotation)) *
                          test::translation(-shift));
}

TEST(Csg, SpansMatchPointMembership) {
    // Seeded random trees (A op B) op C of transformed primitives: along each
    // random ray, a sample point is in a result span exactly when it is in
    // the solid by the primitives' own inequalities, except within 1e-7 of
    // some primitive's span end.
    test::Random random(2024);
    const ShapeType ops[] = {ShapeType::Union, ShapeType::Intersection, ShapeType::Difference};
    int insideSamples = 0;
    for (int tree = 0; tree < 300; ++tree) {
        const SceneObject object =
            boolean(ops[random.index(3)],
                    boolean(ops[random.index(3)], randomPrimitive(random), randomPrimitive(random)),
                    randomPrimitive(random));
        for (int i = 0; i < 20; ++i) {
            const glm::dvec3 d = random.direction();
            const Ray ray{random.inBox(glm::dvec3(-1), glm::dvec3(1)) - 6.0 * d, d};
            const SpanList spans = objectSpans(kNoMeshes, object, ray);
            ASSERT_LE(int(spans.size()), csgMaxSpans(kNoMeshes, object));
            for (std::size_t k = 0; k < spans.size(); ++k) {
                ASSERT_LT(spans[k].enter.t, spans[k].exit.t);
                if (k > 0) {
                    ASSERT_LT(spans[k - 1].exit.t, spans[k].enter.t);
                }
            }
            std::vector<double> ends;
            collectEnds(object, ray, ends);
            for (int step = 0; step <= 1200; ++step) {
                const double t = 0.01 * step;
                bool near = false;
                for (const double end : ends) near = near || std::abs(t - end) < 1e-7;
                if (near) continue;
                bool inSpan = false;
                for (const Span& span : spans)
                    inSpan = inSpan || (t >= span.enter.t && t <= span.exit.t);
                const bool inside = insideWorld(object, ray.origin + t * ray.direction);
                insideSamples += inside;
                ASSERT_EQ(inSpan, inside) << "tree " << tree << " ray " << i << " t " << t;
            }
        }
    }
    EXPECT_GT(insideSamples, 10000);
}

}  // namespace
}  // namespace vkray::reference
