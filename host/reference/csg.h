// Constructive solid geometry by ray intervals (Hill ch. 14): along a ray,
// every solid is the list of spans where the ray is inside it, and union,
// intersection and difference are the boolean operations on those lists.
// Each operand is a whole SceneObject with its own world transform (and may
// itself be a boolean), so the lists are in world t with world normals.
#pragma once

#include "reference/object_intersect.h"
#include "scene/scene.h"

#include <glm/vec3.hpp>

#include <optional>
#include <vector>

namespace vkray::reference {

// One end of a span: where the ray crosses the solid's surface.
struct SpanEnd {
    double t;                    // +-inf: the span is unbounded there (a half-space)
    glm::dvec3 normal;           // world, outward from the solid, not normalised
    glm::dvec3 geometricNormal;  // meshes: the triangle's own; otherwise = normal
    const SceneObject* surface;  // the primitive the end lies on (null at +-inf)
};

// The ray is inside the solid for enter.t <= t <= exit.t. A list is sorted,
// and its spans neither overlap nor touch.
struct Span {
    SpanEnd enter, exit;
};
using SpanList = std::vector<Span>;

// Whether the object bounds a solid: everything but the square and meshes
// that are not closed surfaces (the teapot, most 3VN files).
bool hasInside(const Scene& scene, const SceneObject& object);

// Refuses a boolean (and every boolean inside it) with an operand that has no
// inside: Error "file:line:col: error: 'square' has no inside and cannot be
// an operand of 'union'" at the operand's place. A mesh operand must also
// have its geometry loaded.
void requireCsgOperands(const Scene& scene, const SceneObject& object);

// The spans of any solid along the world ray (over all t). A plane is the
// half-space z <= 0 of its generic space. Throws as requireCsgOperands for
// objects without an inside.
SpanList objectSpans(const Scene& scene, const SceneObject& object, const Ray& worldRay);

// a (op) b for op = Union, Intersection or Difference (a minus b). Ends keep
// their operand's surface and normal; the ends that come from b in a
// difference have their normal negated (b's outside is the result's inside).
// Ends within 64 u max(1, |t|) of each other (u = 2^-53) count as one
// (coinciding faces of the operands): such gaps close and such slivers are
// dropped.
SpanList combineSpans(ShapeType operation, const SpanList& a, const SpanList& b);

// The boolean's nearest hit with t > tMin: the first finite span end after tMin.
std::optional<WorldHit> intersectBoolean(const Scene& scene, const SceneObject& object, int index,
                                         const Ray& worldRay, double tMin);

// The most spans any ray can produce for this object, so that a renderer with
// fixed interval storage (the GPU) can refuse a scene that needs more. Rules:
//   sphere, cube, plane (a half-space), cylinder, cone: 1;
//   taperedCylinder: 1 for s >= 0 (convex), 2 for s < 0 (an hourglass);
//   torus: 2 (a line meets it at most 4 times);
//   closed mesh of T triangles: max(1, floor(T / 2)) (a line crosses each
//     triangle at most once; the mesh's own bound, far above what real rays
//     see, so a renderer may prefer its own cap);
//   square, open mesh: 0 (no inside; not allowed as an operand);
//   union: a + b; difference: a + b (a minus b is a and the complement of
//     b, which has at most b + 1 spans); intersection: a + b - 1 (each result
//     span ends where a span of a or of b ends, and the last spans of a and
//     of b cannot both end one).
// A result never needs more than this bound and its operands need no more
// than theirs, each at most the parent's: so the value for the top object
// bounds every list met while evaluating it. Throws as requireCsgOperands.
int csgMaxSpans(const Scene& scene, const SceneObject& object);

}  // namespace vkray::reference
