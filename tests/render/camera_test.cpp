#include "render/camera.h"
#include "util/error.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vkray {
namespace {

TEST(Camera, BasisIsOrthonormalAndLooksAtTheLookPoint) {
    Camera camera;  // Hill's eye (20,15,20) toward the origin, up +y, 60 degrees
    CameraBasis b = makeCameraBasis(camera, 640, 480);
    EXPECT_NEAR(glm::length(b.u), 1, 1e-15);
    EXPECT_NEAR(glm::length(b.v), 1, 1e-15);
    EXPECT_NEAR(glm::dot(b.u, b.v), 0, 1e-15);
    EXPECT_NEAR(glm::dot(b.u, b.n), 0, 1e-15);
    const glm::dvec3 toLook = glm::normalize(camera.look - camera.eye);
    EXPECT_NEAR(glm::dot(-b.n, toLook), 1, 1e-15);
    EXPECT_GT(b.v.y, 0);  // up stays up
    EXPECT_NEAR(b.tanHalfFov, std::tan(M_PI / 6), 1e-15);
    EXPECT_DOUBLE_EQ(b.aspect, 640.0 / 480.0);
}

TEST(Camera, DegenerateCamerasAreErrors) {
    Camera same;
    same.look = same.eye;
    EXPECT_THROW(makeCameraBasis(same, 10, 10), Error);
    Camera parallel;
    parallel.eye = {0, 10, 0};
    parallel.look = {0, 0, 0};
    parallel.up = {0, 1, 0};
    EXPECT_THROW(makeCameraBasis(parallel, 10, 10), Error);
    Camera wide;
    wide.fovDegrees = 180;
    EXPECT_THROW(makeCameraBasis(wide, 10, 10), Error);
}

TEST(Camera, PrimarySampleIsPixelCentreOrBlockCentre) {
    EXPECT_EQ(primarySample(3, 7, 1).px, 3.5);
    EXPECT_EQ(primarySample(3, 7, 1).py, 7.5);
    // Pixel (5, 6) with block 4 lies in the block starting at (4, 4): centre (6, 6).
    EXPECT_EQ(primarySample(5, 6, 4).px, 6.0);
    EXPECT_EQ(primarySample(5, 6, 4).py, 6.0);
}

// Eye at z = 5 looking down -z, 90 degrees, 3x3 pixels: the centre pixel's
// ray is -z; the top-left corner pixel's goes through (-2/3, 2/3) of the
// unit image plane at distance 1 (tan 45 = 1, pixel centre 0.5 of 1.5).
TEST(Camera, HitPointsAreTheEyePlusDepthAlongSampleZero) {
    Camera camera;
    camera.eye = {0, 0, 5};
    camera.look = {0, 0, 0};
    camera.up = {0, 1, 0};
    camera.fovDegrees = 90;
    const RenderSettings settings{3, 3, 1};
    const CameraBasis basis = makeCameraBasis(camera, 3, 3);
    Frame frame(3, 3);
    std::fill(frame.depth.begin(), frame.depth.end(), std::numeric_limits<float>::infinity());
    frame.depth[frame.index(1, 1)] = 2;
    frame.depth[frame.index(0, 0)] = 3;
    const std::vector<glm::vec3> points = hitPoints(frame, basis, settings);
    ASSERT_EQ(points.size(), 9u);
    EXPECT_EQ(points[frame.index(1, 1)], glm::vec3(0, 0, 3));
    const glm::dvec3 corner = glm::normalize(glm::dvec3(-2.0 / 3, 2.0 / 3, -1));
    const glm::vec3 expected(glm::dvec3(0, 0, 5) + 3.0 * corner);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(points[frame.index(0, 0)][c], expected[c], 1e-6) << c;
    EXPECT_EQ(points[frame.index(2, 2)], glm::vec3(0));  // a miss
    const glm::dvec3 d = primaryDirection(basis, settings, {0.5, 0.5});
    EXPECT_NEAR(glm::length(d), 1, 1e-15);
    EXPECT_NEAR(d.x, corner.x, 1e-15);
}

TEST(Camera, AutoCameraFramesTheFiniteObjects) {
    Scene scene;
    SceneObject sphere;
    sphere.worldFromObject = glm::translate(glm::dmat4(1.0), {10, 0, 0});
    sphere.objectFromWorld = glm::inverse(sphere.worldFromObject);
    scene.objects.push_back(sphere);
    SceneObject plane;  // infinite: must not move the framing
    plane.type = ShapeType::Plane;
    scene.objects.push_back(plane);
    Camera camera = autoCamera(scene);
    EXPECT_EQ(camera.look, glm::dvec3(10, 0, 0));
    // Looking from Hill's direction (20,15,20).
    const glm::dvec3 dir = glm::normalize(camera.eye - camera.look);
    EXPECT_NEAR(glm::dot(dir, glm::normalize(glm::dvec3(20, 15, 20))), 1, 1e-12);
    // The bounding sphere of the object's box (radius sqrt 3) fits in the 60 degree view.
    const double distance = glm::length(camera.eye - camera.look);
    EXPECT_GE(std::asin(std::sqrt(3.0) / distance), 0);
    EXPECT_LE(std::asin(std::sqrt(3.0) / distance), M_PI / 6);
}

}  // namespace
}  // namespace vkray
