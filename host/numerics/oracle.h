// The stress suite's oracle: primary rays intersected in long double (x87
// 80-bit, u = 2^-64 on x86-64 Linux), in each object's generic space, from
// the same Scene the renderers get. The scene's double M^-1 and camera basis
// are taken as exact inputs (docs/numerics-background.md, "Measuring error": the comparison then
// measures the renderers' arithmetic, not the scene's decimal digits).
//
// Besides each pixel's hit, the oracle says how much the answer moves when
// the ray's direction is turned by the rounding a renderer cannot avoid: by
// kBandAngle[float] = 8 u_float or kBandAngle[double] = 8 u_double radians
// toward each of the camera's right, left, up and down. A pixel whose object
// id changes within that band is a silhouette pixel for that arithmetic: no
// renderer working in it can be expected to agree there.
#pragma once

#include "numerics/generic_shapes.h"
#include "scene/camera.h"
#include "scene/scene.h"

#include <glm/vec3.hpp>

#include <vector>

namespace vkray::numerics {

using Real = long double;
using RVec = Vec3<Real>;

// The band half-widths, in radians, for float (index 0) and double (index 1).
inline constexpr double kBandAngle[2] = {8.0 * 0x1p-24, 8.0 * 0x1p-53};

struct OracleRay {
    RVec origin;
    RVec direction;  // unit
};

struct OracleHit {
    Real t = std::numeric_limits<Real>::infinity();
    RVec normal;  // world, unit, facing the ray (as Frame normals do)
    int id = -1;  // scene object index; -1: nothing
};

// Every crossing of one scene object with a world ray, ascending in t (the
// world t when the direction is unit), with the world outward unit normal.
Crossings<Real> objectCrossings(const SceneObject& object, const OracleRay& ray);

// The nearest hit with t > 0 over the scene. Hits within 1e-9 relative of
// each other are a tie (coincident surfaces), won by the lower object index.
OracleHit closestHit(const Scene& scene, const OracleRay& ray);

// The primary ray through image point (px, py) (pixels, y down), as both
// renderers build it, in long double.
OracleRay primaryRay(const CameraBasis& camera, const RenderSettings& settings, Real px, Real py);

// Throws Error at the object's place for what the oracle does not intersect
// (meshes and booleans: the stress suite uses analytic shapes only).
void requireOracleScene(const Scene& scene);

struct OraclePixel {
    OracleHit hit;
    RVec direction;             // the pixel's unit ray direction
    bool silhouette[2] = {};    // [float, double]: the id changes within the band
    double tSpread[2] = {};     // max |t' - t| within the band (same id)
    double normalSpread[2] = {};  // max angle between normals within the band, radians
};

// One OraclePixel per pixel (row-major, row 0 at the top), block 1. Rows are
// shared among `threads` (0: all cores).
std::vector<OraclePixel> renderOracle(const Scene& scene, const CameraBasis& camera,
                                      const RenderSettings& settings, int threads = 0);

// Angle between two directions, accurate at small angles: atan2(|a x b|, a.b).
double angleBetween(const glm::dvec3& a, const glm::dvec3& b);

inline glm::dvec3 toDvec3(const RVec& v) { return {double(v.x), double(v.y), double(v.z)}; }

}  // namespace vkray::numerics
