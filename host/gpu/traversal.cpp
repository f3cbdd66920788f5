#include "gpu/traversal.h"

#include "scene/scene_geometry.h"
#include "util/error.h"

namespace vkray::gpu {

const char* traversalName(Traversal traversal) {
    switch (traversal) {
    case Traversal::Own: return "own";
    case Traversal::RayQuery: return "rayquery";
    case Traversal::Auto: return "auto";
    }
    return "?";
}

Traversal parseTraversal(const std::string& flag, const std::string& text) {
    for (Traversal t : {Traversal::Own, Traversal::RayQuery, Traversal::Auto})
        if (text == traversalName(t)) return t;
    throw Error(flag + " '" + text + "': expected own, rayquery or auto");
}

std::string chooseTraversal(Traversal asked, const DeviceInfo& device, const Scene& scene,
                            ShaderFeatures& features) {
    features.rayQuery = false;
    if (asked == Traversal::Own) return "own walk (--traversal own)";
    std::string cannot;
    if (!device.rayQuery)
        cannot = "the device " + std::to_string(device.index) + " (" + device.name +
                 ") has no ray queries (VK_KHR_ray_query and VK_KHR_acceleration_structure; "
                 "lavapipe has them from Mesa 24.1)";
    else if (features.stressOutput || features.debugPixel)
        cannot = "the stress and debug records count every object test as the own walk makes it";
    std::size_t bounded = 0;
    bool booleans = false;
    for (const SceneObject& object : scene.objects) {
        bounded += worldBounds(object, scene).finite() ? 1 : 0;
        booleans = booleans || isBoolean(object.type);
    }
    if (cannot.empty() && bounded == 0)
        cannot = "the scene has no bounded object for an acceleration structure";
    const auto takeRayQueries = [&] {
        features.rayQuery = true;
        features.objectBvh = true;
        features.meshesInWorld = false;
        features.unrolledObjects = 0;
        features.objectKinds.clear();
    };
    if (asked == Traversal::RayQuery) {
        if (!cannot.empty())
            throw Error("--traversal rayquery: " + cannot + "; render with --traversal own");
        takeRayQueries();
        return "ray queries (--traversal rayquery): the driver's acceleration structure over the "
               "objects' world boxes, the shader's own intersections in each";
    }
    if (!cannot.empty()) return "own walk (auto: " + cannot + ")";
    // The class where the benchmark found ray queries the faster (BENCHMARKS.md):
    // booleans among a few objects, too few for an object BVH, where the own
    // walk tests every object on every ray and the driver's boxes spare the
    // tests of the booleans a ray misses. Measured on lavapipe only.
    if (device.type != "CPU")
        return "own walk (auto: ray queries were measured against it on lavapipe only)";
    if (booleans && !features.objectBvh && bounded >= 2) {
        takeRayQueries();
        return "ray queries (auto: booleans among " + std::to_string(bounded) +
               " bounded objects and no object BVH, the class where the driver's boxes measured "
               "faster than testing every object; --traversal own for the own walk)";
    }
    return "own walk (auto: ray queries measured no faster on this class of scene, "
           "docs/ray-queries.md)";
}

}  // namespace vkray::gpu
