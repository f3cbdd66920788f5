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
// surface's transparency into `through`. `shapes` as for intersectObject.
void testObject(uint index, uint kind, uint shapes, rvec3 origin, rvec3 direction, bool feeler,
                inout Hit hit, inout float through) {
    real t;
    rvec3 n, geometric;
    uint surface;
    real tMax = reach(hit.t, feeler);
    bool met = intersectObject(index, kind, shapes, origin, direction, tMax, t, n, geometric,
                               surface);
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
#if VKRAY_WALK_TRIANGLES
        hit.triangle = NO_TRIANGLE;
#endif
    }
}

// The objects of costly shapes (CSG, the torus) that a walk meets wait in a
// list and are tested after the others (testKeptObjects), not among them:
// on lavapipe every object test runs the code of every shape it may be, and
// CSG's evaluation or the torus's quartic costs many times a closed-form
// shape's test. So a walk pays that code once, not at every object. A full
// list is tested before the walk goes on. Tori are kept only where other
// shapes' tests gain from it (VKRAY_KEEP_TORI, host/gpu/shader_variant.cpp):
// a scene of tori alone would pay the list for nothing (0.87x).
// The ray-query walk has no loop of object tests to keep them out of.
#define VKRAY_KEPT_OBJECTS ((VKRAY_CSG || VKRAY_KEEP_TORI) && !VKRAY_RAY_QUERY)
#if VKRAY_KEPT_OBJECTS
#if VKRAY_KEEP_TORI
const uint KEPT_SHAPES = (1u << KIND_BOOLEAN) | (1u << KIND_TORUS);
#else
const uint KEPT_SHAPES = 1u << KIND_BOOLEAN;
#endif
const uint KEPT_OBJECTS_MAX = 8u;
uint keptObjects[KEPT_OBJECTS_MAX];
uint keptObjectCount;

void testKeptObjects(rvec3 origin, rvec3 direction, bool feeler, inout Hit hit, inout float through) {
    for (uint k = 0u; k < keptObjectCount && through > 0.0; ++k) {
        ++loopTurns;
        uint object = keptObjects[k];
        testObject(object, objectShape(object).x, KEPT_SHAPES, origin, direction, feeler, hit,
                   through);
    }
    keptObjectCount = 0u;
}
#else
const uint KEPT_SHAPES = 0u;
#endif

// Whether the walk can keep one more object (always, with nothing to keep).
bool keptObjectsHaveRoom() {
#if VKRAY_KEPT_OBJECTS
    return keptObjectCount < KEPT_OBJECTS_MAX;
#else
    return true;
#endif
}

