#include "gpu/shader_variant.h"

#include "gpu/context.h"

#include "scene/scene_geometry.h"
#include "scene/triangle_mesh.h"
#include "shaders/layout.h"
#include "util/error.h"

#include <algorithm>
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

// The shape kinds and the material features of an object and its operands.
void addObject(const Scene& scene, const SceneObject& object, ShaderFeatures& features) {
    features.kinds[gpuKindOf(object.type)] = true;
    const Material& m = object.material;
    const bool recursion = scene.maxRecursionDepth > 0;
    if (recursion && m.reflectivity > scene.minReflectivity)
        features.shading[size_t(Shading::Reflection)] = true;
    if (recursion && m.transparency > scene.minTransparency)
        features.shading[size_t(Shading::Refraction)] = true;
    const uint texture = uint(m.texture);
    if (texture == TEXTURE_CHECKERBOARD || texture == TEXTURE_WOOD)
        features.shading[size_t(Shading::Textures)] = true;
    if (texture == TEXTURE_IMAGE) features.shading[size_t(Shading::Pixmaps)] = true;
    for (const SceneObject& operand : object.operands) addObject(scene, operand, features);
}

// Whether a feeler from some lit point can meet an object: always, but for
// a lone plane or square, which a feeler leaving it never meets again. A
// lone sphere or cube can shadow itself: seen from inside (the eye inside,
// or a refracted ray), a point of its inner surface facing a light outside
// sees the light through the rest of the surface.
bool canShadow(const Scene& scene) {
    if (scene.lights.empty() || scene.objects.empty()) return false;
    if (scene.objects.size() > 1) return true;
    const ShapeType type = scene.objects[0].type;
    return type != ShapeType::Plane && type != ShapeType::Square;
}

}  // namespace

bool tracesInOnePass(const ShaderFeatures& f) {
    return !f.has(Shading::Reflection) && !f.has(Shading::Refraction) && !f.has(Shading::Antialias);
}

bool keepsTori(const ShaderFeatures& features) {
    const auto& k = features.kinds;
    return k[KIND_TORUS] && (k[KIND_SPHERE] || k[KIND_PLANE] || k[KIND_SQUARE] || k[KIND_CUBE] ||
                             k[KIND_TAPERED_CYLINDER] || k[KIND_MESH]);
}

bool hintsFeelers(const ShaderFeatures& features) {
    return features.has(Shading::Shadows) && features.objectBvh && !features.unbounded &&
           !features.stressOutput && !features.debugPixel && !features.rayQuery;
}

bool meshesFitWorldSpace(const Scene& scene, const glm::dvec3& eye, std::uint64_t maxTexels) {
    std::size_t triangles = 0;
    std::vector<const SceneObject*> meshObjects;
    for (const SceneObject& object : scene.objects) {
        if (isBoolean(object.type) || gpuKindOf(object.type) != KIND_MESH) continue;
        if (object.mesh < 0 || std::size_t(object.mesh) >= scene.meshes.size() ||
            object.material.transparency != 0)
            return false;
        meshObjects.push_back(&object);
        triangles += scene.meshes[std::size_t(object.mesh)]->triangles.size();
        if (triangles > kWorldTrianglesMax) return false;
    }
    if (meshObjects.empty()) return false;
    std::size_t own = 0;
    for (const auto& mesh : scene.meshes) own += mesh->triangles.size();
    if (std::uint64_t(triangles + own) * TRIANGLE_TEXELS > maxTexels) return false;
    Aabb reached;  // the eye and every bounded object
    reached.grow(eye);
    for (const SceneObject& object : scene.objects) {
        const Aabb box = worldBounds(object, scene);
        if (box.finite()) reached.grow(box);
    }
    for (const SceneObject* object : meshObjects) {
        const Aabb box = worldBounds(*object, scene);
        if (!box.finite()) return false;
        const glm::dvec3 centre = box.centroid();
        const glm::dvec3 farthest =
            glm::max(glm::abs(reached.lo - centre), glm::abs(reached.hi - centre));
        if (!(glm::length(farthest) <= kWorldSpaceReach * glm::length(box.hi - box.lo)))
            return false;
    }
    return true;
}

