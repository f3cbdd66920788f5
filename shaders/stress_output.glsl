// The stress-output variant (VKRAY_STRESS_OUTPUT = 1): the mode's own shader
// writes, per pixel, what its first primary ray (sample 0) and the secondary
// rays of that hit found (GpuStressSample, layout.h), so that `vkray stress`
// counts acne, flips and t errors from the shader itself and `vkray pixel`
// prints its numbers at the precision they were computed in. Included by
// trace.comp before testObject(); three calls reach it:
//   testObject       stressNoteTest: an object a walk tested, and whether it was met
//   traceSamples     stressRecordWalk, after each walk (shade.glsl)
// Nothing here changes what is traced or drawn.
#if VKRAY_STRESS_OUTPUT
layout(std430, set = 0, binding = BINDING_STRESS_OUTPUT) buffer StressBlock {
    GpuStressSample stressSamples[];
};

rvec3 toWorldNormalUnnormalised(uint index, rvec3 v);  // shade.glsl
rvec3 rayEye();  // below in trace.comp

// While the feelers of sample 0's primary hit walk the scene: the object
// they leave, and whether the walk in progress met any object, and that one.
bool stressFeelersOfPrimary = false;
int stressLeftObject = -1;
bool stressMetAny = false, stressMetLeft = false;

void stressNoteTest(uint index, bool feeler, bool met) {
    if (!feeler || !stressFeelersOfPrimary || !met) return;
    stressMetAny = true;
    if (int(index) == stressLeftObject) stressMetLeft = true;
}

uvec4 stressDoubleBits(real a, real b) {
#if VKRAY_PRECISION_FP64
    return uvec4(unpackDouble2x32(a), unpackDouble2x32(b));
#else
    return uvec4(0u);
#endif
}

// After a walk of traceSamples: a feeler (toward `light`) of the hit of a ray
// of `level`, or the ray of `level` itself from origin along direction, with
// `hit` its closest hit; `pixel` the sample's entry.
void stressRecordWalk(uint pixel, uint sampleIndex, uint level, bool feeler, uint light,
                      rvec3 origin, rvec3 direction, Hit hit) {
    if (feeler) {
        if (stressFeelersOfPrimary && light < STRESS_MAX_LIGHTS) {
            uint bit = 1u << light;
            stressSamples[pixel].hit.y |= bit;
            if (stressMetAny) stressSamples[pixel].hit.z |= bit;
            if (stressMetLeft) stressSamples[pixel].hit.w |= bit;
        }
        stressMetAny = stressMetLeft = false;
        return;
    }
    stressFeelersOfPrimary = sampleIndex == RECORDED_SAMPLE && level == 0u && hit.object >= 0;
    if (sampleIndex != RECORDED_SAMPLE) return;
    if (level == 0u) {
        rvec3 n = rvec3(0.0);
        if (hit.object >= 0) {
            n = normalize(toWorldNormalUnnormalised(hit.surface, hit.geometricNormal));
            if (dot(n, direction) > 0.0) n = -n;
        }
        stressLeftObject = hit.object;
        stressSamples[pixel].primary = vec4(vec3(n), float(hit.t));
        stressSamples[pixel].hit = uvec4(uint(hit.object), 0u, 0u, 0u);
        stressSamples[pixel].primaryDouble = stressDoubleBits(hit.t, n.x);
        stressSamples[pixel].normalDouble = stressDoubleBits(n.y, n.z);
        stressSamples[pixel].refracted = vec4(0.0, 0.0, 0.0, INFINITY);
        stressSamples[pixel].refractedHit = uvec4(uint(-1), 0u, 0u, 0u);
        return;
    }
    // Of the primary hit's secondary rays (level 1) the refracted one goes
    // through the surface, against the normal facing the eye; the reflected
    // one (and a total internal reflection) stays on the eye's side.
    if (level != 1u || dot(vec3(direction), stressSamples[pixel].primary.xyz) >= 0.0) return;
    rvec3 p = hit.object >= 0 ? origin + hit.t * direction : rvec3(0.0);
    stressSamples[pixel].refracted = vec4(vec3(p - rayEye()), float(hit.t));
    stressSamples[pixel].refractedHit = uvec4(uint(hit.object), 1u, 0u, 0u);
}
#endif
