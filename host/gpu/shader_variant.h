// Which shader a scene needs. The renderer leaves out what a scene does not
// use: each feature is a preprocessor define of trace.comp, so a variant
// holds only the code of the shapes present (specialisation constants would
// keep the dead code in the SPIR-V that lavapipe JIT-compiles every run).
#pragma once

#include "scene/scene.h"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vkray::gpu {

using Defines = std::vector<std::pair<std::string, std::string>>;  // NAME, VALUE

// The shader's shape kinds, indexed by layout.h's KIND_* values.
struct GpuKind {
    const char* define;  // VKRAY_SHAPE_... (VKRAY_CSG for booleans)
    const char* name;    // in variant descriptions
};
inline constexpr std::array<GpuKind, 8> kGpuKinds{{
    {"VKRAY_SHAPE_SPHERE", "sphere"},
    {"VKRAY_SHAPE_PLANE", "plane"},
    {"VKRAY_SHAPE_SQUARE", "square"},
    {"VKRAY_SHAPE_CUBE", "cube"},
    {"VKRAY_SHAPE_TAPERED_CYLINDER", "taperedCylinder"},
    {"VKRAY_SHAPE_TORUS", "torus"},
    {"VKRAY_SHAPE_MESH", "mesh"},
    {"VKRAY_CSG", "csg"},
}};

// The KIND_* value that renders a scene shape (every mesh-like keyword is
// KIND_MESH; cylinder and cone are tapered cylinders).
std::uint32_t gpuKindOf(ShapeType type);

// More bounded objects than this are found through a BVH; below it, testing
// each object is cheaper than walking nodes.
inline constexpr std::size_t kObjectBvhThreshold = 8;

struct ShaderFeatures {
    std::array<bool, kGpuKinds.size()> kinds{};  // indexed by KIND_*
    bool objectBvh = false;   // objects found through a BVH
    bool debugPixel = false;  // `vkray pixel`: the shader writes a trace record

    bool operator==(const ShaderFeatures&) const = default;
};

// The features `scene` needs (every shape kind when allFeatures; the object
// BVH is a property of the scene's size, not a shape, so it stays as needed).
ShaderFeatures featuresOf(const Scene& scene, bool allFeatures);

// The defines of a variant, followed by the user's own (-D NAME=VALUE).
Defines definesFor(const ShaderFeatures& features, const Defines& userDefines = {});

// "sphere+cube", "all shapes", "no shapes", with "+bvh" and "+debug-pixel".
std::string describe(const ShaderFeatures& features);

// One descriptor (set 0) a variant declares: the host creates and uploads a
// buffer for exactly these, and nothing else.
struct ShaderBinding {
    std::uint32_t binding;  // BINDING_* of shaders/layout.h
    const char* name;       // "objects", "mesh nodes", ...
    bool uniform;           // uniform buffer (else storage buffer)
};
std::vector<ShaderBinding> bindingsFor(const ShaderFeatures& features);

// The variants `vkray shaders check` compiles, each with and without the
// object BVH, and with the debug-pixel record for each kind alone and for all:
// every combination of shape kinds when everyCombination (--all: 530
// variants), else those of at most two kinds or all but at most one (110).
std::vector<ShaderFeatures> allVariants(bool everyCombination = false);

}  // namespace vkray::gpu
