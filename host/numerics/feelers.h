// Secondary rays replayed on the CPU, from the hit points a GPU precision
// mode rendered, to count per pixel what the shader's own secondary rays
// suffer (the shader traces them, but returns only the pixel's colour):
//
//   shadowFeelerAcne      a feeler (unit direction, t up to the light's distance)
//                         from each hit toward each light that lights
//                         it (n.s > 0 for both the mode's and the oracle's
//                         normal) that hits the surface it starts on, where
//                         the exact feeler from the exact point does not: acne.
//   refractionExitErrors  the ray refracted into the hit object (index 1.5)
//                         must leave it where the oracle says, to 1e-3 of the
//                         eye's distance (a pixel's footprint is ~1.6e-3 of
//                         it); re-hitting the entry surface (t below half the
//                         exit's) or missing the exit fails.
//
// Replayed as the mode's shader does: hit point p = eye + t d in the mode's
// world (rebased on the eye for robust and fp64), the object's M^-1 (float
// inverse for naive), the origin moved off the surface as offsetOrigin() of
// shaders/precision.glsl does (fixed epsilon 1e-4 with tMin 1e-4 for naive,
// after Ray Tracing Gems ch. 6 for robust, its double form for fp64), and
// intersected with the robust formulas of numerics/generic_shapes.h, in
// IEEE single (no contraction), or double for fp64.
#pragma once

#include "numerics/oracle.h"
#include "numerics/precision.h"
#include "numerics/stress_suite.h"

#include <cstddef>
#include <vector>

namespace vkray::numerics {

struct FeelerStats {
    std::size_t traced = 0;  // pixels with at least one secondary ray
    std::size_t failed = 0;  // pixels where one of them failed
    std::vector<std::size_t> failedPixels;  // those pixels' indices (row-major), ascending
};

// Only pixels where the mode and the oracle hit the same object outside the
// float band are used.
FeelerStats shadowFeelerAcne(const Scene& scene, const CameraBasis& camera,
                             const std::vector<OraclePixel>& oracle,
                             const std::vector<ModeSample>& samples, Precision precision);

FeelerStats refractionExitErrors(const Scene& scene, const CameraBasis& camera,
                                 const std::vector<OraclePixel>& oracle,
                                 const std::vector<ModeSample>& samples, Precision precision);

// Robust mode's secondary-ray origin (shaders/precision.glsl offsetOrigin):
// p moved off the surface (along n) by OFFSET_SCALE times its largest
// coordinate, or by OFFSET_NEAR_ORIGIN_STEP near the origin, and by at least
// OFFSET_GENERIC_SCALE times genericScale (the world length along n of the
// object's generic rounding unit: shaders/shade.glsl genericScaleAlong); that
// step taken along the new ray's direction `along` as far as
// OFFSET_MAX_FORWARD steps do it, the rest along n. n is the geometric normal
// on the side the new ray leaves from.
Vec3<float> offsetRayOriginRobust(Vec3<float> p, Vec3<float> n, Vec3<float> along,
                                  float genericScale = 0);

}  // namespace vkray::numerics