// Tests object `index` of a walk's loop, one of `shapes`, or keeps it for
// later (KEPT_SHAPES).
void testOrKeepObject(uint index, uint kind, uint shapes, rvec3 origin, rvec3 direction,
                      bool feeler, inout Hit hit, inout float through) {
#if VKRAY_KEPT_OBJECTS
    if (among(KEPT_SHAPES, kind)) {
        keptObjects[keptObjectCount++] = index;
        return;
    }
#endif
    testObject(index, kind, shapes & ~KEPT_SHAPES, origin, direction, feeler, hit, through);
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

#if VKRAY_WORLD_TRIANGLES
// Tests world triangle `index` (layout.h) for a scene walk, `sheared` the
// walk's ray, as testTriangle a mesh's: an object's nearest triangle is its
// hit, which replaces another object's as testObject's would. The host
// places only opaque meshes' triangles in world space, so a feeler that
// meets one is stopped.
void testWorldTriangle(uint index, ShearedRay sheared, bool feeler, inout Hit hit,
                       inout float through) {
    int first = int(index * TRIANGLE_TEXELS);
    vec4 p0 = texelAsVec4(imageLoad(triangleTexels, first));
    vec4 p1 = texelAsVec4(imageLoad(triangleTexels, first + 1));
    vec4 p2 = texelAsVec4(imageLoad(triangleTexels, first + 2));
    real t;
    rvec3 barycentric;
    if (!intersectTriangle(sheared, rvec3(p0.xyz), rvec3(p1.xyz), rvec3(p2.xyz), T_MIN,
                           reach(hit.t, feeler), t, barycentric))
        return;
#if VKRAY_SHADOWS
    if (feeler) {
        through = 0.0;
        return;
    }
#endif
    uint object = floatBitsToUint(p0.w);
    bool again = hit.object == int(object);
    if (again ? t < hit.t : replaces(object, t, hit)) {
        hit.t = t;
        hit.object = int(object);
        hit.surface = object;
        hit.triangle = floatBitsToUint(p1.w);
        hit.barycentric = barycentric;
    }
}
#endif

#if VKRAY_RAY_QUERY
layout(set = 0, binding = BINDING_SCENE_STRUCTURE) uniform accelerationStructureEXT sceneStructure;

// Where the driver's walk stops looking, for a walk whose hits reach `far`:
// a little farther (float, with room for the float ray the driver takes in
// place of the shader's, in double for fp64), so that it leaves out no box
// the shader's own test would take.
float structureReach(real far) {
    return min(float(far) * (1.0 + 1.0 / 65536.0), 3.0e38);
}

// walkScene's walk through the driver's acceleration structure (host:
// gpu/scene_structure.h): the unbounded objects first, then every box the
// driver's walk reports, its object tested by testObject; a ray's closer hit
// is handed to the driver, which leaves out the boxes beyond it (with the
// tie tolerance: reach). A stopped feeler ends the walk.
void walkStructure(rvec3 origin, rvec3 direction, bool feeler, inout Hit hit, inout float through) {
    uint unbounded = frame.counts.z;
    for (uint i = unbounded; i < unbounded + frame.counts.w && through > 0.0; ++i) {
        ++loopTurns;
        uint object = objectAt(i);
        testObject(object, objectShape(object).x, ALL_SHAPES, origin, direction, feeler, hit,
                   through);
    }
    if (!(through > 0.0)) return;
    float far = structureReach(reach(hit.t, feeler));
    rayQueryEXT query;
    rayQueryInitializeEXT(query, sceneStructure, gl_RayFlagsNoneEXT, 0xFFu, vec3(origin), 0.0,
                          vec3(direction), far);
    while (rayQueryProceedEXT(query)) {
        ++loopTurns;
        uint object = objectAt(uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, false)));
        testObject(object, objectShape(object).x, ALL_SHAPES, origin, direction, feeler, hit,
                   through);
        if (!(through > 0.0)) {
            rayQueryTerminateEXT(query);
        } else if (!feeler) {
            float nearer = structureReach(reach(hit.t, false));
            if (nearer < far) {
                far = nearer;
                rayQueryGenerateIntersectionEXT(query, far);
            }
        }
    }
}
#endif

