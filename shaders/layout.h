// The one definition of every structure shared by the host (C++) and the
// compute shader (GLSL). Only vec4/uvec4/uint/float fields (and dvec4 in the
// structs read by the fp64 variant alone), std430 (and std140) compatible
// without hidden padding; host/gpu/layout_check.cpp static_asserts every size
// and offset.
#ifndef VKRAY_LAYOUT_H
#define VKRAY_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace vkray::gpu {
using uint = std::uint32_t;
struct alignas(16) vec4 { float x, y, z, w; };
struct alignas(16) uvec4 { uint x, y, z, w; };
struct alignas(32) dvec4 { double x, y, z, w; };
#define VKRAY_CONST(type, name, value) inline constexpr type name = value
#else
#define VKRAY_CONST(type, name, value) const type name = value
#endif

// Generic shapes, each intersected in its own object space (Hill ch. 14).
VKRAY_CONST(uint, KIND_SPHERE, 0u);            // x^2 + y^2 + z^2 = 1
VKRAY_CONST(uint, KIND_PLANE, 1u);             // z = 0
VKRAY_CONST(uint, KIND_SQUARE, 2u);            // z = 0, |x| <= 1, |y| <= 1
VKRAY_CONST(uint, KIND_CUBE, 3u);              // [-1, 1]^3
VKRAY_CONST(uint, KIND_TAPERED_CYLINDER, 4u);  // x^2 + y^2 = (1 + (s - 1) z)^2, 0 <= z <= 1, capped
VKRAY_CONST(uint, KIND_TORUS, 5u);             // axis z, radii TORUS_MAJOR_RADIUS, TORUS_TUBE_RADIUS
VKRAY_CONST(uint, KIND_MESH, 6u);              // triangles of GpuMesh shape.y
VKRAY_CONST(uint, KIND_BOOLEAN, 7u);           // CSG tree rooted at GpuCsgNode shape.y
VKRAY_CONST(uint, KIND_COUNT, 8u);

VKRAY_CONST(float, TORUS_MAJOR_RADIUS, 1.0);
VKRAY_CONST(float, TORUS_TUBE_RADIUS, 0.25);

// Workgroup shape of trace.comp (also the host's dispatch arithmetic).
VKRAY_CONST(uint, WORKGROUP_X, 8u);
VKRAY_CONST(uint, WORKGROUP_Y, 8u);

// Descriptor bindings of trace.comp (set 0). The scene's read-only arrays
// are storage texel buffers (rgba32ui: one uvec4 a texel; r32ui for the
// uint arrays) that the shader reads through shaders/scene_data.glsl: on
// llvmpipe an imageLoad is a few vector loads, where a storage-buffer read
// inside a loop is a scalar loop over the lanes (docs/lavapipe.md). What a
// ray writes stays in storage buffers.
VKRAY_CONST(uint, BINDING_FRAME, 0u);    // buffer FrameParams
VKRAY_CONST(uint, BINDING_OBJECTS, 1u);  // texels: GpuObjectGeometry[] (what a walk reads)
VKRAY_CONST(uint, BINDING_LIGHTS, 2u);   // texels: GpuLight[]
VKRAY_CONST(uint, BINDING_PIXELS, 3u);   // texels: GpuPixel[] (one tile; the presenter reads it as a buffer)
VKRAY_CONST(uint, BINDING_DEBUG, 4u);    // debug-pixel variant only: buffer GpuDebugHeader + entries
VKRAY_CONST(uint, BINDING_OBJECT_NODES, 5u);  // object-BVH variant: texels: GpuBvhNode[] over objects
VKRAY_CONST(uint, BINDING_OBJECT_INDEX, 6u);  // object-BVH variant: r32ui texels: leaf object indices
VKRAY_CONST(uint, BINDING_MESHES, 7u);        // mesh variant: texels: GpuMesh[]
VKRAY_CONST(uint, BINDING_MESH_NODES, 8u);    // mesh variant: texels: GpuBvhNode[] of all meshes
VKRAY_CONST(uint, BINDING_TRIANGLES, 9u);     // mesh variant: texels: GpuTriangle[] in BVH leaf order
VKRAY_CONST(uint, BINDING_CSG_NODES, 10u);    // CSG variant: texels: GpuCsgNode[]
VKRAY_CONST(uint, BINDING_PIXMAPS, 11u);      // pixmap variant: texels: GpuPixmap[] (slot order)
VKRAY_CONST(uint, BINDING_TEXELS, 12u);       // pixmap variant: r32ui texels: float rgb of all pixmaps
VKRAY_CONST(uint, BINDING_DOUBLE_CAMERA, 13u);   // fp64 variant: buffer GpuDoubleCamera
VKRAY_CONST(uint, BINDING_DOUBLE_OBJECTS, 14u);  // fp64 variant: texels: GpuDoubleObject[]
VKRAY_CONST(uint, BINDING_PROGRESS, 15u);  // texels: GpuRayProgress[]: each ray's state between dispatches
VKRAY_CONST(uint, BINDING_STATUS, 16u);    // buffer GpuDispatchStatus: what one dispatch left undone
VKRAY_CONST(uint, BINDING_RAY_STACK, 17u); // reflection/refraction variants: buffer of uvec4: GpuRayTask[] (or double)
VKRAY_CONST(uint, BINDING_MATERIALS, 18u); // texels: GpuMaterial[] (read once a hit)
VKRAY_CONST(uint, BINDING_STRESS_OUTPUT, 19u);  // stress-output variant: buffer GpuStressSample[] (one tile)
VKRAY_CONST(uint, BINDING_RAY_GROUPS, 20u);  // r32ui texels: the workgroups a dispatch traces (one tile)
VKRAY_CONST(uint, BINDING_TILE, 21u);        // buffer TileParams: the dispatch's tile and work
VKRAY_CONST(uint, BINDING_SCENE_STRUCTURE, 22u);  // ray-query variant: the driver's acceleration structure

