// Whitted shading after Hill ch. 14 (README "Shading"): the local model
// with shadow feelers (VKRAY_SHADOWS), textures (textures.glsl), and the
// reflected (VKRAY_REFLECTION) and refracted (VKRAY_REFRACTION) rays, followed
// with an explicit stack instead of Hill's recursive shade().
// Included by trace.comp after closestHit().

#include "textures.glsl"

// Where a hit lies: the point; n, the world unit normal pointing out of the
// surface (a mesh's interpolated one: refraction enters or leaves by it);
// geometric, the surface's own normal (a mesh's triangle's) turned to face
// the ray, beside which secondary rays leave; and m, n turned to the side of
// `geometric`, which shades.
struct Surface {
    vec3 p;
    vec3 n;
    vec3 geometric;
    vec3 m;
};

// (M^-1)^T v: a generic normal of GpuObject `index` in world space, unit.
vec3 toWorldNormal(uint index, vec3 v) {
    GpuObject object = objects[index];
    return normalize(v.x * object.objectFromWorld[0].xyz + v.y * object.objectFromWorld[1].xyz +
                     v.z * object.objectFromWorld[2].xyz);
}

Surface surfaceAt(Hit hit, vec3 origin, vec3 direction) {
    Surface s;
    s.p = origin + hit.t * direction;
    s.n = toWorldNormal(hit.surface, hit.genericNormal);
    s.geometric = toWorldNormal(hit.surface, hit.geometricNormal);
    if (dot(s.geometric, direction) > 0.0) s.geometric = -s.geometric;
    s.m = dot(s.n, s.geometric) < 0.0 ? -s.n : s.n;
    return s;
}

// The origin of a ray leaving point p toward `side` (a direction; which side
// of the surface with normal n it leaves to): Ray Tracing Gems ch. 6
// (Waechter and Binder). Each coordinate moves a fixed number of ulps of
// itself along the normal, so the offset grows with |p| like the rounding
// error of p; coordinates near 0, where ulps vanish, move by a small constant.
const float OFFSET_NEAR_ORIGIN = 1.0 / 32.0;
const float OFFSET_FLOAT_SCALE = 1.0 / 65536.0;
const float OFFSET_INT_SCALE = 256.0;

vec3 offsetOrigin(vec3 p, vec3 n, vec3 side) {
    if (dot(n, side) < 0.0) n = -n;
    ivec3 ulps = ivec3(OFFSET_INT_SCALE * n);
    // Adding to the bit pattern of a negative float moves it away from zero.
    ivec3 bits = floatBitsToInt(p) + ivec3(p.x < 0.0 ? -ulps.x : ulps.x,
                                           p.y < 0.0 ? -ulps.y : ulps.y,
                                           p.z < 0.0 ? -ulps.z : ulps.z);
    vec3 moved = intBitsToFloat(bits);
    return vec3(abs(p.x) < OFFSET_NEAR_ORIGIN ? p.x + OFFSET_FLOAT_SCALE * n.x : moved.x,
                abs(p.y) < OFFSET_NEAR_ORIGIN ? p.y + OFFSET_FLOAT_SCALE * n.y : moved.y,
                abs(p.z) < OFFSET_NEAR_ORIGIN ? p.z + OFFSET_FLOAT_SCALE * n.z : moved.z);
}

#if VKRAY_SHADOWS
// What object `index` passes of a light along the feeler origin + t
// direction, 0 < t < distance: all (1) when the feeler misses it, else the
// transparency of the surface it meets first; once per object, however many
// of its surfaces the feeler crosses.
float transmittance(uint index, vec3 origin, vec3 direction, float distance) {
    float t;
    vec3 n, geometric;
    uint surface;
    if (!intersectObject(index, origin, direction, distance, t, n, geometric, surface)) return 1.0;
    return objects[surface].material.y;
}

