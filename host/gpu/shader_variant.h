// Which shader a scene needs. The renderer leaves out what a scene does not
// use: each feature is a preprocessor define of trace.comp, so a variant
// holds only the code of the shapes present (specialisation constants would
// keep the dead code in the SPIR-V that lavapipe JIT-compiles every run).
#pragma once

#include "render/camera.h"
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
// each object is cheaper than walking nodes. Up to this many objects, too,
// are tested in an unrolled loop (ShaderFeatures::unrolledObjects).
inline constexpr std::size_t kObjectBvhThreshold = 8;

// Whitted shading (docs/shading.md), each part compiled in only where a
// scene can use it; indexed like ShaderFeatures::shading.
enum class Shading { Shadows, Reflection, Refraction, Textures, Pixmaps, Antialias };
struct GpuShading {
    const char* define;
    const char* name;  // in variant descriptions
};
inline constexpr std::array<GpuShading, 6> kGpuShading{{
    {"VKRAY_SHADOWS", "shadows"},        // lights, and an object that can shade another point
    {"VKRAY_REFLECTION", "reflection"},  // reflectivity > minReflectivity, maxRecursionDepth > 0
    {"VKRAY_REFRACTION", "refraction"},  // transparency > minTransparency, maxRecursionDepth > 0
    {"VKRAY_TEXTURES", "textures"},      // solid textures (checkerboard, wood)
    {"VKRAY_PIXMAPS", "pixmaps"},        // image textures
    {"VKRAY_ANTIALIAS", "antialias"},    // more than one sample per pixel
}};

struct ShaderFeatures {
    std::array<bool, kGpuKinds.size()> kinds{};      // indexed by KIND_*
    std::array<bool, kGpuShading.size()> shading{};  // indexed by Shading
    bool lights = true;         // the scene has lights (without, no light code: VKRAY_LIGHTS 0)
    bool objectBvh = false;     // objects found through a BVH
    bool unbounded = false;     // the scene has objects without a box (planes)
    bool blocks = false;        // --block > 1: each ray fills a block of pixels (VKRAY_BLOCKS)
    bool aovs = true;           // each pixel's depth and normal are written (VKRAY_AOVS)
    bool debugPixel = false;    // `vkray pixel`: the shader writes a trace record
    bool stressOutput = false;  // `vkray stress`, `vkray pixel`: GpuStressSample per pixel
    bool doubles = false;       // --precision fp64: camera and M^-1 read in double
    // The driver's acceleration structure finds the bounded objects
    // (VKRAY_RAY_QUERY; gpu/traversal.h chooses it).
    bool rayQuery = false;
    // The mesh objects may go into the object BVH as their triangles in
    // world space (meshesFitWorldSpace); placesTrianglesInWorld says whether they do.
    bool meshesInWorld = false;
    // VKRAY_OBJECTS: the object count, when the shader tests each object in
    // turn in a loop it unrolls (a few objects, no BVH, no mesh, every torus
    // kept: keepsTori); 0: a loop over the count read at run time.
    std::uint32_t unrolledObjects = 0;
    // VKRAY_OBJECT_KINDS: with an unrolled walk, each object's KIND_*, in
    // order: each test holds its object's shape's code alone.
    std::vector<std::uint32_t> objectKinds;

    bool has(Shading s) const { return shading[size_t(s)]; }
    bool operator==(const ShaderFeatures&) const = default;
};

// Whether the walk keeps the variant's tori for tests after the other
// objects' (VKRAY_KEEP_TORI; CSG objects always are): where another shape's
// tests gain from leaving the torus's code out, not in a variant of tori
// alone, which would pay the list for nothing.
bool keepsTori(const ShaderFeatures& features);

// Whether a feeler's BVH walk first tests what stopped the feeler toward the
// same light two pixels away (VKRAY_FEELER_HINTS): with shadows, an object
// BVH and no unbounded objects, whose tests would take the turn the hint
// fills; not in the stress and debug records, which count each walk's tests
// as the CPU reference makes them.
bool hintsFeelers(const ShaderFeatures& features);

// The most triangles, all mesh objects' together, that a scene may place in
// world space (meshesFitWorldSpace): each is a copy of its mesh's (GpuTriangle).
inline constexpr std::size_t kWorldTrianglesMax = std::size_t(1) << 21;

// How far from a mesh object, in its sizes (its world box's diagonal), the
// eye and every bounded object may be for its triangles to go into world
// space: there float's rounding of their coordinates (2^-24 of the
// distance) and the walk's widening of each box's far side (3.6e-7 of it)
// stay under 1.5e-3 of the mesh. Farther, its walk in generic space starts
// near it (mesh.glsl, meshWalkShift), where world space would meet every
// box of a squashed teapot seen from 5e5 of its sizes.
inline constexpr double kWorldSpaceReach = 4096;

