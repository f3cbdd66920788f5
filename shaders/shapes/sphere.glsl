// Generic unit sphere x^2 + y^2 + z^2 = 1 (Hill ch. 14).
// Ray o + d t in object space; d is NOT normalised, so t is the world t.
// Discriminant as in Ray Tracing Gems ch. 7: a * (1 - |f_perp|^2) with
// f_perp = o - (b/a) d, whose error grows with |o| instead of |o|^2, and the
// smaller root from q = -(b + sign(b) sqrt(disc)) to avoid cancellation.
bool sphereSpan(vec3 o, vec3 d, out float t0, out vec3 n0, out float t1, out vec3 n1) {
    float a = dot(d, d);
    float b = dot(o, d);  // half of the textbook b
#if VKRAY_SPHERE_EARLY_OUT
    // Benchmark experiment (BENCHMARKS.md): origin outside, moving away.
    if (b > 0.0 && dot(o, o) > 1.0) return false;
#endif
    vec3 fPerp = o - (b / a) * d;
    float disc = a * (1.0 - dot(fPerp, fPerp));
    if (disc < 0.0) return false;
    float q = -(b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
    float c = dot(o, o) - 1.0;
    t0 = c / q;
    t1 = q / a;
    if (t0 > t1) { float s = t0; t0 = t1; t1 = s; }
    n0 = o + t0 * d;
    n1 = o + t1 * d;
    return true;
}

bool intersectSphere(vec3 o, vec3 d, float tMin, float tMax, out float t, out vec3 normal) {
    float t0, t1;
    vec3 n0, n1;
    return sphereSpan(o, d, t0, n0, t1, n1) && firstHitOfSpan(t0, n0, t1, n1, tMin, tMax, t, normal);
}
