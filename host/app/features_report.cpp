#include "app/features_report.h"

#include "gpu/gpu_scene.h"
#include "scene/scene_geometry.h"
#include "scene/triangle_mesh.h"
#include "shaders/layout.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

namespace vkray {

namespace {

// "22 cube, 2 cylinder" in keyword order, operands of booleans included.
void countShapes(const SceneObject& object, std::map<ShapeType, int>& counts) {
    ++counts[object.type];
    for (const SceneObject& operand : object.operands) countShapes(operand, counts);
}

std::string listCounts(const std::map<ShapeType, int>& counts, bool booleans) {
    std::string text;
    for (const auto& [type, count] : counts) {
        if (isBoolean(type) != booleans) continue;
        text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + shapeKeyword(type);
    }
    return text.empty() ? "none" : text;
}

template <typename T>
std::string arrayBytes(const std::vector<T>& items) {
    if (items.empty())
        return "empty (one " + std::to_string(sizeof(T)) +
               "-byte element: Vulkan has no empty buffers)";
    return std::to_string(items.size() * sizeof(T)) + " bytes (" + std::to_string(items.size()) +
           " x " + std::to_string(sizeof(T)) + ")";
}

// What the host uploads for one binding (the same arrays as the tracer's).
std::string bufferSize(std::uint32_t binding, const gpu::GpuScene& packed, const Scene& scene,
                       bool doubles) {
    using namespace gpu;
    switch (binding) {
    case BINDING_FRAME: return std::to_string(sizeof(FrameParams)) + " bytes";
    case BINDING_OBJECTS: return arrayBytes(packed.objects);
    case BINDING_MATERIALS: return arrayBytes(packed.materials);
    case BINDING_LIGHTS: return arrayBytes(packed.lights);
    case BINDING_PIXELS: return "one tile of " + std::to_string(sizeof(GpuPixel)) + "-byte pixels";
    case BINDING_RAY_GROUPS: return "one tile's workgroups, 4 bytes each";
    case BINDING_PROGRESS:
        return "one tile of " + std::to_string(sizeof(GpuRayProgress)) + "-byte ray states";
    case BINDING_STATUS: return std::to_string(sizeof(GpuDispatchStatus)) + " bytes";
    case BINDING_TILE: return std::to_string(sizeof(TileParams)) + " bytes";
    case BINDING_RAY_STACK:
        return "one tile of " + std::to_string(pendingRayEntries(scene)) + "-entry stacks of " +
               std::to_string(doubles ? sizeof(GpuDoubleRayTask) : sizeof(GpuRayTask)) +
               "-byte rays";
    case BINDING_DEBUG:
        return std::to_string(sizeof(GpuDebugHeader) +
                              (scene.objects.size() + scene.lights.size()) *
                                  sizeof(GpuDebugEntry)) +
               " bytes";
    case BINDING_OBJECT_NODES: return arrayBytes(packed.objectNodes);
    case BINDING_OBJECT_INDEX: return arrayBytes(packed.objectIndex);
    case BINDING_MESHES: return arrayBytes(packed.meshes);
    case BINDING_MESH_NODES: return arrayBytes(packed.meshNodes);
    case BINDING_TRIANGLES: return arrayBytes(packed.triangles);
    case BINDING_CSG_NODES: return arrayBytes(packed.csgNodes);
    case BINDING_PIXMAPS: return arrayBytes(packed.pixmaps);
    case BINDING_TEXELS: return arrayBytes(packed.texels);
    case BINDING_DOUBLE_CAMERA: return std::to_string(sizeof(GpuDoubleCamera)) + " bytes";
    case BINDING_DOUBLE_OBJECTS: return arrayBytes(packed.doubleObjects);
    case BINDING_SCENE_STRUCTURE:
        return std::to_string(packed.unboundedFirst) +
               " boxes, built by the driver (its size is the driver's)";
    default: return "?";
    }
}

// Every object and operand, with what `visit` makes of each.
template <typename Visit>
void forEachObject(const std::vector<SceneObject>& objects, const Visit& visit) {
    for (const SceneObject& object : objects) {
        visit(object);
        forEachObject(object.operands, visit);
    }
}

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string yesNo(bool on) {
    return on ? "yes" : "no";
}

// "1 light", "3 lights".
std::string count(std::size_t n, const std::string& noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// "yes (2 objects with reflectivity > minReflectivity 0.5, maxRecursionDepth 3)"
// or why not: the material above its threshold that can start a secondary ray.
std::string secondaryRays(bool on, const Scene& scene, const char* property, double threshold,
                          const char* thresholdName, double Material::*field) {
    int above = 0;
    double highest = 0;
    forEachObject(scene.objects, [&](const SceneObject& o) {
        highest = std::max(highest, o.material.*field);
        above += o.material.*field > threshold ? 1 : 0;
    });
    const std::string rule =
        std::string(property) + " > " + thresholdName + " " + number(threshold);
    std::string why;
    const std::string some = count(std::size_t(above), "object") + " with " + rule;
    if (above == 0)
        why = "no object has " + rule + " (highest " + number(highest) + ")";
    else if (scene.maxRecursionDepth == 0)
        why = some + ", but maxRecursionDepth 0";
    else
        why = some + ", maxRecursionDepth " + std::to_string(scene.maxRecursionDepth);
    return yesNo(on) + " (" + why + ")";
}

}  // namespace

std::string formatFeatureReport(const Scene& scene, const RenderSettings& settings,
                                const gpu::ShaderFeatures& features, Precision precision,
                                const gpu::Defines& defines, const std::string& key) {
    std::map<ShapeType, int> counts;
    for (const SceneObject& object : scene.objects) countShapes(object, counts);
    std::size_t bounded = 0, triangles = 0;
    for (const SceneObject& object : scene.objects)
        bounded += worldBounds(object, scene).finite() ? 1 : 0;
    for (const auto& mesh : scene.meshes) triangles += mesh->triangles.size();

    std::ostringstream out;
    out << "scene: " << (scene.path.empty() ? "(text)" : scene.path) << " (" << scene.objects.size()
        << " objects, " << scene.lights.size() << " lights)\n";
    out << "shapes: " << listCounts(counts, false) << "\n";
    out << "booleans: " << listCounts(counts, true) << "\n";
    out << "meshes: ";
    if (scene.meshes.empty())
        out << "none\n";
    else
        out << scene.meshes.size() << " (" << triangles << " triangles)";
    if (gpu::placesTrianglesInWorld(features)) {
        std::size_t placed = 0;
        for (const SceneObject& object : scene.objects)
            if (!isBoolean(object.type) && object.mesh >= 0)
                placed += scene.meshes.at(size_t(object.mesh))->triangles.size();
        out << "; the mesh objects' " << placed
            << " triangles in the object BVH, placed in world space";
    } else if (!scene.meshes.empty() && gpu::meshNodesWithObjects(features)) {
        out << "; each mesh walked in its own space (world space takes opaque meshes near the "
               "eye, up to "
            << gpu::kWorldTrianglesMax << " triangles, in the robust mode)";
    }
    if (!scene.meshes.empty()) out << "\n";
    out << "object BVH: " << (features.objectBvh ? "yes" : "no") << " (" << bounded
        << " bounded objects; more than " << gpu::kObjectBvhThreshold
        << ", or two with a mesh, get one"
        << (gpu::placesTrianglesInWorld(features) ? "; so do triangles in world space" : "") << ")";
    if (features.unrolledObjects == 1)
        out << "; the one object tested alone, with its shape's code only";
    else if (features.unrolledObjects > 1)
        out << "; each object tested in turn, the loop unrolled over the "
            << features.unrolledObjects << ", each test its object's shape's code alone";
    const bool booleans = features.kinds[gpu::KIND_BOOLEAN], tori = gpu::keepsTori(features);
    if (booleans || tori)
        out << "; "
            << (booleans && tori ? "booleans and tori"
                : booleans       ? "booleans"
                                 : "tori")
            << " tested after the other objects";
    out << "\n";
    out << "lights: " << scene.lights.size() << "\n";
    std::map<int, int> textures;
    forEachObject(scene.objects, [&](const SceneObject& o) {
        if (o.material.texture != 0) ++textures[o.material.texture];
    });
    out << "textures:";
    static const char* const kTextureNames[] = {"none", "checkerboard", "wood", "image"};
    for (const auto& [texture, count] : textures)
        out << (texture == textures.begin()->first ? " " : ", ") << count << " "
            << (texture >= 0 && texture <= 3 ? kTextureNames[texture] : "?");
    out << (textures.empty() ? " none\n" : "\n");
    // Whether each kind of secondary ray can ever be traced (shader_variant.cpp's rules).
    const gpu::ShaderFeatures needed = gpu::featuresOf(scene, settings, false);
    std::string shadows;
    if (scene.objects.empty())
        shadows = "no (no objects)";
    else if (scene.lights.empty())
        shadows = "no (no lights)";
    else if (!needed.has(gpu::Shading::Shadows))
        shadows = "no (one plane or square: no feeler can meet it again)";
    else
        shadows = "yes (" + count(scene.lights.size(), "light") + ", " +
                  count(scene.objects.size(), "object") + ")";
    if (gpu::hintsFeelers(features))
        shadows +=
            "; each feeler's walk first tests what stopped the feeler toward the same "
            "light two pixels above";
    out << "shadows: " << shadows << "\n";
    out << "reflection: "
        << secondaryRays(needed.has(gpu::Shading::Reflection), scene, "reflectivity",
                         scene.minReflectivity, "minReflectivity", &Material::reflectivity)
        << "\n";
    out << "refraction: "
        << secondaryRays(needed.has(gpu::Shading::Refraction), scene, "transparency",
                         scene.minTransparency, "minTransparency", &Material::transparency)
        << "\n";
    out << "maxRecursionDepth: " << scene.maxRecursionDepth << "\n";
    out << "samples: " << settings.spp << " per pixel"
        << (settings.spp > 1 ? " (antialiasing)" : " (pixel centres, no antialiasing)") << "\n";
    // The object id always; depth and normal only where asked for (GpuPixel).
    gpu::ShaderFeatures withAovs = features;
    withAovs.aovs = true;
    out << "AOVs: object id" << (features.aovs ? ", depth, normal" : "")
        << (features.aovs
                ? ""
                : "; depth and normal with render --aov (variant " + gpu::describe(withAovs) + ")")
        << "\n";
    out << "precision: " << precisionName(precision)
        << (precision == Precision::Fp64 ? " (double in the shader" : " (float in the shader")
        << "; the CPU reference is double)\n";
    out << "variant: " << gpu::describe(features) << "\n";
    // The flags that are on and the user's defines; every other flag is 0.
    const std::vector<std::string> flags = gpu::variantFlags();
    out << "defines:";
    for (const auto& [name, value] : defines)
        if (value != "0" || std::find(flags.begin(), flags.end(), name) == flags.end())
            out << " " << name << "=" << value;
    out << " (every other variant flag 0)\n";
    out << "key: " << key << " (SPIR-V cache key)\n";
    out << "buffers:\n";
    const gpu::GpuScene packed = gpu::packScene(scene, features);
    for (const gpu::ShaderBinding& b : gpu::bindingsFor(features)) {
        char line[96];
        std::snprintf(line, sizeof line, "  %2u %-24s %-8s ", b.binding, b.name,
                      b.kind == gpu::BindingKind::Storage                 ? "storage"
                      : b.kind == gpu::BindingKind::AccelerationStructure ? "driver's"
                                                                          : "texels");
        out << line << bufferSize(b.binding, packed, scene, features.doubles) << "\n";
    }
    return out.str();
}

}  // namespace vkray
