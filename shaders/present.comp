// `vkray view`: the tracer's tiles summed into the picture, and the picture
// (or one of its AOVs, the CPU reference, their difference) as the 8-bit
// bytes the window shows. The bytes are those a PNG of the same values holds
// (pngByte): each is found among the thresholds the host works out from it.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "layout.h"

layout(local_size_x = PRESENT_WORKGROUP, local_size_y = PRESENT_WORKGROUP) in;

layout(std430, set = 0, binding = PRESENT_BINDING_TILE) readonly buffer TileBlock { GpuPixel tile[]; };
layout(std430, set = 0, binding = PRESENT_BINDING_SUMS) buffer SumBlock { vec4 sums[]; };
layout(std430, set = 0, binding = PRESENT_BINDING_AOVS) buffer AovBlock { GpuPixel aovs[]; };
layout(std430, set = 0, binding = PRESENT_BINDING_CPU) readonly buffer CpuBlock { GpuPixel cpu[]; };
layout(std430, set = 0, binding = PRESENT_BINDING_VIEW) writeonly buffer ViewBlock { uint view[]; };
layout(std430, set = 0, binding = PRESENT_BINDING_BYTES) readonly buffer ByteBlock { float byteFrom[256]; };
layout(std430, set = 0, binding = PRESENT_BINDING_RANGE) buffer RangeBlock { uvec4 depthRange; };
layout(std430, set = 0, binding = PRESENT_BINDING_VERDICTS) readonly buffer VerdictBlock { uint verdicts[]; };
layout(push_constant) uniform ParamBlock { PresentParams params; };

// The byte a PNG stores for v: the largest b with byteFrom[b] <= v (0 for NaN).
uint pngByte(float v) {
    uint lo = 0u, hi = 256u;  // byteFrom[lo] <= v < byteFrom[hi] (byteFrom[256] = +inf)
    if (!(v >= byteFrom[1])) return 0u;
    lo = 1u;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (v >= byteFrom[mid]) lo = mid; else hi = mid;
    }
    return lo;
}

uint packBytes(vec3 c) {
    uvec3 b = uvec3(pngByte(c.r), pngByte(c.g), pngByte(c.b));
    if (params.mode.w != 0u) b = b.bgr;
    return b.x | (b.y << 8) | (b.z << 16) | (255u << 24);
}

// Red (near) to blue (far) through green, evenly in 1 / depth over [near,
// far], so that a floor running to the horizon leaves the near objects
// their colours; a miss is black.
vec3 depthColor(float depth, float near, float far) {
    if (isinf(depth) || isnan(depth)) return vec3(0.0);
    float t = 0.0;
    if (far > near && near > 0.0)
        t = clamp((1.0 / max(depth, near) - 1.0 / far) / (1.0 / near - 1.0 / far), 0.0, 1.0);
    return clamp(vec3(2.0 * t - 1.0, 1.0 - abs(2.0 * t - 1.0), 1.0 - 2.0 * t), 0.0, 1.0);
}

// A colour per object, hues far apart for neighbouring ids (golden-ratio
// steps around the colour wheel); the background black.
vec3 idColor(int id) {
    if (id < 0) return vec3(0.0);
    float hue = fract(float(id) * 0.61803398875);
    vec3 wheel = clamp(abs(fract(hue + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
    return 0.9 * mix(vec3(1.0), wheel, 0.75);
}

// The largest channel difference of the two colours clamped to [0, 1], as
// `vkray compare` measures it: dark grey up to the threshold, then red to
// yellow (at four times the threshold and beyond).
vec3 heat(vec3 a, vec3 b, float threshold) {
    vec3 d = abs(clamp(a, 0.0, 1.0) - clamp(b, 0.0, 1.0));
    float e = max(d.r, max(d.g, d.b));
    if (!(e > threshold)) return vec3(threshold > 0.0 ? 0.3 * e / threshold : 0.0);
    return vec3(1.0, clamp((e - threshold) / (3.0 * max(threshold, 1e-6)), 0.0, 1.0), 0.0);
}

void absorb(uvec2 at) {
    // Member by member: SPIR-V has no store of one block's struct into another's.
    uint t = at.y * params.rect.z + at.x;
    vec4 color = tile[t].color;
    uvec2 pixel = params.rect.xy + at;
    uint i = pixel.y * params.mode.w + pixel.x;
    if (params.mode.y != 0u)
        sums[i] = vec4(color.rgb, 1.0);
    else
        sums[i] = vec4(sums[i].rgb + color.rgb, sums[i].w + 1.0);
    if (params.mode.z != 0u) {
        aovs[i].color = color;
        aovs[i].normal = tile[t].normal;
        float depth = tile[t].normal.w;
        if (!isinf(depth) && !isnan(depth)) {
            atomicMin(depthRange.x, floatBitsToUint(max(depth, 0.0)));
            atomicMax(depthRange.y, floatBitsToUint(max(depth, 0.0)));
        }
    }
}

void compose(uvec2 pixel) {
    uint i = pixel.y * params.rect.z + pixel.x;
    bool fromCpu = params.mode.z != 0u;
    vec4 sample0 = fromCpu ? cpu[i].color : aovs[i].color;  // w: object id
    vec4 normal = fromCpu ? cpu[i].normal : aovs[i].normal;  // w: depth
    vec3 color = fromCpu ? sample0.rgb : sums[i].rgb / sums[i].w;
    int id = floatBitsToInt(sample0.w);
    vec3 shown;
    switch (params.mode.y) {
    case VIEW_DEPTH: shown = depthColor(normal.w, params.range.x, params.range.y); break;
    case VIEW_NORMAL: shown = id < 0 ? vec3(0.0) : 0.5 + 0.5 * normal.xyz; break;
    case VIEW_OBJECT_ID: shown = idColor(id); break;
    case VIEW_DIFFERENCE:
        // Once the margin rule has judged the picture: set-aside pixels blue,
        // unexplained ones red at least (an id, depth or normal may be what
        // differs), the rest by their colour's error.
        if (verdicts[i] == VERDICT_SET_ASIDE) {
            shown = vec3(0.2, 0.4, 1.0);
        } else {
            shown = heat(sums[i].rgb / sums[i].w, cpu[i].color.rgb, params.range.z);
            if (verdicts[i] == VERDICT_UNEXPLAINED && shown.r < 1.0) shown = vec3(1.0, 0.0, 0.0);
        }
        break;
    default: shown = color; break;
    }
    view[i] = packBytes(shown);
}

void main() {
    uvec2 at = gl_GlobalInvocationID.xy;
    if (at.x >= params.rect.z || at.y >= params.rect.w) return;
    if (params.mode.x == PRESENT_ABSORB) absorb(at); else compose(at);
}