// Whether the scene's mesh objects can go into the object BVH as their
// triangles, placed in world space (M p rounded once from double), so that
// a walk meets them as it meets objects, with no mesh to enter: there is a
// mesh object, none is transparent (a feeler that meets a triangle stops:
// one that crossed a transparent mesh would count it twice), `eye` and the
// bounded objects are within kWorldSpaceReach of each, their triangles
// number kWorldTrianglesMax at most, and with the meshes' own they fit one
// texel buffer of maxTexels. The caller asks only in the robust precision
// mode: the textbook's (naive) intersects each mesh in its generic space,
// as Hill does, and fp64 keeps the ray geometry in double.
bool meshesFitWorldSpace(const Scene& scene, const glm::dvec3& eye, std::uint64_t maxTexels);

// Sets meshesInWorld where the meshes fit, and then an object BVH however
// few the objects: a lone mesh is walked as the BVH's triangles, not by a
// walk of its own inside its object's test (the million-triangle mesh of
// vkray_bench 1.10x to 1.13x on Mesa 22.3).
void placeMeshesInWorldWhereTheyFit(const Scene& scene, const glm::dvec3& eye,
                                    std::uint64_t maxTexels, ShaderFeatures& features);

// Whether the variant's walk meets the mesh objects' triangles in world space
// (VKRAY_WORLD_TRIANGLES): where they fit (meshesInWorld), with an object
// BVH; not in the stress and debug records, which count each object's test
// as the CPU reference makes it.
bool placesTrianglesInWorld(const ShaderFeatures& features);

// Whether each invocation finishes its pixel in one dispatch: one ray a pixel
// (its feelers included), no secondary rays, one sample. Its rays never
// pause, so the variant keeps no progress between dispatches (trace.comp's
// VKRAY_ONE_PASS, the same test).
bool tracesInOnePass(const ShaderFeatures& features);

// The features `scene` rendered with `settings` needs (every shape kind and
// shading feature when allFeatures; the object BVH is a property of the
// scene's size, so it stays as needed).
ShaderFeatures featuresOf(const Scene& scene, const RenderSettings& settings, bool allFeatures);

// The defines of a variant, every flag 0 or 1, followed by the user's own
// (-D NAME=VALUE; the precision mode's flags come that way, precisionDefines).
Defines definesFor(const ShaderFeatures& features, const Defines& userDefines = {});

// Every flag a variant defines, 0 or 1: the shapes, the shading features,
// VKRAY_LIGHTS, VKRAY_OBJECT_BVH, VKRAY_BLOCKS, VKRAY_AOVS, VKRAY_DEBUG_PIXEL,
// VKRAY_STRESS_OUTPUT, VKRAY_KEEP_TORI, VKRAY_FEELER_HINTS, VKRAY_WORLD_TRIANGLES, the
// test hook VKRAY_FAULT_NO_OFFSET and the precision modes' two; and the one
// count, VKRAY_OBJECTS. The one list; shaders/variant_flags.glsl checks each
// is defined.
std::vector<std::string> variantFlags();

// "sphere+cube", "all shapes", "no shapes", then the shading features
// ("+shadows+reflection", "+all shading"), "+bvh", "+blocks", "+aovs", "+debug-pixel",
// "+stress-output", "+fp64" and "+world-triangles".
std::string describe(const ShaderFeatures& features);

// How the shader reads a binding (shaders/layout.h, "Descriptor bindings").
enum class BindingKind {
    Storage,                // a storage buffer (what the shader writes; the frame's, the tile's
                            // and fp64's camera parameters; the pending rays)
    Texels,                 // a read-only storage texel buffer, rgba32ui (uimageBuffer)
    UintTexels,             // the same, r32ui
    AccelerationStructure,  // the driver's (VKRAY_RAY_QUERY), not a buffer of vkray's
};

// One descriptor (set 0) a variant declares: the host creates and uploads a
// buffer for exactly these, and nothing else.
struct ShaderBinding {
    std::uint32_t binding;  // BINDING_* of shaders/layout.h
    const char* name;       // "objects", "mesh nodes", ...
    BindingKind kind;
};
std::vector<ShaderBinding> bindingsFor(const ShaderFeatures& features);

// Whether the variant walks meshes in its object BVH's walk, entering each
// mesh object met (an object BVH and meshes, no stress record, no triangles
// in world space; trace.comp's VKRAY_MESH_INSTANCES): the meshes' BVH nodes then follow the
// objects' in one array (BINDING_OBJECT_NODES), and BINDING_MESH_NODES is not bound.
bool meshNodesWithObjects(const ShaderFeatures& features);

// The variants `vkray shaders check` compiles, each with and without the
// object BVH. Shapes without shading features: those of at most two kinds or
// all but at most one, with the debug-pixel record for each kind alone and
// for all (110); every combination when everyCombination (--all: 530). Then
// the shading features, whose code calls every shape's: each alone and all
// together with all shapes, and all together with each kind alone and with
// the debug-pixel record; with --all, every combination of them with all
// shapes and with each kind alone. Then all shapes without the AOV texel,
// with no shading and with all of it; the mesh objects' triangles in world
// space with all shapes, with no shading and with all of it. Last, the
// stress output with everything, with and without the debug-pixel record
// (150 in all; --all: 1,674).
std::vector<ShaderFeatures> allVariants(bool everyCombination = false);

}  // namespace vkray::gpu
