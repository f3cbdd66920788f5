// CSG by ray interval lists (Hill ch. 14): each primitive gives the spans of
// t where the ray is inside it; union, intersection and difference combine
// the lists; the hit is the first span end after tMin. Lists hold at most
// CSG_MAX_SPANS spans and at most CSG_MAX_STACK lists are alive at once; the
// host refuses trees that could need more (host/gpu/gpu_scene.cpp).
layout(set = 0, binding = BINDING_CSG_NODES, rgba32ui) uniform readonly uimageBuffer csgNodeTexels;

// GpuCsgNode[index].node.
uvec4 csgNode(uint index) { return imageLoad(csgNodeTexels, int(index)); }

// The span lists live in a pool of slots, each end's fields in an array of
// its own: lavapipe keeps an array indexed at run time in memory and writes
// each word of it in a loop over the lanes, so a list is written once, where
// it is made, never copied (a whole list is 81 words). The evaluation's
// stack holds slot numbers; one slot more than the stack's depth takes a
// combination's result.
const uint CSG_SLOTS = CSG_MAX_STACK + 1u;
const uint CSG_SLOT_ENDS = 2u * CSG_MAX_SPANS;  // in, out, in, out, ... ascending
real csgEndT[CSG_SLOTS * CSG_SLOT_ENDS];
rvec3 csgEndNormal[CSG_SLOTS * CSG_SLOT_ENDS];  // generic outward normal of the primitive, negated when flipped
uint csgEndPrimitive[CSG_SLOTS * CSG_SLOT_ENDS];  // object index
uint csgSpanCount[CSG_SLOTS];

const real CSG_INFINITY = 1.0 / 0.0;

void setCsgEnd(uint at, real t, rvec3 normal, uint primitive) {
    csgEndT[at] = t;
    csgEndNormal[at] = normal;
    csgEndPrimitive[at] = primitive;
}

// The inside-spans of primitive `index` along the whole line origin + t
// direction into slot `slot`: at most two, found in registers, then written
// by one piece of code whatever the shape.
void primitiveSpans(uint index, rvec3 origin, rvec3 direction, uint slot) {
    rvec3 o, d;
    toObjectSpace(index, origin, direction, o, d);
    uvec4 shape = objectShape(index);
    uint spans = 0u;
    real t0 = CSG_INFINITY, t1 = CSG_INFINITY, t2 = CSG_INFINITY, t3 = CSG_INFINITY;
    rvec3 n0 = rvec3(0.0), n1 = rvec3(0.0), n2 = rvec3(0.0), n3 = rvec3(0.0);
    switch (shape.x) {
#if VKRAY_SHAPE_SPHERE
    case KIND_SPHERE: spans = sphereSpan(o, d, t0, n0, t1, n1) ? 1u : 0u; break;
#endif
#if VKRAY_SHAPE_CUBE
    case KIND_CUBE: spans = cubeSpan(o, d, t0, n0, t1, n1) ? 1u : 0u; break;
#endif
#if VKRAY_SHAPE_PLANE
    case KIND_PLANE: {  // the generic plane as a solid: the half-space z <= 0
        rvec3 up = rvec3(0.0, 0.0, 1.0);
        if (d.z == 0.0) {
            spans = o.z <= 0.0 ? 1u : 0u;
            t0 = -CSG_INFINITY;
            n0 = -up;
            t1 = CSG_INFINITY;
            n1 = up;
            break;
        }
        real t = -o.z / d.z;
        spans = 1u;
        t0 = d.z > 0.0 ? -CSG_INFINITY : t;  // leaves upward, or enters downward
        n0 = d.z > 0.0 ? -up : up;
        t1 = d.z > 0.0 ? t : CSG_INFINITY;
        n1 = up;
        break;
    }
#endif
#if VKRAY_SHAPE_TAPERED_CYLINDER
    case KIND_TAPERED_CYLINDER: {  // an hourglass (s < 0) may give two spans
        TaperedSpans tapered = taperedCylinderSpans(o, d, taperOf(index));
        spans = uint(tapered.count);
        t0 = tapered.t0;
        t1 = tapered.t1;
        t2 = tapered.t2;
        t3 = tapered.t3;
        n0 = tapered.n0;
        n1 = tapered.n1;
        n2 = tapered.n2;
        n3 = tapered.n3;
        break;
    }
#endif
#if VKRAY_SHAPE_TORUS
    case KIND_TORUS: {
        TorusCrossings crossings = torusCrossings(o, d);
        spans = uint(crossings.count) / 2u;
        t0 = crossings.t.x;
        t1 = crossings.t.y;
        t2 = crossings.t.z;
        t3 = crossings.t.w;
        n0 = crossings.n0;
        n1 = crossings.n1;
        n2 = crossings.n2;
        n3 = crossings.n3;
        break;
    }
#endif
#if VKRAY_SHAPE_MESH
    case KIND_MESH:  // convex closed meshes only (the host checks): first and last crossing
        spans = meshSpan(shape.y, o, d, t0, n0, t1, n1) ? 1u : 0u;
        break;
#endif
    default: break;
    }
    uint at = slot * CSG_SLOT_ENDS;
    if (spans > 0u) {
        setCsgEnd(at, t0, n0, index);
        setCsgEnd(at + 1u, t1, n1, index);
    }
    if (spans > 1u) {
        setCsgEnd(at + 2u, t2, n2, index);
        setCsgEnd(at + 3u, t3, n3, index);
    }
    csgSpanCount[slot] = spans;
}

