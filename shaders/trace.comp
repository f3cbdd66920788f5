// vkray's ray tracer, one compute invocation per primary ray (Hill ch. 14):
// build the ray S + c t, intersect every object in its generic space, keep
// the closest hit, and shade it with Hill's local model.
//
// The host compiles a variant holding only what the scene uses (host/gpu/
// shader_variant.h): VKRAY_SHAPE_SPHERE, _PLANE, _SQUARE, _CUBE,
// _TAPERED_CYLINDER, _TORUS, _MESH and VKRAY_CSG are 1 for the shapes
// present; VKRAY_OBJECT_BVH finds objects through a BVH instead of testing
// each; VKRAY_DEBUG_PIXEL (for `vkray pixel`) also records every step of the
// one ray the host dispatches into the debug buffer. VKRAY_PRECISION_NAIVE
// selects the textbook float formulas (precision.glsl).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "layout.h"
#include "precision.glsl"

layout(local_size_x = WORKGROUP_X, local_size_y = WORKGROUP_Y, local_size_z = 1) in;

layout(std140, set = 0, binding = BINDING_FRAME) uniform FrameBlock { FrameParams frame; };
layout(std430, set = 0, binding = BINDING_OBJECTS) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(std430, set = 0, binding = BINDING_LIGHTS) readonly buffer LightBlock { GpuLight lights[]; };
layout(std430, set = 0, binding = BINDING_PIXELS) writeonly buffer PixelBlock { GpuPixel pixels[]; };
layout(push_constant) uniform TileBlock { TileParams tileParams; };
#if VKRAY_DEBUG_PIXEL
layout(std430, set = 0, binding = BINDING_DEBUG) writeonly buffer DebugBlock {
    GpuDebugHeader debugHeader;
    GpuDebugEntry debugEntries[];  // objects, then lights
};
#endif

const float INFINITY = 1.0 / 0.0;

// The world ray in an object's generic space: M^-1 applied and the direction
// not renormalised, so the generic t is the world t.
void toObjectSpace(uint index, vec3 origin, vec3 direction, out vec3 o, out vec3 d) {
    GpuObject object = objects[index];
    o = vec3(dot(object.objectFromWorld[0], vec4(origin, 1.0)),
             dot(object.objectFromWorld[1], vec4(origin, 1.0)),
             dot(object.objectFromWorld[2], vec4(origin, 1.0)));
    d = vec3(dot(object.objectFromWorld[0].xyz, direction),
             dot(object.objectFromWorld[1].xyz, direction),
             dot(object.objectFromWorld[2].xyz, direction));
}

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
    float t;
    int object;          // the scene object (its id), -1 for none
    uint surface;        // the GpuObject whose surface was hit (a CSG primitive, or the object)
    vec3 genericNormal;  // in the generic space of `surface`
};

// The nearest hit of object `index` in (0, tMax); for a CSG object, the
// primitive whose surface it is.
bool intersectObject(uint index, vec3 origin, vec3 direction, float tMax, out float t,
                     out vec3 n, out uint surface) {
#if VKRAY_PRECISION_NAIVE
    const float tMin = NAIVE_EPSILON;  // the textbook's fixed epsilon, on every ray
#else
    const float tMin = 0.0;  // robust: primary rays start at the eye, not on a surface
#endif
    surface = index;
    GpuObject object = objects[index];
#if VKRAY_CSG
    if (object.shape.x == KIND_BOOLEAN)
        return intersectCsg(object.shape.y, origin, direction, tMin, tMax, t, n, surface);
#endif
    vec3 o, d;
    toObjectSpace(index, origin, direction, o, d);
    switch (object.shape.x) {
#if VKRAY_SHAPE_SPHERE
    case KIND_SPHERE: return intersectSphere(o, d, tMin, tMax, t, n);
#endif
#if VKRAY_SHAPE_PLANE
    case KIND_PLANE: return intersectPlane(o, d, tMin, tMax, t, n);
#endif
#if VKRAY_SHAPE_SQUARE
    case KIND_SQUARE: return intersectSquare(o, d, tMin, tMax, t, n);
#endif
#if VKRAY_SHAPE_CUBE
    case KIND_CUBE: return intersectCube(o, d, tMin, tMax, t, n);
#endif
#if VKRAY_SHAPE_TAPERED_CYLINDER
    case KIND_TAPERED_CYLINDER:
        return intersectTaperedCylinder(o, d, uintBitsToFloat(object.shape.y), tMin, tMax, t, n);
#endif
#if VKRAY_SHAPE_TORUS
    case KIND_TORUS: return intersectTorus(o, d, tMin, tMax, t, n);
#endif
#if VKRAY_SHAPE_MESH
    case KIND_MESH: return intersectMesh(object.shape.y, o, d, tMin, tMax, t, n);
#endif
    default: return false;
    }
}

