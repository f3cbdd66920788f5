// The view's mouse camera: orbits keep the distance to the look point and
// the up direction, pans move eye and look alike, zoom scales the distance,
// and the printed line reads back as the same camera.
#include "app/camera_navigation.h"

#include "scene/sdl_reader.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

namespace vkray {
namespace {

Camera sample() {
    Camera c;
    c.eye = {0, 0, 10};
    c.look = {0, 0, 0};
    c.up = {0, 1, 0};
    c.fovDegrees = 40;
    return c;
}

TEST(CameraNavigation, OrbitRightTurnsTheEyeAboutUpAtTheSameDistance) {
    // 90 degrees right from +z about +y: the eye goes to +x (the right of a
    // camera looking down -z with y up).
    const Camera c = orbit(sample(), 90, 0);
    EXPECT_NEAR(c.eye.x, 10, 1e-12);
    EXPECT_NEAR(c.eye.y, 0, 1e-12);
    EXPECT_NEAR(c.eye.z, 0, 1e-12);
    EXPECT_EQ(c.look, sample().look);
    EXPECT_EQ(c.up, sample().up);
}

TEST(CameraNavigation, OrbitOverTheTopStopsShortOfUp) {
    const Camera c = orbit(sample(), 0, 30);  // the eye rises 30 degrees
    EXPECT_NEAR(glm::length(c.eye), 10, 1e-12);
    EXPECT_NEAR(c.eye.y, 10 * std::sin(glm::radians(30.0)), 1e-12);
    const Camera top = orbit(sample(), 0, 500);  // at most 89 degrees up
    EXPECT_NEAR(glm::length(top.eye), 10, 1e-12);
    EXPECT_NEAR(std::acos(top.eye.y / 10), glm::radians(1.0), 1e-12);
}

TEST(CameraNavigation, PanMovesEyeAndLookTogetherByThePixelsAtTheLookPoint) {
    // The view is 2 * 10 * tan(20 deg) high at the look point, over 100 pixels.
    const double perPixel = 20 * std::tan(glm::radians(20.0)) / 100;
    const Camera c = pan(sample(), 10, 5, 100);  // the scene follows the mouse right and up
    const glm::dvec3 expected(-10 * perPixel, -5 * perPixel, 0);
    EXPECT_NEAR(glm::length(c.eye - (sample().eye + expected)), 0, 1e-12);
    EXPECT_NEAR(glm::length(c.look - (sample().look + expected)), 0, 1e-12);
}

TEST(CameraNavigation, ZoomScalesTheDistanceToTheLookPoint) {
    EXPECT_NEAR(zoom(sample(), 2).eye.z, 10 * 0.81, 1e-12);
    EXPECT_NEAR(zoom(sample(), -1).eye.z, 10 / 0.9, 1e-12);
}

TEST(CameraNavigation, PrintedLineReadsBackAsTheSameCamera) {
    const Camera moved = zoom(pan(orbit(sample(), 33.3, 12.7), 3.1, -7.9, 480), 1.7);
    const std::string line = cameraLine(moved);
    EXPECT_EQ(line.rfind("camera eye ", 0), 0u) << line;
    const Scene scene = parseSdl(line + "\n", "pasted.sdl", {});
    ASSERT_TRUE(scene.camera);
    EXPECT_EQ(scene.camera->eye, moved.eye) << line;
    EXPECT_EQ(scene.camera->look, moved.look) << line;
    EXPECT_EQ(scene.camera->up, moved.up) << line;
    EXPECT_EQ(scene.camera->fovDegrees, moved.fovDegrees) << line;
}

}  // namespace
}  // namespace vkray