// The texels (uvec4) of each structure read through a texel buffer, or
// stored as uvec4s (the pending rays; host/gpu/layout_check.cpp checks each
// against its size).
VKRAY_CONST(uint, OBJECT_GEOMETRY_TEXELS, 4u);
VKRAY_CONST(uint, MATERIAL_TEXELS, 6u);
VKRAY_CONST(uint, LIGHT_TEXELS, 2u);
VKRAY_CONST(uint, BVH_NODE_TEXELS, 2u);
VKRAY_CONST(uint, TRIANGLE_TEXELS, 6u);
VKRAY_CONST(uint, DOUBLE_OBJECT_TEXELS, 8u);  // a dvec4 is two texels
VKRAY_CONST(uint, PIXEL_TEXELS, 2u);          // GpuPixel: color, normal
VKRAY_CONST(uint, RAY_PROGRESS_TEXELS, 2u);   // GpuRayProgress: sum, color
VKRAY_CONST(uint, RAY_TASK_TEXELS, 4u);       // GpuRayTask
VKRAY_CONST(uint, DOUBLE_RAY_TASK_TEXELS, 6u);  // GpuDoubleRayTask: a dvec4 is two texels

// Bounds of the shader's fixed-size stacks; the host refuses scenes beyond them.
// A walk's pending nodes: one a level but the leaf's, for the object BVH
// joined to the world triangles' (kMaxBvhDepth + 1 levels, host/gpu/gpu_scene.cpp).
VKRAY_CONST(uint, BVH_STACK_SIZE, 48u);
VKRAY_CONST(uint, CSG_MAX_LEAVES, 32u);  // primitives of a CSG tree: one bit of a word each
VKRAY_CONST(uint, MAX_RECURSION_DEPTH, 64u);  // maxRecursionDepth (kMaxRecursionDepth on the host)
VKRAY_CONST(uint, MEDIUM_STACK_SIZE, 4u);    // nested transparent objects a ray remembers

