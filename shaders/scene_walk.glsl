// The walk of a ray through the scene's objects: through the object BVH
// (VKRAY_OBJECT_BVH) front to back, or every object in turn, each object met
// tested by testObject. Included by trace.comp after intersectObject.

// Surfaces that coincide (stacked cubes, a def used twice) are hit at the same
// t up to rounding. Hits within this relative distance count as a tie, won by
// the lower object index, as in the CPU reference, so the choice does not
// depend on the order the BVH happens to visit them. The tolerance is sized
// to the arithmetic: float's, or in fp64 the CPU reference's (double).
#if VKRAY_PRECISION_FP64
const real TIE_TOLERANCE = 1e-9;
#else
const real TIE_TOLERANCE = 1e-6;
#endif

// How far a walk still looks for hits: up to the closest so far, and for a
// ray (not a feeler) the tie tolerance beyond it, as testObject accepts; so
// a box whose object would tie is not culled, and which object wins a tie
// does not depend on the order the BVH visits them.
real reach(real t, bool feeler) {
    return feeler ? t : t * (1.0 + TIE_TOLERANCE);
}

// Whether object `index`'s hit at t takes the place of `hit`: it is nearer,
// or it ties and has the lower index.
bool replaces(uint index, real t, Hit hit) {
    bool nearer = t < hit.t * (1.0 - TIE_TOLERANCE);
    bool tieWon = hit.object < 0 || int(index) < hit.object;
    return nearer || tieWon;
}

// Tests object `index`, of shape `kind`, for a scene walk (walkScene): a closer hit replaces
// `hit`; for a shadow feeler (VKRAY_SHADOWS), any hit before hit.t passes the
// surface's transparency into `through`. `meshes` and `booleans` as for
// intersectObject.
void testObject(uint index, uint kind, bool meshes, bool booleans, rvec3 origin, rvec3 direction,
                bool feeler, inout Hit hit, inout float through) {
    real t;
    rvec3 n, geometric;
    uint surface;
    real tMax = reach(hit.t, feeler);
    bool met = intersectObject(index, kind, meshes, booleans, origin, direction, tMax, t, n,
                               geometric, surface);
#if VKRAY_STRESS_OUTPUT
    stressNoteTest(index, feeler, met);
#endif
    if (!met) return;
#if VKRAY_SHADOWS
    if (feeler) {
        through *= uintBitsToFloat(objectShape(surface).w);
        return;
    }
#endif
    if (replaces(index, t, hit)) {
        hit.t = t;
        hit.object = int(index);
        hit.surface = surface;
        hit.genericNormal = n;
        hit.geometricNormal = geometric;
#if VKRAY_MESH_INSTANCES
        hit.triangle = NO_TRIANGLE;
#endif
    }
}

// CSG objects met by a walk wait in a list and are tested after the other
// objects (testPendingBooleans), not among them: on lavapipe every object
// test runs the code of every shape it may be, and CSG's evaluation costs
// many times a closed-form shape's. So a walk pays it once, not at every
// object. A full list is tested before the walk goes on.
#if VKRAY_CSG
const uint PENDING_BOOLEANS_MAX = 8u;
uint pendingBooleans[PENDING_BOOLEANS_MAX];
uint pendingBooleanCount;

void testPendingBooleans(rvec3 origin, rvec3 direction, bool feeler, inout Hit hit,
                         inout float through) {
    for (uint k = 0u; k < pendingBooleanCount && through > 0.0; ++k) {
        ++loopTurns;
        testObject(pendingBooleans[k], KIND_BOOLEAN, false, true, origin, direction, feeler, hit,
                   through);
    }
    pendingBooleanCount = 0u;
}
#endif

// Whether the walk can take one more CSG object (always, without CSG).
bool pendingBooleansHaveRoom() {
#if VKRAY_CSG
    return pendingBooleanCount < PENDING_BOOLEANS_MAX;
#else
    return true;
#endif
}