// Surfaces that coincide (stacked cubes, a def used twice) are hit at the same
// t up to rounding. Hits within this relative distance count as a tie, won by
// the lower object index, as in the CPU reference, so the choice does not
// depend on the order the BVH happens to visit them.
const float TIE_TOLERANCE = 1e-6;

void testObject(uint index, vec3 origin, vec3 direction, inout Hit hit) {
    float t;
    vec3 n;
    uint surface;
    if (!intersectObject(index, origin, direction, hit.t * (1.0 + TIE_TOLERANCE), t, n, surface))
        return;
    bool nearer = t < hit.t * (1.0 - TIE_TOLERANCE);
    bool tieWon = hit.object < 0 || int(index) < hit.object;
    if (nearer || tieWon) {
        hit.t = t;
        hit.object = int(index);
        hit.surface = surface;
        hit.genericNormal = n;
    }
}

#if VKRAY_OBJECT_BVH
layout(std430, set = 0, binding = BINDING_OBJECT_NODES) readonly buffer ObjectNodeBlock { GpuBvhNode objectNodes[]; };
layout(std430, set = 0, binding = BINDING_OBJECT_INDEX) readonly buffer ObjectIndexBlock { uint objectIndex[]; };

#endif

Hit closestHit(vec3 origin, vec3 direction) {
    Hit hit;
    hit.t = INFINITY;
    hit.object = -1;
    hit.surface = 0u;
    hit.genericNormal = vec3(0.0);
#if VKRAY_OBJECT_BVH
    // Unbounded objects (planes) first, then the BVH over the rest.
    for (uint i = frame.counts.z; i < frame.counts.z + frame.counts.w; ++i)
        testObject(objectIndex[i], origin, direction, hit);
    vec3 invD = 1.0 / direction;
    uint stack[BVH_STACK_SIZE];
    float stackEnter[BVH_STACK_SIZE];
    uint top = 0u;
    uint node = 0u;
    float enter;
    GpuBvhNode root = objectNodes[0];
    bool walking = hitsBox(root.lo.xyz, root.hi.xyz, origin, invD, 0.0, hit.t, enter);
    while (walking) {
        GpuBvhNode n = objectNodes[node];
        uint count = floatBitsToUint(n.hi.w), first = floatBitsToUint(n.lo.w);
        if (count == 0u) {
            uint nearIndex, farIndex;
            float farEnter;
            int hits = orderChildren(objectNodes[node + 1u], node + 1u, objectNodes[first], first,
                                     origin, invD, 0.0, hit.t, nearIndex, farIndex, farEnter);
            if (hits == 2) {
                stack[top] = farIndex;
                stackEnter[top++] = farEnter;
            }
            if (hits > 0) {
                node = nearIndex;
                continue;
            }
        } else {
            for (uint i = first; i < first + count; ++i) testObject(objectIndex[i], origin, direction, hit);
        }
        // Next: the nearest kept node the ray still reaches before its hit.
        walking = false;
        while (top > 0u && !walking) {
            --top;
            walking = stackEnter[top] <= hit.t;
            node = stack[top];
        }
    }
#else
    for (uint i = 0u; i < frame.image.w; ++i) testObject(i, origin, direction, hit);
#endif
    return hit;
}

// World normal = (M^-1)^T n_generic, normalised, turned to face the ray.
vec3 worldNormal(uint index, vec3 genericNormal, vec3 direction) {
    GpuObject object = objects[index];
    vec3 n = normalize(genericNormal.x * object.objectFromWorld[0].xyz +
                       genericNormal.y * object.objectFromWorld[1].xyz +
                       genericNormal.z * object.objectFromWorld[2].xyz);
    return dot(n, direction) > 0.0 ? -n : n;
}

