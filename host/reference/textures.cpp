// Solid and image textures, in double, from docs/shading.md, "Textures".
#include "reference/textures.h"

#include "image/image_io.h"
#include "scene/pixmaps.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vkray::reference {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

double fract(double x) {
    return x - std::floor(x);
}

// The angle about the generic z axis, as u in [0, 1].
double aroundZ(const glm::dvec3& g) {
    return 0.5 + std::atan2(g.y, g.x) / kTwoPi;
}

bool isOdd(double whole) {
    return std::fmod(whole, 2.0) != 0;  // fmod keeps the sign: -1 is odd too
}

// Parameter i of the material, or its default when the scene gave fewer.
double parameter(const Material& material, std::size_t i, double fallback) {
    return i < material.textureParameters.size() ? material.textureParameters[i] : fallback;
}

glm::dvec3 oddColor(const Material& material, const glm::dvec3& fallback) {
    return {parameter(material, 1, fallback.r), parameter(material, 2, fallback.g),
            parameter(material, 3, fallback.b)};
}

}  // namespace

glm::dvec3 checkerboard(const glm::dvec3& g, double size, const glm::dvec3& color) {
    // Half a cell of shift puts the generic shapes' faces (0, +-1) inside
    // cells rather than on their borders when size = 1/n.
    const double cell =
        std::floor(g.x / size + 0.5) + std::floor(g.y / size + 0.5) + std::floor(g.z / size + 0.5);
    return isOdd(cell) ? color : glm::dvec3(1);
}

glm::dvec3 woodRings(const glm::dvec3& g, double width, const glm::dvec3& color) {
    // Half a ring of shift, as for the checkerboard's cells: when width = 1/n
    // the generic cylinder's wall (radius 1) and the axis lie mid-ring.
    const double ring = std::floor(std::sqrt(g.x * g.x + g.y * g.y) / width + 0.5);
    return isOdd(ring) ? color : glm::dvec3(1);
}

glm::dvec2 surfaceUv(ShapeType type, const glm::dvec3& g, const glm::dvec3& genericNormal) {
    switch (type) {
    case ShapeType::Sphere:
        return {aroundZ(g), 0.5 + std::asin(std::clamp(g.z, -1.0, 1.0)) / std::numbers::pi};
    case ShapeType::Plane: return {fract(g.x / 2 + 0.5), fract(g.y / 2 + 0.5)};
    case ShapeType::Square: return {(g.x + 1) / 2, (g.y + 1) / 2};
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder: {
        // Caps have the normal +-z; the wall's leans out by at least
        // 1 / (1 + |s - 1|), far above rounding for any sane taper.
        const double side = std::hypot(genericNormal.x, genericNormal.y);
        if (side <= 1e-9 * std::abs(genericNormal.z)) return {(g.x + 1) / 2, (g.y + 1) / 2};
        return {aroundZ(g), g.z};
    }
    case ShapeType::Cube: {
        const glm::dvec3 a = glm::abs(g);
        if (a.x >= a.y && a.x >= a.z) return {(g.y + 1) / 2, (g.z + 1) / 2};
        if (a.y >= a.z) return {(g.x + 1) / 2, (g.z + 1) / 2};
        return {(g.x + 1) / 2, (g.y + 1) / 2};
    }
    case ShapeType::Torus:
        return {aroundZ(g),
                0.5 + std::atan2(g.z, std::hypot(g.x, g.y) - kTorusMajorRadius) / kTwoPi};
    default:  // meshes, polyhedra, teapot, extrusions
        return {fract((g.x + 1) / 2), fract((g.y + 1) / 2)};
    }
}

glm::dvec3 nearestTexel(const Image& image, glm::dvec2 uv) {
    const double u = fract(uv.x), v = std::clamp(uv.y, 0.0, 1.0);
    const int x = std::clamp(int(std::floor(u * image.width)), 0, image.width - 1);
    const int y = std::clamp(int(std::floor((1 - v) * image.height)), 0, image.height - 1);
    const float* texel =
        &image.pixels[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) *
                      std::size_t(image.channels)];
    return {texel[0], texel[1], texel[2]};
}

glm::dvec3 textureColor(const Scene& scene, const SceneObject& surface, const glm::dvec3& p,
                        const glm::dvec3& worldNormal) {
    const Material& material = surface.material;
    if (material.texture == 0) return glm::dvec3(1);
    const glm::dvec3 g = glm::dvec3(surface.objectFromWorld * glm::dvec4(p, 1));
    switch (material.texture) {
    case 1:
        return checkerboard(g, parameter(material, 0, 0.5),
                            oddColor(material, glm::dvec3(0, 0, 0)));
    case 2:
        return woodRings(g, parameter(material, 0, 0.1),
                         oddColor(material, glm::dvec3(0.55, 0.35, 0.15)));
    case 3: {
        // The world normal is (M^-1)^T n_generic, so M^T takes it back.
        const glm::dvec3 genericNormal =
            glm::transpose(glm::dmat3(surface.worldFromObject)) * worldNormal;
        const Pixmap* pixmap = findPixmap(scene, pixmapIndexOf(material));
        if (!pixmap) return glm::dvec3(1);  // loadPixmaps refused or dropped it already
        return nearestTexel(*pixmap->image, surfaceUv(surface.type, g, genericNormal));
    }
    default: return glm::dvec3(1);  // the reader accepts 0..3 only
    }
}

}  // namespace vkray::reference
