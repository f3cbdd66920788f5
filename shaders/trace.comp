// vkray's ray tracer, one compute invocation per pixel (or block; Hill ch.
// 14): build the ray S + c t, intersect every object in its generic space,
// keep the closest hit, and shade it as Hill's shade() does (shade.glsl).
//
// The host compiles a variant holding only what the scene uses (host/gpu/
// shader_variant.h), every flag defined 0 or 1 (variant_flags.glsl checks):
// VKRAY_SHAPE_SPHERE, _PLANE, _SQUARE, _CUBE, _TAPERED_CYLINDER, _TORUS,
// _MESH and VKRAY_CSG are 1 for the shapes present; VKRAY_SHADOWS,
// _REFLECTION, _REFRACTION, _TEXTURES, _PIXMAPS and _ANTIALIAS add the parts
// of Whitted shading the scene uses;
// VKRAY_OBJECT_BVH finds objects through a BVH instead of testing each, and
// VKRAY_FEELER_HINTS has its feelers' walks first test what stopped a feeler
// nearby (shade.glsl);
// VKRAY_RAY_QUERY has the driver's acceleration structure find the objects
// (scene_walk.glsl, --traversal rayquery);
// VKRAY_BLOCKS (--block > 1) fills each ray's block of pixels;
// VKRAY_DEBUG_PIXEL (for `vkray pixel`) also records every step of the one
// ray the host dispatches into the debug buffer; VKRAY_STRESS_OUTPUT (for
// `vkray stress` and `vkray pixel`) what each pixel's primary ray and its
// secondary rays met (stress_output.glsl). VKRAY_PRECISION_NAIVE
// selects the textbook float formulas (precision.glsl).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "variant_flags.glsl"
#if VKRAY_RAY_QUERY
#extension GL_EXT_ray_query : require
#endif
#include "layout.h"
#if VKRAY_ANTIALIAS
#include "sampling.h"
#endif
#include "precision.glsl"

// Benchmarks try other shapes (GpuRenderOptions::workgroupX/Y).
#ifdef VKRAY_WORKGROUP_X
layout(local_size_x = VKRAY_WORKGROUP_X, local_size_y = VKRAY_WORKGROUP_Y, local_size_z = 1) in;
#else
layout(local_size_x = WORKGROUP_X, local_size_y = WORKGROUP_Y, local_size_z = 1) in;
#endif

// The frame's and the dispatch's parameters: storage buffers, which lavapipe
// does not inline (layout.h, TileParams).
layout(std430, set = 0, binding = BINDING_FRAME) readonly buffer FrameBlock { FrameParams frameBlock; };
layout(std430, set = 0, binding = BINDING_TILE) readonly buffer TileBlock { TileParams tileBlock; };
// The tile's pixels and each ray's progress as texels, GpuPixel and
// GpuRayProgress bit for bit: on llvmpipe an imageLoad or imageStore is a few
// vector loads or stores under the lane mask, where a storage-buffer access
// inside an if or a loop is a scalar loop over the 8 lanes (docs/lavapipe.md).
layout(set = 0, binding = BINDING_PIXELS, rgba32ui) uniform uimageBuffer pixelTexels;
layout(set = 0, binding = BINDING_RAY_GROUPS, r32ui) uniform readonly uimageBuffer rayGroupTexels;
// A ray pauses only between two rays of a pixel (traceSamples), never between
// a hit and its feelers: a variant of one ray a pixel (no secondary rays, one
// sample; shadow feelers or not) finishes every pixel in one dispatch and
// keeps no progress.
#define VKRAY_ONE_PASS (!VKRAY_REFLECTION && !VKRAY_REFRACTION && !VKRAY_ANTIALIAS)
#if !VKRAY_ONE_PASS
layout(set = 0, binding = BINDING_PROGRESS, rgba32ui) uniform uimageBuffer progressTexels;
#endif
layout(std430, set = 0, binding = BINDING_STATUS) buffer StatusBlock { GpuDispatchStatus status; };
#if VKRAY_DEBUG_PIXEL
layout(std430, set = 0, binding = BINDING_DEBUG) writeonly buffer DebugBlock {
    GpuDebugHeader debugHeader;
    GpuDebugEntry debugEntries[];  // objects, then lights
};
#endif
#if VKRAY_PRECISION_FP64
// The camera in double, read instead of its float copy in FrameParams (and
// every M^-1, scene_data.glsl, instead of GpuObjectGeometry's).
layout(std430, set = 0, binding = BINDING_DOUBLE_CAMERA) readonly buffer DoubleCameraBlock { GpuDoubleCamera doubleCameraBlock; };
GpuDoubleCamera doubleCamera;
#endif
// Copies of the frame's and the tile's parameters, made at the top of
// main(): llvmpipe reads a buffer inside any if or loop as a loop over its 8
// lanes, and outside them with one scalar load (docs/lavapipe.md).
FrameParams frame;
TileParams tileParams;
// The sample whose primary hit gives the AOVs, the debug record and the
// stress output: sample 0, or for `vkray pixel --sample K` the one traced.
#if VKRAY_DEBUG_PIXEL
#define RECORDED_SAMPLE tileParams.samples.x
#else
#define RECORDED_SAMPLE 0u
#endif