// A secondary ray's origin moves off the surface (along the normal) by
// OFFSET_SCALE times its largest coordinate (float modes; shaders/precision.glsl
// offsetOrigin). After Ray Tracing Gems ch. 6 (Waechter and Binder), whose
// 256 float spacings of each coordinate are sized for world coordinates;
// vkray works in the eye's frame, where a hit point and the re-intersection
// of a ray leaving it are off by a few spacings of the largest coordinate in
// any direction: 2^-18 of it (32 to 64 of its spacings) along the normal,
// whatever its direction (docs/numerics.md). Ray Tracing Gems' constant step
// near the origin (1/65536 within 1/32) is left out: there the origin is the
// eye, and the step let light through objects smaller than it.
VKRAY_CONST(float, OFFSET_SCALE, 1.0 / 262144.0);
// ... and by at least OFFSET_GENERIC_SCALE (2^-18 = 64 u, u = 2^-24) times
// the world size of the object's generic rounding unit along the normal (the
// world length of one generic unit along it times the generic shape's
// extent; genericScaleAlong in shade.glsl): a hit's generic coordinates are
// O(1) and rounded to a few u whatever the eye's distance, which the
// eye-sized step above does not cover once the object is over ~64 times
// larger than that distance. Measured need (a sphere, a cylinder and a torus
// of size 2000 to 1e5 seen from 0.05 to 0.3): 1 u, 4 u and 16 u; 64 u
// leaves 4 times the worst (docs/numerics.md, "Envelope").
VKRAY_CONST(float, OFFSET_GENERIC_SCALE, 1.0 / 262144.0);
// The step is taken along the new ray itself, up to OFFSET_MAX_FORWARD times
// its length (rays leaving within ~83 degrees of the normal), the rest along
// the normal: the ray stays on the exact one's line instead of running beside
// it (precision.glsl offsetOrigin).
VKRAY_CONST(float, OFFSET_MAX_FORWARD, 8.0);

// GpuObjectGeometry.shape.z: the secondary rays a hit on the surface spawns, decided
// on the host in double (reflectivity > minReflectivity, transparency >
// minTransparency) so that GPU and CPU never disagree on a borderline value.
VKRAY_CONST(uint, FOLLOW_REFLECTION, 1u);
VKRAY_CONST(uint, FOLLOW_REFRACTION, 2u);

// Texture codes (`texture n`; docs/shading.md, "Textures").
VKRAY_CONST(uint, TEXTURE_NONE, 0u);
VKRAY_CONST(uint, TEXTURE_CHECKERBOARD, 1u);  // parameters: size, r g b
VKRAY_CONST(uint, TEXTURE_WOOD, 2u);          // parameters: ring width, r g b
VKRAY_CONST(uint, TEXTURE_IMAGE, 3u);         // parameters: pixmap index

// One object placed in the world, as a scene walk reads it. The host
// computes objectFromWorld = M^-1 in double; the shader only applies it.
struct GpuObjectGeometry {
    vec4 objectFromWorld[3];  // rows of the affine M^-1: p_obj.i = dot(row_i, vec4(p, 1))
    uvec4 shape;              // x = KIND_*; y = taper (float bits), mesh or CSG root;
                              // z = FOLLOW_* flags; w = transparency (float bits: shadow feelers)
};

// The object's material, read once a hit (GpuObjectGeometry's index).
struct GpuMaterial {
    vec4 ambient;   // rgb; w unused
    vec4 diffuse;   // rgb; w unused
    vec4 specular;  // rgb; w = specularExponent
    vec4 emissive;  // rgb; w unused
    vec4 material;  // x = reflectivity, y = transparency, z = speedOfLight,
                    // w = TEXTURE_* (uint bits)
    vec4 texture;   // the texture's parameters, defaults filled in:
                    // checkerboard: x = cell size, yzw = odd cells' rgb;
                    // wood: x = ring width, yzw = odd rings' rgb;
                    // image: x = GpuPixmap slot (uint bits)
};

// A BVH node (host/scene/bvh.h) as the shader walks it: the root first,
// then the two children of each interior node side by side (breadth first),
// so that a walk reads both children's boxes where it stands, and learns
// from them whether each is a leaf, without a turn of its own for a child.
// An interior node's children are nodes `first` and `first + 1`; a leaf
// (count > 0) covers entries first .. first + count - 1 (object indices or
// triangles). A walk's stack keeps a node as first * 8 + count
// (bvhNodeCode in shapes/span.glsl), hence the bounds below.
struct GpuBvhNode {
    vec4 lo;  // xyz; w = first (uint bits)
    vec4 hi;  // xyz; w = count (uint bits; 0 = interior)
};
VKRAY_CONST(uint, BVH_LEAF_MAX, 7u);           // entries a leaf may hold (maxLeafSize is 4)
VKRAY_CONST(uint, BVH_FIRST_MAX, 536870911u);  // 2^29 - 1

