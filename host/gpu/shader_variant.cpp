#include "gpu/shader_variant.h"

#include "scene/error.h"
#include "scene/scene_geometry.h"
#include "shaders/layout.h"

#include <bit>

namespace vkray::gpu {

std::uint32_t gpuKindOf(ShapeType type) {
    switch (type) {
    case ShapeType::Sphere: return KIND_SPHERE;
    case ShapeType::Plane: return KIND_PLANE;
    case ShapeType::Square: return KIND_SQUARE;
    case ShapeType::Cube: return KIND_CUBE;
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder: return KIND_TAPERED_CYLINDER;
    case ShapeType::Torus: return KIND_TORUS;
    case ShapeType::Union:
    case ShapeType::Intersection:
    case ShapeType::Difference: return KIND_BOOLEAN;
    default: return KIND_MESH;  // mesh, extrude, the polyhedra, teapot
    }
}

namespace {

void addKinds(const SceneObject& object, ShaderFeatures& features) {
    features.kinds[gpuKindOf(object.type)] = true;
    for (const SceneObject& operand : object.operands) addKinds(operand, features);
}

}  // namespace

ShaderFeatures featuresOf(const Scene& scene, bool allFeatures) {
    ShaderFeatures features;
    for (const SceneObject& object : scene.objects) addKinds(object, features);
    if (allFeatures) features.kinds.fill(true);
    std::size_t bounded = 0;
    for (const SceneObject& object : scene.objects)
        bounded += worldBounds(object, scene).finite() ? 1 : 0;
    features.objectBvh = bounded > kObjectBvhThreshold;
    return features;
}

Defines definesFor(const ShaderFeatures& features, const Defines& userDefines) {
    Defines defines;
    for (std::size_t kind = 0; kind < kGpuKinds.size(); ++kind)
        if (features.kinds[kind]) defines.emplace_back(kGpuKinds[kind].define, "1");
    if (features.objectBvh) defines.emplace_back("VKRAY_OBJECT_BVH", "1");
    if (features.debugPixel) defines.emplace_back("VKRAY_DEBUG_PIXEL", "1");
    defines.insert(defines.end(), userDefines.begin(), userDefines.end());
    return defines;
}

std::string describe(const ShaderFeatures& features) {
    std::string text;
    std::size_t count = 0;
    for (std::size_t kind = 0; kind < kGpuKinds.size(); ++kind) {
        if (!features.kinds[kind]) continue;
        if (!text.empty()) text += '+';
        text += kGpuKinds[kind].name;
        ++count;
    }
    if (count == kGpuKinds.size()) text = "all shapes";
    if (count == 0) text = "no shapes";
    if (features.objectBvh) text += "+bvh";
    if (features.debugPixel) text += "+debug-pixel";
    return text;
}

std::vector<ShaderBinding> bindingsFor(const ShaderFeatures& features) {
    // The same conditions as the #if around each binding in trace.comp and
    // shapes/*.glsl (the test ShaderVariant.BindingsMatchTheSpirv checks).
    std::vector<ShaderBinding> bindings{{BINDING_FRAME, "frame", true},
                                        {BINDING_OBJECTS, "objects", false},
                                        {BINDING_LIGHTS, "lights", false},
                                        {BINDING_PIXELS, "pixels", false}};
    if (features.debugPixel) bindings.push_back({BINDING_DEBUG, "debug record", false});
    if (features.objectBvh) {
        bindings.push_back({BINDING_OBJECT_NODES, "object BVH nodes", false});
        bindings.push_back({BINDING_OBJECT_INDEX, "object BVH index", false});
    }
    if (features.kinds[KIND_MESH]) {
        bindings.push_back({BINDING_MESHES, "meshes", false});
        bindings.push_back({BINDING_MESH_NODES, "mesh BVH nodes", false});
        bindings.push_back({BINDING_TRIANGLES, "triangles", false});
    }
    if (features.kinds[KIND_BOOLEAN]) bindings.push_back({BINDING_CSG_NODES, "CSG nodes", false});
    return bindings;
}

std::vector<ShaderFeatures> allVariants(bool everyCombination) {
    std::vector<ShaderFeatures> variants;
    const unsigned kinds = unsigned(kGpuKinds.size());
    const unsigned all = (1u << kinds) - 1;
    for (unsigned mask = 0; mask <= all; ++mask) {
        const int count = std::popcount(mask);
        // Shape code interacts pairwise at most (CSG calls the others' span
        // functions), so pairs and "all but one" cover what can break.
        if (!everyCombination && count > 2 && count < int(kinds) - 1) continue;
        ShaderFeatures f;
        for (unsigned kind = 0; kind < kinds; ++kind) f.kinds[kind] = (mask >> kind) & 1u;
        for (bool bvh : {false, true}) {
            f.objectBvh = bvh;
            f.debugPixel = false;
            variants.push_back(f);
            // The debug record touches every shape's path: each kind alone, and all.
            if (count == 1 || mask == all) {
                f.debugPixel = true;
                variants.push_back(f);
            }
        }
    }
    return variants;
}

}  // namespace vkray::gpu