#include "scene_data.glsl"

GpuPixel loadPixel(uint index) {
    int first = int(index * PIXEL_TEXELS);
    return GpuPixel(texelAsVec4(imageLoad(pixelTexels, first)),
                    texelAsVec4(imageLoad(pixelTexels, first + 1)));
}

// On llvmpipe every 32-bit word stored costs a loop over the 8 lanes: the
// AOV texel is written only when the host asked for it (VKRAY_AOVS).
void storePixel(uint index, GpuPixel pixel) {
    int first = int(index * PIXEL_TEXELS);
    imageStore(pixelTexels, first, floatBitsToUint(pixel.color));
#if VKRAY_AOVS
    imageStore(pixelTexels, first + 1, floatBitsToUint(pixel.normal));
#endif
}

#if !VKRAY_ONE_PASS
GpuRayProgress loadProgress(uint index) {
    int first = int(index * RAY_PROGRESS_TEXELS);
    return GpuRayProgress(texelAsVec4(imageLoad(progressTexels, first)),
                          texelAsVec4(imageLoad(progressTexels, first + 1)));
}

void storeProgress(uint index, GpuRayProgress ray) {
    int first = int(index * RAY_PROGRESS_TEXELS);
    imageStore(progressTexels, first, floatBitsToUint(ray.sum));
    imageStore(progressTexels, first + 1, floatBitsToUint(ray.color));
}
#endif

const float INFINITY = 1.0 / 0.0;

// The loop turns this invocation has run in this dispatch, counted in the
// loops whose turns grow with the scene: the scene walk, a mesh's BVH, the
// torus's root finder, CSG. Its rays pause once it passes the dispatch's
// budget (TileParams.work.x), well before llvmpipe's loop limit.
uint loopTurns = 0u;

// The world ray in an object's generic space: M^-1 applied and the direction
// not renormalised, so the generic t is the world t.
void toObjectSpace(uint index, rvec3 origin, rvec3 direction, out rvec3 o, out rvec3 d) {
#if VKRAY_PRECISION_FP64
    dvec4 rows[3] = dvec4[3](doubleObjectRow(index, 0u), doubleObjectRow(index, 1u), doubleObjectRow(index, 2u));
#else
    vec4 rows[3] = vec4[3](objectRow(index, 0u), objectRow(index, 1u), objectRow(index, 2u));
#endif
    o = rvec3(dot(rows[0], rvec4(origin, 1.0)), dot(rows[1], rvec4(origin, 1.0)),
              dot(rows[2], rvec4(origin, 1.0)));
    d = rvec3(dot(rows[0].xyz, direction), dot(rows[1].xyz, direction),
              dot(rows[2].xyz, direction));
}

