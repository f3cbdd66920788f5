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
// Robust: zero direction components handled before dividing. Each slab in
// a call of its own, not a loop: a loop that returns from its body is not
// unrolled, and a scene of a few objects would lose the unrolled walk
// (VKRAY_OBJECTS) that the cube's loop sits in.
void cubeSlab(real o, real d, int axis, inout real t0, inout real t1, inout int enterAxis,
              inout int exitAxis, inout bool outside) {
    if (d == 0.0) {
        outside = outside || abs(o) > 1.0;
        return;
    }
    real inv = 1.0 / d;
    real tNear = (-sign(d) - o) * inv;
    real tFar = (sign(d) - o) * inv;
    if (tNear > t0) { t0 = tNear; enterAxis = axis; }
    if (tFar < t1) { t1 = tFar; exitAxis = axis; }
}

bool cubeSpan(rvec3 o, rvec3 d, out real t0, out rvec3 n0, out real t1, out rvec3 n1) {
    t0 = -1.0 / 0.0;
    t1 = 1.0 / 0.0;
    int enterAxis = 0, exitAxis = 0;
    bool outside = false;
    cubeSlab(o.x, d.x, 0, t0, t1, enterAxis, exitAxis, outside);
    cubeSlab(o.y, d.y, 1, t0, t1, enterAxis, exitAxis, outside);
    cubeSlab(o.z, d.z, 2, t0, t1, enterAxis, exitAxis, outside);
    if (outside || t0 > t1) return false;
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