// One mesh in its object space: its BVH nodes and triangles (node indices
// and leaf ranges are relative to firstNode and firstTriangle).
struct GpuMesh {
    uvec4 range;  // x = firstNode, y = firstTriangle, z = triangle count, w unused
};

struct GpuTriangle {
    vec4 p0, p1, p2;  // xyz positions (object space)
    vec4 n0, n1, n2;  // xyz unit normals at the corners, interpolated
};
// A mesh object's triangle placed in world space (VKRAY_WORLD_TRIANGLES):
// a GpuTriangle whose corners are M p; p0.w is the object's index and p1.w
// the triangle's own GpuTriangle (its normals), as uint bits. These come
// first in the triangle array, object by object, each in its mesh's leaf
// order (host/gpu/gpu_scene.cpp).

// CSG trees in post order: a leaf pushes whether the ray is inside its
// primitive, an operator combines the two on top (shapes/csg.glsl). The
// tree's leaves follow it again, in the same order. Primitives are objects
// stored after the scene's objects (index >= object count).
VKRAY_CONST(uint, CSG_LEAF, 0u);
VKRAY_CONST(uint, CSG_UNION, 1u);
VKRAY_CONST(uint, CSG_INTERSECTION, 2u);
VKRAY_CONST(uint, CSG_DIFFERENCE, 3u);
struct GpuCsgNode {
    uvec4 node;  // x = CSG_*; y = leaf: primitive object index; root: z = the tree's node count,
                 // w = its leaf count; leaf: w = 1 where its normals turn (it is subtracted in an
                 // odd number of differences)
};

// One decoded `makePixmap` image: its rgb texels, row 0 at the top, start at
// float `first` of the texel buffer (3 floats a texel, row-major).
struct GpuPixmap {
    uvec4 image;  // x = first, y = width, z = height, w unused
};

struct GpuLight {
    vec4 position;  // xyz world position; w unused
    vec4 color;     // rgb; w unused
};

// Per-frame constants (a storage buffer, as TileParams). The camera basis is built on the host
// in double: a primary ray through image point (sx, sy) in [-1, 1]^2 is
// dir = normalize(-n + sx * tanHalfFov * aspect * u + sy * tanHalfFov * v).
struct FrameParams {
    vec4 eye;            // xyz eye position; w = tan(verticalFov / 2)
    vec4 cameraU;        // xyz right; w = aspect (width / height)
    vec4 cameraV;        // xyz up
    vec4 cameraN;        // xyz backwards (from look point to eye); w unused
    vec4 background;     // rgb
    vec4 globalAmbient;  // rgb
    uvec4 image;         // x = width, y = height, z = block size, w = object count
    uvec4 counts;        // x = light count; y = BVH nodes over objects (0: no BVH);
                         // z, w = first and count of unbounded objects in the object index
    uvec4 sampling;      // x = samples per pixel, y = seed, z = maxRecursionDepth,
                         // w = pending-ray stack entries per ray (maxRecursionDepth + 1)
};

// The fp64 variant (--precision fp64) reads the ray geometry's inputs in
// double from these instead of their float copies in FrameParams and
// GpuObjectGeometry; the other variants neither bind nor declare them.
#if defined(__cplusplus) || (defined(VKRAY_PRECISION_FP64) && VKRAY_PRECISION_FP64)
struct GpuDoubleCamera {
    dvec4 eye;      // as FrameParams.eye (w = tan(verticalFov / 2))
    dvec4 cameraU;  // w = aspect
    dvec4 cameraV;
    dvec4 cameraN;
};

struct GpuDoubleObject {
    dvec4 objectFromWorld[3];  // GpuObjectGeometry.objectFromWorld, unrounded
    dvec4 parameters;          // x = a tapered cylinder's s (GpuObjectGeometry.shape.y); yzw unused
};

// GpuRayTask with its origin and direction in double.
struct GpuDoubleRayTask {
    dvec4 origin;    // xyz; w = level
    dvec4 direction;  // xyz; w = medium depth
    vec4 weight;
    vec4 speeds;
};
#endif

// A dispatch traces only the workgroups of its tile whose primary rays may
// meet an object (host/render/primary_cover.h): workgroup i of the dispatch
// is the tile's workgroup at (x, y) of ray-groups texel i, x | y << 16. The
// host writes the other workgroups' pixels, which show the background.
VKRAY_CONST(uint, RAY_GROUP_SHIFT, 16u);