// A tapered cylinder's s (GpuObjectGeometry.shape.y's float bits; unrounded in fp64).
real taperOf(uint index) {
#if VKRAY_PRECISION_FP64
    return doubleObjectParameters(index).x;
#else
    return uintBitsToFloat(objectShape(index).y);
#endif
}

// A walk through an object BVH enters the meshes it meets and walks their
// BVHs in the same loops (scene_walk.glsl), where a mesh's test would hold a
// walk of its own: on llvmpipe every loop runs its body once each time it is
// reached, so that a nested walk costs in every object test of the leaves.
// (The stress record counts each object's test, as the CPU reference's.)
// The host packs the nodes to match (meshNodesWithObjects).
// Where the host has placed every mesh object's triangles in the object BVH
// in world space instead (VKRAY_WORLD_TRIANGLES), the walk has no mesh to enter.
// The ray-query walk leaves each mesh to its object's test (intersectMesh).
#define VKRAY_MESH_INSTANCES                                                            \
    (VKRAY_OBJECT_BVH && VKRAY_SHAPE_MESH && !VKRAY_STRESS_OUTPUT && !VKRAY_WORLD_TRIANGLES && \
     !VKRAY_RAY_QUERY)
// A walk that meets triangles: a mesh's, or the world's.
#define VKRAY_WALK_TRIANGLES (VKRAY_MESH_INSTANCES || VKRAY_WORLD_TRIANGLES)

// Where an object's hits start along a ray.
#if VKRAY_PRECISION_NAIVE
const real T_MIN = NAIVE_EPSILON;  // the textbook's fixed epsilon, on every ray
#else
const real T_MIN = 0.0;  // robust: secondary rays start off the surface (offsetOrigin)
#endif

// Only the shapes of this variant are compiled in.
#include "shapes/span.glsl"
#if VKRAY_SHAPE_SPHERE
#include "shapes/sphere.glsl"
#endif
#if VKRAY_SHAPE_PLANE
#include "shapes/plane.glsl"
#endif
#if VKRAY_SHAPE_SQUARE
#include "shapes/square.glsl"
#endif
#if VKRAY_SHAPE_CUBE
#include "shapes/cube.glsl"
#endif
#if VKRAY_SHAPE_TAPERED_CYLINDER
#include "shapes/tapered_cylinder.glsl"
#endif
#if VKRAY_SHAPE_TORUS
#include "shapes/torus.glsl"
#endif
#if VKRAY_SHAPE_MESH
#include "shapes/mesh.glsl"
#endif
#if VKRAY_CSG
#include "shapes/csg.glsl"
#endif

struct Hit {
    real t;
    int object;          // the scene object (its id), -1 for none
    uint surface;        // the object whose surface was hit (a CSG primitive, or the object)
    rvec3 genericNormal;  // outward, in the generic space of `surface`
    rvec3 geometricNormal;  // the same, but a mesh's triangle's own instead of the interpolated
#if VKRAY_WALK_TRIANGLES
    // A mesh's triangle met by the walk (NO_TRIANGLE: none), whose normals
    // the walk works out at its end, from the barycentric coordinates.
    uint triangle;
    rvec3 barycentric;
#endif
#if VKRAY_FEELER_HINTS
    // A feeler's: the BVH walk's entry (objectAt) of the object that
    // stopped it, the hint for a feeler nearby (NO_ENTRY: none).
    uint entry;
#endif
};
const uint NO_TRIANGLE = 0xFFFFFFFFu;
const uint NO_ENTRY = 0xFFFFFFFFu;

// Sets of shapes (bit KIND_* set) that a call of intersectObject may meet.
const uint ALL_SHAPES = 0xFFFFFFFFu;
bool among(uint shapes, uint kind) { return (shapes & (1u << kind)) != 0u; }

