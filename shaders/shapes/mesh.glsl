// Triangle meshes in object space, each with its own BVH (host/scene/bvh.h).
// Triangles use the watertight test of Woop, Benthin and Wald (docs/numerics-background.md,
// "Watertight triangles"): edge functions in a ray-aligned frame, so two triangles sharing
// an edge see it with exactly opposite signs and no ray slips between them.
layout(set = 0, binding = BINDING_MESHES, rgba32ui) uniform readonly uimageBuffer meshTexels;
layout(set = 0, binding = BINDING_TRIANGLES, rgba32ui) uniform readonly uimageBuffer triangleTexels;

GpuMesh meshOf(uint index) { return GpuMesh(imageLoad(meshTexels, int(index))); }
#if VKRAY_MESH_INSTANCES
// The meshes' nodes follow the objects' (host: meshNodesWithObjects), for the
// one walk through both.
GpuBvhNode meshNode(uint index) { return objectNode(index); }
#else
layout(set = 0, binding = BINDING_MESH_NODES, rgba32ui) uniform readonly uimageBuffer meshNodeTexels;
GpuBvhNode meshNode(uint index) { return BVH_NODE(meshNodeTexels, index); }
#endif

// Corner k (0..2) of triangle `index`: its position, or (normal) its normal.
vec3 triangleCorner(uint index, uint k) {
    return texelAsVec4(imageLoad(triangleTexels, int(index * TRIANGLE_TEXELS + k))).xyz;
}
vec3 triangleNormal(uint index, uint k) {
    return texelAsVec4(imageLoad(triangleTexels, int(index * TRIANGLE_TEXELS + 3u + k))).xyz;
}

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

// Where a mesh's walk starts: o, or from a generic origin far from the mesh
// the point where the ray enters the mesh's root box (`enter`, its t), the
// walk and the triangle tests then measuring from o + shift d and adding
// shift back to every t. From far away (|M^-1 eye| = 4e10 for a teapot
// squashed by 1.8e-6 between rotations seen from 1e5, the generic direction
// 4e5 long) every slab distance (lo - o) / d is about |o| / |d|: float
// rounds all of them alike, and hitsBox's widening of the far end (3.6e-7
// of it: 0.035 of the world t 1e5, 1.4e4 generic units along the ray) is
// thousands of times the mesh, so every box passed and each of the
// teapot's 16256 triangles was tested, past llvmpipe's loop limit. From the
// entry point the distances are those of the boxes. The start is o + shift d
// rounded once (fma), on the ray to the rounding of its own small
// coordinates. Nearer than MESH_FAR_SIZES times the mesh's size (its root
// box's diagonal) the widening is under 0.024 of the mesh, a leaf box's
// size, and the walk starts at o, as it always does in the textbook mode.
const float MESH_FAR_SIZES = 65536.0;
#if VKRAY_PRECISION_FP64
const double MESH_LOCAL_SLACK = 4.4408920985006262e-16lf;  // 2^-51, four units of double's rounding
#else
const float MESH_LOCAL_SLACK = 2.3841858e-7;  // 2^-22, four units of float's rounding
#endif
real meshWalkShift(GpuBvhNode root, rvec3 d, real enter) {
#if VKRAY_PRECISION_NAIVE
    return 0.0;
#else
    float size = length(root.hi.xyz - root.lo.xyz);
    return enter * length(d) > real(MESH_FAR_SIZES * size) ? enter : real(0.0);
#endif
}

// The far bound tMax of a walk measured from `shift` along the ray, widened
// by its rounding, so that no box or hit short of tMax is lost.
real meshLocalBound(real tMax, real shift) {
    real local = tMax - shift;
    return local + abs(local) * MESH_LOCAL_SLACK;
}

// Triangle `index`'s normal interpolated at `barycentric` and its own
// (geometric) one, unnormalised.
void triangleNormals(uint index, rvec3 barycentric, out rvec3 normal, out rvec3 geometric) {
    normal = barycentric.x * triangleNormal(index, 0u) + barycentric.y * triangleNormal(index, 1u) +
             barycentric.z * triangleNormal(index, 2u);
    vec3 p0 = triangleCorner(index, 0u);
    geometric = cross(triangleCorner(index, 1u) - p0, triangleCorner(index, 2u) - p0);
}

