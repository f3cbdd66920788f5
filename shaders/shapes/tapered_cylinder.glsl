// Hill's generic tapered cylinder: axis z from 0 to 1, radius 1 at z = 0 and
// |s| at z = 1 (cylinder s = 1, cone s = 0), closed by its caps. With
// k = s - 1 and rho(z) = 1 + k z the solid is where the ray is inside both
//     the slab        0 <= z <= 1,
//     the quadric     Q = x^2 + y^2 - rho(z)^2 <= 0 (a double cone, or a cylinder),
// and along the ray Q = A t^2 + 2 B t + C (docs/numerics-background.md,
// "Tapered cylinder"). As in the
// CPU reference, each inside-span is a piece of the quadric's inside clipped
// to the slab, the binding constraint naming the surface (slab: a cap,
// quadric: the wall); the quadric clips the caps' disks (radius 1 and |s|),
// so wall and cap share one inequality at the rim. Within the slab the
// quadric is one nappe for s >= 0 (its apex z = 1 / (1 - s) lies at or
// beyond z = 1, or below z = 0 for s > 1): a convex solid, one span. For
// s < 0 both nappes meet at the apex inside the slab: an hourglass, which a
// line can enter twice.

const real TAPER_INFINITY = 1.0 / 0.0;

// The inside-spans along a line: [t0, t1] and, for count 2, [t2, t3],
// ascending, with the outward normals at those ends. (Scalars, not arrays:
// lavapipe keeps an array it indexes at run time in memory.)
struct TaperedSpans {
    int count;  // 0, 1 or 2
    real t0, t1, t2, t3;
    rvec3 n0, n1, n2, n3;
};

