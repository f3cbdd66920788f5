// The generic torus: axis z, centre circle of radius R = TORUS_MAJOR_RADIUS in
// z = 0, tube radius r = TORUS_TUBE_RADIUS; F(p) = (|p|^2 + R^2 - r^2)^2 -
// 4 R^2 (px^2 + py^2) = 0.
//
// Closed-form quartic solvers lose everything in float (their coefficients
// grow like |o|^4; docs/numerics-background.md, "Torus"). So: move the origin to where the
// line enters the torus's bounding sphere and use a unit direction, which
// makes the coefficients O(1); split [0, L] into intervals where the quartic
// is monotone (at the roots of its derivative, found the same way one degree
// down); find the root of each interval with a sign change by Newton's method
// kept inside its bracket (Yuksel, HPG 2022); polish with one Newton step on
// F itself. Tangent double roots (no sign change) are missed: a grazing ray.

// Up to four roots travel in a vector, read and written through selects
// (rootAt, withRoot): lavapipe keeps an array indexed at run time in memory
// and writes each word of it in a loop over the lanes; a vector stays in
// registers. (Arrays indexed by constants only, as the coefficients below
// once the loops over them are unrolled, stay in registers too.)
real rootAt(rvec4 roots, int i) {
    return i == 0 ? roots.x : (i == 1 ? roots.y : (i == 2 ? roots.z : roots.w));
}

rvec4 withRoot(rvec4 roots, int i, real x) {
    return rvec4(i == 0 ? x : roots.x, i == 1 ? x : roots.y, i == 2 ? x : roots.z,
                 i == 3 ? x : roots.w);
}

real polynomialAt(real c[5], int degree, real x) {
    real f = c[degree];
    for (int i = degree - 1; i >= 0; --i) f = f * x + c[i];
    return f;
}

// A root of the polynomial in [a, b], where its values at a and b differ in sign.
real bracketedRoot(real c[5], int degree, real a, real b) {
    real fa = polynomialAt(c, degree, a);
    real x = 0.5 * (a + b);
    for (int i = 0; i < 40; ++i) {
        ++loopTurns;
        real f = c[degree], df = 0.0;
        for (int k = degree - 1; k >= 0; --k) {
            df = df * x + f;
            f = f * x + c[k];
        }
        if (f == 0.0) return x;
        if ((f > 0.0) == (fa > 0.0)) { a = x; fa = f; } else { b = x; }
        real next = x - f / df;
        if (!(next > a && next < b)) next = 0.5 * (a + b);  // Newton left the bracket: bisect
        if (abs(next - x) <= ROOT_TOLERANCE * max(1.0, abs(next))) return next;
        x = next;
    }
    return x;
}