// The nearest triangle of mesh `index` in (tMin, tMax), with the interpolated
// normal and the triangle's own (geometric) one, unnormalised.
bool intersectMesh(uint index, rvec3 o, rvec3 d, real tMin, real tMax, out real t, out rvec3 normal,
                   out rvec3 geometricNormal) {
    GpuMesh mesh = meshOf(index);
    rvec3 invD = 1.0 / d;
    t = tMax;
    real enter;
    GpuBvhNode root = meshNode(mesh.range.x);
    if (!hitsBox(root.lo.xyz, root.hi.xyz, o, invD, tMin, tMax, enter)) return false;
    // From the start on, t is measured from it (`local`); a hit's t is shift
    // + local, taken only within (tMin, tMax) as such. tMin - shift is exact
    // (where shift is not 0, tMin is 0 or -inf); the far bound is widened by
    // its rounding, so no box or hit short of tMax is lost.
    real shift = meshWalkShift(root, d, enter);
    rvec3 start = fma(rvec3(shift), d, o);
    ShearedRay sheared = shearRay(start, d);
    real localMin = tMin - shift;
    real local = meshLocalBound(tMax, shift);
    bool found = false;
    uint nearest = 0u;  // the triangle of the closest hit so far
    rvec3 nearestBarycentric = rvec3(0.0);
    uint stack[BVH_STACK_SIZE];  // as in walkScene (trace.comp)
    real stackEnter[BVH_STACK_SIZE];
    stack[0] = bvhNodeCode(root);
    stackEnter[0] = enter - shift;
    uint top = 1u;
    uint leafFirst = 0u, leafCount = 0u;
    while (true) {
        loopTurns += leafCount;
        for (uint i = mesh.range.y + leafFirst; i < mesh.range.y + leafFirst + leafCount; ++i) {
            real tHit;
            rvec3 bary;
            if (intersectTriangle(sheared, triangleCorner(i, 0u), triangleCorner(i, 1u),
                                  triangleCorner(i, 2u), localMin, local, tHit, bary) &&
                shift + tHit > tMin && shift + tHit < tMax) {
                local = tHit;
                t = shift + tHit;
                nearest = i;
                nearestBarycentric = bary;
                found = true;
            }
        }
        leafCount = 0u;
        bool walking = false;
        uint children = 0u;
        while (true) {
            ++loopTurns;
            if (!walking) {
                bool kept = false;
                uint code = 0u;
                while (top > 0u && !kept) {
                    --top;
                    kept = stackEnter[top] <= local;
                    code = stack[top];
                }
                if (!kept) break;
                if ((code & 7u) != 0u) {
                    leafFirst = code >> 3u;
                    leafCount = code & 7u;
                    break;
                }
                children = code >> 3u;
            }
            uint nearCode, farCode;
            real farEnter;
            int hits = orderChildren(meshNode(mesh.range.x + children), meshNode(mesh.range.x + children + 1u),
                                     start, invD, localMin, local, nearCode, farCode, farEnter);
            if (hits == 2) {
                stack[top] = farCode;
                stackEnter[top++] = farEnter;
            }
            walking = hits > 0 && (nearCode & 7u) == 0u;
            children = nearCode >> 3u;
            if (hits > 0 && !walking) {
                leafFirst = nearCode >> 3u;
                leafCount = nearCode & 7u;
                break;
            }
        }
        if (leafCount == 0u) break;
    }
    // The normals of the nearest triangle only (read once, not at every closer hit).
    if (found) triangleNormals(nearest, nearestBarycentric, normal, geometricNormal);
    return found;
}

// A convex closed mesh as a solid (CSG): the first and last crossing of the
// whole line, with their normals.
bool meshSpan(uint index, rvec3 o, rvec3 d, out real t0, out rvec3 n0, out real t1, out rvec3 n1) {
    GpuMesh mesh = meshOf(index);
    rvec3 invD = 1.0 / d;
    const real INF = 1.0 / 0.0;
    t0 = INF;
    t1 = -INF;
    real enter;
    GpuBvhNode root = meshNode(mesh.range.x);
    if (!hitsBox(root.lo.xyz, root.hi.xyz, o, invD, -INF, INF, enter)) return false;
    // Measured from where the line enters the root box, as in intersectMesh.
    real shift = meshWalkShift(root, d, enter);
    rvec3 start = fma(rvec3(shift), d, o);
    ShearedRay sheared = shearRay(start, d);
    uint stack[BVH_STACK_SIZE];  // nodes the line crosses (bvhNodeCode)
    stack[0] = bvhNodeCode(root);
    uint top = 1u;
    while (top > 0u) {
        ++loopTurns;
        uint code = stack[--top], first = code >> 3u, count = code & 7u;
        if (count == 0u) {
            GpuBvhNode a = meshNode(mesh.range.x + first), b = meshNode(mesh.range.x + first + 1u);
            if (hitsBox(a.lo.xyz, a.hi.xyz, start, invD, -INF, INF, enter)) stack[top++] = bvhNodeCode(a);
            if (hitsBox(b.lo.xyz, b.hi.xyz, start, invD, -INF, INF, enter)) stack[top++] = bvhNodeCode(b);
            continue;
        }
        for (uint i = mesh.range.y + first; i < mesh.range.y + first + count; ++i) {
            ++loopTurns;
            real t;
            rvec3 bary;
            if (!intersectTriangle(sheared, triangleCorner(i, 0u), triangleCorner(i, 1u),
                                   triangleCorner(i, 2u), -INF, INF, t, bary))
                continue;
            rvec3 normal = bary.x * triangleNormal(i, 0u) + bary.y * triangleNormal(i, 1u) +
                           bary.z * triangleNormal(i, 2u);
            t += shift;
            if (t < t0) { t0 = t; n0 = normal; }
            if (t > t1) { t1 = t; n1 = normal; }
        }
    }
    return t0 <= t1;
}