// The nearest hit of object `index`, of shape `kind` (KIND_*), in (0, tMax);
// for a CSG object, the primitive whose surface it is. `geometric` differs
// from n only on meshes. `shapes` (a constant at each call) holds the shapes
// `kind` may be; where it is a constant too (an unrolled walk), the compiler
// leaves only the code of those shapes, or of that one.
bool intersectObject(uint index, uint kind, uint shapes, rvec3 origin, rvec3 direction, real tMax,
                     out real t, out rvec3 n, out rvec3 geometric, out uint surface) {
    const real tMin = T_MIN;
    surface = index;
    t = INFINITY;
    n = rvec3(0.0);
#if VKRAY_CSG
    if (among(shapes, KIND_BOOLEAN) && kind == KIND_BOOLEAN) {
        // Meshes in CSG are convex (the host checks): their spans carry the
        // interpolated normal only.
        bool hit = intersectCsg(objectShape(index).y, origin, direction, tMin, tMax, t, n, surface);
        geometric = n;
        return hit;
    }
#endif
    rvec3 o, d;
    toObjectSpace(index, origin, direction, o, d);
#if VKRAY_SHAPE_MESH
    if (among(shapes, KIND_MESH) && kind == KIND_MESH)
        return intersectMesh(objectShape(index).y, o, d, tMin, tMax, t, n, geometric);
#endif
    bool hit = false;
    switch (kind) {
#if VKRAY_SHAPE_SPHERE
    case KIND_SPHERE:
        if (among(shapes, KIND_SPHERE)) hit = intersectSphere(o, d, tMin, tMax, t, n);
        break;
#endif
#if VKRAY_SHAPE_PLANE
    case KIND_PLANE:
        if (among(shapes, KIND_PLANE)) hit = intersectPlane(o, d, tMin, tMax, t, n);
        break;
#endif
#if VKRAY_SHAPE_SQUARE
    case KIND_SQUARE:
        if (among(shapes, KIND_SQUARE)) hit = intersectSquare(o, d, tMin, tMax, t, n);
        break;
#endif
#if VKRAY_SHAPE_CUBE
    case KIND_CUBE:
        if (among(shapes, KIND_CUBE)) hit = intersectCube(o, d, tMin, tMax, t, n);
        break;
#endif
#if VKRAY_SHAPE_TAPERED_CYLINDER
    case KIND_TAPERED_CYLINDER:
        if (among(shapes, KIND_TAPERED_CYLINDER))
            hit = intersectTaperedCylinder(o, d, taperOf(index), tMin, tMax, t, n);
        break;
#endif
#if VKRAY_SHAPE_TORUS
    case KIND_TORUS:
        if (among(shapes, KIND_TORUS)) hit = intersectTorus(o, d, tMin, tMax, t, n);
        break;
#endif
    default: break;
    }
    geometric = n;
    return hit;
}

#include "stress_output.glsl"

#include "scene_walk.glsl"

// The unit direction of the primary ray through image point (x right, y
// down, in pixels), in the ray's precision: fp64's jittered samples would
// otherwise be placed to float's rounding of the pixel's coordinates.
rvec3 primaryDirection(rvec2 imagePoint) {
    rvec2 screen = rvec2(2.0 * imagePoint.x / real(frame.image.x) - 1.0,
                         1.0 - 2.0 * imagePoint.y / real(frame.image.y));
#if VKRAY_PRECISION_FP64
    GpuDoubleCamera camera = doubleCamera;
#else
    FrameParams camera = frame;
#endif
    real tanHalfFov = camera.eye.w;
    real aspect = camera.cameraU.w;
    return normalize(-camera.cameraN.xyz + screen.x * tanHalfFov * aspect * camera.cameraU.xyz +
                     screen.y * tanHalfFov * camera.cameraV.xyz);
}

// The invocation's pixel (or block) and its sample grid, set by main().
uvec2 rayPixel;
#if VKRAY_ANTIALIAS
uint rayPixelIndex, sampleGridColumns, sampleGridRows;
#endif

rvec3 rayEye() {
#if VKRAY_PRECISION_FP64
    return doubleCamera.eye.xyz;
#else
    return frame.eye.xyz;
#endif
}

