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

// Tests object `index`, of shape `kind`, for a scene walk (walkScene): a closer hit replaces
// `hit`; for a shadow feeler (VKRAY_SHADOWS), any hit before hit.t passes the
// surface's transparency into `through`.
void testObject(uint index, uint kind, rvec3 origin, rvec3 direction, bool feeler, inout Hit hit,
                inout float through) {
    real t;
    rvec3 n, geometric;
    uint surface;
    real tMax = reach(hit.t, feeler);
    bool met = intersectObject(index, kind, origin, direction, tMax, t, n, geometric, surface);
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
    bool nearer = t < hit.t * (1.0 - TIE_TOLERANCE);
    bool tieWon = hit.object < 0 || int(index) < hit.object;
    if (nearer || tieWon) {
        hit.t = t;
        hit.object = int(index);
        hit.surface = surface;
        hit.genericNormal = n;
        hit.geometricNormal = geometric;
    }
}

// Every object the ray origin + t direction may meet in (0, tMax), each
// tested once: for a ray (feeler false, tMax infinite) `hit` ends as the
// closest hit; for a shadow feeler (tMax = the light's distance) `through`
// ends as the product of the transparencies of the objects met, the walk
// stopping at 0. This is the shader's only call of testObject: lavapipe
// inlines every function, so one call site keeps the shapes' code (CSG
// above all) compiled once, or VKRAY_OBJECTS times when the loop is unrolled
// (closed-form shapes only, shader_variant.cpp).
void walkScene(rvec3 origin, rvec3 direction, real tMax, bool feeler, out Hit hit,
               out float through) {
    hit.t = tMax;
    hit.object = -1;
    hit.surface = 0u;
    hit.genericNormal = rvec3(0.0);
    hit.geometricNormal = rvec3(0.0);
    through = 1.0;
#if VKRAY_OBJECT_BVH
    // The unbounded objects (planes) first, as if a leaf, then the BVH's
    // leaves front to back: each turn of the inner loop tests the two
    // children of the node at hand and goes on to the nearer one the ray
    // enters, keeping the farther; a leaf ends the turn, its objects tested
    // by the outer loop. A feeler keeps hit.t = tMax: it visits every node
    // it crosses.
    uint leafFirst = frame.counts.z, leafCount = frame.counts.w;
    rvec3 invD = 1.0 / direction;
    uint stack[BVH_STACK_SIZE];  // nodes to visit (bvhNodeCode), with where the ray enters them
    real stackEnter[BVH_STACK_SIZE];
    uint top = 0u;
    real enter;
    GpuBvhNode root = objectNode(0u);
    if (hitsBox(root.lo.xyz, root.hi.xyz, origin, invD, 0.0, hit.t, enter)) {
        stack[0] = bvhNodeCode(root);
        stackEnter[0] = enter;
        top = 1u;
    }
    while (through > 0.0) {
        loopTurns += leafCount;
        for (uint i = leafFirst; i < leafFirst + leafCount && through > 0.0; ++i)
            testObject(objectAt(i), objectShape(objectAt(i)).x, origin, direction, feeler, hit,
                       through);
        leafCount = 0u;
        bool walking = false;  // `children` is the first of the two to test next
        uint children = 0u;
        while (true) {
            ++loopTurns;
            if (!walking) {
                // The nearest kept node the ray still reaches before its hit.
                bool found = false;
                uint code = 0u;
                while (top > 0u && !found) {
                    --top;
                    found = stackEnter[top] <= reach(hit.t, feeler);
                    code = stack[top];
                }
                if (!found) break;
                if ((code & 7u) != 0u) {
                    leafFirst = code >> 3u;
                    leafCount = code & 7u;
                    break;
                }
                children = code >> 3u;
            }
            uint nearCode, farCode;
            real farEnter;
            int hits = orderChildren(objectNode(children), objectNode(children + 1u), origin, invD,
                                     0.0, reach(hit.t, feeler), nearCode, farCode, farEnter);
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
        testObject(i, kinds[i], origin, direction, feeler, hit, through);
#else
    loopTurns += frame.image.w;
    for (uint i = 0u; i < frame.image.w && through > 0.0; ++i)
        testObject(i, objectShape(i).x, origin, direction, feeler, hit, through);
#endif
    if (!feeler && hit.object < 0) hit.t = INFINITY;
}