// Where the current dispatch writes, and how much work each ray may do in
// it (a storage buffer per tile in flight, written before each dispatch).
// Not a push constant nor a uniform buffer: lavapipe compiles a new variant
// of a shader, at every dispatch, with the values of the uniforms that its
// ifs and loops test inlined (its uniform inlining), so that a tile's
// parameters cost a compile a dispatch, and the canary's turns (below)
// could be unrolled away. llvmpipe ends every loop of an invocation, silently,
// once 65 535 loop turns have run in it; so a ray's work is cut into
// dispatches of at most `work.x` counted turns, its state kept in
// GpuRayProgress between them, and a canary loop of `work.z` turns at the
// end of each invocation tells whether the driver cut any loop short
// (docs/lavapipe.md, "The loop limit").
struct TileParams {
    uvec4 tile;     // x, y = origin; z, w = width, height
    uvec4 work;     // x = turn budget of this dispatch, y = 1 on the tile's first dispatch,
                    // z = canary turns, w = rays per tile row
    uvec4 samples;  // the samples each ray traces, of its grid of frame.sampling.x:
                    // x = the first, y = one past the last (a render: 0 and all of them)
};

// One ray's (one invocation's) state between the dispatches of its tile.
// It is done when all its samples are.
struct GpuRayProgress {
    vec4 sum;    // rgb: the colours of its finished samples, summed in order;
                 // w = how many are finished (uint bits)
    vec4 color;  // rgb: the current sample's colour so far; w = pending rays on its stack (uint bits)
};

// Written by atomics during one dispatch; the host zeroes it before each.
struct GpuDispatchStatus {
    uvec4 counts;  // x = rays that paused with work left, y = invocations whose canary ran short
};

// A ray waiting on a ray's pending-ray stack (reflection and refraction).
struct GpuRayTask {
    vec4 origin;     // xyz; w = level (a whole number; 0: the primary ray)
    vec4 direction;  // xyz; w = medium depth (a whole number)
    vec4 weight;     // rgb; w unused
    vec4 speeds;     // speeds of light of the media it is inside, innermost last
};

// One pixel of the output tile. The AOV texel (`normal`) is written only by
// variants that were asked for it (VKRAY_AOVS): on llvmpipe each word a
// shader stores costs a loop over its 8 lanes.
struct GpuPixel {
    vec4 color;   // rgb radiance (unclamped); w = object id (int bits; -1 = background)
    vec4 normal;  // xyz world unit normal facing the ray; w = depth (distance along the unit
                  // ray, +inf on a miss)
};

// The stress-output variant (VKRAY_STRESS_OUTPUT; `vkray stress`, `vkray
// pixel`): what the mode's own shader found for each pixel's first primary
// ray (sample 0) and the secondary rays of its hit, one per pixel of the tile
// (shaders/stress_output.glsl). Feelers are recorded for lights 0 to
// STRESS_MAX_LIGHTS - 1, bit i for light i.
VKRAY_CONST(uint, STRESS_MAX_LIGHTS, 32u);
struct GpuStressSample {
    vec4 primary;        // xyz: the world unit normal of the surface hit (its geometric
                         // normal), facing the ray; w = t (float; +inf on a miss)
    uvec4 hit;           // x = object id (int bits; -1: none); y = lights whose shadow
                         // feeler was traced; z = those whose feeler met a surface;
                         // w = those whose feeler met the object it left
    uvec4 primaryDouble; // fp64 variant (else 0): xy = t, zw = normal.x, each a double's
                         // 32-bit halves, least significant first (unpackDouble2x32)
    uvec4 normalDouble;  // fp64 variant (else 0): xy = normal.y, zw = normal.z
    vec4 refracted;      // the ray refracted into the primary hit's surface: xyz = the
                         // point it met a surface at, relative to the eye; w = its t
                         // (+inf: it met none)
    uvec4 refractedHit;  // x = its object id (int bits; -1: none); y = 1 when it was
                         // traced; zw unused
};

