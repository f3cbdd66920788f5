// Whitted shading for the CPU reference (Hill ch. 14, docs/shading.md):
// the local model with shadow feelers through transparent occluders,
// textures, and reflected and refracted rays followed recursively down to
// maxRecursionDepth, all in double.
#pragma once

#include "image/pixel_trace.h"
#include "reference/scene_intersector.h"
#include "scene/bvh.h"
#include "scene/scene.h"

#include <glm/vec3.hpp>

#include <array>
#include <optional>
#include <vector>

namespace vkray::reference {

// The media a ray travels in, innermost last: the speeds of light of up to
// kMediumStackSize nested transparent objects it has entered (air, speed 1,
// outside them all). Deeper nesting is counted, but the ray keeps the
// deepest remembered speed (the GPU's bound, shared so both agree).
inline constexpr int kMediumStackSize = 4;
struct Medium {
    std::array<double, kMediumStackSize> speeds{};
    int depth = 0;

    double speed() const;                // c of the medium the ray is in
    Medium entered(double speed) const;  // through the surface of an object of that speed
    Medium left() const;                 // out of the innermost object
};

// Where a secondary ray leaving hit point p in `direction` starts: p moved
// off the surface along the geometric normal n (unit, either side; turned
// to the side the ray leaves to) by max(|p|_inf, 1) * 2^-32. This is Ray
// Tracing Gems ch. 6's idea (an offset that scales with the magnitude of
// the coordinates, as their rounding error does) with double's ulps: about
// 2^20 ulps of |p|, far above the intersectors' error and far below any
// feature of a scene.
inline constexpr double kSecondaryRayOffset = 0x1p-32;
glm::dvec3 offsetRayOrigin(const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& direction);

// Mirror direction of unit d about the unit normal m.
glm::dvec3 reflectDirection(const glm::dvec3& d, const glm::dvec3& m);

// Snell's law for unit d meeting the unit normal m (m.d < 0) with
// eta = c2 / c1 (the ratio of the speeds of light beyond and before the
// surface): the unit transmitted direction, or nothing beyond the critical
// angle (total internal reflection).
std::optional<glm::dvec3> refractDirection(const glm::dvec3& d, const glm::dvec3& m, double eta);

// The material that shades a hit: the surface's own (for a boolean, the
// operand that was hit, as in Hill ch. 14).
const Material& materialOf(const Scene& scene, const WorldHit& hit);

// A GPU mode's error, relative to how far from the eye a ray works (its
// reach: reachOf): where float places a hit and from where a secondary ray
// leaves, how far a ray's direction may turn, and where a texture is
// looked up.
struct ErrorBound {
    double position = 0;           // relative to the ray's reach
    double primaryTilt = 0;        // radians, the primary ray
    double secondaryTilt = 0;      // radians, every secondary ray
    double secondaryPosition = 0;  // a secondary ray's origin: of |origin - eye|
    double texture = 0;            // relative to the hit's reach
    double absolute = 0;           // added to every bound: a fixed epsilon's (naive)
};

// A GPU mode's rounding played on the reference's rays (margins.h): every
// ray of a sample's tree, before it is intersected, moved `side` of it by
// the bound's `position` of its reach (reachOf) and tilted by its tilt; its
// secondary rays leave the surface as the GPU's do (offsetOrigin's step);
// its texture looked up the bound's `texture` of the hit's reach to the
// side; a feeler's blocker within the bound of the light counted
// (feelerSide +1) or not (-1); and, with `runnerUp`, a hit within the bound
// of the closest won by the object of the highest index instead of the
// lowest. Each decision the shader takes can then go the way the GPU's
// rounding may take it.
struct RayPerturbation {
    glm::dvec3 eye{0};  // the GPU's coordinates are the eye's
    ErrorBound bound;
    double angle = 0;      // the side: radians about the ray
    bool sideways = true;  // false: no move, no tilt
    int feelerSide = 1;
    // Where a ray leaves a surface, the GPU's step taken that much further
    // along the new ray (+1) or short of it (-1), in the bound's measure:
    // the step lands in float, rounded as every eye-frame point is.
    int stepAhead = 0;
    bool runnerUp = false;
    // Every object's world box (worldBounds), in scene order: a ray counts
    // an object's reach where it passes within the bound of its box (a
    // sphere's silhouette touches its box).
    const std::vector<Aabb>* boxes = nullptr;
};

// How far from the GPU's origin (the eye) a ray at `origin` works: the
// larger of |origin - eye| and, for each object the ray may meet, its
// generic reach |M^-1 origin| (at least 1) times M's scale (every
// primitive of a boolean): float places a hit to ~u of it.
double reachOf(const Scene& scene, const SceneObject& object, const glm::dvec3& origin);

class WhittedShader {
public:
    // Both must outlive the shader; `intersector` may walk the BVH or not.
    // With `perturbation`, every ray is played as it says (it must outlive
    // the shader too).
    WhittedShader(const Scene& scene, const SceneIntersector& intersector,
                  const RayPerturbation* perturbation = nullptr);