// Hill's local model: emissive + ambient * globalAmbient + for each light
// (diffuse max(0, m.s) + specular max(0, m.h)^exponent) * light colour.
vec3 shade(uint index, vec3 p, vec3 m, vec3 v) {
    GpuObject object = objects[index];
    vec3 color = object.emissive.rgb + object.ambient.rgb * frame.globalAmbient.rgb;
    for (uint i = 0u; i < frame.counts.x; ++i) {
        vec3 s = normalize(lights[i].position.xyz - p);
        float mDotS = dot(m, s);
        vec3 diffuse = mDotS > 0.0 ? mDotS * object.diffuse.rgb * lights[i].color.rgb : vec3(0.0);
        vec3 h = normalize(v + s);
        float mDotH = dot(m, h);
        vec3 specular = mDotH > 0.0
            ? pow(mDotH, object.specular.w) * object.specular.rgb * lights[i].color.rgb
            : vec3(0.0);
        color += diffuse + specular;
#if VKRAY_DEBUG_PIXEL
        debugEntries[frame.image.w + i] = GpuDebugEntry(vec4(diffuse, mDotS), vec4(specular, mDotH));
#endif
    }
    return color;
}

#if VKRAY_DEBUG_PIXEL
// Every object on its own, for `vkray pixel`: its generic ray and nearest t.
void recordObjectTests(vec3 origin, vec3 direction) {
    for (uint i = 0u; i < frame.image.w; ++i) {
        vec3 o, d, n;
        toObjectSpace(i, origin, direction, o, d);
        float t;
        uint surface;
        if (!intersectObject(i, origin, direction, INFINITY, t, n, surface)) t = INFINITY;
        debugEntries[i] = GpuDebugEntry(vec4(o, t), vec4(d, 0.0));
    }
}
#endif

void main() {
    // This invocation's ray: one per pixel, or one per block x block pixels.
    uint block = frame.image.z;
    uvec2 rayInTile = gl_GlobalInvocationID.xy;
    uvec2 tileOrigin = tileParams.tile.xy;
    uvec2 tileSize = tileParams.tile.zw;
    uvec2 first = rayInTile * block;  // first pixel of the block, tile-relative
    if (first.x >= tileSize.x || first.y >= tileSize.y) return;
    uvec2 pixel = tileOrigin + first;

    vec2 imagePoint = vec2(pixel) + 0.5 * float(block);
    vec2 screen = vec2(2.0 * imagePoint.x / float(frame.image.x) - 1.0,
                       1.0 - 2.0 * imagePoint.y / float(frame.image.y));
    float tanHalfFov = frame.eye.w;
    float aspect = frame.cameraU.w;
    vec3 direction = normalize(-frame.cameraN.xyz +
                               screen.x * tanHalfFov * aspect * frame.cameraU.xyz +
                               screen.y * tanHalfFov * frame.cameraV.xyz);
    vec3 origin = frame.eye.xyz;

    GpuPixel result;
    Hit hit = closestHit(origin, direction);
    vec3 p = vec3(0.0);
    if (hit.object < 0) {
        result.color = vec4(frame.background.rgb, INFINITY);
        result.normal = vec4(0.0, 0.0, 0.0, intBitsToFloat(-1));
    } else {
        p = origin + hit.t * direction;
        vec3 m = worldNormal(hit.surface, hit.genericNormal, direction);
        result.color = vec4(shade(hit.surface, p, m, -direction), hit.t);
        result.normal = vec4(m, intBitsToFloat(hit.object));
    }
#if VKRAY_DEBUG_PIXEL
    recordObjectTests(origin, direction);
    GpuObject object = objects[hit.surface];
    bool hitSomething = hit.object >= 0;
    debugHeader.rayOrigin = vec4(origin, 0.0);
    debugHeader.rayDirection = vec4(direction, 0.0);
    debugHeader.hitPoint = vec4(p, hit.t);
    debugHeader.normal = result.normal;
    debugHeader.emissive = vec4(hitSomething ? object.emissive.rgb : vec3(0.0), 0.0);
    debugHeader.ambient =
        vec4(hitSomething ? object.ambient.rgb * frame.globalAmbient.rgb : vec3(0.0), 0.0);
    debugHeader.color = vec4(result.color.rgb, 0.0);
    debugHeader.counts = uvec4(frame.image.w, hitSomething ? frame.counts.x : 0u, 0u, 0u);
#endif

    // Fill the block (clipped to the tile).
    uvec2 last = min(first + uvec2(block), tileSize);
    for (uint y = first.y; y < last.y; ++y)
        for (uint x = first.x; x < last.x; ++x)
            pixels[y * tileSize.x + x] = result;
}