// Tests object `index` of a walk's loop, or puts it on the list of CSG
// objects to test after the others.
void testOrKeepObject(uint index, uint kind, bool meshes, rvec3 origin, rvec3 direction,
                      bool feeler, inout Hit hit, inout float through) {
#if VKRAY_CSG
    if (kind == KIND_BOOLEAN) {
        pendingBooleans[pendingBooleanCount++] = index;
        return;
    }
#endif
    testObject(index, kind, meshes, false, origin, direction, feeler, hit, through);
}

#if VKRAY_MESH_INSTANCES
// A mesh object that the scene walk has entered: the ray in its generic space
// as intersectMesh (mesh.glsl) takes it, measured from `start`, `shift` along
// it; its BVH's nodes follow the objects' from `nodes` on.
struct MeshVisit {
    bool inside;   // the walk is in the mesh's BVH
    bool leaving;  // a feeler has met the mesh: the rest of its BVH is skipped
    uint object;
    uint nodes, triangles;  // GpuMesh.range
    real shift;
    rvec3 start, invD;
    real localMin;
    ShearedRay sheared;
    real nearest;  // the local t of the mesh's hit so far
};

// Where a stack entry is a mesh object to enter (world entries start at 0 or
// later) and where it is the end of a mesh's entries (local ones are finite).
const real MESH_ENTRY_ENTER = -1.0;
const real MESH_END_ENTER = -1.0 / 0.0;

// Sets `visit` up for mesh object `object` and gives its root's code and
// local entry t: false where the ray misses the root's box within (T_MIN, far).
bool enterMesh(uint object, rvec3 origin, rvec3 direction, real far, out MeshVisit visit,
               out uint rootCode, out real rootEnter) {
    rvec3 o, d;
    toObjectSpace(object, origin, direction, o, d);
    GpuMesh mesh = meshOf(objectShape(object).y);
    visit.inside = true;
    visit.leaving = false;
    visit.object = object;
    visit.nodes = mesh.range.x;
    visit.triangles = mesh.range.y;
    visit.invD = 1.0 / d;
    GpuBvhNode root = objectNode(mesh.range.x);
    real enter;
    bool met = hitsBox(root.lo.xyz, root.hi.xyz, o, visit.invD, T_MIN, far, enter);
    visit.shift = meshWalkShift(root, d, enter);
    visit.start = fma(rvec3(visit.shift), d, o);
    visit.sheared = shearRay(visit.start, d);
    visit.localMin = T_MIN - visit.shift;
    visit.nearest = 1.0 / 0.0;
    rootCode = bvhNodeCode(root);
    rootEnter = enter - visit.shift;
    return met;
}

// Tests triangle `index` of the visited mesh, as intersectMesh and testObject
// would: the mesh's nearest triangle is its hit.
void testTriangle(uint index, bool feeler, inout MeshVisit visit, inout Hit hit,
                  inout float through) {
    real far = reach(hit.t, feeler);
    real local, t;
    rvec3 barycentric;
    if (!intersectTriangle(visit.sheared, triangleCorner(index, 0u), triangleCorner(index, 1u),
                           triangleCorner(index, 2u), visit.localMin,
                           meshLocalBound(far, visit.shift), local, barycentric))
        return;
    t = visit.shift + local;
    if (!(t > T_MIN && t < far)) return;
#if VKRAY_SHADOWS
    if (feeler) {
        through *= uintBitsToFloat(objectShape(visit.object).w);
        visit.leaving = true;
        return;
    }
#endif
    bool again = hit.object == int(visit.object);
    if (again ? local < visit.nearest : replaces(visit.object, t, hit)) {
        hit.t = t;
        hit.object = int(visit.object);
        hit.surface = visit.object;
        hit.triangle = index;
        hit.barycentric = barycentric;
        visit.nearest = local;
    }
}
#endif

