// Whitted shading after Hill ch. 14 (README "Shading"): the local model
// with shadow feelers (VKRAY_SHADOWS), textures (textures.glsl), and the
// reflected (VKRAY_REFLECTION) and refracted (VKRAY_REFRACTION) rays, followed
// with an explicit stack instead of Hill's recursive shade().
// Included by trace.comp after walkScene(). Secondary rays leave from
// offsetOrigin() (precision.glsl: the offset of each precision mode); ray
// geometry is `real` (double in the fp64 variant), shading float.

#include "textures.glsl"

// Where a hit lies: the point; n, the world unit normal pointing out of the
// surface (a mesh's interpolated one: refraction enters or leaves by it);
// geometric, the surface's own normal (a mesh's triangle's) turned to face
// the ray, beside which secondary rays leave; m, n turned to the side of
// `geometric`, which shades; and genericScale, the world length along
// `geometric` of the object's generic rounding (genericScaleAlong), which
// sizes the secondary rays' offset (offsetOrigin in precision.glsl).
struct Surface {
    rvec3 p;
    vec3 n;
    vec3 geometric;
    vec3 m;
    real genericScale;
    // The largest coordinate of p or of the origin of the ray that met it:
    // p = o + t d is rounded as the larger of the two (offsetOrigin).
    real reach;
};

// (M^-1)^T v: a generic normal of object `index` in world space, not
// normalised (computed with the ray geometry's M^-1: in double for fp64).
rvec3 toWorldNormalUnnormalised(uint index, rvec3 v) {
#if VKRAY_PRECISION_FP64
    dvec4 rows[3] = dvec4[3](doubleObjectRow(index, 0u), doubleObjectRow(index, 1u), doubleObjectRow(index, 2u));
#else
    vec4 rows[3] = vec4[3](objectRow(index, 0u), objectRow(index, 1u), objectRow(index, 2u));
#endif
    return v.x * rows[0].xyz + v.y * rows[1].xyz + v.z * rows[2].xyz;
}

// (M^-1)^T v, unit.
vec3 toWorldNormal(uint index, rvec3 v) { return vec3(normalize(toWorldNormalUnnormalised(index, v))); }

// The size of the generic coordinates of object `index`'s surface that
// its distance from a point depends on, whose rounding the secondary rays'
// offset must cover: 1 for the sphere and the cube (and the torus: 1.25,
// within the offset's margin), max(1, |s|) for a tapered cylinder, a mesh's
// largest bound coordinate (at most 1 for the built-in polyhedra, 1.72 for
// the teapot; a mesh file's or an outline's coordinates are its own). 0 for
// the plane and the square: their distance is generic z alone, O(the eye's
// height), which the eye-sized step covers; a mirror floor scaled by 1e7
// would otherwise have its reflected rays start 64 u x 1e7 = 38 units up.
real genericExtent(uint index) {
    uvec4 shape = objectShape(index);
    if (shape.x == KIND_PLANE || shape.x == KIND_SQUARE) return 0.0;
#if VKRAY_SHAPE_TAPERED_CYLINDER
    if (shape.x == KIND_TAPERED_CYLINDER) return max(real(1.0), abs(taperOf(index)));
#endif
#if VKRAY_SHAPE_MESH
    if (shape.x == KIND_MESH) {
        GpuBvhNode root = meshNode(meshOf(shape.y).range.x);
        vec3 reach = max(abs(root.lo.xyz), abs(root.hi.xyz));
        return real(max(1.0, max(reach.x, max(reach.y, reach.z))));
    }
#endif
    return 1.0;
}

// The world length, along the world normal w = (M^-1)^T g of generic normal
// g, of one generic unit: a point moved by delta along the unit world normal
// moves by delta |w| / |g| along the unit generic normal, so a generic
// distance e is the world distance e |g| / |w| (at most the largest singular
// value of M's linear part; smaller across a squashed axis). Times the
// generic extent: the world size of the generic coordinates' rounding unit
// at the hit. 0 where w is 0 (a degenerate normal).
real genericScaleAlong(uint index, rvec3 g, rvec3 w) {
    real lengthW = length(w);
    return lengthW > 0.0 ? length(g) / lengthW * genericExtent(index) : real(0.0);
}