// The primary ray of sample k: through the centre, or (VKRAY_ANTIALIAS) N
// jittered in a grid of cells (sampling.h, shared with the CPU reference).
rvec3 sampleDirection(uint k) {
    vec2 offset = vec2(0.5);
#if VKRAY_ANTIALIAS
    if (frame.sampling.x > 1u)
        offset = vec2(gridOffsetX(frame.sampling.y, rayPixelIndex, k, sampleGridColumns),
                      gridOffsetY(frame.sampling.y, rayPixelIndex, k, sampleGridColumns,
                                  sampleGridRows));
#endif
    return primaryDirection(rvec2(rayPixel) + rvec2(offset) * real(frame.image.z));
}

#if VKRAY_DEBUG_PIXEL
Hit debugHit;  // sample 0's primary hit and ray, for the debug record
rvec3 debugDirection;
#endif

#include "shade.glsl"


#if VKRAY_DEBUG_PIXEL
// Every object on its own, for `vkray pixel`: its generic ray and nearest t.
void recordObjectTests(rvec3 origin, rvec3 direction) {
    for (uint i = 0u; i < frame.image.w; ++i) {
        rvec3 o, d, n, geometric;
        toObjectSpace(i, origin, direction, o, d);
        real t;
        uint surface;
        if (!intersectObject(i, objectShape(i).x, ALL_SHAPES, origin, direction, INFINITY, t, n,
                             geometric, surface))
            t = INFINITY;
        debugEntries[i] = GpuDebugEntry(vec4(o, t), vec4(d, 0.0));
    }
}

// The debug record of the one ray `vkray pixel` traces, whose pixel is `result`.
void recordDebug(GpuPixel result) {
    rvec3 origin = rayEye();
    recordObjectTests(origin, debugDirection);
    GpuMaterial object = materialOf(debugHit.surface);
    bool hitSomething = debugHit.object >= 0;
    rvec3 p = hitSomething ? origin + debugHit.t * debugDirection : rvec3(0.0);
    debugHeader.rayOrigin = vec4(origin, 0.0);
    debugHeader.rayDirection = vec4(debugDirection, 0.0);
    debugHeader.hitPoint = vec4(p, debugHit.t);
    debugHeader.normal = vec4(result.normal.xyz, result.color.w);
    debugHeader.emissive = vec4(hitSomething ? object.emissive.rgb : vec3(0.0), 0.0);
    debugHeader.ambient = vec4(
        hitSomething ? debugTexture * object.ambient.rgb * frame.globalAmbient.rgb : vec3(0.0), 0.0);
    debugHeader.color = vec4(result.color.rgb, 0.0);
    debugHeader.counts = uvec4(frame.image.w, hitSomething ? frame.counts.x : 0u, 0u, 0u);
}
#endif

// The pixel of a ray, or (VKRAY_BLOCKS) every pixel of its block clipped to
// the tile; `first` is the block's first pixel, firstPixel its index.
void writePixels(uvec2 first, uint firstPixel, uvec2 tileSize, GpuPixel result) {
#if VKRAY_BLOCKS
    uvec2 last = min(first + uvec2(frame.image.z), tileSize);
    for (uint y = first.y; y < last.y; ++y)
        for (uint x = first.x; x < last.x; ++x)
            storePixel(y * tileSize.x + x, result);
#else
    storePixel(firstPixel, result);  // no loop: its first turn costs, needed or not
#endif
}

