// The secondary rays of each pixel's primary hit, as the mode's own shader
// traced them (its stress output, image/stress_sample.h), against the
// oracle's exact ones from the exact hit point:
//
//   acne          a shadow feeler that met the object it left, where the
//                 exact feeler from the exact point meets that object nowhere
//                 before the light (self-intersection);
//   shadow flips  a feeler that did not meet the object it left whose
//                 verdict (met a surface or not) differs from the exact
//                 feeler's, where the other objects decide the exact feeler
//                 the same from the mode's own hit point (else the primary t
//                 error, judged on its own, explains it) and from the exact
//                 point moved by the mode's origin footprint either way along
//                 the normal (else the offset, which every secondary ray
//                 starts at by design, does): else a shadow edge, set aside,
//                 as are feelers the oracle cannot decide;
//   exit errors   the ray refracted into the hit surface (Snell's law with the
//                 object's speedOfLight, entering from air) met the entry
//                 surface again (t short of half the exact exit's), met
//                 nothing or another object, or left more than a pixel's
//                 footprint (1e-3 of the primary t) from the exact exit point.
//
// Only pixels where the mode and the oracle hit the same object, outside the
// set-aside (oracle.h), and only lights on the lit side for both are compared.
#pragma once

#include "gpu/precision.h"
#include "image/stress_sample.h"
#include "numerics/oracle.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <cstddef>
#include <vector>

namespace vkray::numerics {

struct SecondaryStats {
    std::size_t feelerPixels = 0;  // pixels with at least one feeler compared
    std::size_t acne = 0;          // pixels with a self-intersecting feeler
    std::size_t shadowFlips = 0;   // pixels with a feeler verdict unexplained
    std::size_t shadowEdges = 0;   // pixels whose verdict the primary t error explains
    std::size_t refracted = 0;     // pixels whose refracted ray was compared
    std::size_t exitErrors = 0;
    std::vector<std::size_t> failedPixels;  // with acne, a shadow flip or an exit error, ascending
};

// How far a mode's secondary rays start from the surface, at most (twice
// its offset, shaders/precision.glsl): `relative` times the larger of the
// point's largest coordinate in the eye's frame and the object's generic
// scale along the normal (oracle.h genericScaleAlong), plus `absolute`.
struct OriginFootprint {
    double relative = 0, absolute = 0;
};
OriginFootprint originFootprintOf(Precision precision);

// `a`: the mode's arithmetic, whose set-aside (oracle.h) is left out.
SecondaryStats checkSecondaryRays(const Scene& scene, const CameraBasis& camera,
                                  const std::vector<OraclePixel>& oracle,
                                  const std::vector<StressSample>& samples, Arithmetic a,
                                  const OriginFootprint& footprint, int threads);

}  // namespace vkray::numerics
