// Hill's generic tapered cylinder: axis z from 0 to 1, radius 1 at z = 0 and
// s at z = 1 (cylinder s = 1, cone s = 0), closed by its caps. With
// k = s - 1 and rho(z) = 1 + k z the wall is x^2 + y^2 = rho(z)^2; the ray
// gives A t^2 + 2 B t + C = 0 (NUMERICS.md section 7). The solid is convex, so
// its span is the first and last of the wall and cap hits.
void spanAdd(float t, vec3 n, inout float t0, inout vec3 n0, inout float t1, inout vec3 n1) {
    if (t < t0) { t0 = t; n0 = n; }
    if (t > t1) { t1 = t; n1 = n; }
}

bool taperedCylinderSpan(vec3 origin, vec3 d, float s, out float t0, out vec3 n0, out float t1,
                         out vec3 n1) {
    t0 = 1.0 / 0.0;
    t1 = -1.0 / 0.0;
    n0 = n1 = vec3(0.0);
#if VKRAY_PRECISION_NAIVE
    float shift = 0.0;  // naive (textbook): the quadratic in the ray's own origin
#else
    // Robust (origin shift, NUMERICS.md section 7): solve from the point of
    // the line nearest the axis' middle: seen from far away, C and B^2 - AC
    // cancel; from there they are of the shape's size.
    float shift = dot(vec3(0.0, 0.0, 0.5) - origin, d) / dot(d, d);
#endif
    vec3 o = origin + shift * d;
    float k = s - 1.0;
    float rhoO = 1.0 + k * o.z;
    float A = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
    float B = o.x * d.x + o.y * d.y - k * rhoO * d.z;
    float C = o.x * o.x + o.y * o.y - rhoO * rhoO;
    float disc = B * B - A * C;
    if (disc >= 0.0) {
#if VKRAY_PRECISION_NAIVE
        // Naive: t = (-B -+ sqrt(disc)) / A, which cancels for the smaller
        // root and divides by A = 0 for a ray along a generator.
        float root = sqrt(disc);
        float roots[2] = float[2]((-B - root) / A, (-B + root) / A);
#else
        // Robust: the stable pair q / A and C / q (Ray Tracing Gems ch. 7).
        float q = -(B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
        // q = 0 only for A = B = 0 (a ray along the axis of a cylinder): caps only.
        // A = 0 (parallel to a generator) leaves the one root C / q.
        float roots[2] = float[2](q != 0.0 ? C / q : 1.0 / 0.0, A != 0.0 ? q / A : 1.0 / 0.0);
#endif
        for (int i = 0; i < 2; ++i) {
            float z = o.z + roots[i] * d.z;
            if (isinf(roots[i]) || z < 0.0 || z > 1.0) continue;
            vec3 p = o + roots[i] * d;
            float rho = 1.0 + k * z;
            // The apex of a cone has no wall normal: use the axis.
#if VKRAY_PRECISION_NAIVE
            vec3 n = vec3(p.xy, -k * rho);  // naive: zero (NaN once normalised) at a cone's apex
#else
            vec3 n = rho > 0.0 ? vec3(p.xy, -k * rho) : vec3(0.0, 0.0, 1.0);
#endif
            spanAdd(shift + roots[i], n, t0, n0, t1, n1);
        }
    }
    if (d.z != 0.0) {
        float tBottom = -o.z / d.z;
        vec2 pb = o.xy + tBottom * d.xy;
        if (dot(pb, pb) <= 1.0) spanAdd(shift + tBottom, vec3(0.0, 0.0, -1.0), t0, n0, t1, n1);
        float tTop = (1.0 - o.z) / d.z;
        vec2 pt = o.xy + tTop * d.xy;
        if (s > 0.0 && dot(pt, pt) <= s * s) spanAdd(shift + tTop, vec3(0.0, 0.0, 1.0), t0, n0, t1, n1);
    }
    return t0 <= t1;
}

bool intersectTaperedCylinder(vec3 o, vec3 d, float s, float tMin, float tMax, out float t,
                              out vec3 normal) {
    float t0, t1;
    vec3 n0, n1;
    return taperedCylinderSpan(o, d, s, t0, n0, t1, n1) &&
           firstHitOfSpan(t0, n0, t1, n1, tMin, tMax, t, normal);
}
