// Anti-aliasing samples, one definition for the compute shader (GLSL) and the
// CPU reference (C++), so that both place sample k of a pixel at the very
// same point for a given --seed (docs/shading.md, "Anti-aliasing").
//
// ξ = sampleRandom(seed, pixel, k, dim) in [0, 1): a counter-based hash, no
// state, so any pixel and sample can be drawn in any order on any thread.
// Only 32-bit integer arithmetic and one exact float conversion: the values
// are bit-identical in GLSL and C++.
#ifndef VKRAY_SAMPLING_H
#define VKRAY_SAMPLING_H

#ifdef __cplusplus
#include <cstdint>
namespace vkray::sampling {
using uint = std::uint32_t;
#define VKRAY_SAMPLING_FN inline
#else
#define VKRAY_SAMPLING_FN
#endif

// Chris Wellons' "lowbias32" integer mixer (hash-prospector): every input bit
// affects every output bit with bias about 0.17 %.
VKRAY_SAMPLING_FN uint lowbias32(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// Dimension dim (0: x, 1: y) of sample k of pixel `pixel` (y * width + x) for
// `seed`: the top 24 bits of the hash times 2^-24, exact in float, in [0, 1).
VKRAY_SAMPLING_FN float sampleRandom(uint seed, uint pixel, uint k, uint dim) {
    const uint h = lowbias32(seed ^ lowbias32(pixel ^ lowbias32(k * 2u + dim)));
    return float(h >> 8u) * 5.9604644775390625e-8;  // 2^-24
}

// Columns of the stratification grid for n samples: ceil(sqrt(n)), in
// integers (a float sqrt need not be exact on a GPU).
VKRAY_SAMPLING_FN uint sampleColumns(uint n) {
    uint m = 1u;
    while (m * m < n) m += 1u;
    return m;
}

// Rows of the grid: ceil(n / columns).
VKRAY_SAMPLING_FN uint sampleRows(uint n) {
    const uint m = sampleColumns(n);
    return (n + m - 1u) / m;
}

// The largest float below 1: the division below can round (m - 2^-24) / m up
// to 1, which would put the sample on the next pixel's edge.
VKRAY_SAMPLING_FN float belowOne(float x) {
    return x < 0.999999940395355224609375 ? x : 0.999999940395355224609375;  // 1 - 2^-24
}

// Sample k of n (0 <= k < n) as an offset in [0, 1)^2 from the pixel's (or
// block's) top-left corner, x right, y down: jittered in cell
// (k mod m, k div m) of an m x ceil(n / m) grid, m = ceil(sqrt(n)). Every
// cell of the first ceil(n / m) - 1 rows, and the first n - m (rows - 1)
// cells of the last, holds exactly one sample.
VKRAY_SAMPLING_FN float gridOffsetX(uint seed, uint pixel, uint k, uint columns) {
    return belowOne((float(k % columns) + sampleRandom(seed, pixel, k, 0u)) / float(columns));
}

VKRAY_SAMPLING_FN float gridOffsetY(uint seed, uint pixel, uint k, uint columns, uint rows) {
    return belowOne((float(k / columns) + sampleRandom(seed, pixel, k, 1u)) / float(rows));
}

// The same, the grid worked out from n (the shader works it out once per
// pixel instead: each sampleColumns is a loop of ceil(sqrt(n)) turns).
VKRAY_SAMPLING_FN float sampleOffsetX(uint seed, uint pixel, uint k, uint n) {
    return gridOffsetX(seed, pixel, k, sampleColumns(n));
}

VKRAY_SAMPLING_FN float sampleOffsetY(uint seed, uint pixel, uint k, uint n) {
    return gridOffsetY(seed, pixel, k, sampleColumns(n), sampleRows(n));
}

#ifdef __cplusplus
}  // namespace vkray::sampling
#endif
#undef VKRAY_SAMPLING_FN
#endif  // VKRAY_SAMPLING_H
