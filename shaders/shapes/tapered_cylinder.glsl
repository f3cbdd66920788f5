// Hill's generic tapered cylinder: axis z from 0 to 1, radius 1 at z = 0 and
// s at z = 1 (cylinder s = 1, cone s = 0), closed by its caps. With
// k = s - 1 and rho(z) = 1 + k z the wall is x^2 + y^2 = rho(z)^2; the ray
// gives A t^2 + 2 B t + C = 0 (NUMERICS.md section 7). The solid is convex, so
// its span is the first and last of the wall and cap hits.
void spanAdd(real t, rvec3 n, inout real t0, inout rvec3 n0, inout real t1, inout rvec3 n1) {
    if (t < t0) { t0 = t; n0 = n; }
    if (t > t1) { t1 = t; n1 = n; }
}

bool taperedCylinderSpan(rvec3 origin, rvec3 d, real s, out real t0, out rvec3 n0, out real t1,
                         out rvec3 n1) {
    t0 = 1.0 / 0.0;
    t1 = -1.0 / 0.0;
    n0 = n1 = rvec3(0.0);
#if VKRAY_PRECISION_NAIVE
    real shift = 0.0;  // naive (textbook): the quadratic in the ray's own origin
#else
    // Robust (origin shift, NUMERICS.md section 7): solve from the point of
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
    real disc = B * B - A * C;
    if (disc >= 0.0) {
#if VKRAY_PRECISION_NAIVE
        // Naive: t = (-B -+ sqrt(disc)) / A, which cancels for the smaller
        // root and divides by A = 0 for a ray along a generator.
        real root = sqrt(disc);
        real roots[2] = real[2]((-B - root) / A, (-B + root) / A);
#else
        // Robust: the stable pair q / A and C / q (Ray Tracing Gems ch. 7).
        real q = -(B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
        // q = 0 only for A = B = 0 (a ray along the axis of a cylinder): caps only.
        // A = 0 (parallel to a generator) leaves the one root C / q.
        real roots[2] = real[2](q != 0.0 ? C / q : 1.0 / 0.0, A != 0.0 ? q / A : 1.0 / 0.0);
#endif
        for (int i = 0; i < 2; ++i) {
            real z = o.z + roots[i] * d.z;
            if (isinf(roots[i]) || z < 0.0 || z > 1.0) continue;
            rvec3 p = o + roots[i] * d;
            real rho = 1.0 + k * z;
            // The apex of a cone has no wall normal: use the axis.
#if VKRAY_PRECISION_NAIVE
            rvec3 n = rvec3(p.xy, -k * rho);  // naive: zero (NaN once normalised) at a cone's apex
#else
            rvec3 n = rho > 0.0 ? rvec3(p.xy, -k * rho) : rvec3(0.0, 0.0, 1.0);
#endif
            spanAdd(shift + roots[i], n, t0, n0, t1, n1);
        }
    }
    if (d.z != 0.0) {
        real tBottom = -o.z / d.z;
        rvec2 pb = o.xy + tBottom * d.xy;
        if (dot(pb, pb) <= 1.0) spanAdd(shift + tBottom, rvec3(0.0, 0.0, -1.0), t0, n0, t1, n1);
        real tTop = (1.0 - o.z) / d.z;
        rvec2 pt = o.xy + tTop * d.xy;
        if (s > 0.0 && dot(pt, pt) <= s * s) spanAdd(shift + tTop, rvec3(0.0, 0.0, 1.0), t0, n0, t1, n1);
    }
    return t0 <= t1;
}

bool intersectTaperedCylinder(rvec3 o, rvec3 d, real s, real tMin, real tMax, out real t,
                              out rvec3 normal) {
    real t0, t1;
    rvec3 n0, n1;
    return taperedCylinderSpan(o, d, s, t0, n0, t1, n1) &&
           firstHitOfSpan(t0, n0, t1, n1, tMin, tMax, t, normal);
}
