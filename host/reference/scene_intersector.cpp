// Closest hit over the scene: object BVH and brute force (see scene_intersector.h).
#include "reference/scene_intersector.h"

#include "reference/bvh_walk.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace vkray::reference {
namespace {

// Surfaces that coincide (stacked cubes, an object written twice) are met
// at the same t up to rounding, which would pick between them pixel by pixel.
// Hits this close, relative to t, are a tie, won by the lower object index
// (the GPU does the same with a float-sized tolerance).
constexpr double kTieTolerance = 1e-9;

// Nearest first; within the tie tolerance, the lower object index.
void keepBetter(const std::optional<WorldHit>& hit, std::optional<WorldHit>& best) {
    if (!hit) return;
    if (!best) {
        best = hit;
        return;
    }
    const double band = kTieTolerance * std::max(std::abs(hit->t), std::abs(best->t));
    const bool nearer = hit->t < best->t - band;
    const bool tieWon = std::abs(hit->t - best->t) <= band && hit->object < best->object;
    if (nearer || tieWon) best = hit;
}

}  // namespace

SceneIntersector::SceneIntersector(const Scene& scene, bool bruteForce)
    : scene_(scene), bruteForce_(bruteForce) {
    if (!bruteForce_) bvh_ = buildObjectBvh(scene);
}

std::optional<WorldHit> SceneIntersector::closestHit(const Ray& worldRay, double tMin) const {
    if (bruteForce_) return closestHitBruteForce(scene_, worldRay, tMin);
    std::optional<WorldHit> best;
    const auto test = [&](std::uint32_t index) {
        keepBetter(intersectObject(scene_, scene_.objects[index], int(index), worldRay, tMin),
                   best);
    };
    for (const std::uint32_t index : bvh_.unbounded) test(index);
    // Boxes up to the best t so far and its tie band: a tie may still go to a
    // lower-numbered object further on. The largest finite t rather than inf
    // keeps the slab test of rays parallel to a box face well defined.
    const auto tMax = [&best] {
        return best ? best->t + kTieTolerance * std::abs(best->t)
                    : std::numeric_limits<double>::max();
    };
    walkBvh(bvh_.bvh, worldRay, tMin, tMax, test);
    return best;
}

void SceneIntersector::forEachCandidate(const Ray& worldRay, double tMin, double tMax,
                                        const std::function<bool(int)>& visit) const {
    if (bruteForce_) {
        for (std::size_t i = 0; i < scene_.objects.size(); ++i)
            if (!visit(int(i))) return;
        return;
    }
    for (const std::uint32_t index : bvh_.unbounded)
        if (!visit(int(index))) return;
    // Stopping: a tMax below tMin makes every box left a miss.
    bool stopped = false;
    walkBvh(
        bvh_.bvh, worldRay, tMin, [&] { return stopped ? -1.0 : tMax; },
        [&](std::uint32_t index) {
            if (!stopped) stopped = !visit(int(index));
        });
}

std::optional<WorldHit> closestHit(const Scene& scene, const Ray& worldRay, double tMin) {
    return SceneIntersector(scene).closestHit(worldRay, tMin);
}

std::optional<WorldHit> closestHitBruteForce(const Scene& scene, const Ray& worldRay, double tMin) {
    std::optional<WorldHit> best;
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        keepBetter(intersectObject(scene, scene.objects[i], int(i), worldRay, tMin), best);
    return best;
}

}  // namespace vkray::reference