void main() {
    frame = frameBlock;
    tileParams = tileBlock;
#if VKRAY_PRECISION_FP64
    doubleCamera = doubleCameraBlock;
#endif
    // This invocation's pixel: one per pixel, or one per block x block
    // pixels, in the tile's workgroup that this one of the dispatch traces.
    uint block = frame.image.z;
    uint group = imageLoad(rayGroupTexels, int(gl_WorkGroupID.x)).x;
    uvec2 groupInTile = uvec2(group & ((1u << RAY_GROUP_SHIFT) - 1u), group >> RAY_GROUP_SHIFT);
    uvec2 rayInTile = groupInTile * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy;
#ifndef VKRAY_ROW_LANES  // an experiment: off unless -D defines it (BENCHMARKS.md)
    // llvmpipe runs 8 invocations consecutive in x as one SIMD vector, and
    // a loop turns until its slowest lane is done: each vector (a row of an
    // 8x8 workgroup) takes a compact 4x2 block of rays, whose paths stay
    // closer than those of 8 in a row.
    if (gl_WorkGroupSize.x == 8u && gl_WorkGroupSize.y % 2u == 0u) {
        uvec2 local = gl_LocalInvocationID.xy;
        rayInTile = groupInTile * gl_WorkGroupSize.xy +
                    uvec2((local.y & 1u) * 4u + (local.x & 3u), (local.y >> 1u) * 2u + (local.x >> 2u));
    }
#endif
    uvec2 tileSize = tileParams.tile.zw;
    uvec2 first = rayInTile * block;  // first pixel of the block, tile-relative
    if (first.x >= tileSize.x || first.y >= tileSize.y) return;
    rayPixel = tileParams.tile.xy + first;
    uint rayIndex = rayInTile.y * tileParams.work.w + rayInTile.x;
    uint firstPixel = first.y * tileSize.x + first.x;
#if VKRAY_ANTIALIAS
    uint samples = frame.sampling.x;
    rayPixelIndex = rayPixel.y * frame.image.x + rayPixel.x;
    sampleGridColumns = sampleColumns(samples);
    sampleGridRows = sampleRows(samples);
#endif
#if VKRAY_RAY_STACK
    rayStackBase = rayIndex * frame.sampling.w;
#endif

    // Its samples (those of tileParams.samples: all of them, but for
    // `vkray view`'s one a pass) go on from where the last dispatch left
    // them. The colour is their mean; the AOVs are those of sample 0.
    uint firstSample = tileParams.samples.x, endSample = tileParams.samples.y;
    bool aovFound;
    GpuPixel aov;
#if VKRAY_ONE_PASS
    // The pixel's one ray (and its feelers), traced whole in this dispatch:
    // sample 0, whose hit gives the AOVs, and the colour.
    GpuRayProgress ray = GpuRayProgress(vec4(0.0, 0.0, 0.0, uintBitsToFloat(firstSample)), vec4(0.0));
    traceSamples(ray, endSample, firstPixel, tileParams.work.x, aovFound, aov);
    GpuPixel result = aov;
    result.color.rgb = ray.sum.rgb;
    writePixels(first, firstPixel, tileSize, result);
#if VKRAY_DEBUG_PIXEL
    recordDebug(result);
#endif
#else
    GpuRayProgress ray;
    if (tileParams.work.y != 0u)  // none of its samples finished, none pending
        ray = GpuRayProgress(vec4(0.0, 0.0, 0.0, uintBitsToFloat(firstSample)), vec4(0.0));
    else
        ray = loadProgress(rayIndex);
    if (floatBitsToUint(ray.sum.w) < endSample) {
        traceSamples(ray, endSample, firstPixel, tileParams.work.x, aovFound, aov);
        storeProgress(rayIndex, ray);
        bool done = floatBitsToUint(ray.sum.w) >= endSample;
        if (!done) atomicAdd(status.counts.x, 1u);
        // Sample 0's AOVs, from this dispatch or the one that traced it;
        // written when found (the pixel's colour still 0 if the ray pauses)
        // and again with the colour once the ray is done.
        GpuPixel result = aovFound ? aov : loadPixel(firstPixel);
        // The samples' sum: the host divides it by their count, correctly
        // rounded (Vulkan lets a device's division be 2.5 ulp off).
        if (done) result.color.rgb = ray.sum.rgb;
        if (done || aovFound) writePixels(first, firstPixel, tileSize, result);
#if VKRAY_DEBUG_PIXEL
        if (done) recordDebug(result);
#endif
    }
#endif

    // The canary: a loop of work.z turns (read from a buffer, so that no
    // compiler can unroll it) runs short only if the driver's loop limit
    // was reached in this invocation; then the dispatch is not to be trusted.
    uint canary = 0u;
    for (uint i = 0u; i < tileParams.work.z; ++i) ++canary;
    if (canary != tileParams.work.z) atomicAdd(status.counts.y, 1u);
}