// Every object the ray origin + t direction may meet in (0, tMax), each
// tested once: for a ray (feeler false, tMax infinite) `hit` ends as the
// closest hit; for a shadow feeler (tMax = the light's distance) `through`
// ends as the product of the transparencies of the objects met, the walk
// stopping at 0. Lavapipe inlines every function: the walk calls
// testObject once for every shape but CSG (compiled VKRAY_OBJECTS times when
// the loop is unrolled: closed-form shapes only, shader_variant.cpp) and
// once for CSG alone (testPendingBooleans).
void walkScene(rvec3 origin, rvec3 direction, real tMax, bool feeler, out Hit hit,
               out float through) {
    hit.t = tMax;
    hit.object = -1;
    hit.surface = 0u;
    hit.genericNormal = rvec3(0.0);
    hit.geometricNormal = rvec3(0.0);
#if VKRAY_MESH_INSTANCES
    hit.triangle = NO_TRIANGLE;
    hit.barycentric = rvec3(0.0);
#endif
    through = 1.0;
#if VKRAY_CSG
    pendingBooleanCount = 0u;
#endif
#if VKRAY_OBJECT_BVH
    // The unbounded objects (planes) first, as if a leaf, then the BVH's
    // leaves front to back: each turn of the inner loop tests the two
    // children of the node at hand and goes on to the nearer one the ray
    // enters, keeping the farther; a leaf ends the turn, its objects tested
    // by the outer loop. A feeler keeps hit.t = tMax: it visits every node
    // it crosses. With VKRAY_MESH_INSTANCES a leaf's meshes are kept on the
    // stack instead of tested; the outer loop enters one when it comes off,
    // putting an end mark and its root on the stack: the same loops then walk
    // its BVH, the leaves' triangles tested, until the mark comes off.
    uint leafFirst = frame.counts.z, leafCount = frame.counts.w;
    rvec3 invD = 1.0 / direction;
#if VKRAY_MESH_INSTANCES
    // The objects' path, a leaf's meshes, a mesh's end mark and its path.
    const uint STACK_SIZE = 2u * BVH_STACK_SIZE + BVH_LEAF_MAX + 1u;
    const bool MESHES_IN_TESTS = false;
    MeshVisit visit;
    visit.inside = false;
    visit.leaving = false;
    visit.shift = 0.0;
    uint meshToEnter = 0u;
    bool entering = false;
#else
    const uint STACK_SIZE = BVH_STACK_SIZE;
    const bool MESHES_IN_TESTS = true;
#endif
    uint stack[STACK_SIZE];  // nodes to visit (bvhNodeCode), with where the ray enters them
    real stackEnter[STACK_SIZE];
    uint top = 0u;
    real enter;
    GpuBvhNode root = objectNode(0u);
    if (hitsBox(root.lo.xyz, root.hi.xyz, origin, invD, 0.0, hit.t, enter)) {
        stack[0] = bvhNodeCode(root);
        stackEnter[0] = enter;
        top = 1u;
    }
#if VKRAY_CSG
    bool paused = true;  // by a full CSG list; the walk goes on after its test
    while (paused) {
        paused = false;
#endif
    while (through > 0.0) {
        loopTurns += leafCount;
        uint objects = leafCount;
#if VKRAY_MESH_INSTANCES
        if (visit.inside) objects = 0u;
#endif
        uint i = leafFirst;
        for (; i < leafFirst + objects && through > 0.0 && pendingBooleansHaveRoom(); ++i) {
            uint object = objectAt(i), kind = objectShape(object).x;
#if VKRAY_MESH_INSTANCES
            if (kind == KIND_MESH) {
                stack[top] = object;
                stackEnter[top++] = MESH_ENTRY_ENTER;
                continue;
            }
#endif
            testOrKeepObject(object, kind, MESHES_IN_TESTS, origin, direction, feeler, hit, through);
        }
#if VKRAY_CSG
        if (i < leafFirst + objects && through > 0.0) {
            // The CSG list is full: the rest of this leaf after its test.
            leafCount = leafFirst + objects - i;
            leafFirst = i;
            paused = true;
            break;
        }
#endif
#if VKRAY_MESH_INSTANCES
        uint triangles = visit.inside ? leafCount : 0u;
        for (uint i = visit.triangles + leafFirst;
             i < visit.triangles + leafFirst + triangles && !visit.leaving; ++i)
            testTriangle(i, feeler, visit, hit, through);
#endif
        leafCount = 0u;
        bool walking = false;  // `children` is the first of the two to test next
        uint children = 0u;
        while (true) {
            ++loopTurns;
            real far = reach(hit.t, feeler);
#if VKRAY_MESH_INSTANCES
            real localFar = meshLocalBound(far, visit.shift);
#endif
            if (!walking) {
                // The nearest kept node the ray still reaches before its hit.
                bool found = false;
                uint code = 0u;
                while (top > 0u && !found) {
                    --top;
                    code = stack[top];
#if VKRAY_MESH_INSTANCES
                    real at = stackEnter[top];
                    if (visit.inside && at == MESH_END_ENTER) {
                        visit.inside = false;
                        continue;
                    }
                    found = !(visit.inside && visit.leaving) &&
                            at <= (visit.inside ? localFar : far);
                    entering = !visit.inside && at == MESH_ENTRY_ENTER;
#else
                    found = stackEnter[top] <= far;
#endif
                }
                if (!found) break;
#if VKRAY_MESH_INSTANCES
                if (entering) {
                    meshToEnter = code;
                    break;
                }
#endif
                if ((code & 7u) != 0u) {
                    leafFirst = code >> 3u;
                    leafCount = code & 7u;
                    break;
                }
                children = code >> 3u;
            }
            uint nearCode, farCode;
            real farEnter;
#if VKRAY_MESH_INSTANCES
            children += visit.inside ? visit.nodes : 0u;
            int hits = orderChildren(objectNode(children), objectNode(children + 1u),
                                     visit.inside ? visit.start : origin,
                                     visit.inside ? visit.invD : invD,
                                     visit.inside ? visit.localMin : 0.0,
                                     visit.inside ? localFar : far, nearCode, farCode, farEnter);
#else
            int hits = orderChildren(objectNode(children), objectNode(children + 1u), origin, invD,
                                     0.0, far, nearCode, farCode, farEnter);
#endif
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
#if VKRAY_MESH_INSTANCES
        if (entering) {
            entering = false;
            uint rootCode;
            real rootEnter;
            if (enterMesh(meshToEnter, origin, direction, reach(hit.t, feeler), visit, rootCode,
                          rootEnter)) {
                stack[top] = 0u;
                stackEnter[top++] = MESH_END_ENTER;
                stack[top] = rootCode;
                stackEnter[top++] = rootEnter;
            } else {
                visit.inside = false;
            }
            continue;
        }
#endif
        if (leafCount == 0u) break;
    }
#if VKRAY_CSG
        testPendingBooleans(origin, direction, feeler, hit, through);
        paused = paused && through > 0.0;
    }
#endif
#if VKRAY_MESH_INSTANCES
    // The normals of the mesh's hit triangle, as intersectMesh gives them.
    if (hit.triangle != NO_TRIANGLE)
        triangleNormals(hit.triangle, hit.barycentric, hit.genericNormal, hit.geometricNormal);
#endif
#elif VKRAY_OBJECTS > 0
    // A few objects, as many as the host counted, each of the shape the host
    // named (VKRAY_OBJECT_KINDS): the loop unrolled, each test holds the code
    // of its object's shape alone, where a loop over a count read at run time
    // costs several object tests a ray and each test every shape's code
    // (BENCHMARKS.md). A feeler that is already stopped (through 0) stays
    // stopped.
#ifndef VKRAY_OBJECT_KINDS
#error "VKRAY_OBJECT_KINDS is not defined: an unrolled walk (VKRAY_OBJECTS > 0) needs each object's KIND_*"
#endif
    const uint kinds[VKRAY_OBJECTS] = uint[](VKRAY_OBJECT_KINDS);
    loopTurns += VKRAY_OBJECTS;
    [[unroll]] for (uint i = 0u; i < VKRAY_OBJECTS; ++i)
        testObject(i, kinds[i], true, false, origin, direction, feeler, hit, through);
#else
    loopTurns += frame.image.w;
    uint next = 0u;
#if VKRAY_CSG
    do {
#endif
        for (; next < frame.image.w && through > 0.0 && pendingBooleansHaveRoom(); ++next)
            testOrKeepObject(next, objectShape(next).x, true, origin, direction, feeler, hit,
                             through);
#if VKRAY_CSG
        testPendingBooleans(origin, direction, feeler, hit, through);
    } while (next < frame.image.w && through > 0.0);
#endif
#endif
    if (!feeler && hit.object < 0) hit.t = INFINITY;
}
