// CSG by ray interval lists (Hill ch. 14): each primitive gives the spans of
// t where the ray is inside it; union, intersection and difference combine
// the lists; the hit is the first span end after tMin. Lists hold at most
// CSG_MAX_SPANS spans and at most CSG_MAX_STACK lists are alive at once; the
// host refuses trees that could need more (host/gpu/gpu_scene.cpp).
layout(set = 0, binding = BINDING_CSG_NODES, rgba32ui) uniform readonly uimageBuffer csgNodeTexels;

// GpuCsgNode[index].node.
uvec4 csgNode(uint index) { return imageLoad(csgNodeTexels, int(index)); }

// One end of a span: where the ray crosses a primitive's surface.
struct SpanEnd {
    real t;
    rvec3 normal;     // generic outward normal of `primitive`, negated when flipped
    uint primitive;  // object index
};

struct SpanList {
    uint count;
    SpanEnd ends[2 * CSG_MAX_SPANS];  // in, out, in, out, ... ascending
};

const real CSG_INFINITY = 1.0 / 0.0;

void addSpan(inout SpanList list, real t0, rvec3 n0, real t1, rvec3 n1, uint primitive) {
    list.ends[2u * list.count] = SpanEnd(t0, n0, primitive);
    list.ends[2u * list.count + 1u] = SpanEnd(t1, n1, primitive);
    list.count++;
}

// The generic plane as a solid: the half-space z <= 0.
void planeSpans(rvec3 o, rvec3 d, uint primitive, inout SpanList list) {
    rvec3 up = rvec3(0.0, 0.0, 1.0);
    if (d.z == 0.0) {
        if (o.z <= 0.0) addSpan(list, -CSG_INFINITY, -up, CSG_INFINITY, up, primitive);
        return;
    }
    real t = -o.z / d.z;
    if (d.z > 0.0) addSpan(list, -CSG_INFINITY, -up, t, up, primitive);  // leaves upward
    else addSpan(list, t, up, CSG_INFINITY, up, primitive);
}

// The inside-spans of primitive `index` along the whole line origin + t direction.
SpanList primitiveSpans(uint index, rvec3 origin, rvec3 direction) {
    SpanList list;
    list.count = 0u;
    rvec3 o, d;
    toObjectSpace(index, origin, direction, o, d);
    uvec4 shape = objectShape(index);
    real t0, t1;
    rvec3 n0, n1;
    switch (shape.x) {
#if VKRAY_SHAPE_SPHERE
    case KIND_SPHERE: if (sphereSpan(o, d, t0, n0, t1, n1)) addSpan(list, t0, n0, t1, n1, index); break;
#endif
#if VKRAY_SHAPE_CUBE
    case KIND_CUBE: if (cubeSpan(o, d, t0, n0, t1, n1)) addSpan(list, t0, n0, t1, n1, index); break;
#endif
#if VKRAY_SHAPE_PLANE
    case KIND_PLANE: planeSpans(o, d, index, list); break;
#endif
#if VKRAY_SHAPE_TAPERED_CYLINDER
    case KIND_TAPERED_CYLINDER: {  // an hourglass (s < 0) may give two spans
        TaperedSpans spans = taperedCylinderSpans(o, d, taperOf(index));
        if (spans.count > 0) addSpan(list, spans.t0, spans.n0, spans.t1, spans.n1, index);
        if (spans.count > 1) addSpan(list, spans.t2, spans.n2, spans.t3, spans.n3, index);
        break;
    }
#endif
#if VKRAY_SHAPE_TORUS
    case KIND_TORUS: {
        real ts[4];
        rvec3 ns[4];
        int n = torusRoots(o, d, ts, ns);
        for (int i = 0; i + 1 < n; i += 2) addSpan(list, ts[i], ns[i], ts[i + 1], ns[i + 1], index);
        break;
    }
#endif
#if VKRAY_SHAPE_MESH
    case KIND_MESH:  // convex closed meshes only (the host checks): first and last crossing
        if (meshSpan(shape.y, o, d, t0, n0, t1, n1)) addSpan(list, t0, n0, t1, n1, index);
        break;
#endif
    default: break;
    }
    return list;
}

bool insideOf(uint op, bool inA, bool inB) {
    if (op == CSG_UNION) return inA || inB;
    if (op == CSG_INTERSECTION) return inA && inB;
    return inA && !inB;  // CSG_DIFFERENCE
}

// Merges the span ends of a and b in t order and keeps the ends where the
// combination's inside-ness changes. In a difference, b's surface bounds the
// result from outside b, so its normals turn around.
SpanList combine(uint op, SpanList a, SpanList b) {
    SpanList result;
    result.count = 0u;
    uint i = 0u, j = 0u;
    bool inA = false, inB = false, inside = false;
    uint endsA = 2u * a.count, endsB = 2u * b.count;
    SpanEnd start;
    while (i < endsA || j < endsB) {
        ++loopTurns;
        bool fromA = j >= endsB || (i < endsA && a.ends[i].t <= b.ends[j].t);
        SpanEnd end = fromA ? a.ends[i++] : b.ends[j++];
        if (fromA) inA = !inA;
        else {
            inB = !inB;
            if (op == CSG_DIFFERENCE) end.normal = -end.normal;
        }
        bool now = insideOf(op, inA, inB);
        if (now == inside) continue;
        inside = now;
        if (inside) start = end;
        else if (result.count < CSG_MAX_SPANS) {
            result.ends[2u * result.count] = start;
            result.ends[2u * result.count + 1u] = end;
            result.count++;
        }
    }
    return result;
}

// The nearest surface in (tMin, tMax) of the CSG tree whose post-order nodes
// start at GpuCsgNode `first` (that node's z holds the tree's node count),
// evaluated with a stack of span lists.
bool intersectCsg(uint first, rvec3 origin, rvec3 direction, real tMin, real tMax, out real t,
                  out rvec3 genericNormal, out uint primitive) {
    SpanList stack[CSG_MAX_STACK];
    uint top = 0u;
    uint nodeCount = csgNode(first).z;
    for (uint i = first; i < first + nodeCount; ++i) {
        ++loopTurns;
        uvec4 node = csgNode(i);
        if (node.x == CSG_LEAF) {
            stack[top++] = primitiveSpans(node.y, origin, direction);
        } else {
            SpanList b = stack[--top];
            SpanList a = stack[--top];
            stack[top++] = combine(node.x, a, b);
        }
    }
    SpanList result = stack[0];
    for (uint k = 0u; k < 2u * result.count; ++k) {
        SpanEnd end = result.ends[k];
        if (end.t > tMin && end.t < tMax) {
            t = end.t;
            genericNormal = end.normal;
            primitive = end.primitive;
            return true;
        }
    }
    return false;
}
