// The stress suite's oracle: primary rays intersected in float128 (Boost
// .Multiprecision, 113 bits) with rigorous error bounds, in each object's
// generic space, shape by shape from their implicit equations
// (numerics/exact_shapes.h), from the same Scene the renderers get. The
// scene's double M^-1 and camera basis are taken as exact inputs
// (docs/numerics-background.md, "Measuring error": the comparison then
// measures the renderers' arithmetic, not the scene's decimal digits).
//
// Its error bound: every t is certified to lie within tBound of the exact
// intersection of the exact ray (the inputs' own rounding to float128
// included); where it cannot tell (a tangent ray, a point on an edge or rim
// within its bounds, a tie it cannot order) the hit is marked uncertain.
//
// For each pixel it also gives what the stress verdicts are measured
// against (stress_suite.h): the conditioning of t and of the normal at the
// hit, and the set-aside of pixels whose footprint straddles an edge: whose
// ray, turned by the footprint a renderer's rounding allows, meets another
// object.
#pragma once

#include "numerics/exact_shapes.h"
#include "render/camera.h"
#include "scene/scene.h"

#include <glm/vec3.hpp>

#include <limits>
#include <vector>

namespace vkray::numerics {

using Real = Quad;
using RVec = QVec;

// How a renderer computes, for its allowances and footprint: in float
// (naive, robust), in double from the world rebased on the eye (fp64), or in
// double from the world as the scene writes it (the CPU reference).
enum Arithmetic { kFloat = 0, kDouble = 1, kDoubleAsWritten = 2 };
inline constexpr double kUnitRoundoff[3] = {0x1p-24, 0x1p-53, 0x1p-53};

// The footprint's multiple of the rounding a renderer's ray suffers (below).
inline constexpr double kFootprintMultiple = 8;

struct OracleRay {
    BVec origin;
    BVec direction;  // unit, within its bounds
};

OracleRay exactRay(const glm::dvec3& origin, const glm::dvec3& direction);

struct OracleHit {
    Quad t = std::numeric_limits<Quad>::infinity();
    Quad tBound = 0;         // |t - t exact| <= tBound
    QVec normal;             // world, unit, facing the ray (as Frame normals do)
    int id = -1;             // scene object index; -1: nothing
    bool entering = false;   // the ray enters the object's solid there (against its outward normal)
    bool uncertain = false;  // the oracle cannot tell (a tangent, an edge, a tie)
    QVec genericNormal;      // unit, outward, in the object's generic space
    double curvature = 0;    // the generic surface's largest curvature there
};

// Every crossing of one scene object with a world ray, ascending in t, with
// world outward unit normals (none where the line certainly misses the
// object's generic bounding ball).
struct WorldCrossing {
    Quad t, tBound;
    QVec normal;         // world, outward, unit
    QVec genericNormal;  // generic, outward, unit
    double curvature;
    CrossingKind kind;
};
std::vector<WorldCrossing> objectCrossings(const SceneObject& object, const OracleRay& ray);

// The world length, along the world normal at a hit on `object` with unit
// generic normal n, of the size of its generic coordinates there (the
// shape's extent, below): extent / |A^T n|.
double genericScaleAlong(const SceneObject& object, const QVec& genericNormal);

// The nearest hit with t > tMin over the scene. Hits within 1e-9 relative of
// each other are a tie (coincident surfaces), won by the lower object index.
OracleHit closestHit(const Scene& scene, const OracleRay& ray, const Quad& tMin = 0);

// Whether the ray meets `object` at some t in (tMin, tMax).
enum class Meets { No, Yes, Uncertain };
Meets meets(const SceneObject& object, const OracleRay& ray, const Quad& tMin, const Quad& tMax);

// The primary ray through image point (px, py) (pixels, y down), as both
// renderers build it.
OracleRay primaryRay(const CameraBasis& camera, const RenderSettings& settings, double px,
                     double py);

// Throws Error at the object's place for what the oracle does not intersect
// (meshes and booleans: the stress suite uses analytic shapes only).
void requireOracleScene(const Scene& scene);

// How sensitive a pixel's answer is to the rounding of the renderer that
// computes it, from the hit object's generic quantities: the generic origin
// o = A eye + b (A, b: M^-1's rows), direction d = A w (w the unit world ray),
// t, the unit generic normal n at p = o + t d, the shape's extent e (its
// generic coordinates' size: 1; a tapered cylinder's sqrt(2 max(1, s^2) + 1),
// the torus's R + r; 0 for a plane), its largest generic curvature k there,
//   alphaD = |(|A| |w|)|           the size of what d is computed from, and
//   alphaO = |(|A| |eye| + |b|)|   of what o is computed from, in the world
//                                   as the scene writes it.
// A renderer of unit roundoff u that is exact to a few roundings of every
// quantity it computes (o, d, the generic point of size e) perturbs the hit
// point by about u (|o| + t (alphaD + |d|) + e) along the normal, and so t
// by that over |n.d|:
//   t = (|o| + t (alphaD + |d|) + e) / (t |n.d|)   relative.
// One that forms o from the world's coordinates as written (the CPU
// reference; naive, in float) also pays u_double alphaO for it, which the
// rebased modes do not (the host rebases in compensated arithmetic):
//   tWorld = alphaO / (t |n.d|).
// The normal turns by the curvature times the point's tangential error (the
// perturbation and its move along the ray: (1 + 1 / cos) times it, cos =
// |n.d| / |d|) and is mapped to the world by normalize(A^T n), whose
// sensitivity (and rounding) is at most J = ||A||_F / |A^T n|:
//   normal = J (1 + k t |d| (1 + cos) t),  normalWorld = J k t |d| (1 + cos) tWorld.
// The stress verdicts allow C (u t + u_double tWorld) and the same for the
// normal, tWorld only for a renderer working as written (stress_suite.h).
struct Conditioning {
    double t = 0, tWorld = 0;
    double normal = 0, normalWorld = 0;
};

struct OraclePixel {
    OracleHit hit;
    RVec direction;             // the pixel's unit ray direction
    Conditioning conditioning;  // at the hit (zero on a miss)
    // By Arithmetic: the pixel is set aside: its footprint straddles an edge
    // (the ray turned by the footprint meets another object, or the oracle
    // cannot tell there). The footprint is kFootprintMultiple times the angle
    // a renderer's rounding can turn its ray by, for each object the pixel
    // and its 8 neighbours meet: u (2 + e / |o| + alphaD / |d|) radians, and
    // u_d alphaO / |o| more as written. Only pixels beside an id change are
    // tried.
    bool setAside[3] = {};
    bool besideEdge = false;  // a neighbour's id differs (where the set-aside is tried)
};

// One OraclePixel per pixel (row-major, row 0 at the top), block 1. Rows are
// shared among `threads` (0: all cores).
std::vector<OraclePixel> renderOracle(const Scene& scene, const CameraBasis& camera,
                                      const RenderSettings& settings, int threads = 0);

// Angle between two directions, accurate at small angles: atan2(|a x b|, a.b).
double angleBetween(const glm::dvec3& a, const glm::dvec3& b);

inline glm::dvec3 toDvec3(const RVec& v) {
    return {double(v.x), double(v.y), double(v.z)};
}

}  // namespace vkray::numerics
