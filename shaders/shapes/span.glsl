// Helpers every variant includes. The solid shapes report the span of t where the ray is inside them (entry
// t0 and exit t1 with their outward normals): the closest hit is the first
// end after tMin, and CSG combines the spans.
bool firstHitOfSpan(real t0, rvec3 n0, real t1, rvec3 n1, real tMin, real tMax,
                    out real t, out rvec3 normal) {
    if (t0 > tMin) {
        t = t0;
        normal = n0;
    } else {
        t = t1;
        normal = n1;
    }
    return t > tMin && t < tMax;
}

// Slab test of a box (a BVH node) against o + d t in [tMin, tMax], given
// invD = 1 / d. Conservative: the far end is widened by 1 + 2 gamma(3)
// (pbrt-v4) so rounding never culls a box the ray touches. An axis-parallel
// ray on a slab plane gives 0 * inf = NaN, and GLSL's min and max are
// undefined on NaN, so NaN is replaced first: the ray lies in that slab.
bool hitsBox(rvec3 lo, rvec3 hi, rvec3 o, rvec3 invD, real tMin, real tMax, out real enter) {
    rvec3 t0 = (lo - o) * invD;
    rvec3 t1 = (hi - o) * invD;
    const real INF = 1.0 / 0.0;
    for (int i = 0; i < 3; ++i) {
        if (isnan(t0[i])) t0[i] = -INF;
        if (isnan(t1[i])) t1[i] = INF;
    }
    rvec3 tNear = min(t0, t1), tFar = max(t0, t1);
    enter = max(tMin, max(tNear.x, max(tNear.y, tNear.z)));
    real exit = min(tMax, min(tFar.x, min(tFar.y, tFar.z)));
    return enter <= exit + abs(exit) * 3.6e-7;
}

// A BVH node as a walk's stack keeps it: first * 8 + count (layout.h, GpuBvhNode).
uint bvhNodeCode(GpuBvhNode n) { return (floatBitsToUint(n.lo.w) << 3u) | floatBitsToUint(n.hi.w); }

// Front-to-back BVH walks (trace.comp over objects, mesh.glsl over
// triangles) share this step: at an interior node, which of its children a
// and b the ray enters within [tMin, tMax], the nearer first. Returns how
// many (0, 1, 2), with their codes (bvhNodeCode); with 2 the far one is to be
// kept on the stack with its entry t. (Scalars only: passing the walk's
// stack in and out of a function would copy it.)
int orderChildren(GpuBvhNode a, GpuBvhNode b, rvec3 o, rvec3 invD, real tMin, real tMax,
                  out uint nearCode, out uint farCode, out real farEnter) {
    real enterA, enterB;
    bool hitA = hitsBox(a.lo.xyz, a.hi.xyz, o, invD, tMin, tMax, enterA);
    bool hitB = hitsBox(b.lo.xyz, b.hi.xyz, o, invD, tMin, tMax, enterB);
    bool aFirst = hitA && (!hitB || enterA <= enterB);
    uint codeA = bvhNodeCode(a), codeB = bvhNodeCode(b);
    nearCode = aFirst ? codeA : codeB;
    farCode = aFirst ? codeB : codeA;
    farEnter = aFirst ? enterB : enterA;
    return int(hitA) + int(hitB);
}
