// The host's view of shaders/layout.h must match std430/std140 exactly: every
// size and offset is checked here at compile time.
#include "shaders/layout.h"

#include "gpu/shader_variant.h"
#include "scene/bvh.h"

#include <cstddef>

namespace vkray::gpu {

static_assert(sizeof(vec4) == 16 && alignof(vec4) == 16);
static_assert(sizeof(uvec4) == 16 && alignof(uvec4) == 16);

static_assert(offsetof(GpuObjectGeometry, objectFromWorld) == 0);
static_assert(offsetof(GpuObjectGeometry, shape) == 48);
static_assert(offsetof(GpuMaterial, ambient) == 0);
static_assert(offsetof(GpuMaterial, diffuse) == 16);
static_assert(offsetof(GpuMaterial, specular) == 32);
static_assert(offsetof(GpuMaterial, emissive) == 48);
static_assert(offsetof(GpuMaterial, material) == 64);
static_assert(offsetof(GpuMaterial, texture) == 80);

// Each structure read through a texel buffer is a whole number of texels
// (scene_data.glsl indexes them by *_TEXELS).
constexpr std::size_t kTexel = sizeof(uvec4);
static_assert(sizeof(GpuObjectGeometry) == OBJECT_GEOMETRY_TEXELS * kTexel);
static_assert(sizeof(GpuMaterial) == MATERIAL_TEXELS * kTexel);
static_assert(sizeof(GpuLight) == LIGHT_TEXELS * kTexel);
static_assert(sizeof(GpuBvhNode) == BVH_NODE_TEXELS * kTexel);
static_assert(sizeof(GpuTriangle) == TRIANGLE_TEXELS * kTexel);
static_assert(sizeof(GpuDoubleObject) == DOUBLE_OBJECT_TEXELS * kTexel);
static_assert(sizeof(GpuPixel) == PIXEL_TEXELS * kTexel);
static_assert(sizeof(GpuRayProgress) == RAY_PROGRESS_TEXELS * kTexel);
static_assert(sizeof(GpuRayTask) == RAY_TASK_TEXELS * kTexel);
static_assert(sizeof(GpuDoubleRayTask) == DOUBLE_RAY_TASK_TEXELS * kTexel);
static_assert(sizeof(GpuMesh) == kTexel && sizeof(GpuCsgNode) == kTexel &&
              sizeof(GpuPixmap) == kTexel);

static_assert(sizeof(GpuPixmap) == 16);

static_assert(offsetof(GpuLight, position) == 0);
static_assert(offsetof(GpuLight, color) == 16);
static_assert(sizeof(GpuLight) == 32);

static_assert(offsetof(FrameParams, eye) == 0);
static_assert(offsetof(FrameParams, cameraU) == 16);
static_assert(offsetof(FrameParams, cameraV) == 32);
static_assert(offsetof(FrameParams, cameraN) == 48);
static_assert(offsetof(FrameParams, background) == 64);
static_assert(offsetof(FrameParams, globalAmbient) == 80);
static_assert(offsetof(FrameParams, image) == 96);
static_assert(offsetof(FrameParams, counts) == 112);
static_assert(offsetof(FrameParams, sampling) == 128);
static_assert(sizeof(FrameParams) == 144);

static_assert(sizeof(dvec4) == 32 && alignof(dvec4) == 32);
static_assert(offsetof(GpuDoubleCamera, cameraU) == 32);
static_assert(offsetof(GpuDoubleCamera, cameraN) == 96);
static_assert(sizeof(GpuDoubleCamera) == 128);
static_assert(offsetof(GpuDoubleObject, parameters) == 96);
static_assert(sizeof(GpuDoubleObject) == 128);

static_assert(offsetof(TileParams, work) == 16);
static_assert(offsetof(TileParams, samples) == 32);
static_assert(sizeof(TileParams) == 48);
static_assert(offsetof(GpuRayProgress, color) == 16);
static_assert(sizeof(GpuRayProgress) == 32);
static_assert(sizeof(GpuDispatchStatus) == 16);
static_assert(offsetof(GpuRayTask, speeds) == 48);
static_assert(sizeof(GpuRayTask) == 64);
static_assert(offsetof(GpuDoubleRayTask, weight) == 64);
static_assert(sizeof(GpuDoubleRayTask) == 96);

static_assert(offsetof(PresentParams, mode) == 16);
static_assert(offsetof(PresentParams, range) == 32);
static_assert(sizeof(PresentParams) == 48);
static_assert(offsetof(GpuPixel, color) == 0);
static_assert(offsetof(GpuPixel, normal) == 16);
static_assert(sizeof(GpuPixel) == 32);

static_assert(offsetof(GpuDebugHeader, color) == 96);
static_assert(offsetof(GpuDebugHeader, counts) == 112);
static_assert(offsetof(GpuStressSample, hit) == 16);
static_assert(offsetof(GpuStressSample, primaryDouble) == 32);
static_assert(offsetof(GpuStressSample, normalDouble) == 48);
static_assert(offsetof(GpuStressSample, refracted) == 64);
static_assert(offsetof(GpuStressSample, refractedHit) == 80);
static_assert(sizeof(GpuStressSample) == 96);

static_assert(sizeof(GpuDebugHeader) == 128);
static_assert(sizeof(GpuDebugEntry) == 32);

static_assert(sizeof(GpuBvhNode) == 32);
static_assert(sizeof(GpuMesh) == 16);
static_assert(sizeof(GpuTriangle) == 96);
static_assert(sizeof(GpuCsgNode) == 16);

static_assert(kGpuKinds.size() == KIND_COUNT);
static_assert(BVH_STACK_SIZE == kMaxBvhDepth,
              "the shader's BVH stack holds a walk's pending nodes: kMaxBvhDepth + 1 levels, "
              "the object BVH joined to the world triangles'");
static_assert(MAX_RECURSION_DEPTH == kMaxRecursionDepth,
              "the shader's ray stack holds the deepest ray tree the reader accepts");
static_assert(TORUS_MAJOR_RADIUS == kTorusMajorRadius && TORUS_TUBE_RADIUS == kTorusTubeRadius);

}  // namespace vkray::gpu
