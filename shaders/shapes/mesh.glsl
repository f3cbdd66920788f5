// Triangle meshes in object space, each with its own BVH (host/scene/bvh.h).
// Triangles use the watertight test of Woop, Benthin and Wald (docs/numerics-background.md,
// "Watertight triangles"): edge functions in a ray-aligned frame, so two triangles sharing
// an edge see it with exactly opposite signs and no ray slips between them.
layout(std430, set = 0, binding = BINDING_MESHES) readonly buffer MeshBlock { GpuMesh meshes[]; };
layout(std430, set = 0, binding = BINDING_MESH_NODES) readonly buffer MeshNodeBlock { GpuBvhNode meshNodes[]; };
layout(std430, set = 0, binding = BINDING_TRIANGLES) readonly buffer TriangleBlock { GpuTriangle triangles[]; };

// The ray in the frame where it runs along +z (per ray, shared by all triangles).
struct ShearedRay {
    rvec3 o;
    ivec3 axes;   // kx, ky, kz
    rvec3 shear;   // Sx, Sy, Sz
};

ShearedRay shearRay(rvec3 o, rvec3 d) {
    ShearedRay r;
    r.o = o;
    rvec3 a = abs(d);
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (d[kz] < 0.0) { int s = kx; kx = ky; ky = s; }  // keep the winding
    r.axes = ivec3(kx, ky, kz);
    r.shear = rvec3(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
    return r;
}

// The hit of the ray with triangle p0 p1 p2 in (tMin, tMax): t and barycentrics.
bool intersectTriangle(ShearedRay r, rvec3 p0, rvec3 p1, rvec3 p2, real tMin, real tMax,
                       out real t, out rvec3 barycentric) {
    rvec3 a = p0 - r.o, b = p1 - r.o, c = p2 - r.o;
    ivec3 k = r.axes;
    precise real ax = a[k.x] - r.shear.x * a[k.z], ay = a[k.y] - r.shear.y * a[k.z];
    precise real bx = b[k.x] - r.shear.x * b[k.z], by = b[k.y] - r.shear.y * b[k.z];
    precise real cx = c[k.x] - r.shear.x * c[k.z], cy = c[k.y] - r.shear.y * c[k.z];
    precise real u = cx * by - cy * bx;
    precise real v = ax * cy - ay * cx;
    precise real w = bx * ay - by * ax;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
    real det = u + v + w;
    if (det == 0.0) return false;
    real scaledT = r.shear.z * (u * a[k.z] + v * b[k.z] + w * c[k.z]);
    t = scaledT / det;
    if (!(t > tMin && t < tMax)) return false;
    barycentric = rvec3(u, v, w) / det;
    return true;
}

// The nearest triangle of mesh `index` in (tMin, tMax), with the interpolated
// normal and the triangle's own (geometric) one, unnormalised.
bool intersectMesh(uint index, rvec3 o, rvec3 d, real tMin, real tMax, out real t, out rvec3 normal,
                   out rvec3 geometricNormal) {
    GpuMesh mesh = meshes[index];
    ShearedRay sheared = shearRay(o, d);
    rvec3 invD = 1.0 / d;
    bool found = false;
    t = tMax;
    uint stack[BVH_STACK_SIZE];
    real stackEnter[BVH_STACK_SIZE];
    uint top = 0u;
    uint node = 0u;
    real enter;
    GpuBvhNode root = meshNodes[mesh.range.x];
    bool walking = hitsBox(root.lo.xyz, root.hi.xyz, o, invD, tMin, t, enter);
    while (walking) {
        ++loopTurns;
        GpuBvhNode n = meshNodes[mesh.range.x + node];
        uint count = floatBitsToUint(n.hi.w), first = floatBitsToUint(n.lo.w);
        if (count == 0u) {
            uint nearIndex, farIndex;
            real farEnter;
            int hits = orderChildren(meshNodes[mesh.range.x + node + 1u], node + 1u,
                                     meshNodes[mesh.range.x + first], first, o, invD, tMin, t,
                                     nearIndex, farIndex, farEnter);
            if (hits == 2) {
                stack[top] = farIndex;
                stackEnter[top++] = farEnter;
            }
            if (hits > 0) {
                node = nearIndex;
                continue;
            }
        } else {
            loopTurns += count;
            for (uint i = first; i < first + count; ++i) {
                GpuTriangle tri = triangles[mesh.range.y + i];
                real tHit;
                rvec3 bary;
                if (intersectTriangle(sheared, tri.p0.xyz, tri.p1.xyz, tri.p2.xyz, tMin, t, tHit, bary)) {
                    t = tHit;
                    normal = bary.x * tri.n0.xyz + bary.y * tri.n1.xyz + bary.z * tri.n2.xyz;
                    geometricNormal = cross(tri.p1.xyz - tri.p0.xyz, tri.p2.xyz - tri.p0.xyz);
                    found = true;
                }
            }
        }
        walking = false;
        while (top > 0u && !walking) {
            ++loopTurns;
            --top;
            walking = stackEnter[top] <= t;
            node = stack[top];
        }
    }
    return found;
}

// A convex closed mesh as a solid (CSG): the first and last crossing of the
// whole line, with their normals.
bool meshSpan(uint index, rvec3 o, rvec3 d, out real t0, out rvec3 n0, out real t1, out rvec3 n1) {
    GpuMesh mesh = meshes[index];
    ShearedRay sheared = shearRay(o, d);
    rvec3 invD = 1.0 / d;
    const real INF = 1.0 / 0.0;
    uint stack[BVH_STACK_SIZE];
    uint top = 0u;
    uint node = 0u;
    t0 = INF;
    t1 = -INF;
    while (true) {
        ++loopTurns;
        GpuBvhNode n = meshNodes[mesh.range.x + node];
        real enter;
        if (hitsBox(n.lo.xyz, n.hi.xyz, o, invD, -INF, INF, enter)) {
            uint count = floatBitsToUint(n.hi.w), first = floatBitsToUint(n.lo.w);
            if (count == 0u) {
                stack[top++] = first;
                node = node + 1u;
                continue;
            }
            for (uint i = first; i < first + count; ++i) {
                ++loopTurns;
                GpuTriangle tri = triangles[mesh.range.y + i];
                real t;
                rvec3 bary;
                if (!intersectTriangle(sheared, tri.p0.xyz, tri.p1.xyz, tri.p2.xyz, -INF, INF, t, bary))
                    continue;
                rvec3 normal = bary.x * tri.n0.xyz + bary.y * tri.n1.xyz + bary.z * tri.n2.xyz;
                if (t < t0) { t0 = t; n0 = normal; }
                if (t > t1) { t1 = t; n1 = normal; }
            }
        }
        if (top == 0u) break;
        node = stack[--top];
    }
    return t0 <= t1;
}