Surface surfaceAt(Hit hit, rvec3 origin, rvec3 direction) {
    Surface s;
    s.p = origin + hit.t * direction;
    rvec3 extent = max(abs(s.p), abs(origin));
    s.reach = max(extent.x, max(extent.y, extent.z));
    s.n = toWorldNormal(hit.surface, hit.genericNormal);
    rvec3 geometric = toWorldNormalUnnormalised(hit.surface, hit.geometricNormal);
    s.geometric = vec3(normalize(geometric));
    s.genericScale = genericScaleAlong(hit.surface, hit.geometricNormal, geometric);
    if (dot(s.geometric, vec3(direction)) > 0.0) s.geometric = -s.geometric;
    s.m = dot(s.n, s.geometric) < 0.0 ? -s.n : s.n;
    return s;
}

// Light i's term of Hill's local model at surface point s seen from
// direction v (unit, toward the viewer), with texture colour k scaling the
// diffuse reflection:
//     a L (k diffuse max(0, m.s) + specular max(0, m.h)^exponent)
// where a (`through`) is what the light's feeler let through; a light
// behind the surface (m.s <= 0) is shadowed by the surface itself (a = 0).
// `record`: write the terms into the debug record (the primary hit of
// `vkray pixel`).
#if VKRAY_LIGHTS
vec3 lightTerm(GpuMaterial object, Surface s, vec3 v, vec3 k, uint i, float through, bool record) {
    GpuLight light = lightOf(i);
    vec3 lightColor = light.color.rgb;
    vec3 toLight = normalize(light.position.xyz - vec3(s.p));
    float mDotS = dot(s.m, toLight);
    float mDotH = dot(s.m, normalize(v + toLight));
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    if (mDotS > 0.0 && through > 0.0) {
        diffuse = through * mDotS * k * object.diffuse.rgb * lightColor;
        if (mDotH > 0.0)
            specular = through * pow(mDotH, object.specular.w) * object.specular.rgb * lightColor;
    }
#if VKRAY_DEBUG_PIXEL
    if (record)
        debugEntries[frame.image.w + i] = GpuDebugEntry(vec4(diffuse, mDotS), vec4(specular, mDotH));
#endif
    return diffuse + specular;
}
#endif
// The generic point of a hit of the ray origin + t direction: o + t d on the
// ray's own generic form, the one the surface was intersected on, in `real`
// (double, from GpuDoubleObject's rows, in fp64), rounded to float only once
// O(1). Computed from the float world point instead (M^-1 p in float), fp64
// textures were float's seen from afar: the generic eye's magnitude |M^-1 eye|
// cancels down to the O(1) point, leaving an error of ~u |M^-1 eye| (a
// checkered unit sphere seen from 8000 radii, cells of 0.05: 0.19 % of the
// pixels on the wrong side of a cell border). In robust mode the ray itself is off by that much
// (its float direction and generic eye), so o + t d is no better there than
// M^-1 p (docs/numerics.md, "Envelope": the distance within which robust's
// textures agree).
vec3 genericHitPoint(Hit hit, rvec3 origin, rvec3 direction) {
    rvec3 o, d;
    toObjectSpace(hit.surface, origin, direction, o, d);
    return vec3(o + hit.t * d);
}

// k(p) at a hit of the ray origin + t direction: (1, 1, 1) unless a texture
// variant is compiled in.
vec3 hitTexture(Hit hit, rvec3 origin, rvec3 direction) {
#if VKRAY_TEXTURES || VKRAY_PIXMAPS
    return textureColor(materialOf(hit.surface), objectShape(hit.surface).x,
                        genericHitPoint(hit, origin, direction),
                        vec3(hit.genericNormal));
#else
    return vec3(1.0);
#endif
}

#if VKRAY_DEBUG_PIXEL
vec3 debugTexture;  // k at the primary hit, for the debug record's ambient term
#endif

// The media a ray is inside, innermost last (air outside all): the speeds of
// light of up to MEDIUM_STACK_SIZE nested transparent objects. Deeper
// nesting is counted but keeps the speed of the deepest one remembered.
struct Medium {
    vec4 speeds;
    uint depth;
};