// The fraction of a light that reaches the feeler's origin: the product of
// what every object between passes, 0 as soon as an opaque one is met.
float lightThrough(vec3 origin, vec3 direction, float distance) {
    float through = 1.0;
#if VKRAY_OBJECT_BVH
    uint unboundedEnd = frame.counts.z + frame.counts.w;
    for (uint i = frame.counts.z; i < unboundedEnd && through > 0.0; ++i)
        through *= transmittance(objectIndex[i], origin, direction, distance);
    // Every node the feeler crosses, in any order: the first child next, the
    // second kept (so the stack holds at most one node per level).
    vec3 invD = 1.0 / direction;
    uint stack[BVH_STACK_SIZE];
    uint top = 0u;
    uint node = 0u;
    while (through > 0.0) {
        GpuBvhNode n = objectNodes[node];
        float enter;
        if (hitsBox(n.lo.xyz, n.hi.xyz, origin, invD, 0.0, distance, enter)) {
            uint count = floatBitsToUint(n.hi.w), first = floatBitsToUint(n.lo.w);
            if (count == 0u) {
                stack[top++] = first;
                node = node + 1u;
                continue;
            }
            for (uint i = first; i < first + count && through > 0.0; ++i)
                through *= transmittance(objectIndex[i], origin, direction, distance);
        }
        if (top == 0u) break;
        node = stack[--top];
    }
#else
    for (uint i = 0u; i < frame.image.w && through > 0.0; ++i)
        through *= transmittance(i, origin, direction, distance);
#endif
    return max(through, 0.0);
}
#endif

// Hill's local model at surface point s seen from direction v (unit, toward
// the viewer), with texture colour k scaling ambient and diffuse:
//   emissive + k ambient globalAmbient
//     + sum over lights of a L (k diffuse max(0, m.s) + specular max(0, m.h)^exponent)
// where a is what lightThrough() lets through. A light behind the surface
// (m.s <= 0) is shadowed by the surface itself. `record`: write the terms
// into the debug record (the primary hit of `vkray pixel`).
vec3 localShade(GpuObject object, Surface s, vec3 v, vec3 k, bool record) {
    vec3 color = object.emissive.rgb + k * object.ambient.rgb * frame.globalAmbient.rgb;
#if VKRAY_SHADOWS
    vec3 feelerOrigin = offsetOrigin(s.p, s.geometric, s.m);  // lit lights are on m's side
#endif
    for (uint i = 0u; i < frame.counts.x; ++i) {
        vec3 lightPosition = lights[i].position.xyz;
        vec3 lightColor = lights[i].color.rgb;
        vec3 toLight = normalize(lightPosition - s.p);
        float mDotS = dot(s.m, toLight);
        vec3 h = normalize(v + toLight);
        float mDotH = dot(s.m, h);
        float through = mDotS > 0.0 ? 1.0 : 0.0;
#if VKRAY_SHADOWS
        if (through > 0.0) {
            vec3 feeler = lightPosition - feelerOrigin;
            float distance = length(feeler);
            through = lightThrough(feelerOrigin, feeler / distance, distance);
        }
#endif
        vec3 diffuse = vec3(0.0), specular = vec3(0.0);
        if (through > 0.0) {
            diffuse = through * mDotS * k * object.diffuse.rgb * lightColor;
            if (mDotH > 0.0)
                specular = through * pow(mDotH, object.specular.w) * object.specular.rgb * lightColor;
        }
        color += diffuse + specular;
#if VKRAY_DEBUG_PIXEL
        if (record)
            debugEntries[frame.image.w + i] = GpuDebugEntry(vec4(diffuse, mDotS), vec4(specular, mDotH));
#endif
    }
    return color;
}

// The generic coordinates of world point p on GpuObject `index`.
vec3 genericPoint(uint index, vec3 p) {
    GpuObject object = objects[index];
    return vec3(dot(object.objectFromWorld[0], vec4(p, 1.0)),
                dot(object.objectFromWorld[1], vec4(p, 1.0)),
                dot(object.objectFromWorld[2], vec4(p, 1.0)));
}

// k(p) at a hit: (1, 1, 1) unless a texture variant is compiled in.
vec3 hitTexture(Hit hit, Surface s) {
#if VKRAY_TEXTURES || VKRAY_PIXMAPS
    return textureColor(objects[hit.surface], genericPoint(hit.surface, s.p), hit.genericNormal);
#else
    return vec3(1.0);
#endif
}

#if VKRAY_DEBUG_PIXEL
vec3 debugTexture;  // k at the primary hit, for the debug record's ambient term
#endif

#if VKRAY_REFLECTION || VKRAY_REFRACTION
// The media a ray is inside, innermost last (air outside all): the speeds of
// light of up to MEDIUM_STACK_SIZE nested transparent objects. Deeper
// nesting is counted but keeps the speed of the deepest one remembered.
struct Medium {
    vec4 speeds;
    uint depth;
};

