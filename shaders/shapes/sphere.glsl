// Generic unit sphere x^2 + y^2 + z^2 = 1 (Hill ch. 14).
// Ray o + d t in object space; d is NOT normalised, so t is the world t.
// Discriminant as in Ray Tracing Gems ch. 7: a * (1 - |f_perp|^2) with
// f_perp = o - (b/a) d, whose error grows with |o| instead of |o|^2, and the
// smaller root from q = -(b + sign(b) sqrt(disc)) to avoid cancellation.
#if VKRAY_PRECISION_NAIVE
// Naive (textbook): A t^2 + B t + C = 0, disc = B^2 - 4AC, t = (-B -+ sqrt(disc)) / 2A.
// B^2 and 4AC are both ~|o|^2 |d|^2: seen from |o| > ~4096 radii the
// discriminant is rounding noise (docs/numerics-background.md, "Sphere", failure A), and the
// root (-B + sqrt(disc)) cancels when sqrt(disc) ~ |B| (failure B).
bool sphereSpan(rvec3 o, rvec3 d, out real t0, out rvec3 n0, out real t1, out rvec3 n1) {
    real A = dot(d, d);
    real B = 2.0 * dot(o, d);
    real C = dot(o, o) - 1.0;
    real disc = B * B - 4.0 * A * C;
    if (disc < 0.0) return false;
    real root = sqrt(disc);
    t0 = (-B - root) / (2.0 * A);
    t1 = (-B + root) / (2.0 * A);
    n0 = o + t0 * d;
    n1 = o + t1 * d;
    return true;
}
#else
// Robust (Ray Tracing Gems ch. 7, Haines et al.): the discriminant from the
// line's point nearest the centre, f_perp, and the stable root pair c / q,
// q / a. Two additions of ours for huge anisotropy (a sphere squashed by 1e-8,
// seen from 1e8 generic radii along the squashed axis):
// - f_perp is projected a second time: rounding t_c d in o - t_c d leaves an
//   error of u |o| along d, which the second projection removes (one step of
//   iterative refinement);
// - the normals are f_perp -+ h d (h the half chord in t), not o + t d, which
//   would cancel to noise the same way.
bool sphereSpan(rvec3 o, rvec3 d, out real t0, out rvec3 n0, out real t1, out rvec3 n1) {
    real a = dot(d, d);
    real b = dot(o, d);  // half of the textbook b
#ifdef VKRAY_SPHERE_EARLY_OUT  // an experiment: off unless -D defines it
    // Benchmark experiment (BENCHMARKS.md): origin outside, moving away.
    if (b > 0.0 && dot(o, o) > 1.0) return false;
#endif
    rvec3 fPerp = o - (b / a) * d;
    fPerp -= (dot(fPerp, d) / a) * d;
    real disc = a * (1.0 - dot(fPerp, fPerp));
    if (disc < 0.0) return false;
    real root = sqrt(disc);
    real q = -(b + (b >= 0.0 ? 1.0 : -1.0) * root);
    real c = dot(o, o) - 1.0;
    t0 = c / q;
    t1 = q / a;
    if (t0 > t1) { real s = t0; t0 = t1; t1 = s; }
    rvec3 halfChord = (root / a) * d;
    n0 = fPerp - halfChord;
    n1 = fPerp + halfChord;
    return true;
}
#endif

bool intersectSphere(rvec3 o, rvec3 d, real tMin, real tMax, out real t, out rvec3 normal) {
    real t0, t1;
    rvec3 n0, n1;
    return sphereSpan(o, d, t0, n0, t1, n1) && firstHitOfSpan(t0, n0, t1, n1, tMin, tMax, t, normal);
}