// Where A t^2 + 2 B t + C <= 0: [lo0, hi0] and, when it returns 2,
// [lo1, hi1] (ascending, possibly unbounded); returns how many.
int taperedQuadricInside(real A, real B, real C, out real lo0, out real hi0, out real lo1,
                         out real hi1) {
    lo0 = lo1 = -TAPER_INFINITY;
    hi0 = hi1 = TAPER_INFINITY;
#if VKRAY_PRECISION_NAIVE
    // Naive: t = (-B -+ sqrt(disc)) / A, which cancels for the smaller root
    // and divides by A = 0 for a ray along a generator (then the wall is lost).
    real disc = B * B - A * C;
    if (disc < 0.0) return A > 0.0 ? 0 : 1;  // no root: Q has the sign of A all along
    real root = sqrt(disc);
    real t1 = (-B - root) / A, t2 = (-B + root) / A;
#else
    if (A == 0.0) {  // parallel to a generator: 2 B t + C <= 0
        if (B == 0.0) return C > 0.0 ? 0 : 1;  // along the axis of a cylinder: never, or all along
        real t = -C / (2.0 * B);
        if (B > 0.0) hi0 = t;
        else lo0 = t;
        return 1;
    }
    real disc = B * B - A * C;
    if (disc < 0.0) return A > 0.0 ? 0 : 1;  // no root: Q has the sign of A all along
    // Robust: the stable pair q / A and C / q (Ray Tracing Gems ch. 7); q = 0
    // only for a double root at 0 (B = C = 0).
    real q = -(B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
    real t1 = q / A, t2 = q != 0.0 ? C / q : t1;
#endif
    if (t1 > t2) {
        real swap = t1;
        t1 = t2;
        t2 = swap;
    }
    if (A > 0.0) {
        lo0 = t1;
        hi0 = t2;
        return 1;
    }
    // A < 0 (steeper than the generators): the line crosses both nappes.
    hi0 = t1;
    lo1 = t2;
    return 2;
}

// The wall's outward normal grad Q / 2 = (x, y, -k rho(z)) at p.
rvec3 taperedWallNormal(rvec3 p, real k) {
    rvec3 n = rvec3(p.xy, -k * (1.0 + k * p.z));
#if VKRAY_PRECISION_NAIVE
    return n;  // naive: zero (NaN once normalised) at a cone's apex
#else
    return n == rvec3(0.0) ? rvec3(0.0, 0.0, 1.0) : n;  // the apex has none: the axis stands in
#endif
}

// The quadric's inside-piece [wallLo, wallHi] clipped to the slab
// [slabLo, slabHi] (entered through the cap with normal capIn): [lo, hi]
// with their normals, or false when empty. On a tie (the rim) the cap's
// plane names the surface.
bool taperedPiece(real wallLo, real wallHi, real slabLo, real slabHi, rvec3 capIn, rvec3 o,
                  rvec3 d, real k, out real lo, out rvec3 nLo, out real hi, out rvec3 nHi) {
    bool capIsIn = slabLo >= wallLo, capIsOut = slabHi <= wallHi;
    lo = capIsIn ? slabLo : wallLo;
    hi = capIsOut ? slabHi : wallHi;
    nLo = nHi = rvec3(0.0);
    if (!(lo <= hi)) return false;
    nLo = capIsIn ? capIn : taperedWallNormal(o + lo * d, k);
    nHi = capIsOut ? -capIn : taperedWallNormal(o + hi * d, k);
    return true;
}

// The inside-spans of the solid along the whole line origin + t d.
TaperedSpans taperedCylinderSpans(rvec3 origin, rvec3 d, real s) {
    TaperedSpans spans;
    spans.count = 0;
    spans.t0 = spans.t1 = spans.t2 = spans.t3 = TAPER_INFINITY;
    spans.n0 = spans.n1 = spans.n2 = spans.n3 = rvec3(0.0);
#if VKRAY_PRECISION_NAIVE
    real shift = 0.0;  // naive (textbook): the quadratic in the ray's own origin
#else
    // Robust (origin shift, docs/numerics-background.md, "Tapered cylinder"):
    // solve from the point of
    // the line nearest the axis' middle: seen from far away, C and B^2 - AC
    // cancel; from there they are of the shape's size.
    real shift = dot(rvec3(0.0, 0.0, 0.5) - origin, d) / dot(d, d);
#endif
    rvec3 o = origin + shift * d;
    real k = s - 1.0;
    real rhoO = 1.0 + k * o.z;
    real A = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
    real B = o.x * d.x + o.y * d.y - k * rhoO * d.z;
    real C = o.x * o.x + o.y * o.y - rhoO * rhoO;
    real wallLo0, wallHi0, wallLo1, wallHi1;
    int walls = taperedQuadricInside(A, B, C, wallLo0, wallHi0, wallLo1, wallHi1);
    if (walls == 0) return spans;

    // The slab, entered through z = 0 going up and through z = 1 going down.
    real slabLo = -TAPER_INFINITY, slabHi = TAPER_INFINITY;
    rvec3 capIn = rvec3(0.0);
    if (d.z == 0.0) {
        if (!(o.z >= 0.0 && o.z <= 1.0)) return spans;
    } else {
        real tBottom = -o.z / d.z, tTop = (1.0 - o.z) / d.z;
        slabLo = d.z > 0.0 ? tBottom : tTop;
        slabHi = d.z > 0.0 ? tTop : tBottom;
        capIn = rvec3(0.0, 0.0, d.z > 0.0 ? -1.0 : 1.0);
    }

    real lo0, hi0, lo1, hi1;
    rvec3 nLo0, nHi0, nLo1, nHi1;
    bool has0 =
        taperedPiece(wallLo0, wallHi0, slabLo, slabHi, capIn, o, d, k, lo0, nLo0, hi0, nHi0);
    bool has1 = walls == 2 &&
        taperedPiece(wallLo1, wallHi1, slabLo, slabHi, capIn, o, d, k, lo1, nLo1, hi1, nHi1);
    if (has0 && has1 && (s >= 0.0 || lo1 <= hi0)) {
        // Convex (s >= 0): the second piece can only be the apex itself,
        // reached by rounding; an hourglass's pieces that touch are one.
        // Either way: one span over both.
        if (hi1 > hi0) {
            hi0 = hi1;
            nHi0 = nHi1;
        }
        has1 = false;
    }
    if (!has0 && has1) {
        lo0 = lo1;
        hi0 = hi1;
        nLo0 = nLo1;
        nHi0 = nHi1;
        has0 = true;
        has1 = false;
    }
    if (has0) {
        spans.count = 1;
        spans.t0 = shift + lo0;
        spans.t1 = shift + hi0;
        spans.n0 = nLo0;
        spans.n1 = nHi0;
    }
    if (has1) {
        spans.count = 2;
        spans.t2 = shift + lo1;
        spans.t3 = shift + hi1;
        spans.n2 = nLo1;
        spans.n3 = nHi1;
    }
    return spans;
}

// The nearest crossing in (tMin, tMax): the first span end after tMin,
// entering the solid or, from inside, leaving it.
bool intersectTaperedCylinder(rvec3 o, rvec3 d, real s, real tMin, real tMax, out real t,
                              out rvec3 normal) {
    TaperedSpans spans = taperedCylinderSpans(o, d, s);
    t = TAPER_INFINITY;  // the ends of a missing span are infinite: never a hit
    normal = rvec3(0.0);
    if (spans.t0 > tMin) { t = spans.t0; normal = spans.n0; }
    else if (spans.t1 > tMin) { t = spans.t1; normal = spans.n1; }
    else if (spans.t2 > tMin) { t = spans.t2; normal = spans.n2; }
    else if (spans.t3 > tMin) { t = spans.t3; normal = spans.n3; }
    return t < tMax;
}
