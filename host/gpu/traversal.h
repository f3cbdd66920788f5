// Which walk finds the objects a ray meets: vkray's own BVH walk in GLSL, or
// the driver's acceleration structure through VK_KHR_ray_query, the shader's
// own intersection run on each box the driver reports (docs/ray-queries.md).
#pragma once

#include "gpu/context.h"
#include "gpu/shader_variant.h"
#include "scene/scene.h"

#include <string>

namespace vkray::gpu {

enum class Traversal { Own, RayQuery, Auto };

const char* traversalName(Traversal traversal);  // "own", "rayquery", "auto"

// Parses "own", "rayquery" or "auto"; throws Error naming `flag` otherwise.
Traversal parseTraversal(const std::string& flag, const std::string& text);

// Sets features.rayQuery as `asked`, the device and the scene decide, with
// what the ray-query walk needs beside it (the object BVH's entries, meshes
// walked in their own space, no feeler hints); returns why, for `vkray
// features`. Throws Error where rayquery is asked for and cannot run: the
// device lacks ray queries, the scene has no bounded object, or the variant
// records every object test (stress output, debug pixel), as only the own
// walk makes them.
std::string chooseTraversal(Traversal asked, const DeviceInfo& device, const Scene& scene,
                            ShaderFeatures& features);

}  // namespace vkray::gpu