#if VKRAY_REFRACTION
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
    // cos2^2 = 1 - eta^2 (1 - cos1^2), as (1 - eta^2) + eta^2 cos1^2: in the
    // textbook's order 1 - cos1^2 rounds to 1 once cos1 < ~2.4e-4, and a
    // grazing ray passing between equal speeds (eta = 1) left along the
    // surface instead of straight on; here it keeps its cos1^2 exactly.
    float cos2Squared = (1.0 - eta * eta) + eta * eta * (cos1 * cos1);
    if (cos2Squared < 0.0) return normalize(d - 2.0 * dot(d, s.m) * s.m);
    medium = beyond;
    return normalize(eta * d + (eta * cos1 - sqrt(cos2Squared)) * s.m);
}
#endif

// One ray still to follow: it adds weight times what it sees.
struct RayTask {
    rvec3 origin;
    rvec3 direction;
    vec3 weight;
    uint level;  // 0: the primary ray
    Medium medium;
};

// Rays to follow. A hit spawns at most two, one level deeper: the first
// (the reflected ray, else the refracted one) is followed next, from
// registers (nextRay); the refracted ray of a hit that also reflects waits
// on a stack, for after the reflected ray's tree, as in Hill's shade(). On
// llvmpipe each word a shader stores is a loop over the 8 lanes, so a chain
// of rays (reflection or refraction alone) stores none, and a tree one ray a
// branch. maxRecursionDepth + 1 entries (frame.sampling.w) hold the deepest
// tree. The stack lives in a storage buffer, frame.sampling.w entries per
// invocation, so that it outlasts a dispatch: a ray that pauses puts its next
// ray there too. A storage buffer, not a texel buffer as the scene's arrays:
// llvmpipe stores a uvec4 of a storage buffer in one loop over the lanes but
// an image texel a word a loop (a push: 4 loops, not 16), and its loads skip
// the lanes that do not pop, where a texel load reads all eight every turn.
// Without secondary rays the next ray is a sample's primary ray, made again
// when a dispatch resumes.
#define VKRAY_RAY_STACK (VKRAY_REFLECTION || VKRAY_REFRACTION)
RayTask nextRay;
bool haveNext;

#if VKRAY_RAY_STACK
// GpuRayTask, or GpuDoubleRayTask in fp64, as uvec4s.
layout(std430, set = 0, binding = BINDING_RAY_STACK) buffer PendingRays { uvec4 pendingRays[]; };
uint rayStackBase;  // this invocation's first entry

#if VKRAY_PRECISION_FP64
const uint PENDING_RAY_TEXELS = DOUBLE_RAY_TASK_TEXELS;
void storeReal4(int at, dvec4 v) {
    pendingRays[at] = uvec4(unpackDouble2x32(v.x), unpackDouble2x32(v.y));
    pendingRays[at + 1] = uvec4(unpackDouble2x32(v.z), unpackDouble2x32(v.w));
}
dvec4 loadReal4(int at) {
    uvec4 xy = pendingRays[at], zw = pendingRays[at + 1];
    return dvec4(packDouble2x32(xy.xy), packDouble2x32(xy.zw), packDouble2x32(zw.xy),
                 packDouble2x32(zw.zw));
}
#else
const uint PENDING_RAY_TEXELS = RAY_TASK_TEXELS;
void storeReal4(int at, vec4 v) { pendingRays[at] = floatBitsToUint(v); }
vec4 loadReal4(int at) { return texelAsVec4(pendingRays[at]); }
#endif
const int REAL4_TEXELS = int(PENDING_RAY_TEXELS - 2u) / 2;  // 1, or 2 in fp64

void pushRay(inout uint top, RayTask task) {
    int at = int((rayStackBase + top++) * PENDING_RAY_TEXELS);
    storeReal4(at, rvec4(task.origin, real(task.level)));
    storeReal4(at + REAL4_TEXELS, rvec4(task.direction, real(task.medium.depth)));
    pendingRays[at + 2 * REAL4_TEXELS] = floatBitsToUint(vec4(task.weight, 0.0));
    pendingRays[at + 2 * REAL4_TEXELS + 1] = floatBitsToUint(task.medium.speeds);
}

