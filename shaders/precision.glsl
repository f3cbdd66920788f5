// Precision modes (host/numerics/precision.h, README "Numerics").
// VKRAY_PRECISION_NAIVE = 1 selects the textbook formulas inside the shape
// files (each under `#if VKRAY_PRECISION_NAIVE`, the robust remedy named in
// the `#else` branch) and the textbook's fixed epsilon below. The default,
// robust, needs no define.
#ifndef VKRAY_PRECISION_NAIVE
#define VKRAY_PRECISION_NAIVE 0
#endif

// Naive mode's fixed epsilon: the smallest t a hit may have on every ray, and
// the distance a secondary ray's origin is pushed along the normal. A fixed
// length cannot suit every scale: at 1e5 from the origin it is below the
// float spacing (0.0078) and rounds away (NUMERICS.md section 3).
const float NAIVE_EPSILON = 1e-4;

// Hook for secondary rays (shadow, reflection, refraction): naive mode offsets
// their origins by the fixed epsilon, robust mode as Ray Tracing Gems ch. 6
// (Waechter and Binder). `n` is the geometric normal turned to the side the
// new ray leaves from.
vec3 naiveOffsetRayOrigin(vec3 p, vec3 n) { return p + NAIVE_EPSILON * n; }
