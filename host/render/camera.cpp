#include "render/camera.h"

#include "shaders/sampling.h"
#include "util/error.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

namespace vkray {

namespace {

// "(1, 2, 3)"
std::string text(const glm::dvec3& v) {
    std::ostringstream out;
    out << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return out.str();
}

// A direction scaled so that its largest component is 1: its length can then
// be taken without overflow or underflow; zero stays zero.
glm::dvec3 wellScaled(const glm::dvec3& v) {
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return largest > 0 ? v / largest : v;
}

}  // namespace

CameraBasis makeCameraBasis(const Camera& camera, int width, int height) {
    // At the scene's `camera` word, or (overridden or automatic) without a place.
    const auto fail = [&camera](const std::string& message) {
        if (camera.loc.known())
            throw Error(formatDiagnostic(camera.loc, nullptr, "error", "camera: " + message));
        throw Error("camera: " + message);
    };
    for (const glm::dvec3* point : {&camera.eye, &camera.look, &camera.up})
        for (int i = 0; i < 3; ++i)
            if (!(std::abs((*point)[i]) <= kMaxSceneMagnitude))
                fail("eye, look and up must be finite and within 1e18, found " + text(*point));
    CameraBasis b;
    b.eye = camera.eye;
    const glm::dvec3 back = wellScaled(camera.eye - camera.look);
    if (back == glm::dvec3(0))
        fail("eye and look are the same point " + text(camera.eye) + "; move one of them");
    b.n = glm::normalize(back);
    const glm::dvec3 up = wellScaled(camera.up);
    if (up == glm::dvec3(0)) fail("the up vector is zero; use e.g. up 0 1 0");
    const glm::dvec3 right = glm::cross(glm::normalize(up), b.n);
    if (glm::length(right) < 1e-12)
        fail("the up vector " + text(camera.up) + " is parallel to the view direction " +
             text(camera.look - camera.eye) + "; choose another up");
    b.u = glm::normalize(right);
    b.v = glm::cross(b.n, b.u);
    if (!(camera.fovDegrees > 0 && camera.fovDegrees < 180))
        fail("fov must be between 0 and 180 degrees (exclusive)");
    b.tanHalfFov = std::tan(glm::radians(camera.fovDegrees) * 0.5);
    b.aspect = double(width) / double(height);
    return b;
}

namespace {

// World bounds of the generic [-1,1]^3 box under an object's transform: a
// conservative box for every finite generic shape this project knows (sphere,
// square, cube; tapered cylinders live in [-1,1]^2 x [0,1]).
void growByObject(const SceneObject& object, glm::dvec3& lo, glm::dvec3& hi) {
    if (object.type == ShapeType::Plane) return;  // infinite: does not frame
    for (const SceneObject& operand : object.operands) growByObject(operand, lo, hi);
    if (!object.operands.empty()) return;
    for (int corner = 0; corner < 8; ++corner) {
        glm::dvec4 p((corner & 1) ? 1 : -1, (corner & 2) ? 1 : -1, (corner & 4) ? 1 : -1, 1);
        glm::dvec3 w = glm::dvec3(object.worldFromObject * p);
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
}

}  // namespace

Camera autoCamera(const Scene& scene) {
    const double inf = std::numeric_limits<double>::infinity();
    glm::dvec3 lo(inf), hi(-inf);
    for (const SceneObject& object : scene.objects) growByObject(object, lo, hi);
    Camera camera;
    glm::dvec3 center(0);
    double radius = 1;
    if (lo.x <= hi.x) {
        center = 0.5 * (lo + hi);
        radius = std::max(0.5 * glm::length(hi - lo), 1e-9);
    }
    const double halfFov = glm::radians(camera.fovDegrees) * 0.5;
    const double distance = radius / std::sin(halfFov) * 1.05;
    camera.look = center;
    camera.eye = center + glm::normalize(glm::dvec3(20, 15, 20)) * distance;
    return camera;
}

PixelSample jitteredSample(int x, int y, const RenderSettings& settings, int k) {
    const int block = std::max(settings.block, 1);
    if (settings.spp <= 1) return primarySample(x, y, block);
    const int x0 = x - x % block, y0 = y - y % block;
    const auto pixel = std::uint32_t(y0) * std::uint32_t(settings.width) + std::uint32_t(x0);
    const auto n = std::uint32_t(settings.spp);
    const double dx = sampling::sampleOffsetX(settings.seed, pixel, std::uint32_t(k), n);
    const double dy = sampling::sampleOffsetY(settings.seed, pixel, std::uint32_t(k), n);
    return {x0 + block * dx, y0 + block * dy};
}

glm::dvec3 primaryDirection(const CameraBasis& camera, const RenderSettings& settings,
                            PixelSample s) {
    const double sx = 2 * s.px / settings.width - 1;   // -1 left .. 1 right
    const double sy = 1 - 2 * s.py / settings.height;  // -1 bottom .. 1 top
    return glm::normalize(-camera.n + sx * camera.tanHalfFov * camera.aspect * camera.u +
                          sy * camera.tanHalfFov * camera.v);
}

std::vector<glm::vec3> hitPoints(const Frame& frame, const CameraBasis& camera,
                                 const RenderSettings& settings) {
    std::vector<glm::vec3> points(frame.pixelCount(), glm::vec3(0));
    for (int y = 0; y < frame.height; ++y) {
        for (int x = 0; x < frame.width; ++x) {
            const size_t i = frame.index(x, y);
            const double t = frame.depth[i];
            if (!std::isfinite(t)) continue;
            points[i] =
                glm::vec3(camera.eye + t * primaryDirection(camera, settings,
                                                            jitteredSample(x, y, settings, 0)));
        }
    }
    return points;
}

int sampleEnd(const RenderSettings& settings) {
    const int end =
        settings.sampleCount > 0 ? settings.firstSample + settings.sampleCount : settings.spp;
    if (settings.firstSample < 0 || settings.sampleCount < 0 || settings.firstSample >= end ||
        end > settings.spp)
        throw Error("render: samples " + std::to_string(settings.firstSample) + " .. " +
                    std::to_string(end - 1) + " are not among the pixel's " +
                    std::to_string(settings.spp));
    return end;
}

PixelSample primarySample(int x, int y, int block) {
    if (block <= 1) return {x + 0.5, y + 0.5};
    const int x0 = x - x % block, y0 = y - y % block;
    return {x0 + 0.5 * block, y0 + 0.5 * block};
}

}  // namespace vkray
