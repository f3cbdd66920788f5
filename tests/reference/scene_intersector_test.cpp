// The closest hit over a scene through the object BVH against brute force
// (the oracle), on seeded random scenes of 10 000 transformed objects; and
// whole renders of every shape kind, BVH against brute force, with each
// boolean shaded by the material of the operand it shows.
#include "reference/scene_intersector.h"

#include "reference/reference_tracer.h"
#include "reference_test_util.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <memory>

namespace vkray::reference {
namespace {

using test::boolean;
using test::makeObject;
using test::placed;

SceneObject randomObject(test::Random& random, ShapeType type) {
    const glm::dvec3 a = random.direction();
    const glm::dvec3 b = glm::normalize(glm::cross(a, random.direction()));
    const glm::dmat3 rotation(a, b, glm::cross(a, b));
    const glm::dvec3 scale = random.inBox(glm::dvec3(0.2), glm::dvec3(2));
    const glm::dvec3 shift = random.inBox(glm::dvec3(-50), glm::dvec3(50));
    SceneObject object =
        makeObject(type, test::translation(shift) * glm::dmat4(rotation) * test::scaling(scale),
                   test::scaling(1.0 / scale) * glm::dmat4(glm::transpose(rotation)) *
                       test::translation(-shift));
    object.taper = random.uniform(0, 1.5);
    return object;
}

Scene randomScene(std::uint64_t seed, int count) {
    test::Random random(seed);
    Scene scene;
    const ShapeType types[] = {ShapeType::Sphere,          ShapeType::Cube,
                               ShapeType::Cylinder,        ShapeType::Cone,
                               ShapeType::TaperedCylinder, ShapeType::Torus};
    for (int i = 0; i < count; ++i) scene.objects.push_back(randomObject(random, types[i % 6]));
    // A few booleans (one of them unbounded) and a plane far below.
    for (int i = 0; i < 20; ++i) {
        scene.objects.push_back(boolean(ShapeType::Difference,
                                        randomObject(random, ShapeType::Cube),
                                        randomObject(random, ShapeType::Sphere)));
    }
    scene.objects.push_back(boolean(ShapeType::Union, randomObject(random, ShapeType::Torus),
                                    placed(ShapeType::Plane, {0, 0, -80})));
    scene.objects.push_back(placed(ShapeType::Plane, {0, 0, -60}));
    return scene;
}

TEST(SceneIntersector, BvhMatchesBruteForceOnTenThousandObjects) {
    for (const std::uint64_t seed : {1u, 2u}) {
        const Scene scene = randomScene(seed, 10000);
        const SceneIntersector bvh(scene);
        const SceneIntersector bruteForce(scene, true);
        test::Random random(seed + 100);
        int hits = 0;
        for (int i = 0; i < 2000; ++i) {
            const glm::dvec3 origin = random.inBox(glm::dvec3(-60), glm::dvec3(60));
            const Ray ray{origin, random.direction() * random.uniform(0.5, 2)};
            const double tMin = i % 2 ? 0 : random.uniform(0, 20);
            const auto fast = bvh.closestHit(ray, tMin);
            const auto slow = bruteForce.closestHit(ray, tMin);
            ASSERT_EQ(bool(fast), bool(slow)) << "seed " << seed << " ray " << i;
            if (!fast) continue;
            ++hits;
            ASSERT_EQ(fast->object, slow->object) << "seed " << seed << " ray " << i;
            ASSERT_EQ(fast->t, slow->t) << "seed " << seed << " ray " << i;
            ASSERT_EQ(fast->normal, slow->normal) << "seed " << seed << " ray " << i;
        }
        EXPECT_GT(hits, 1000) << seed;
    }
}

TEST(SceneIntersector, ConveniencesAgree) {
    const Scene scene = randomScene(5, 300);
    test::Random random(6);
    for (int i = 0; i < 300; ++i) {
        const Ray ray{random.inBox(glm::dvec3(-60), glm::dvec3(60)), random.direction()};
        const auto a = closestHit(scene, ray, 0);
        const auto b = closestHitBruteForce(scene, ray, 0);
        ASSERT_EQ(bool(a), bool(b)) << i;
        if (a) {
            ASSERT_EQ(a->object, b->object) << i;
            ASSERT_EQ(a->t, b->t) << i;
        }
    }
}

// Every kind of shape in one small scene, looked at from the front.
Scene everyShape() {
    Scene scene;
    scene.lights.push_back({{5, 8, 10}, {1, 1, 1}, {}});
    auto mesh = std::make_shared<TriangleMesh>(test::tessellatedSphere(16, 24));
    scene.meshes.push_back(mesh);
    const auto add = [&](SceneObject object, const glm::dvec3& diffuse) {
        object.material.diffuse = diffuse;
        scene.objects.push_back(std::move(object));
    };
    add(placed(ShapeType::Sphere, {-3, 1.5, 0}), {1, 0, 0});
    add(placed(ShapeType::Cube, {0, 1.5, 0}, glm::dvec3(0.7)), {0, 1, 0});
    add(placed(ShapeType::Cylinder, {3, 1.5, -0.5}), {0, 0, 1});
    add(placed(ShapeType::Torus, {-3, -1.5, 0}), {1, 1, 0});
    SceneObject ball = placed(ShapeType::Icosahedron, {0, -1.5, 0});
    ball.mesh = 0;
    add(ball, {0, 1, 1});
    SceneObject red = placed(ShapeType::Sphere, {2.7, -1.5, 0});
    red.material.diffuse = {1, 0, 0};
    SceneObject blue = placed(ShapeType::Sphere, {3.3, -1.5, 0});
    blue.material.diffuse = {0, 0, 1};
    add(boolean(ShapeType::Union, red, blue), {0.5, 0.5, 0.5});
    add(placed(ShapeType::Plane, {0, 0, -2}), {0.3, 0.3, 0.3});
    return scene;
}

TEST(ReferenceTracer, BvhRenderEqualsBruteForceRender) {
    const Scene scene = everyShape();
    Camera c;
    c.eye = {0, 0, 12};
    c.look = {0, 0, 0};
    const CameraBasis camera = makeCameraBasis(c, 96, 64);
    const Frame fast = render(scene, camera, {96, 64, 1}, {.threads = 3});
    const Frame slow = render(scene, camera, {96, 64, 1}, {.threads = 2, .bruteForce = true});
    int seen[7] = {};
    for (size_t i = 0; i < fast.pixelCount(); ++i) {
        ASSERT_EQ(fast.id[i], slow.id[i]) << i;
        ASSERT_EQ(fast.depth[i], slow.depth[i]) << i;
        ASSERT_EQ(fast.color[i], slow.color[i]) << i;
        if (fast.id[i] >= 0) ++seen[fast.id[i]];
    }
    for (int id = 0; id < 7; ++id) EXPECT_GT(seen[id], 10) << "object " << id;
}

TEST(ReferenceTracer, BooleanIsShadedByTheOperandItShows) {
    // The union's left half is the red operand, its right half the blue one;
    // the boolean's own material (grey) is never used.
    const Scene scene = everyShape();
    Camera c;
    c.eye = {3, -1.5, 12};
    c.look = {3, -1.5, 0};
    const CameraBasis camera = makeCameraBasis(c, 41, 41);
    const Frame frame = render(scene, camera, {41, 41, 1});
    const glm::vec3 left = frame.color[frame.index(17, 20)];
    const glm::vec3 right = frame.color[frame.index(23, 20)];
    EXPECT_EQ(frame.id[frame.index(17, 20)], 5);
    EXPECT_GT(left.r, 0.3f);
    EXPECT_LT(left.b, 0.2f);
    EXPECT_GT(right.b, 0.3f);
    EXPECT_LT(right.r, 0.2f);
    // tracePixel agrees, object by object.
    const PixelTrace trace = tracePixel(scene, camera, {41, 41, 1}, 17, 20);
    EXPECT_EQ(trace.hitObject, 5);
    ASSERT_EQ(trace.objects.size(), scene.objects.size());
    ASSERT_TRUE(trace.objects[5].t);
    EXPECT_EQ(*trace.objects[5].t, trace.t);
    EXPECT_NEAR(trace.color.r, left.r, 1e-6);
}

}  // namespace
}  // namespace vkray::reference
