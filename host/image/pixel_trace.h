// PixelTrace: everything one primary ray went through, as `vkray pixel`
// prints it side by side for the GPU and the CPU reference. Like Frame, both
// renderers produce the same record, so they can be compared term by term.
#pragma once

#include <glm/vec3.hpp>

#include <limits>
#include <optional>
#include <vector>

namespace vkray {

struct PixelTrace {
    // Each object of the scene, tested on its own (not only the closest).
    struct ObjectTest {
        glm::dvec3 genericOrigin{0}, genericDirection{0};  // the ray after M^-1
        std::optional<double> t;                           // its nearest hit, if any
    };
    // One light's contribution at the closest hit.
    struct LightTerms {
        double mDotS = 0, mDotH = 0;
        glm::dvec3 diffuse{0}, specular{0};  // the terms added to the colour
        // Its shadow feeler, where one was traced: whether it met a surface
        // before the light, and (where recorded) the object it left.
        std::optional<bool> feelerMet, feelerMetLeft;
    };

    int x = 0, y = 0;  // the pixel
    // Significant digits that show each number as it was computed: 9 for a
    // float, 17 for a double. geometryDigits: t and the normal.
    int digits = 17, geometryDigits = 17;
    glm::dvec3 rayOrigin{0}, rayDirection{0};
    std::vector<ObjectTest> objects;
    int hitObject = -1;  // -1: the background
    double t = std::numeric_limits<double>::infinity();
    glm::dvec3 point{0}, normal{0};
    glm::dvec3 emissive{0}, ambient{0};  // ambient = material ambient * global ambient
    std::vector<LightTerms> lights;
    glm::dvec3 color{0};
};

}  // namespace vkray
