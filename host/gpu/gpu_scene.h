// The scene as the shader reads it: the std430 arrays of shaders/layout.h,
// packed from the double-precision Scene (M^-1 rounded to float only here).
// Everything the shader bounds (BVH depth, CSG spans and stack) is checked
// here, so a scene beyond a bound is refused with its place before rendering.
#pragma once

#include "gpu/shader_variant.h"
#include "render/camera.h"
#include "scene/bvh.h"
#include "scene/scene.h"
#include "shaders/layout.h"

#include <optional>
#include <vector>

namespace vkray::gpu {

struct GpuScene {
    std::vector<GpuObjectGeometry> objects;      // the scene's objects (ids), then CSG primitives
    std::vector<GpuMaterial> materials;          // theirs, in the same order
    std::vector<GpuDoubleObject> doubleObjects;  // the same in double (fp64 variant)
    std::vector<GpuLight> lights;
    // features.objectBvh: nodes over the bounded objects; objectIndex holds
    // the leaves' object indices, then the unbounded objects'.
    std::vector<GpuBvhNode> objectNodes;
    std::vector<uint> objectIndex;
    uint unboundedFirst = 0, unboundedCount = 0;
    std::optional<Bvh> objectBvh;  // the same nodes in double (a primary cover's boxes)
    // features.kinds[KIND_MESH]:
    std::vector<GpuMesh> meshes;  // indexed like Scene::meshes
    // Their nodes, or none where they follow objectNodes (meshNodesWithObjects).
    std::vector<GpuBvhNode> meshNodes;
    std::vector<GpuTriangle> triangles;
    // features.kinds[KIND_BOOLEAN]: every tree in post order.
    std::vector<GpuCsgNode> csgNodes;
    // Shading::Pixmaps: one entry per Scene::pixmaps slot, and their texels.
    std::vector<GpuPixmap> pixmaps;
    std::vector<float> texels;
};

GpuScene packScene(const Scene& scene, const ShaderFeatures& features);

// The camera of FrameParams in double (fp64 variant).
GpuDoubleCamera packDoubleCamera(const CameraBasis& camera);

// Entries of one ray's pending-ray stack (reflection and refraction
// variants): taking a ray adds at most two one level deeper, so
// maxRecursionDepth + 1 hold the deepest tree.
inline int pendingRayEntries(const Scene& scene) {
    return scene.maxRecursionDepth + 1;
}

FrameParams packFrame(const Scene& scene, const GpuScene& packed, const CameraBasis& camera,
                      const RenderSettings& settings);

}  // namespace vkray::gpu