RayTask popRay(inout uint top) {
    int at = int((rayStackBase + --top) * PENDING_RAY_TEXELS);
    rvec4 origin = loadReal4(at), direction = loadReal4(at + REAL4_TEXELS);
    vec4 weight = texelAsVec4(pendingRays[at + 2 * REAL4_TEXELS]);
    vec4 speeds = texelAsVec4(pendingRays[at + 2 * REAL4_TEXELS + 1]);
    return RayTask(origin.xyz, direction.xyz, weight.rgb, uint(origin.w),
                   Medium(speeds, uint(direction.w)));
}
#endif

RayTask primaryTask(uint k) {
    return RayTask(rayEye(), sampleDirection(k), vec3(1.0), 0u, Medium(vec4(1.0), 0u));
}

#if VKRAY_SHADOWS
// The first light from `i` on that faces surface s (whose feeler is to be
// walked); a light behind the surface adds nothing (a = 0), so it needs no
// step of its own. The lights passed over are recorded for `vkray pixel`.
uint nextFacingLight(uint i, GpuMaterial object, Surface s, vec3 v, vec3 k, bool record) {
    for (; i < frame.counts.x; ++i) {
        ++loopTurns;
        if (dot(s.m, lightOf(i).position.xyz - vec3(s.p)) > 0.0) break;
#if VKRAY_DEBUG_PIXEL
        lightTerm(object, s, v, k, i, 0.0, record);
#endif
    }
    return i;
}

// The shadow feeler from surface s toward light i: from just off the
// surface, on m's side (where lit lights are), to the light.
void feelerToward(uint i, Surface s, out rvec3 origin, out rvec3 direction, out real tMax) {
    origin = offsetOrigin(s.p, s.reach, s.geometric, s.m, lightOf(i).position.xyz - vec3(s.p), s.genericScale);
    direction = lightOf(i).position.xyz - origin;
    tMax = length(direction);
    direction /= tMax;
}
#endif

// Where a walk is a few objects' tests unrolled (VKRAY_OBJECTS), it is a
// small part of a turn of traceSamples' loop, and the hit's shading most of
// it, which llvmpipe runs on every turn whatever the lanes need: a hit's
// feelers are then walked in a loop of their own at the hit, its shading
// run once for them all, at the price of a second copy of the walk's code.
// A BVH's walk, or one with CSG's evaluation, is most of a turn and much
// more code: there each feeler takes a turn of the loop, which walks the
// scene in one place only (BENCHMARKS.md, ninth round).
#define VKRAY_FEELER_LOOP (VKRAY_SHADOWS && VKRAY_OBJECTS > 0 && !VKRAY_CSG)

#if VKRAY_FEELER_HINTS
// The hints of feelers' BVH walks (walkScene): the entry of the object that
// stopped the last feeler toward each of the first HINT_LIGHTS lights, kept
// for each of the two rows of lanes of an 8-lane vector (a 4x2 block of
// pixels). llvmpipe runs a workgroup's vectors one after the other, so a
// feeler's hint is what stopped the feeler toward the same light two pixels
// above (rows of an 8x8 workgroup, trace.comp's main), most often the wall
// whose shadow both lie in; on a GPU that runs the vectors at once it is
// another nearby invocation's, or anything: whether a feeler gets through
// never depends on its hint, only how long its walk takes.
const uint HINT_LIGHTS = 4u;
shared uint walkHints[2u * gl_WorkGroupSize.x * HINT_LIGHTS];
#endif

