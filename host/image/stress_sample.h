// StressSample: what a GPU precision mode's own shader found for one pixel's
// first primary ray and the secondary rays of its hit (the stress-output
// variant, shaders/stress_output.glsl), as `vkray stress` counts it and
// `vkray pixel` prints it. Values are those the shader computed, in its own
// arithmetic: float, or double for t and the normal in fp64 (inDouble).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>

namespace vkray {

struct StressSample {
    double t = std::numeric_limits<double>::infinity();  // +inf on a miss
    glm::dvec3 normal{0};   // world unit geometric normal, facing the ray
    int object = -1;        // -1: the background
    bool inDouble = false;  // t and normal computed and returned in double (fp64)
    // Shadow feelers from the hit, bit i for light i (the first 32 lights):
    std::uint32_t feelersTraced = 0;   // traced (the light is on the lit side)
    std::uint32_t feelersMet = 0;      // met a surface before the light
    std::uint32_t feelersMetLeft = 0;  // met the object they left
    // The ray refracted into the hit surface, where the shader follows one.
    bool refractedTraced = false;
    int refractedObject = -1;  // what it met (-1: nothing)
    double refractedT = std::numeric_limits<double>::infinity();
    glm::dvec3 refractedPoint{0};  // where, relative to the eye

    bool feelerTraced(int light) const { return (feelersTraced >> light) & 1u; }
    bool feelerMet(int light) const { return (feelersMet >> light) & 1u; }
    bool feelerMetLeft(int light) const { return (feelersMetLeft >> light) & 1u; }
};

}  // namespace vkray