void placeMeshesInWorldWhereTheyFit(const Scene& scene, const glm::dvec3& eye,
                                    std::uint64_t maxTexels, ShaderFeatures& features) {
    if (!meshesFitWorldSpace(scene, eye, maxTexels)) return;
    features.meshesInWorld = true;
    features.objectBvh = true;
    features.unrolledObjects = 0;
    features.objectKinds.clear();
}

bool placesTrianglesInWorld(const ShaderFeatures& features) {
    return features.meshesInWorld && features.objectBvh && !features.stressOutput &&
           !features.debugPixel && !features.rayQuery;
}

ShaderFeatures featuresOf(const Scene& scene, const RenderSettings& settings, bool allFeatures) {
    ShaderFeatures features;
    features.aovs = settings.aovs;
    for (const SceneObject& object : scene.objects) addObject(scene, object, features);
    features.shading[size_t(Shading::Shadows)] = canShadow(scene);
    features.lights = !scene.lights.empty() || allFeatures;
    features.shading[size_t(Shading::Antialias)] = settings.spp > 1;
    // A loop fills a ray's block; every loop costs a turn on llvmpipe, needed or not.
    features.blocks = settings.block > 1 || allFeatures;
    if (allFeatures) {
        features.kinds.fill(true);
        features.shading.fill(true);
    }
    std::size_t bounded = 0;
    bool meshObjects = false;
    for (const SceneObject& object : scene.objects) {
        const Aabb box = worldBounds(object, scene);
        bounded += box.finite() ? 1 : 0;
        features.unbounded = features.unbounded || (!box.empty() && !box.finite());
        meshObjects = meshObjects || gpuKindOf(object.type) == KIND_MESH;
    }
    // Mesh objects go through the BVH however few the objects: their walks
    // are the walk's own there (VKRAY_MESH_INSTANCES), entered only where
    // the ray comes near, not each one a loop inside every object test.
    features.objectBvh = bounded > kObjectBvhThreshold || (meshObjects && bounded > 1);
    // On lavapipe a loop over a count read at run time costs several object
    // tests on every ray (BENCHMARKS.md); a constant count is unrolled, each
    // test holding its object's shape's code alone. Tori and CSG objects
    // unrolled are only put on the list of objects tested after the others
    // (one copy of their code); a mesh's walk, or a torus that is not kept,
    // would be compiled eight times: those keep the loop, unless alone.
    const bool unrollable =
        scene.objects.size() == 1 ||
        (!features.kinds[KIND_MESH] && (!features.kinds[KIND_TORUS] || keepsTori(features)));
    if (!allFeatures && !features.objectBvh && unrollable &&
        scene.objects.size() <= kObjectBvhThreshold) {
        features.unrolledObjects = std::uint32_t(scene.objects.size());
        for (const SceneObject& object : scene.objects)
            features.objectKinds.push_back(gpuKindOf(object.type));
    }
    return features;
}

Defines definesFor(const ShaderFeatures& features, const Defines& userDefines) {
    // Every flag, 0 or 1: trace.comp refuses to compile without one
    // (shaders/variant_flags.glsl), so a flag cannot go missing in silence.
    const auto flag = [](bool on) { return on ? "1" : "0"; };
    Defines defines;
    for (std::size_t kind = 0; kind < kGpuKinds.size(); ++kind)
        defines.emplace_back(kGpuKinds[kind].define, flag(features.kinds[kind]));
    for (std::size_t i = 0; i < kGpuShading.size(); ++i)
        defines.emplace_back(kGpuShading[i].define, flag(features.shading[i]));
    // Shadows are feelers toward lights: they bring the light code in.
    defines.emplace_back("VKRAY_LIGHTS", flag(features.lights || features.has(Shading::Shadows)));
    defines.emplace_back("VKRAY_OBJECT_BVH", flag(features.objectBvh));
    defines.emplace_back("VKRAY_BLOCKS", flag(features.blocks));
    defines.emplace_back("VKRAY_AOVS", flag(features.aovs));
    defines.emplace_back("VKRAY_DEBUG_PIXEL", flag(features.debugPixel));
    defines.emplace_back("VKRAY_STRESS_OUTPUT", flag(features.stressOutput));
    defines.emplace_back("VKRAY_KEEP_TORI", flag(keepsTori(features)));
    defines.emplace_back("VKRAY_FEELER_HINTS", flag(hintsFeelers(features)));
    defines.emplace_back("VKRAY_WORLD_TRIANGLES", flag(placesTrianglesInWorld(features)));
    defines.emplace_back("VKRAY_RAY_QUERY", flag(features.rayQuery));
    defines.emplace_back("VKRAY_OBJECTS", std::to_string(features.unrolledObjects));
    if (features.unrolledObjects > 0) {
        std::string kinds;
        for (const std::uint32_t kind : features.objectKinds)
            kinds += (kinds.empty() ? "" : ",") + std::to_string(kind) + "u";
        defines.emplace_back("VKRAY_OBJECT_KINDS", kinds);
    }
    // A test hook, never set otherwise (gpu/context.h, VKRAY_FAULT=no-offset).
    defines.emplace_back("VKRAY_FAULT_NO_OFFSET", flag(injectedFault() == Fault::NoOffset));
    defines.insert(defines.end(), userDefines.begin(), userDefines.end());
    return defines;
}