bool insideOf(uint op, bool inA, bool inB) {
    if (op == CSG_UNION) return inA || inB;
    if (op == CSG_INTERSECTION) return inA && inB;
    return inA && !inB;  // CSG_DIFFERENCE
}

// Merges the span ends of slots a and b in t order into slot `result`,
// keeping the ends where the combination's inside-ness changes: each is
// written as it comes (a kept span's start when the result goes in, its end
// when it comes out), one end a turn, the code of one write. In a
// difference, b's surface bounds the result from outside b, so its normals
// turn around.
void combine(uint op, uint a, uint b, uint result) {
    uint i = 0u, j = 0u, count = 0u;
    bool inA = false, inB = false, inside = false;
    uint endsA = 2u * csgSpanCount[a], endsB = 2u * csgSpanCount[b];
    uint baseA = a * CSG_SLOT_ENDS, baseB = b * CSG_SLOT_ENDS, baseResult = result * CSG_SLOT_ENDS;
    while (i < endsA || j < endsB) {
        ++loopTurns;
        bool fromA = j >= endsB || (i < endsA && csgEndT[baseA + i] <= csgEndT[baseB + j]);
        uint end = fromA ? baseA + i : baseB + j;
        bool flipped = !fromA && op == CSG_DIFFERENCE;
        if (fromA) {
            inA = !inA;
            ++i;
        } else {
            inB = !inB;
            ++j;
        }
        bool now = insideOf(op, inA, inB);
        if (now != inside && count < CSG_MAX_SPANS) {
            setCsgEnd(baseResult + 2u * count + (now ? 0u : 1u), csgEndT[end],
                      flipped ? -csgEndNormal[end] : csgEndNormal[end], csgEndPrimitive[end]);
            if (!now) count++;
        }
        inside = now;
    }
    csgSpanCount[result] = count;
}

// The nearest surface in (tMin, tMax) of the CSG tree whose post-order nodes
// start at GpuCsgNode `first` (that node's z holds the tree's node count),
// evaluated with a stack of span lists.
bool intersectCsg(uint first, rvec3 origin, rvec3 direction, real tMin, real tMax, out real t,
                  out rvec3 genericNormal, out uint primitive) {
    // The stack's slots, and the one it does not hold: a permutation of them all.
    uint stackSlot[CSG_MAX_STACK];
    for (uint k = 0u; k < CSG_MAX_STACK; ++k) stackSlot[k] = k;
    uint spare = CSG_MAX_STACK;
    uint top = 0u;
    uint nodeCount = csgNode(first).z;
    for (uint i = first; i < first + nodeCount; ++i) {
        ++loopTurns;
        uvec4 node = csgNode(i);
        if (node.x == CSG_LEAF) {
            primitiveSpans(node.y, origin, direction, stackSlot[top++]);
        } else {
            uint a = stackSlot[top - 2u], b = stackSlot[top - 1u];
            combine(node.x, a, b, spare);
            stackSlot[top - 2u] = spare;
            spare = a;
            --top;
        }
    }
    uint result = stackSlot[0] * CSG_SLOT_ENDS;
    uint ends = 2u * csgSpanCount[stackSlot[0]];
    for (uint k = result; k < result + ends; ++k) {
        real at = csgEndT[k];
        if (at > tMin && at < tMax) {
            t = at;
            genericNormal = csgEndNormal[k];
            primitive = csgEndPrimitive[k];
            return true;
        }
    }
    return false;
}
