// Generic cube [-1, 1]^3 by slabs. A zero direction component is handled
// explicitly: (1 - o) / 0 would give inf, and 0 * inf = NaN on a face-grazing
// ray, and GLSL's min/max are undefined on NaN.
#if VKRAY_PRECISION_NAIVE
// Naive (textbook slabs, Kay and Kajiya): divide by each direction component
// as it comes; a face-grazing ray gives (1 - 1) * inf = NaN.
bool cubeSpan(rvec3 o, rvec3 d, out real t0, out rvec3 n0, out real t1, out rvec3 n1) {
    t0 = -1.0 / 0.0;
    t1 = 1.0 / 0.0;
    int enterAxis = 0, exitAxis = 0;
    for (int i = 0; i < 3; ++i) {
        real inv = 1.0 / d[i];
        real tNear = (-1.0 - o[i]) * inv;
        real tFar = (1.0 - o[i]) * inv;
        if (tNear > tFar) { real s = tNear; tNear = tFar; tFar = s; }
        if (tNear > t0) { t0 = tNear; enterAxis = i; }
        if (tFar < t1) { t1 = tFar; exitAxis = i; }
    }
    if (!(t0 <= t1)) return false;
    n0 = rvec3(0.0);
    n0[enterAxis] = -sign(d[enterAxis]);
    n1 = rvec3(0.0);
    n1[exitAxis] = sign(d[exitAxis]);
    return true;
}
#else
// Robust: zero direction components handled before dividing.
bool cubeSpan(rvec3 o, rvec3 d, out real t0, out rvec3 n0, out real t1, out rvec3 n1) {
    t0 = -1.0 / 0.0;
    t1 = 1.0 / 0.0;
    int enterAxis = 0, exitAxis = 0;
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0) {
            if (abs(o[i]) > 1.0) return false;
            continue;
        }
        real inv = 1.0 / d[i];
        real tNear = (-sign(d[i]) - o[i]) * inv;
        real tFar = (sign(d[i]) - o[i]) * inv;
        if (tNear > t0) { t0 = tNear; enterAxis = i; }
        if (tFar < t1) { t1 = tFar; exitAxis = i; }
    }
    if (t0 > t1) return false;
    n0 = rvec3(0.0);
    n0[enterAxis] = -sign(d[enterAxis]);
    n1 = rvec3(0.0);
    n1[exitAxis] = sign(d[exitAxis]);
    return true;
}
#endif

bool intersectCube(rvec3 o, rvec3 d, real tMin, real tMax, out real t, out rvec3 normal) {
    real t0, t1;
    rvec3 n0, n1;
    return cubeSpan(o, d, t0, n0, t1, n1) && firstHitOfSpan(t0, n0, t1, n1, tMin, tMax, t, normal);
}
