#include "app/camera_navigation.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace vkray {

namespace {

// v turned by `angle` radians about the unit `axis` (Rodrigues).
glm::dvec3 rotated(const glm::dvec3& v, const glm::dvec3& axis, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1 - c);
}

std::string shortest(double value) {
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
    return ec == std::errc() ? std::string(text, end) : std::string("0");
}

}  // namespace

Camera orbit(const Camera& camera, double right, double down) {
    const glm::dvec3 up = glm::normalize(camera.up);
    glm::dvec3 offset = camera.eye - camera.look;  // look point to eye
    offset = rotated(offset, up, glm::radians(right));
    // Over the top: the angle between up and the offset stays in [1, 179] degrees.
    const double length = glm::length(offset);
    const double polar = std::acos(std::clamp(glm::dot(offset / length, up), -1.0, 1.0));
    const double turned =
        std::clamp(polar - glm::radians(down), glm::radians(1.0), glm::radians(179.0));
    const glm::dvec3 side = glm::cross(up, offset);
    if (glm::length(side) > 0) offset = rotated(offset, glm::normalize(side), turned - polar);
    Camera result = camera;
    result.eye = camera.look + offset;
    return result;
}

Camera pan(const Camera& camera, double right, double up, int height) {
    const glm::dvec3 forward = glm::normalize(camera.look - camera.eye);
    const glm::dvec3 side = glm::normalize(glm::cross(forward, camera.up));
    const glm::dvec3 screenUp = glm::cross(side, forward);
    // One pixel at the look point's distance: the view's height there over the window's.
    const double perPixel = 2 * glm::length(camera.look - camera.eye) *
                            std::tan(glm::radians(camera.fovDegrees) / 2) / std::max(height, 1);
    const glm::dvec3 move = (-right * side - up * screenUp) * perPixel;
    Camera result = camera;
    result.eye += move;
    result.look += move;
    return result;
}

Camera zoom(const Camera& camera, double steps) {
    Camera result = camera;
    result.eye = camera.look + (camera.eye - camera.look) * std::pow(0.9, steps);
    return result;
}

std::string cameraLine(const Camera& camera) {
    const auto vector = [](const glm::dvec3& v) {
        return shortest(v.x) + " " + shortest(v.y) + " " + shortest(v.z);
    };
    return "camera eye " + vector(camera.eye) + " look " + vector(camera.look) + " up " +
           vector(camera.up) + " fov " + shortest(camera.fovDegrees);
}

}  // namespace vkray