// The real roots in [lo, hi] of the polynomial of `degree` (2, 3 or 4) with
// sign changes, ascending; returns how many. Degree 2 in closed form.
int rootsQuadratic(real c0, real c1, real c2, real lo, real hi, out rvec4 roots) {
    int n = 0;
    roots = rvec4(0.0);
    if (c2 == 0.0) {
        if (c1 != 0.0) { real x = -c0 / c1; if (x >= lo && x <= hi) roots = withRoot(roots, n++, x); }
        return n;
    }
    real disc = c1 * c1 - 4.0 * c2 * c0;
    if (disc < 0.0) return 0;
    real q = -0.5 * (c1 + (c1 >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
    real x0 = q / c2, x1 = q != 0.0 ? c0 / q : x0;
    if (x0 > x1) { real s = x0; x0 = x1; x1 = s; }
    if (x0 >= lo && x0 <= hi) roots = withRoot(roots, n++, x0);
    if (x1 >= lo && x1 <= hi) roots = withRoot(roots, n++, x1);
    return n;
}

// Roots of a polynomial of `degree` on [lo, hi] between the given extrema.
int rootsBetween(real c[5], int degree, real lo, real hi, rvec4 extrema, int extremaCount,
                 out rvec4 roots) {
    int n = 0;
    roots = rvec4(0.0);
    real a = lo;
    real fa = polynomialAt(c, degree, a);
    for (int i = 0; i <= extremaCount; ++i) {
        real b = i < extremaCount ? rootAt(extrema, i) : hi;
        real fb = polynomialAt(c, degree, b);
        if (fa == 0.0 && n < 4) roots = withRoot(roots, n++, a);
        else if ((fa < 0.0) != (fb < 0.0) && fb != 0.0 && n < 4)
            roots = withRoot(roots, n++, bracketedRoot(c, degree, a, b));
        a = b;
        fa = fb;
    }
    if (fa == 0.0 && n < 4) roots = withRoot(roots, n++, a);
    return n;
}

int quarticRoots(real c[5], real lo, real hi, out rvec4 roots) {
    // Derivative chain: quartic -> cubic -> quadratic (closed form).
    real cubic[5] = real[5](c[1], 2.0 * c[2], 3.0 * c[3], 4.0 * c[4], 0.0);
    // The cubic's extrema are the roots of its derivative, a quadratic.
    rvec4 quadraticExtrema;
    int e2 = rootsQuadratic(cubic[1], 2.0 * cubic[2], 3.0 * cubic[3], lo, hi, quadraticExtrema);
    rvec4 cubicRoots;
    int e3 = rootsBetween(cubic, 3, lo, hi, quadraticExtrema, e2, cubicRoots);
    return rootsBetween(c, 4, lo, hi, cubicRoots, e3, roots);
}

// Every crossing of the torus along a line, ascending in t: `count` (0, 2 or
// 4 in general) t values with the outward normal at each.
struct TorusCrossings {
    int count;
    rvec4 t;
    rvec3 n0, n1, n2, n3;
};

void setTorusNormal(inout TorusCrossings crossings, int i, rvec3 n) {
    if (i == 0) crossings.n0 = n;
    if (i == 1) crossings.n1 = n;
    if (i == 2) crossings.n2 = n;
    if (i == 3) crossings.n3 = n;
}

rvec3 torusNormalAt(TorusCrossings crossings, int i) {
    return i == 0 ? crossings.n0 : (i == 1 ? crossings.n1 : (i == 2 ? crossings.n2 : crossings.n3));
}

// The crossings along the whole line o + d t.
#if VKRAY_PRECISION_NAIVE
// Naive (textbook): the quartic's coefficients straight from the ray's own
// origin and direction. They grow like |o|^4 and cancel: from 100 units away
// about half the hits flip (docs/numerics-background.md, "Torus"). Same root finder, no
// origin shift, no unit direction, no polish.
TorusCrossings torusCrossings(rvec3 o, rvec3 d) {
    const real R = TORUS_MAJOR_RADIUS, r = TORUS_TUBE_RADIUS;
    TorusCrossings crossings;
    crossings.count = 0;
    crossings.t = rvec4(0.0);
    crossings.n0 = crossings.n1 = crossings.n2 = crossings.n3 = rvec3(0.0);
    real boundRadius = 1.01 * (R + r);
    real G = dot(d, d), H = dot(o, d), K = dot(o, o) + R * R - r * r;
    real disc = H * H - G * (dot(o, o) - boundRadius * boundRadius);
    if (disc <= 0.0) return crossings;
    real lo = (-H - sqrt(disc)) / G, hi = (-H + sqrt(disc)) / G;
    real a2 = d.x * d.x + d.y * d.y, a1 = o.x * d.x + o.y * d.y, a0 = o.x * o.x + o.y * o.y;
    real c[5] = real[5](K * K - 4.0 * R * R * a0, 4.0 * H * K - 8.0 * R * R * a1,
                          4.0 * H * H + 2.0 * G * K - 4.0 * R * R * a2, 4.0 * G * H, G * G);
    crossings.count = quarticRoots(c, lo, hi, crossings.t);
    for (int i = 0; i < crossings.count; ++i) {
        rvec3 p = o + rootAt(crossings.t, i) * d;
        real k = dot(p, p) + R * R - r * r;
        setTorusNormal(crossings, i, 4.0 * k * p - 8.0 * R * R * rvec3(p.xy, 0.0));
    }
    return crossings;
}
#else
// Robust: origin shifted to the bounding sphere, unit direction, polish on F.
TorusCrossings torusCrossings(rvec3 o, rvec3 d) {
    const real R = TORUS_MAJOR_RADIUS, r = TORUS_TUBE_RADIUS;
    TorusCrossings crossings;
    crossings.count = 0;
    crossings.t = rvec4(0.0);
    crossings.n0 = crossings.n1 = crossings.n2 = crossings.n3 = rvec3(0.0);
    real dLength = sqrt(dot(d, d));
    rvec3 u = d / dLength;
    // The line through the bounding sphere (a little larger, so that F > 0 at
    // both ends): t_e and t_x in units along u.
    real boundRadius = 1.01 * (R + r);
    real b = dot(o, u);
    rvec3 fPerp = o - b * u;
    real disc = boundRadius * boundRadius - dot(fPerp, fPerp);
    if (disc <= 0.0) return crossings;
    real halfChord = sqrt(disc);
    real tEnter = -b - halfChord;
    rvec3 e = o + tEnter * u;  // the shifted origin: |e| = boundRadius
    real H = dot(e, u);
    real K = dot(e, e) + R * R - r * r;
    real a2 = u.x * u.x + u.y * u.y, a1 = e.x * u.x + e.y * u.y, a0 = e.x * e.x + e.y * e.y;
    real c[5] = real[5](K * K - 4.0 * R * R * a0, 4.0 * H * K - 8.0 * R * R * a1,
                          4.0 * H * H + 2.0 * K - 4.0 * R * R * a2, 4.0 * H, 1.0);
    rvec4 s;
    crossings.count = quarticRoots(c, 0.0, 2.0 * halfChord, s);
    for (int i = 0; i < crossings.count; ++i) {
        // One Newton step on F at the point itself, then back to the caller's t.
        real si = rootAt(s, i);
        rvec3 p = e + si * u;
        real k = dot(p, p) + R * R - r * r;
        real F = k * k - 4.0 * R * R * dot(p.xy, p.xy);
        rvec3 gradient = 4.0 * k * p - 8.0 * R * R * rvec3(p.xy, 0.0);
        real slope = dot(gradient, u);
        real step = slope != 0.0 ? F / slope : real(0.0);
        if (abs(step) < 1e-2) {
            rvec3 q = e + (si - step) * u;
            real kq = dot(q, q) + R * R - r * r;
            rvec3 polished = 4.0 * kq * q - 8.0 * R * R * rvec3(q.xy, 0.0);
            // Near a grazing ray's pair of roots the slope is small and the
            // step long: one that crosses the pair's tangent point (F's slope
            // changes sign) has left the root's monotone interval, and its
            // normal faced the other way (an entry shaded as an exit). Keep
            // the bracketed root there.
            if (dot(polished, u) * slope > 0.0) {
                si -= step;
                gradient = polished;
            }
        }
        setTorusNormal(crossings, i, gradient);
        crossings.t = withRoot(crossings.t, i, (tEnter + si) / dLength);
    }
    return crossings;
}
#endif

bool intersectTorus(rvec3 o, rvec3 d, real tMin, real tMax, out real t, out rvec3 normal) {
    TorusCrossings crossings = torusCrossings(o, d);
    for (int i = 0; i < crossings.count; ++i) {
        real at = rootAt(crossings.t, i);
        if (at > tMin && at < tMax) {
            t = at;
            normal = torusNormalAt(crossings, i);
            return true;
        }
    }
    return false;
}
