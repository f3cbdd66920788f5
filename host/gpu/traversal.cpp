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
    else {
        bool bounded = false;
        for (const SceneObject& object : scene.objects)
            bounded = bounded || worldBounds(object, scene).finite();
        if (!bounded) cannot = "the scene has no bounded object for an acceleration structure";
    }
    if (asked == Traversal::RayQuery) {
        if (!cannot.empty())
            throw Error("--traversal rayquery: " + cannot + "; render with --traversal own");
        features.rayQuery = true;
        features.objectBvh = true;
        features.meshesInWorld = false;
        features.unrolledObjects = 0;
        features.objectKinds.clear();
        return "ray queries (--traversal rayquery): the driver's acceleration structure over the "
               "objects' world boxes, the shader's own intersections in each";
    }
    if (!cannot.empty()) return "own walk (auto: " + cannot + ")";
    return "own walk (auto: faster than the driver's on every scene class measured, "
           "docs/ray-queries.md)";
}

}  // namespace vkray::gpu