// `vkray pixel` (the VKRAY_DEBUG_PIXEL variant): what the shader saw for the
// one ray it traces. The debug buffer holds a GpuDebugHeader, then one
// GpuDebugEntry per object (scene order), then one per light.
struct GpuDebugHeader {
    vec4 rayOrigin;     // xyz world
    vec4 rayDirection;  // xyz world, unit
    vec4 hitPoint;      // xyz world; w = t (+inf on a miss)
    vec4 normal;        // xyz world unit normal facing the ray; w = object id (int bits)
    vec4 emissive;      // rgb: the emissive term
    vec4 ambient;       // rgb: ambient * globalAmbient
    vec4 color;         // rgb: the pixel's colour
    uvec4 counts;       // x = object entries written, y = light entries written
};

struct GpuDebugEntry {
    vec4 first;   // object: generic ray origin, w = its nearest t (+inf: miss)
                  // light: the diffuse term rgb, w = m.s
    vec4 second;  // object: generic ray direction
                  // light: the specular term rgb, w = m.h
};

// `vkray view` (present.comp): the tracer's tiles summed into the picture
// and shown in the window, all on the device. Descriptor bindings (set 0):
VKRAY_CONST(uint, PRESENT_BINDING_TILE, 0u);   // readonly GpuPixel[]: the tile just traced
VKRAY_CONST(uint, PRESENT_BINDING_SUMS, 1u);   // vec4[] a pixel: rgb = its samples summed in order,
                                               // w = how many
VKRAY_CONST(uint, PRESENT_BINDING_AOVS, 2u);   // GpuPixel[] a pixel: the last pass with sample 0
VKRAY_CONST(uint, PRESENT_BINDING_CPU, 3u);    // readonly GpuPixel[] a pixel: the CPU reference
VKRAY_CONST(uint, PRESENT_BINDING_VIEW, 4u);   // uint[] a pixel: the view as 8-bit RGBA (or BGRA)
VKRAY_CONST(uint, PRESENT_BINDING_BYTES, 5u);  // readonly float[256]: [b] = the least value
                                               // a PNG stores as byte b or more (pngByte)
VKRAY_CONST(uint, PRESENT_BINDING_RANGE, 6u);  // uvec4: x, y = float bits of the least and the
                                               // greatest finite depth of the pass (atomics)
VKRAY_CONST(uint, PRESENT_BINDING_VERDICTS, 7u);  // readonly uint[] a pixel: the margin rule's
                                                  // verdict (VERDICT_*)
VKRAY_CONST(uint, PRESENT_WORKGROUP, 8u);      // present.comp's local size, square

VKRAY_CONST(uint, PRESENT_ABSORB, 0u);   // a tile into the sums (and the AOVs)
VKRAY_CONST(uint, PRESENT_COMPOSE, 1u);  // the view of the whole image

// The difference view's verdicts: none yet (the threshold's heat alone), the
// same, set aside (blue, as `render --diff` draws it), unexplained (heat).
VKRAY_CONST(uint, VERDICT_NONE, 0u);
VKRAY_CONST(uint, VERDICT_SAME, 1u);
VKRAY_CONST(uint, VERDICT_SET_ASIDE, 2u);
VKRAY_CONST(uint, VERDICT_UNEXPLAINED, 3u);

VKRAY_CONST(uint, VIEW_COLOR, 0u);
VKRAY_CONST(uint, VIEW_DEPTH, 1u);       // false colour, even in 1 / depth over range.xy
VKRAY_CONST(uint, VIEW_NORMAL, 2u);      // 0.5 + 0.5 n
VKRAY_CONST(uint, VIEW_OBJECT_ID, 3u);   // a colour per object
VKRAY_CONST(uint, VIEW_DIFFERENCE, 4u);  // GPU - CPU heat map, over range.z in red to yellow

struct PresentParams {
    uvec4 rect;   // absorb: the tile's x, y, width, height; compose: 0, 0 and the image's size
    uvec4 mode;   // x = PRESENT_ABSORB or PRESENT_COMPOSE;
                  // absorb: y = 1 when the tile starts its pixels' sums afresh (else adds to
                  // them), z = 1 when it traced sample 0 (it has AOVs), w = the image's width;
                  // compose: y = VIEW_*, z = 1 to show the CPU reference, w = 1 for BGRA
    vec4 range;   // compose: x, y = the depth range shown; z = the difference's threshold
};

#ifdef __cplusplus
}  // namespace vkray::gpu
#endif
#undef VKRAY_CONST
#endif  // VKRAY_LAYOUT_H
