// The device's peak rate of fused multiply-adds: each invocation runs
// CHAINS independent vec4 chains a = fma(a, m, c) for `iterations` steps, so
// that the compiler can keep every FMA unit busy (independent chains hide
// the FMA latency). m and c come from push constants so that nothing can be
// folded at compile time; the sums are written so nothing is dead code.
// Flops: 2 (multiply + add) x 4 (components) x CHAINS x iterations per invocation.
#version 460

#ifndef CHAINS
#define CHAINS 4
#endif

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
layout(std430, set = 0, binding = 0) writeonly buffer Result { vec4 result[]; };
layout(push_constant) uniform Parameters {
    uint iterations;
    float m;  // near 1, so that a converges to c / (1 - m) without overflow or denormals
    float c;
};

void main() {
    uint id = gl_GlobalInvocationID.x;
    vec4 seed = vec4(float(id & 255u) * 1e-3) + vec4(0.0, 0.25, 0.5, 0.75);
    vec4 a[CHAINS];
    for (int k = 0; k < CHAINS; ++k) a[k] = seed + float(k);
    vec4 mv = vec4(m), cv = vec4(c);
    for (uint i = 0u; i < iterations; ++i) {
        for (int k = 0; k < CHAINS; ++k) a[k] = fma(a[k], mv, cv);
    }
    vec4 sum = vec4(0.0);
    for (int k = 0; k < CHAINS; ++k) sum += a[k];
    result[id] = sum;
}
