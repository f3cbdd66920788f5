#include "app/features_report.h"

#include "gpu/gpu_scene.h"
#include "scene/scene_geometry.h"
#include "scene/triangle_mesh.h"
#include "shaders/layout.h"

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
        return "empty (one " + std::to_string(sizeof(T)) + "-byte element: Vulkan has no empty buffers)";
    return std::to_string(items.size() * sizeof(T)) + " bytes (" + std::to_string(items.size()) +
           " x " + std::to_string(sizeof(T)) + ")";
}

// What the host uploads for one binding (the same arrays as the tracer's).
std::string bufferSize(std::uint32_t binding, const gpu::GpuScene& packed, const Scene& scene) {
    using namespace gpu;
    switch (binding) {
    case BINDING_FRAME: return std::to_string(sizeof(FrameParams)) + " bytes";
    case BINDING_OBJECTS: return arrayBytes(packed.objects);
    case BINDING_LIGHTS: return arrayBytes(packed.lights);
    case BINDING_PIXELS: return "one tile of " + std::to_string(sizeof(GpuPixel)) + "-byte pixels";
    case BINDING_DEBUG:
        return std::to_string(sizeof(GpuDebugHeader) +
                              (scene.objects.size() + scene.lights.size()) * sizeof(GpuDebugEntry)) +
               " bytes";
    case BINDING_OBJECT_NODES: return arrayBytes(packed.objectNodes);
    case BINDING_OBJECT_INDEX: return arrayBytes(packed.objectIndex);
    case BINDING_MESHES: return arrayBytes(packed.meshes);
    case BINDING_MESH_NODES: return arrayBytes(packed.meshNodes);
    case BINDING_TRIANGLES: return arrayBytes(packed.triangles);
    case BINDING_CSG_NODES: return arrayBytes(packed.csgNodes);
    default: return "?";
    }
}

}  // namespace

std::string formatFeatureReport(const Scene& scene, const gpu::ShaderFeatures& features,
                                const gpu::Defines& defines, const std::string& key) {
    std::map<ShapeType, int> counts;
    for (const SceneObject& object : scene.objects) countShapes(object, counts);
    std::size_t bounded = 0, triangles = 0;
    for (const SceneObject& object : scene.objects)
        bounded += worldBounds(object, scene).finite() ? 1 : 0;
    for (const auto& mesh : scene.meshes) triangles += mesh->triangles.size();

    std::ostringstream out;
    out << "scene: " << (scene.path.empty() ? "(text)" : scene.path) << " ("
        << scene.objects.size() << " objects, " << scene.lights.size() << " lights)\n";
    out << "shapes: " << listCounts(counts, false) << "\n";
    out << "booleans: " << listCounts(counts, true) << "\n";
    out << "meshes: ";
    if (scene.meshes.empty()) out << "none\n";
    else out << scene.meshes.size() << " (" << triangles << " triangles)\n";
    out << "object BVH: " << (features.objectBvh ? "yes" : "no") << " (" << bounded
        << " bounded objects; more than " << gpu::kObjectBvhThreshold << " get one)\n";
    out << "lights: " << scene.lights.size() << "\n";
    out << "variant: " << gpu::describe(features) << "\n";
    out << "defines:";
    for (const auto& [name, value] : defines) out << " " << name << "=" << value;
    out << (defines.empty() ? " none\n" : "\n");
    out << "key: " << key << " (SPIR-V cache key)\n";
    out << "buffers:\n";
    const gpu::GpuScene packed = gpu::packScene(scene, features);
    for (const gpu::ShaderBinding& b : gpu::bindingsFor(features)) {
        char line[80];
        std::snprintf(line, sizeof line, "  %2u %-17s %-8s ", b.binding, b.name,
                      b.uniform ? "uniform" : "storage");
        out << line << bufferSize(b.binding, packed, scene) << "\n";
    }
    return out.str();
}

}  // namespace vkray