std::vector<std::string> variantFlags() {
    std::vector<std::string> flags;
    for (const GpuKind& kind : kGpuKinds) flags.push_back(kind.define);
    for (const GpuShading& shading : kGpuShading) flags.push_back(shading.define);
    for (const char* other :
         {"VKRAY_LIGHTS", "VKRAY_OBJECT_BVH", "VKRAY_BLOCKS", "VKRAY_AOVS", "VKRAY_DEBUG_PIXEL",
          "VKRAY_STRESS_OUTPUT", "VKRAY_FAULT_NO_OFFSET", "VKRAY_PRECISION_NAIVE",
          "VKRAY_PRECISION_FP64", "VKRAY_KEEP_TORI", "VKRAY_FEELER_HINTS", "VKRAY_WORLD_TRIANGLES",
          "VKRAY_RAY_QUERY", "VKRAY_OBJECTS"})
        flags.push_back(other);
    return flags;
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
    const auto shading = std::count(features.shading.begin(), features.shading.end(), true);
    if (shading == std::ssize(features.shading))
        text += "+all shading";
    else
        for (std::size_t i = 0; i < kGpuShading.size(); ++i)
            if (features.shading[i]) text += std::string("+") + kGpuShading[i].name;
    if (features.objectBvh) text += "+bvh";
    if (features.blocks) text += "+blocks";
    if (features.aovs) text += "+aovs";
    if (features.debugPixel) text += "+debug-pixel";
    if (features.stressOutput) text += "+stress-output";
    if (features.doubles) text += "+fp64";
    if (placesTrianglesInWorld(features)) text += "+world-triangles";
    if (features.rayQuery) text += "+ray-query";
    return text;
}

std::vector<ShaderBinding> bindingsFor(const ShaderFeatures& features) {
    // The same conditions as the #if around each binding in trace.comp and
    // the files it includes (the test ShaderVariant.BindingsMatchTheSpirv checks).
    using enum BindingKind;
    std::vector<ShaderBinding> bindings{{BINDING_FRAME, "frame", Storage},
                                        {BINDING_TILE, "tile", Storage},
                                        {BINDING_OBJECTS, "objects", Texels},
                                        {BINDING_MATERIALS, "materials", Texels}};
    if (features.lights || features.has(Shading::Shadows))
        bindings.push_back({BINDING_LIGHTS, "lights", Texels});
    bindings.push_back({BINDING_PIXELS, "pixels", Texels});
    bindings.push_back({BINDING_RAY_GROUPS, "ray groups", UintTexels});
    if (!tracesInOnePass(features)) bindings.push_back({BINDING_PROGRESS, "ray progress", Texels});
    bindings.push_back({BINDING_STATUS, "dispatch status", Storage});
    if (features.has(Shading::Reflection) || features.has(Shading::Refraction))
        bindings.push_back({BINDING_RAY_STACK, "pending rays", Storage});
    if (features.debugPixel) bindings.push_back({BINDING_DEBUG, "debug record", Storage});
    if (features.objectBvh) {
        bindings.push_back({BINDING_OBJECT_NODES, "object BVH nodes", Texels});
        bindings.push_back({BINDING_OBJECT_INDEX, "object BVH index", UintTexels});
    }
    if (features.kinds[KIND_MESH]) {
        bindings.push_back({BINDING_MESHES, "meshes", Texels});
        if (!meshNodesWithObjects(features))
            bindings.push_back({BINDING_MESH_NODES, "mesh BVH nodes", Texels});
        bindings.push_back({BINDING_TRIANGLES, "triangles", Texels});
    }
    if (features.kinds[KIND_BOOLEAN]) bindings.push_back({BINDING_CSG_NODES, "CSG nodes", Texels});
    if (features.has(Shading::Pixmaps)) {
        bindings.push_back({BINDING_PIXMAPS, "pixmaps", Texels});
        bindings.push_back({BINDING_TEXELS, "pixmap texels", UintTexels});
    }
    if (features.doubles) {
        bindings.push_back({BINDING_DOUBLE_CAMERA, "camera in double", Storage});
        bindings.push_back({BINDING_DOUBLE_OBJECTS, "objects' M^-1 in double", Texels});
    }
    if (features.stressOutput)
        bindings.push_back({BINDING_STRESS_OUTPUT, "stress output", Storage});
    if (features.rayQuery)
        bindings.push_back(
            {BINDING_SCENE_STRUCTURE, "acceleration structure", AccelerationStructure});
    return bindings;
}