// This invocation's samples, from where `ray` (GpuRayProgress) says an
// earlier dispatch left them, until they are done or loopTurns has passed
// `budget`. Each sample is Hill's shade() down to maxRecursionDepth, its
// recursion unrolled: the tree of reflected and refracted rays is walked
// depth first with the stack of pending rays; the shadow feelers of a hit
// are walked one per turn, or (VKRAY_FEELER_LOOP) all of them at the hit.
// Each turn walks a ray or a feeler (or a ray, then its hit's feelers):
// llvmpipe runs a loop's whole body on every turn, walk included, whatever
// the lanes need, so the decision to stop is taken at the end of the turn
// that finished the work, never at the start of an extra one. A dispatch
// stops only between two rays, when all that is pending is on the stack,
// so a paused sample goes on as if it had never stopped: the image does not
// depend on the budget. When this dispatch traced sample 0's primary ray,
// aovFound is true and `aov` holds the pixel's object id and AOVs (its
// colour 0); `firstPixel` is the pixel of the stress output.
void traceSamples(inout GpuRayProgress ray, uint samples, uint firstPixel, uint budget,
                  out bool aovFound, out GpuPixel aov) {
    uint sampleIndex = floatBitsToUint(ray.sum.w);
    uint top = floatBitsToUint(ray.color.w);  // rays on the stack
    vec3 sum = ray.sum.rgb, color = ray.color.rgb;
    // The sample's primary ray, unless a paused sample left rays on the
    // stack: both sides of an if run on llvmpipe, so it is made for both.
    nextRay = primaryTask(sampleIndex);
    haveNext = top == 0u;
    // The hit whose lights are being visited (while light < the light count).
    RayTask task;
    Surface s;
    GpuMaterial object;
    vec3 k;
    const uint lightCount = frame.counts.x;
    uint light = lightCount;
    // Sample 0's primary hit (the AOVs), for main() to write.
    aovFound = false;
#if VKRAY_FEELER_HINTS
    uint hintLane = gl_LocalInvocationID.x + (gl_LocalInvocationID.y & 1u) * gl_WorkGroupSize.x;
#endif
    while (true) {
        ++loopTurns;
        // This turn's walk: the feeler toward the next facing light, or the next ray.
#if VKRAY_FEELER_LOOP
        const bool feeler = false;
#else
        bool feeler = light < lightCount;
#endif
        rvec3 walkOrigin, walkDirection;
        real walkMax = INFINITY;
        if (feeler) {
#if VKRAY_SHADOWS
            feelerToward(light, s, walkOrigin, walkDirection, walkMax);
#endif
        } else {
#if VKRAY_RAY_STACK
            task = haveNext ? nextRay : popRay(top);
#else
            task = nextRay;
#endif
            haveNext = false;
            walkOrigin = task.origin;
            walkDirection = task.direction;
        }

        Hit hit;
        float through;
#if VKRAY_FEELER_HINTS
        bool hinted = feeler && light < HINT_LIGHTS;
        uint hintSlot = hintLane * HINT_LIGHTS + min(light, HINT_LIGHTS - 1u);
        uint hint = hinted ? walkHints[hintSlot] : NO_ENTRY;
#ifdef VKRAY_ARBITRARY_HINTS
        // A test hook (variant_equivalence_test.cpp): a number from the
        // pixel and the light, an entry of any object or none, in place of
        // the hint: the picture must not change.
        hint = ((rayPixel.x * 73856093u) ^ (rayPixel.y * 19349663u) ^ (light * 83492791u)) %
               (frame.counts.z + 4u);
#endif
        walkScene(walkOrigin, walkDirection, walkMax, feeler, hint, hit, through);
        if (hinted) walkHints[hintSlot] = hit.entry;
#else
        walkScene(walkOrigin, walkDirection, walkMax, feeler, NO_ENTRY, hit, through);
#endif
#if VKRAY_STRESS_OUTPUT
        stressRecordWalk(firstPixel, sampleIndex, task.level, feeler, light, walkOrigin,
                         walkDirection, hit);
#endif

        bool record = task.level == 0u && sampleIndex == RECORDED_SAMPLE;
        vec3 v = -vec3(task.direction);
        if (feeler) {
#if VKRAY_SHADOWS
            color += task.weight * lightTerm(object, s, v, k, light, through, record);
            light = nextFacingLight(light + 1u, object, s, v, k, record);
#endif
        } else {
            if (record) {
#if VKRAY_DEBUG_PIXEL
                debugHit = hit;
                debugDirection = task.direction;
#endif
                aovFound = true;
                aov = GpuPixel(vec4(0.0, 0.0, 0.0, intBitsToFloat(hit.object)),
                               vec4(0.0, 0.0, 0.0, float(hit.t)));
            }
            if (hit.object < 0) {
                color += task.weight * frame.background.rgb;
            } else {
#if VKRAY_FEELER_LOOP
                // This hit's own: no later turn reads them (with llvmpipe's
                // lane masks, the loop's would be carried from turn to turn).
                Surface s;
                GpuMaterial object;
                vec3 k;
#endif
                s = surfaceAt(hit, task.origin, task.direction);
                k = hitTexture(hit, task.origin, task.direction);
                object = materialOf(hit.surface);
                uint follow = objectShape(hit.surface).z;
                if (record) {
                    aov.normal.xyz = s.m;
#if VKRAY_DEBUG_PIXEL
                    debugTexture = k;
#endif
                }
                // Emissive and ambient now; each facing light's feeler in the
                // turns that follow, or now (VKRAY_FEELER_LOOP; without
                // shadows, every light now).
                color += task.weight * (object.emissive.rgb + k * object.ambient.rgb * frame.globalAmbient.rgb);
#if VKRAY_SHADOWS && VKRAY_FEELER_LOOP
                for (uint light = nextFacingLight(0u, object, s, v, k, record); light < lightCount;
                     light = nextFacingLight(light + 1u, object, s, v, k, record)) {
                    ++loopTurns;
                    rvec3 feelerOrigin, feelerDirection;
                    real feelerMax;
                    feelerToward(light, s, feelerOrigin, feelerDirection, feelerMax);
                    Hit blocker;
                    float through;
                    walkScene(feelerOrigin, feelerDirection, feelerMax, true, NO_ENTRY, blocker,
                              through);
#if VKRAY_STRESS_OUTPUT
                    stressRecordWalk(firstPixel, sampleIndex, task.level, true, light, feelerOrigin,
                                     feelerDirection, blocker);
#endif
                    color += task.weight * lightTerm(object, s, v, k, light, through, record);
                }
#elif VKRAY_SHADOWS
                light = nextFacingLight(0u, object, s, v, k, record);
#elif VKRAY_LIGHTS
                for (uint i = 0u; i < lightCount; ++i) {
                    ++loopTurns;
                    bool facing = dot(s.m, lightOf(i).position.xyz - vec3(s.p)) > 0.0;
                    color += task.weight * lightTerm(object, s, v, k, i, facing ? 1.0 : 0.0, record);
                }
#endif
                // The secondary rays wait until the lights are done; the
                // reflected ray goes next, the refracted one after its tree.
                if (task.level < min(frame.sampling.z, MAX_RECURSION_DEPTH)) {
#if VKRAY_REFRACTION
                    if ((follow & FOLLOW_REFRACTION) != 0u) {
                        Medium medium = task.medium;
                        vec3 t = refracted(vec3(task.direction), s, object.material.z, medium);
                        nextRay = RayTask(offsetOrigin(s.p, s.reach, s.geometric, t, t, s.genericScale), t,
                                          task.weight * object.material.y, task.level + 1u, medium);
                        haveNext = true;
                    }
#endif
#if VKRAY_REFLECTION
                    if ((follow & FOLLOW_REFLECTION) != 0u) {
#if VKRAY_REFRACTION
                        if (haveNext) pushRay(top, nextRay);  // the refracted ray waits
#endif
                        rvec3 r = normalize(task.direction - 2.0 * dot(task.direction, rvec3(s.m)) * rvec3(s.m));
                        nextRay = RayTask(offsetOrigin(s.p, s.reach, s.geometric, vec3(r), vec3(r), s.genericScale), r,
                                          task.weight * object.material.x, task.level + 1u, task.medium);
                        haveNext = true;
                    }
#endif
                }
            }
        }

        // Between two rays (no feeler left): the sample ends when nothing is
        // pending, its colour joining the sum in sample order; the dispatch
        // pauses once past the budget.
        if (light >= lightCount) {
            if (!haveNext && top == 0u) {
                sum += color;
                color = vec3(0.0);
#if VKRAY_ANTIALIAS
                if (++sampleIndex == samples) break;
                nextRay = primaryTask(sampleIndex);
                haveNext = true;
#else
                // One sample a pixel: no next ray to make (were there one, it
                // would start in the next dispatch, the ray not done).
                ++sampleIndex;
                break;
#endif
            }
            if (loopTurns >= budget) break;
        }
    }
#if VKRAY_RAY_STACK
    if (haveNext) pushRay(top, nextRay);  // paused: it waits for the next dispatch
#endif
    ray = GpuRayProgress(vec4(sum, uintBitsToFloat(sampleIndex)), vec4(color, uintBitsToFloat(top)));
}