// Every object the ray origin + t direction may meet in (0, tMax), each
// tested once: for a ray (feeler false, tMax infinite) `hit` ends as the
// closest hit; for a shadow feeler (tMax = the light's distance) `through`
// ends as the product of the transparencies of the objects met, the walk
// stopping at 0. A feeler's `hint` (VKRAY_FEELER_HINTS) is an entry of the
// object BVH's order to test first (NO_ENTRY: none); hit.entry ends as the
// entry that stopped it. Lavapipe inlines every function: the walk calls
// testObject once for the shapes it does not keep (compiled VKRAY_OBJECTS
// times when the loop is unrolled, each with one shape's code:
// shader_variant.cpp) and once for those it keeps (testKeptObjects).
void walkScene(rvec3 origin, rvec3 direction, real tMax, bool feeler, uint hint, out Hit hit,
               out float through) {
    hit.t = tMax;
    hit.object = -1;
    hit.surface = 0u;
    hit.genericNormal = rvec3(0.0);
    hit.geometricNormal = rvec3(0.0);
#if VKRAY_WALK_TRIANGLES
    hit.triangle = NO_TRIANGLE;
    hit.barycentric = rvec3(0.0);
#endif
#if VKRAY_FEELER_HINTS
    hit.entry = NO_ENTRY;
#endif
    through = 1.0;
#if VKRAY_KEPT_OBJECTS
    keptObjectCount = 0u;
#endif
#if VKRAY_RAY_QUERY
    walkStructure(origin, direction, feeler, hit, through);
#elif VKRAY_OBJECT_BVH
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
#if VKRAY_FEELER_HINTS
    // A feeler's first turn tests its hint's entry, where it would otherwise
    // test nothing (and run the leaf's loop all the same): the host asks for
    // hints only in scenes without unbounded objects, whose tests take that
    // turn. Testing an opaque object twice does not change whether a feeler
    // gets through; a transparent one is passed over, lest its transparency
    // count twice, and so is one whose shape waits on the list of kept
    // objects. So the hint, from another invocation, may be anything: only
    // an entry of the BVH is taken.
    bool hinting = feeler && hint < frame.counts.z;
    if (hinting) {
        leafFirst = hint;
        leafCount = 1u;
    }
#endif
    rvec3 invD = 1.0 / direction;
#if VKRAY_MESH_INSTANCES
    // The objects' path, a leaf's meshes, a mesh's end mark and its path.
    const uint STACK_SIZE = 2u * BVH_STACK_SIZE + BVH_LEAF_MAX + 1u;
    const uint WALK_SHAPES = ALL_SHAPES & ~(1u << KIND_MESH);  // meshes are entered
    MeshVisit visit;
    visit.inside = false;
    visit.leaving = false;
    visit.shift = 0.0;
    uint meshToEnter = 0u;
    bool entering = false;
#else
    const uint STACK_SIZE = BVH_STACK_SIZE;
#if VKRAY_WORLD_TRIANGLES
    // Leaves whose entries start past the object index's (the bounded
    // objects', then the unbounded ones) hold triangles in world space
    // (host: packScene); no mesh object is left among the objects.
    const uint WALK_SHAPES = ALL_SHAPES & ~(1u << KIND_MESH);
    uint triangleFirst = frame.counts.z + frame.counts.w;
    ShearedRay sheared = shearRay(origin, direction);
#else
    const uint WALK_SHAPES = ALL_SHAPES;
#endif
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
#if VKRAY_KEPT_OBJECTS
    bool paused = true;  // by a full list of kept objects; the walk goes on after their tests
    while (paused) {
        paused = false;
#endif
    while (through > 0.0) {
        loopTurns += 1u + leafCount;
        uint objects = leafCount;
#if VKRAY_MESH_INSTANCES
        if (visit.inside) objects = 0u;
#elif VKRAY_WORLD_TRIANGLES
        if (leafFirst >= triangleFirst) objects = 0u;
#endif
        uint i = leafFirst;
        for (; i < leafFirst + objects && through > 0.0 && keptObjectsHaveRoom(); ++i) {
            uint object = objectAt(i), kind = objectShape(object).x;
#if VKRAY_FEELER_HINTS
            if (hinting && (objectShape(object).w != 0u || among(KEPT_SHAPES, kind))) continue;
#endif
#if VKRAY_MESH_INSTANCES
            if (kind == KIND_MESH) {
                stack[top] = object;
                stackEnter[top++] = MESH_ENTRY_ENTER;
                continue;
            }
#endif
            testOrKeepObject(object, kind, WALK_SHAPES, origin, direction, feeler, hit, through);
#if VKRAY_FEELER_HINTS
            if (through == 0.0) hit.entry = i;
#endif
        }
#if VKRAY_FEELER_HINTS
        hinting = false;
#endif
#if VKRAY_KEPT_OBJECTS
        if (i < leafFirst + objects && through > 0.0) {
            // The list of kept objects is full: the rest of this leaf after their tests.
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
#elif VKRAY_WORLD_TRIANGLES
        uint triangles = leafCount - objects;
        for (uint i = leafFirst - triangleFirst; i < leafFirst - triangleFirst + triangles &&
                                                 through > 0.0; ++i)
            testWorldTriangle(i, sheared, feeler, hit, through);
#endif
        leafCount = 0u;
        if (!(through > 0.0)) top = 0u;  // a stopped feeler looks for no next leaf
#if VKRAY_MESH_INSTANCES
        bool walking = false;  // `children` is the first of the two to test next
        uint children = 0u;
        while (true) {
            ++loopTurns;
            real far = reach(hit.t, feeler);
            real localFar = meshLocalBound(far, visit.shift);
            if (!walking) {
                // The nearest kept node the ray still reaches before its hit.
                bool found = false;
                uint code = 0u;
                while (top > 0u && !found) {
                    --top;
                    code = stack[top];
                    real at = stackEnter[top];
                    if (visit.inside && at == MESH_END_ENTER) {
                        visit.inside = false;
                        continue;
                    }
                    found = !(visit.inside && visit.leaving) &&
                            at <= (visit.inside ? localFar : far);
                    entering = !visit.inside && at == MESH_ENTRY_ENTER;
                }
                if (!found) break;
                if (entering) {
                    meshToEnter = code;
                    break;
                }
                if ((code & 7u) != 0u) {
                    leafFirst = code >> 3u;
                    leafCount = code & 7u;
                    break;
                }
                children = code >> 3u;
            }
            uint nearCode, farCode;
            real farEnter;
            children += visit.inside ? visit.nodes : 0u;
            int hits = orderChildren(objectNode(children), objectNode(children + 1u),
                                     visit.inside ? visit.start : origin,
                                     visit.inside ? visit.invD : invD,
                                     visit.inside ? visit.localMin : 0.0,
                                     visit.inside ? localFar : far, nearCode, farCode, farEnter);
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
        if (leafCount == 0u) break;
#else
        // The next leaf without the pop inside the steps down: the nearest
        // kept node the ray still reaches comes off the stack, then each
        // turn of the inner loop tests the two children of the node at hand
        // and goes on to the nearer one the ray enters, keeping the farther,
        // down to a leaf. llvmpipe would run a pop's loop on every step down,
        // whatever the lanes need (100 000 and 10 000 spheres 1.15x). A node
        // whose children the ray misses ends the turn, whose successor
        // tests no leaf and pops: cheap for these walks' leaves, not for a
        // walk that enters meshes (castle.dat 0.97x), which keeps the loop
        // above.
        real far = reach(hit.t, feeler);
        bool found = false;
        uint code = 0u;
        while (top > 0u && !found) {
            --top;
            code = stack[top];
            found = stackEnter[top] <= far;
        }
        if (!found) break;
        if ((code & 7u) != 0u) {
            leafFirst = code >> 3u;
            leafCount = code & 7u;
            continue;
        }
        uint children = code >> 3u;
        while (true) {
            ++loopTurns;
            uint nearCode, farCode;
            real farEnter;
            int hits = orderChildren(objectNode(children), objectNode(children + 1u), origin, invD,
                                     0.0, far, nearCode, farCode, farEnter);
            if (hits == 2) {
                stack[top] = farCode;
                stackEnter[top++] = farEnter;
            }
            if (hits == 0) break;
            children = nearCode >> 3u;
            if ((nearCode & 7u) != 0u) {
                leafFirst = children;
                leafCount = nearCode & 7u;
                break;
            }
        }
#endif
    }
#if VKRAY_KEPT_OBJECTS
        testKeptObjects(origin, direction, feeler, hit, through);
        paused = paused && through > 0.0;
    }
#endif
#if VKRAY_WALK_TRIANGLES
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
    // Kept objects (tori, CSG) only go on their list: their code, once, after.
    [[unroll]] for (uint i = 0u; i < VKRAY_OBJECTS; ++i)
        testOrKeepObject(i, kinds[i], ALL_SHAPES, origin, direction, feeler, hit, through);
#if VKRAY_KEPT_OBJECTS
#if VKRAY_OBJECTS > 8
#error "an unrolled walk of more than 8 objects could overflow the list of kept objects"
#endif
    testKeptObjects(origin, direction, feeler, hit, through);
#endif
#else
    loopTurns += frame.image.w;
    uint next = 0u;
#if VKRAY_KEPT_OBJECTS
    do {
#endif
        for (; next < frame.image.w && through > 0.0 && keptObjectsHaveRoom(); ++next)
            testOrKeepObject(next, objectShape(next).x, ALL_SHAPES, origin, direction, feeler, hit,
                             through);
#if VKRAY_KEPT_OBJECTS
        testKeptObjects(origin, direction, feeler, hit, through);
    } while (next < frame.image.w && through > 0.0);
#endif
#endif
    if (!feeler && hit.object < 0) hit.t = INFINITY;
}
