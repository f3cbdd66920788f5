// Precision modes: how much care the GPU renderer takes with
// float arithmetic. Each mode is a set of shader defines plus what the host
// does to the scene, in double, before it is rounded to float:
//
//   naive   the textbook: the plain quadratic formula, unshifted polynomials,
//           slabs without guards, a fixed epsilon (tMin) on every ray, M^-1
//           inverted in float from float M, world coordinates as written.
//   robust  (default) the remedies named in docs/numerics.md: Ray Tracing
//           Gems ch. 7 sphere, shifted cylinder and torus solvers, guarded
//           slabs, M^-1 composed in double from exact inverses, and the world
//           rebased on the eye in double (camera-relative coordinates).
//   fp64    robust, with the ray geometry in double in the shader (the
//           camera, M^-1, ray, generic intersection, t and hit point);
//           shading stays float. Needs the device's shaderFloat64
//           (gpu/gpu_tracer.h refuses it, naming the device, where absent).
#pragma once

#include "render/camera.h"
#include "scene/scene.h"

#include <string>
#include <utility>
#include <vector>

namespace vkray {

enum class Precision { Naive, Robust, Fp64 };

inline constexpr Precision kAllPrecisions[] = {Precision::Naive, Precision::Robust,
                                               Precision::Fp64};

const char* precisionName(Precision precision);  // "naive", "robust", "fp64"

// Parses "naive", "robust" or "fp64"; throws Error naming `flag` otherwise.
Precision parsePrecision(const std::string& flag, const std::string& text);

// The shader defines of a mode (VKRAY_PRECISION_NAIVE=1 for naive,
// VKRAY_PRECISION_FP64=1 for fp64).
std::vector<std::pair<std::string, std::string>> precisionDefines(Precision precision);

// The scene and camera the GPU gets in this mode: for robust and fp64, rebased on the
// eye (every object, light and the camera moved by -eye, in double); for
// naive, each M^-1 replaced by the float inverse of float M. The generic
// ray of every object is unchanged in exact arithmetic, and so are t, normals
// and object ids.
struct GpuInputs {
    Scene scene;
    CameraBasis camera;
};
GpuInputs prepareGpuInputs(Precision precision, const Scene& scene, const CameraBasis& camera);

// The steps of prepareGpuInputs, on their own (tests).
Scene rebasedOnPoint(const Scene& scene, const glm::dvec3& origin);
Scene withFloatInverses(const Scene& scene);

}  // namespace vkray
