// CSG by ray intervals (Hill ch. 14), swept without lists: each primitive
// gives the spans of t where the ray is inside it; the tree's inside-ness is
// a boolean function of which primitives the ray is inside. From tMin the
// sweep steps to the nearest primitive surface ahead, takes every primitive
// that changes there together, and stops where the tree's inside-ness
// changes: that surface is the hit. Nothing per ray is kept in an array (on
// lavapipe an array indexed at run time lives in memory, written a lane at a
// time): the primitives' inside flags are the bits of one word, and the tree
// is evaluated on them with a stack of bits in another. Each step tests every
// primitive again; a step passes one end of one primitive's spans at least,
// so a tree of n primitives takes at most 4n steps. The host keeps trees to
// CSG_MAX_LEAVES primitives (host/gpu/gpu_scene.cpp).
layout(set = 0, binding = BINDING_CSG_NODES, rgba32ui) uniform readonly uimageBuffer csgNodeTexels;

// GpuCsgNode[index].node.
uvec4 csgNode(uint index) { return imageLoad(csgNodeTexels, int(index)); }

const real CSG_INFINITY = 1.0 / 0.0;

// A primitive's inside-spans along the whole line origin + t direction:
// at most two, [t0, t1] and [t2, t3], with the generic outward normals at
// their ends; +inf where it has fewer.
struct CsgSpans {
    real t0, t1, t2, t3;
    rvec3 n0, n1, n2, n3;
};

CsgSpans primitiveSpans(uint index, rvec3 origin, rvec3 direction) {
    rvec3 o, d;
    toObjectSpace(index, origin, direction, o, d);
    uvec4 shape = objectShape(index);
    uint spans = 0u;
    CsgSpans s;
    s.t0 = CSG_INFINITY;
    s.t1 = CSG_INFINITY;
    s.t2 = CSG_INFINITY;
    s.t3 = CSG_INFINITY;
    s.n0 = rvec3(0.0);
    s.n1 = rvec3(0.0);
    s.n2 = rvec3(0.0);
    s.n3 = rvec3(0.0);
    switch (shape.x) {
#if VKRAY_SHAPE_SPHERE
    case KIND_SPHERE: spans = sphereSpan(o, d, s.t0, s.n0, s.t1, s.n1) ? 1u : 0u; break;
#endif
#if VKRAY_SHAPE_CUBE
    case KIND_CUBE: spans = cubeSpan(o, d, s.t0, s.n0, s.t1, s.n1) ? 1u : 0u; break;
#endif
#if VKRAY_SHAPE_PLANE
    case KIND_PLANE: {  // the generic plane as a solid: the half-space z <= 0
        rvec3 up = rvec3(0.0, 0.0, 1.0);
        if (d.z == 0.0) {
            spans = o.z <= 0.0 ? 1u : 0u;
            s.t0 = -CSG_INFINITY;
            s.n0 = -up;
            s.t1 = CSG_INFINITY;
            s.n1 = up;
            break;
        }
        real t = -o.z / d.z;
        spans = 1u;
        s.t0 = d.z > 0.0 ? -CSG_INFINITY : t;  // leaves upward, or enters downward
        s.n0 = d.z > 0.0 ? -up : up;
        s.t1 = d.z > 0.0 ? t : CSG_INFINITY;
        s.n1 = up;
        break;
    }
#endif
#if VKRAY_SHAPE_TAPERED_CYLINDER
    case KIND_TAPERED_CYLINDER: {  // an hourglass (s < 0) may give two spans
        TaperedSpans tapered = taperedCylinderSpans(o, d, taperOf(index));
        spans = uint(tapered.count);
        s.t0 = tapered.t0;
        s.t1 = tapered.t1;
        s.t2 = tapered.t2;
        s.t3 = tapered.t3;
        s.n0 = tapered.n0;
        s.n1 = tapered.n1;
        s.n2 = tapered.n2;
        s.n3 = tapered.n3;
        break;
    }
#endif
#if VKRAY_SHAPE_TORUS
    case KIND_TORUS: {
        TorusCrossings crossings = torusCrossings(o, d);
        spans = uint(crossings.count) / 2u;
        s.t0 = crossings.t.x;
        s.t1 = crossings.t.y;
        s.t2 = crossings.t.z;
        s.t3 = crossings.t.w;
        s.n0 = crossings.n0;
        s.n1 = crossings.n1;
        s.n2 = crossings.n2;
        s.n3 = crossings.n3;
        break;
    }
#endif
#if VKRAY_SHAPE_MESH
    case KIND_MESH:  // convex closed meshes only (the host checks): first and last crossing
        spans = meshSpan(shape.y, o, d, s.t0, s.n0, s.t1, s.n1) ? 1u : 0u;
        break;
#endif
    default: break;
    }
    if (spans < 1u) {
        s.t0 = CSG_INFINITY;
        s.t1 = CSG_INFINITY;
    }
    if (spans < 2u) {
        s.t2 = CSG_INFINITY;
        s.t3 = CSG_INFINITY;
    }
    return s;
}