float speedOf(Medium medium) {
    return medium.depth == 0u ? 1.0 : medium.speeds[min(medium.depth, MEDIUM_STACK_SIZE) - 1u];
}

// Snell's law at s for the unit direction d travelling in `medium` into or
// out of an object whose speed of light is objectSpeed: entering (against the
// outward normal) pushes it, leaving pops. Beyond the critical angle (total
// internal reflection) the mirror direction, in the same medium.
vec3 refracted(vec3 d, Surface s, float objectSpeed, inout Medium medium) {
    Medium beyond = medium;
    if (dot(s.n, d) < 0.0) {
        if (beyond.depth < MEDIUM_STACK_SIZE) beyond.speeds[beyond.depth] = objectSpeed;
        beyond.depth++;
    } else if (beyond.depth > 0u) {
        beyond.depth--;
    }
    float eta = speedOf(beyond) / speedOf(medium);  // c2 / c1
    float cos1 = -dot(s.m, d);
    float cos2Squared = 1.0 - eta * eta * (1.0 - cos1 * cos1);
    if (cos2Squared < 0.0) return normalize(d - 2.0 * dot(d, s.m) * s.m);
    medium = beyond;
    return normalize(eta * d + (eta * cos1 - sqrt(cos2Squared)) * s.m);
}

// One ray still to follow: it adds weight times what it sees.
struct RayTask {
    vec3 origin;
    vec3 direction;
    vec3 weight;
    uint level;  // 0: the primary ray
    Medium medium;
};
#endif

// What the ray origin + t direction sees: Hill's shade(), down to
// maxRecursionDepth. The tree of reflected and refracted rays is walked
// depth first with a stack: taking one ray adds at most two, one level
// deeper, so maxRecursionDepth + 1 entries suffice. `primary` and
// `primaryNormal` (m) describe the first hit, for the AOVs.
vec3 radiance(vec3 origin, vec3 direction, out Hit primary, out vec3 primaryNormal) {
    primaryNormal = vec3(0.0);
#if VKRAY_REFLECTION || VKRAY_REFRACTION
    uint maxLevel = min(frame.sampling.z, MAX_RECURSION_DEPTH);
    RayTask stack[MAX_RECURSION_DEPTH + 1u];
    uint top = 0u;
    stack[top++] = RayTask(origin, direction, vec3(1.0), 0u, Medium(vec4(1.0), 0u));
    vec3 color = vec3(0.0);
    while (top > 0u) {
        RayTask ray = stack[--top];
        Hit hit = closestHit(ray.origin, ray.direction);
        bool first = ray.level == 0u;
        if (first) primary = hit;
        if (hit.object < 0) {
            color += ray.weight * frame.background.rgb;
            continue;
        }
        Surface s = surfaceAt(hit, ray.origin, ray.direction);
        vec3 k = hitTexture(hit, s);
        if (first) {
            primaryNormal = s.m;
#if VKRAY_DEBUG_PIXEL
            debugTexture = k;
#endif
        }
        GpuObject object = objects[hit.surface];
        color += ray.weight * localShade(object, s, -ray.direction, k, first);
        if (ray.level >= maxLevel) continue;
        // Pushed refraction first, so that reflection is followed first, as Hill's shade() does.
#if VKRAY_REFRACTION
        if ((object.shape.z & FOLLOW_REFRACTION) != 0u) {
            Medium medium = ray.medium;
            vec3 t = refracted(ray.direction, s, object.material.z, medium);
            stack[top++] = RayTask(offsetOrigin(s.p, s.geometric, t), t, ray.weight * object.material.y,
                                   ray.level + 1u, medium);
        }
#endif
#if VKRAY_REFLECTION
        if ((object.shape.z & FOLLOW_REFLECTION) != 0u) {
            vec3 r = normalize(ray.direction - 2.0 * dot(ray.direction, s.m) * s.m);
            stack[top++] = RayTask(offsetOrigin(s.p, s.geometric, r), r, ray.weight * object.material.x,
                                   ray.level + 1u, ray.medium);
        }
#endif
    }
    return color;
#else
    primary = closestHit(origin, direction);
    if (primary.object < 0) return frame.background.rgb;
    Surface s = surfaceAt(primary, origin, direction);
    primaryNormal = s.m;
    vec3 k = hitTexture(primary, s);
#if VKRAY_DEBUG_PIXEL
    debugTexture = k;
#endif
    return localShade(objects[primary.surface], s, -direction, k, true);
#endif
}
