// The closest hit of a ray over a whole scene: through the BVH over the
// objects' world bounds (scene_geometry.h), with the unbounded objects
// (planes, booleans around them) tested for every ray; and by brute force,
// the oracle the BVH is tested against.
#pragma once

#include "reference/object_intersect.h"
#include "scene/scene.h"
#include "scene/scene_geometry.h"

#include <functional>
#include <optional>

namespace vkray::reference {

// Built once per render (the BVH over the objects), then shared by every
// thread: closestHit is const and keeps no state between rays. The scene
// must outlive it.
class SceneIntersector {
public:
    explicit SceneIntersector(const Scene& scene, bool bruteForce = false);

    // The nearest hit with t > tMin. Hits within 1e-9 t of each other are a
    // tie (coinciding surfaces), won by the lower object index, as
    // closestHitBruteForce decides, whatever order the BVH meets them in.
    std::optional<WorldHit> closestHit(const Ray& worldRay, double tMin) const;

    // Calls visit(index) once for each object the ray might meet within
    // (tMin, tMax): the unbounded ones, then those whose world box the ray
    // crosses there (every object by brute force). Stops when visit returns
    // false. Shadow feelers test each candidate on its own (intersectObject).
    void forEachCandidate(const Ray& worldRay, double tMin, double tMax,
                          const std::function<bool(int)>& visit) const;

private:
    const Scene& scene_;
    ObjectBvh bvh_;
    bool bruteForce_;
};

// One-off conveniences: closestHit builds the object BVH for this one ray
// (tests and single rays; render() builds a SceneIntersector once).
std::optional<WorldHit> closestHit(const Scene& scene, const Ray& worldRay, double tMin);
std::optional<WorldHit> closestHitBruteForce(const Scene& scene, const Ray& worldRay, double tMin);

}  // namespace vkray::reference
