// Precision modes (host/gpu/precision.h, docs/numerics.md).
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
// float spacing (0.0078) and rounds away (docs/numerics-background.md,
// "Secondary-ray origins").
const float NAIVE_EPSILON = 1e-4;

// The origin of a secondary ray (shadow feeler, reflection, refraction)
// leaving point p toward `side` (a direction; which side of the surface with
// normal n it leaves to) in direction `along`; `reach` is the largest
// coordinate of p or of the origin of the ray that met p (Surface.reach):
// p = o + t d is rounded as the larger, so a ray that crossed the scene to a
// hit near the eye brings its origin's rounding with it (a refracted ray
// 1400 on met a glass cube 16 from the eye again 4e-5 inside it, where 2^-18
// of p's own coordinates was 6e-5). The one implementation of the
// offset; each mode keeps its own:
//   naive   p moved by the fixed epsilon along n (and tMin = NAIVE_EPSILON);
//   robust  after Ray Tracing Gems ch. 6 (Waechter and Binder): moved off
//           the surface by a distance `step` that grows with `reach` like the
//           rounding error of p and of the ray re-intersecting the surface:
//           2^-18 of it, 32 to 64 of its float spacings
//           (OFFSET_SCALE of layout.h), and at least OFFSET_GENERIC_SCALE
//           (2^-18 = 64 u) times genericScale, which covers the rounding of
//           the point in the object's own generic space (see below). No
//           constant near the origin (Ray Tracing Gems' 1/65536 within 1/32
//           of it): the origin is the eye, where points are as exact as
//           their size, and a constant there leaks light past objects
//           smaller than it;
//   fp64    the same in double (2^-47 of `reach`, 2^-47 =
//           64 u of double times genericScale).
// The step off the surface (along n) is taken along the ray itself, as far as
// OFFSET_MAX_FORWARD steps do it, the rest along n: moved along n alone, the
// ray ran beside the exact one, `step` to the side, and every edge it passed
// (a reflected or refracted object's, a shadow's) moved by up to that, which
// at 2^-18 of the eye's distance put GPU and CPU samples on either side of an
// edge (docs/numerics.md); along itself it stays on the exact ray's line.
// genericScale is the world length along n of one generic unit of the
// surface's object times the generic shape's extent (genericScaleAlong in
// shade.glsl): the generic point of a hit on a shape of extent ~1 is O(1),
// rounded to a few u (the rows of M^-1 applied to p, the generic eye, the
// re-intersection's near root), which M scales back to a few u times that
// length in the world: measured, 1 u for a sphere, 4 u for a cylinder, 16 u
// for the torus (its root is found from the bounding sphere); 64 u leaves 4
// times the worst. Sized from the eye distance alone, the offset fell below
// that once an object was over ~64 times larger than its distance from the
// eye (a sphere of radius 2000 seen from 0.1 above: acne on 5 % of pixels).
vec3 naiveOffsetRayOrigin(vec3 p, vec3 n) { return p + NAIVE_EPSILON * n; }

#if VKRAY_PRECISION_FP64
const double OFFSET_DOUBLE_SCALE = 1.0lf / 140737488355328.0lf;  // 2^-47 = 32 * 2^-52
const double OFFSET_DOUBLE_GENERIC_SCALE = 1.0lf / 140737488355328.0lf;  // 2^-47 = 64 * 2^-53
#endif

rvec3 offsetOrigin(rvec3 p, real reach, vec3 n, vec3 side, vec3 along, real genericScale) {
#if VKRAY_FAULT_NO_OFFSET
    return p;  // a test hook (VKRAY_FAULT=no-offset): on the surface, to show the acne that follows
#endif
    if (dot(n, side) < 0.0) n = -n;
#if VKRAY_PRECISION_NAIVE
    return naiveOffsetRayOrigin(p, n);
#else
#if VKRAY_PRECISION_FP64
    real step = max(OFFSET_DOUBLE_SCALE * reach, OFFSET_DOUBLE_GENERIC_SCALE * genericScale);
#else
    real step = max(OFFSET_SCALE * reach, OFFSET_GENERIC_SCALE * genericScale);
#endif
    vec3 a = normalize(along);
    float c = dot(n, a);  // how far one unit along the ray leaves the surface
    real forward = c > 0.0 ? min(step / real(c), real(OFFSET_MAX_FORWARD) * step) : real(0.0);
    return p + forward * rvec3(a) + max(step - forward * real(c), real(0.0)) * rvec3(n);
#endif
}