bool meshNodesWithObjects(const ShaderFeatures& features) {
    return features.objectBvh && features.kinds[KIND_MESH] && !features.stressOutput &&
           !placesTrianglesInWorld(features) && !features.rayQuery;
}

std::vector<ShaderFeatures> allVariants(bool everyCombination) {
    std::vector<ShaderFeatures> variants;
    const unsigned kinds = unsigned(kGpuKinds.size());
    const unsigned allKinds = (1u << kinds) - 1;
    const auto add = [&](unsigned kindMask, unsigned shadingMask, bool debugPixel) {
        ShaderFeatures f;
        for (unsigned kind = 0; kind < kinds; ++kind) f.kinds[kind] = (kindMask >> kind) & 1u;
        for (unsigned i = 0; i < kGpuShading.size(); ++i) f.shading[i] = (shadingMask >> i) & 1u;
        f.debugPixel = debugPixel;
        for (bool bvh : {false, true}) {
            f.objectBvh = bvh;
            variants.push_back(f);
        }
    };
    // Shapes alone.
    for (unsigned mask = 0; mask <= allKinds; ++mask) {
        const int count = std::popcount(mask);
        // Shape code interacts pairwise at most (CSG calls the others' span
        // functions), so pairs and "all but one" cover what can break.
        if (!everyCombination && count > 2 && count < int(kinds) - 1) continue;
        add(mask, 0, false);
        // The debug record touches every shape's path: each kind alone, and all.
        if (count == 1 || mask == allKinds) add(mask, 0, true);
    }
    // Shading: its code (feelers, the ray stack, textures' (u, v) per kind)
    // calls every shape's, but its features do not call one another's.
    const unsigned allShading = (1u << kGpuShading.size()) - 1;
    for (unsigned shading = 1; shading <= allShading; ++shading) {
        if (!everyCombination && std::popcount(shading) != 1 && shading != allShading) continue;
        add(allKinds, shading, false);
        if (shading != allShading && !everyCombination) continue;
        for (unsigned kind = 0; kind < kinds; ++kind) add(1u << kind, shading, false);
    }
    add(allKinds, allShading, true);
    // `vkray render` without --aov: no depth and normal, in one pass and
    // with everything.
    for (unsigned shading : {0u, allShading}) {
        add(allKinds, shading, false);
        for (std::size_t i = variants.size() - 2; i < variants.size(); ++i)
            variants[i].aovs = false;
    }
    // Meshes as triangles in world space, with every shape (a mesh in CSG
    // keeps its own space), without shading and with all of it.
    for (unsigned shading : {0u, allShading}) {
        ShaderFeatures f;
        f.kinds.fill(true);
        for (unsigned i = 0; i < kGpuShading.size(); ++i) f.shading[i] = (shading >> i) & 1u;
        f.objectBvh = true;
        f.meshesInWorld = true;
        variants.push_back(f);
    }
    // `vkray stress` and `vkray pixel`: the stress output with everything.
    ShaderFeatures stress;
    stress.kinds.fill(true);
    stress.shading.fill(true);
    stress.stressOutput = true;
    for (bool debugPixel : {false, true}) {
        stress.debugPixel = debugPixel;
        variants.push_back(stress);
    }
    return variants;
}

}  // namespace vkray::gpu