// Inside just after t: within a span of positive length, its start included
// (an end where another span starts leaves the ray inside; a tangent, a span
// of length 0, changes nothing).
bool insideAfter(CsgSpans s, real t) {
    return (s.t0 <= t && t < s.t1) || (s.t2 <= t && t < s.t3);
}

// The nearest span end beyond t, and its normal.
void nextEnd(CsgSpans s, real t, inout real at, inout rvec3 normal) {
    at = CSG_INFINITY;
    if (s.t3 > t) {
        at = s.t3;
        normal = s.n3;
    }
    if (s.t2 > t && s.t2 <= at) {
        at = s.t2;
        normal = s.n2;
    }
    if (s.t1 > t && s.t1 <= at) {
        at = s.t1;
        normal = s.n1;
    }
    if (s.t0 > t && s.t0 <= at) {
        at = s.t0;
        normal = s.n0;
    }
}

bool insideOf(uint op, bool inA, bool inB) {
    if (op == CSG_UNION) return inA || inB;
    if (op == CSG_INTERSECTION) return inA && inB;
    return inA && !inB;  // CSG_DIFFERENCE
}

// Whether the tree (post-order nodes from `first`) is inside with the
// primitives `inside` (bit k: the k-th leaf), and with `other` too: two
// stacks of bits, the top in bit 0.
void treeInside(uint first, uint nodeCount, uint inside, uint other, out bool a, out bool b) {
    uint stack = 0u, otherStack = 0u, leaf = 0u;
    for (uint i = first; i < first + nodeCount; ++i) {
        ++loopTurns;
        uint op = csgNode(i).x;
        if (op == CSG_LEAF) {
            stack = (stack << 1u) | ((inside >> leaf) & 1u);
            otherStack = (otherStack << 1u) | ((other >> leaf) & 1u);
            ++leaf;
        } else {
            uint combined = uint(insideOf(op, (stack & 2u) != 0u, (stack & 1u) != 0u));
            uint otherCombined =
                uint(insideOf(op, (otherStack & 2u) != 0u, (otherStack & 1u) != 0u));
            stack = ((stack >> 2u) << 1u) | combined;
            otherStack = ((otherStack >> 2u) << 1u) | otherCombined;
        }
    }
    a = (stack & 1u) != 0u;
    b = (otherStack & 1u) != 0u;
}

// The nearest surface in (tMin, tMax) of the CSG tree whose post-order nodes
// start at GpuCsgNode `first`, its leaves after them (layout.h).
bool intersectCsg(uint first, rvec3 origin, rvec3 direction, real tMin, real tMax, out real t,
                  out rvec3 genericNormal, out uint primitive) {
    t = CSG_INFINITY;
    genericNormal = rvec3(0.0);
    primitive = 0u;
    uvec4 root = csgNode(first);
    uint nodeCount = root.z, leaves = first + nodeCount, leafEnd = leaves + root.w;
    real now = tMin;
    for (uint step = 0u; step <= 4u * root.w; ++step) {
        uint inside = 0u;    // the leaves the ray is inside just after `now`
        uint changing = 0u;  // those whose inside-ness changes at `next`
        real next = CSG_INFINITY;
        rvec3 nextNormal = rvec3(0.0);
        uint nextPrimitive = 0u;
        bool found = false;  // a changing leaf at `next` gave the normal
        uint bit = 1u;
        for (uint i = leaves; i < leafEnd; ++i) {
            ++loopTurns;
            uvec4 node = csgNode(i);
            CsgSpans s = primitiveSpans(node.y, origin, direction);
            bool inNow = insideAfter(s, now);
            real end;
            rvec3 normal = rvec3(0.0);
            nextEnd(s, now, end, normal);
            bool changes = insideAfter(s, end) != inNow;
            if (end < next) {
                next = end;
                changing = 0u;
                found = false;
            }
            if (end == next && changes) {
                changing |= bit;
                if (!found) {
                    found = true;
                    nextNormal = node.w != 0u ? -normal : normal;
                    nextPrimitive = node.y;
                }
            }
            if (inNow) inside |= bit;
            bit <<= 1u;
        }
        if (!(next < tMax)) return false;
        bool before, after;
        treeInside(first, nodeCount, inside, inside ^ changing, before, after);
        if (before != after) {
            t = next;
            genericNormal = nextNormal;
            primitive = nextPrimitive;
            return true;
        }
        now = next;
    }
    return false;
}