    // What a ray sees: the background where it hits nothing, else Hill's
    // shade() at its hit, `level` deep in the tree of secondary rays (0:
    // primary), travelling in `medium`. `firstHit` receives the ray's own hit
    // (the AOVs); `trace` receives the terms of its hit's local model.
    glm::dvec3 radiance(const Ray& ray, int level, const Medium& medium,
                        std::optional<WorldHit>* firstHit = nullptr,
                        PixelTrace* trace = nullptr) const;

    // The fraction of light at `lightPosition` that reaches `origin` (a
    // feeler origin already off the surface): the product of the
    // transparencies of the objects the feeler meets before the light, each
    // object once (a boolean is one object, with the transparency of the
    // operand met first); 0 from the first opaque one.
    // `surface`: the normal of the surface the feeler leaves (its origin's
    // moves stay along that surface), or null.
    glm::dvec3 lightThrough(const glm::dvec3& origin, const glm::dvec3& lightPosition,
                            const glm::dvec3* surface = nullptr) const;

private:
    // `from`: the origin of the ray that met the hit.
    glm::dvec3 localShade(const WorldHit& hit, const glm::dvec3& from, const Material& material,
                          const glm::dvec3& v, const glm::dvec3& k, PixelTrace* trace) const;
    // The perturbed parts (perturbation_ set).
    double reachAlong(const Ray& ray) const;
    double boundOf(const Ray& ray, int level) const;
    // Moved to a side of the ray by `reach` (and tilted): for a ray that
    // leaves a surface of normal `surface`, along that surface only. A hit
    // point is rounded along its surface; across it, the GPU's offset
    // (offsetOrigin) covers the rounding by design, and a move across would
    // start the ray inside the surface it leaves, which the GPU's never
    // does.
    Ray moved(const Ray& ray, double reach, int level, const glm::dvec3* surface = nullptr) const;
    glm::dvec3 radianceLeaving(const Ray& ray, int level, const Medium& medium,
                               const glm::dvec3* leftNormal, std::optional<WorldHit>* firstHit,
                               PixelTrace* trace) const;
    std::optional<WorldHit> perturbedHit(const Ray& ray, double bound) const;
    // Where a ray along `direction` leaves the hit that a ray from `from`
    // met, on `side`'s side of the surface (a feeler: the shading normal's;
    // else its own direction's).
    glm::dvec3 leave(const WorldHit& hit, const glm::dvec3& from, const glm::dvec3& direction,
                     const glm::dvec3& side) const;
    glm::dvec3 leave(const WorldHit& hit, const glm::dvec3& from,
                     const glm::dvec3& direction) const {
        return leave(hit, from, direction, direction);
    }

    const Scene& scene_;
    const SceneIntersector& intersector_;
    const RayPerturbation* perturbation_;
    int maxDepth_;
};

}  // namespace vkray::reference
