// Precision modes (host/numerics/precision.h, README "Numerics").
// VKRAY_PRECISION_NAIVE = 1 selects the textbook formulas inside the shape
// files (each under `#if VKRAY_PRECISION_NAIVE`, the robust remedy named in
// the `#else` branch) and the textbook's fixed epsilon below. The default,
// robust, needs no define; VKRAY_PRECISION_FP64 = 1 is robust with ray
// geometry in double (`real` below).
#ifndef VKRAY_PRECISION_NAIVE
#define VKRAY_PRECISION_NAIVE 0
#endif
#ifndef VKRAY_PRECISION_FP64
#define VKRAY_PRECISION_FP64 0
#endif

// The type of ray geometry: the ray's origin, direction and t, the inverse
// transforms applied to it, and every generic intersection (shapes/*.glsl).
// float, or double in the fp64 variant (VKRAY_PRECISION_FP64 = 1, needs the
// device's shaderFloat64). Shading (lights, textures, colours) stays float.
#if VKRAY_PRECISION_FP64
#define real double
#define rvec2 dvec2
#define rvec3 dvec3
#define rvec4 dvec4
const double ROOT_TOLERANCE = 1e-15lf;  // relative step at which iterative root finders stop
#else
#define real float
#define rvec2 vec2
#define rvec3 vec3
#define rvec4 vec4
const float ROOT_TOLERANCE = 1e-7;
#endif

// Naive mode's fixed epsilon: the smallest t a hit may have on every ray, and
// the distance a secondary ray's origin is pushed along the normal. A fixed
// length cannot suit every scale: at 1e5 from the origin it is below the
// float spacing (0.0078) and rounds away (NUMERICS.md section 3).
const float NAIVE_EPSILON = 1e-4;

// The origin of a secondary ray (shadow feeler, reflection, refraction)
// leaving point p toward `side` (a direction; which side of the surface with
// normal n it leaves to). The one implementation of the offset; each mode
// keeps its own:
//   naive   p moved by the fixed epsilon along n (and tMin = NAIVE_EPSILON);
//   robust  Ray Tracing Gems ch. 6 (Waechter and Binder): each coordinate
//           moves a fixed number of ulps of itself along the normal, so the
//           offset grows with |p| like the rounding error of p; coordinates
//           near 0, where ulps vanish, move by a small constant (the
//           OFFSET_* constants of layout.h);
//   fp64    the same idea in double (below).
vec3 naiveOffsetRayOrigin(vec3 p, vec3 n) { return p + NAIVE_EPSILON * n; }


#if VKRAY_PRECISION_FP64
// fp64: RTG6 carried over to double: each coordinate moves about 256
// spacings of itself (2^-44 |p|), or 2^-45 near the origin.
const double OFFSET_DOUBLE_RELATIVE = 256.0lf / 4503599627370496.0lf;  // 256 * 2^-52
const double OFFSET_DOUBLE_NEAR_ORIGIN = 1.0lf / 35184372088832.0lf;   // 2^-45
#endif

rvec3 offsetOrigin(rvec3 p, vec3 n, vec3 side) {
    if (dot(n, side) < 0.0) n = -n;
#if VKRAY_PRECISION_NAIVE
    return naiveOffsetRayOrigin(p, n);
#elif VKRAY_PRECISION_FP64
    return p + dvec3(n) * max(abs(p) * OFFSET_DOUBLE_RELATIVE, dvec3(OFFSET_DOUBLE_NEAR_ORIGIN));
#else
    ivec3 ulps = ivec3(OFFSET_INT_SCALE * n);
    // Adding to the bit pattern of a negative float moves it away from zero.
    ivec3 bits = floatBitsToInt(p) + ivec3(p.x < 0.0 ? -ulps.x : ulps.x,
                                           p.y < 0.0 ? -ulps.y : ulps.y,
                                           p.z < 0.0 ? -ulps.z : ulps.z);
    vec3 moved = intBitsToFloat(bits);
    return vec3(abs(p.x) < OFFSET_NEAR_ORIGIN ? p.x + OFFSET_FLOAT_SCALE * n.x : moved.x,
                abs(p.y) < OFFSET_NEAR_ORIGIN ? p.y + OFFSET_FLOAT_SCALE * n.y : moved.y,
                abs(p.z) < OFFSET_NEAR_ORIGIN ? p.z + OFFSET_FLOAT_SCALE * n.z : moved.z);
#endif
}
