// Booleans by ray intervals (Hill ch. 14; see csg.h).
#include "reference/csg.h"

#include "reference/mesh_intersect.h"
#include "util/error.h"
#include "util/file_loc.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <string>

namespace vkray::reference {
namespace {

// A generic span end in world space.
SpanEnd worldEnd(const SceneObject& object, const GenericHit& end) {
    if (std::isinf(end.t)) return {end.t, glm::dvec3(0), glm::dvec3(0), nullptr};
    const glm::dvec3 normal = toWorldNormal(object, end.normal);
    const glm::dvec3 geometric =
        end.geometricNormal == glm::dvec3(0) ? normal : toWorldNormal(object, end.geometricNormal);
    return {end.t, normal, geometric, &object};
}

template <typename GenericSpans>
SpanList worldSpans(const SceneObject& object, const GenericSpans& spans) {
    SpanList list;
    list.reserve(spans.size());
    for (const GenericSpan& span : spans)
        list.push_back({worldEnd(object, span.enter), worldEnd(object, span.exit)});
    return list;
}

Error noInside(const Scene& scene, const SceneObject& operand, const SceneObject* boolean) {
    std::string message = std::string("'") + shapeKeyword(operand.type) + "' has no inside";
    if (boolean)
        message +=
            std::string(" and cannot be an operand of '") + shapeKeyword(boolean->type) + "'";
    if (operand.type == ShapeType::Mesh || operand.type == ShapeType::Extrude)
        message += " (" + meshOf(scene, operand).name + " is not a closed surface)";
    return Error(formatDiagnostic(operand.loc, nullptr, "error", message));
}

// Faces of two operands that coincide (a cube cut by a cube flush with it)
// are met at the same t up to rounding, leaving slivers of result a few ulps
// long, or gaps as small between spans: either would speckle the face. Ends
// this close, relative to t, are taken as one: the gap closes, the sliver goes.
// The two t differ by a few units of double's rounding (u = 2^-53) of t,
// each end found from its own operand's generic ray; 64 u leaves over ten
// times that, and keeps a real thin result: at 1e-9 of t, a union squashed
// to 3e-6 seen from 2.2e4 away (3e-10 of t) was removed as a sliver, and at
// 1e-12 the corner of a cube in a union squashed to 2e-7, 2.4e-13 of t,
// where the GPU rightly drew both.
constexpr double kCoincident = 64 * 0x1p-53;

bool coincident(double a, double b) {
    return std::isfinite(a) && std::isfinite(b) &&
           std::abs(a - b) <= kCoincident * std::max({1.0, std::abs(a), std::abs(b)});
}

SpanList withoutSlivers(const SpanList& spans) {
    SpanList merged;
    merged.reserve(spans.size());
    for (const Span& span : spans) {
        if (!merged.empty() && coincident(merged.back().exit.t, span.enter.t)) {
            merged.back().exit = span.exit;
        } else {
            merged.push_back(span);
        }
    }
    std::erase_if(merged, [](const Span& span) { return coincident(span.enter.t, span.exit.t); });
    return merged;
}

bool insideOf(ShapeType operation, bool inA, bool inB) {
    switch (operation) {
    case ShapeType::Union: return inA || inB;
    case ShapeType::Intersection: return inA && inB;
    default: return inA && !inB;  // Difference
    }
}

}  // namespace

bool hasInside(const Scene& scene, const SceneObject& object) {
    if (object.type == ShapeType::Square) return false;
    if (isMeshShape(object.type)) return meshOf(scene, object).closed;
    return true;
}

void requireCsgOperands(const Scene& scene, const SceneObject& object) {
    if (!isBoolean(object.type)) return;
    if (object.operands.size() != 2)
        throw Error(formatDiagnostic(
            object.loc, nullptr, "error",
            std::string("'") + shapeKeyword(object.type) + "' needs exactly two operands"));
    for (const SceneObject& operand : object.operands) {
        if (!hasInside(scene, operand)) throw noInside(scene, operand, &object);
        requireCsgOperands(scene, operand);
    }
}

SpanList objectSpans(const Scene& scene, const SceneObject& object, const Ray& worldRay) {
    if (isBoolean(object.type)) {
        requireCsgOperands(scene, object);
        return combineSpans(object.type, objectSpans(scene, object.operands[0], worldRay),
                            objectSpans(scene, object.operands[1], worldRay));
    }
    if (!hasInside(scene, object)) throw noInside(scene, object, nullptr);
    const Ray ray = toObjectSpace(object, worldRay);
    switch (object.type) {
    case ShapeType::Sphere: return worldSpans(object, sphereSpans(ray));
    case ShapeType::Plane: return worldSpans(object, planeSpans(ray));
    case ShapeType::Cube: return worldSpans(object, cubeSpans(ray));
    case ShapeType::Cylinder:
    case ShapeType::Cone:
    case ShapeType::TaperedCylinder:
        return worldSpans(object, taperedCylinderSpans(ray, taperOf(object)));
    case ShapeType::Torus: return worldSpans(object, torusSpans(ray));
    default: return worldSpans(object, meshSpans(meshOf(scene, object), ray));
    }
}

// A sweep over every span end of both lists in t order. Ends at the same t
// are taken together, so that touching spans merge and a span of length 0
// (a tangent) changes nothing; after each group, each operand is inside when
// a span of positive length starts there, outside when one ends there, and
// as before otherwise. Where the result's inside changes, the end of the
// operand that changed (a's first) becomes a boundary of the result.
SpanList combineSpans(ShapeType operation, const SpanList& a, const SpanList& b) {
    struct Event {
        double t;
        int operand;  // 0: a, 1: b
        bool enter;   // an enter end of a span of positive length
        const SpanEnd* end;
    };
    std::vector<Event> events;
    events.reserve(2 * (a.size() + b.size()));
    const SpanList* lists[2] = {&a, &b};
    for (int operand = 0; operand < 2; ++operand) {
        for (const Span& span : *lists[operand]) {
            if (span.enter.t < span.exit.t)
                events.push_back({span.enter.t, operand, true, &span.enter});
            events.push_back({span.exit.t, operand, false, &span.exit});
        }
    }
    std::stable_sort(events.begin(), events.end(),
                     [](const Event& x, const Event& y) { return x.t < y.t; });

    SpanList result;
    SpanEnd open{};
    bool in[2] = {false, false};
    for (std::size_t i = 0; i < events.size();) {
        std::size_t j = i;
        bool after[2] = {in[0], in[1]};
        const SpanEnd* entered[2] = {nullptr, nullptr};
        const SpanEnd* left[2] = {nullptr, nullptr};
        for (; j < events.size() && events[j].t == events[i].t; ++j)
            (events[j].enter ? entered : left)[events[j].operand] = events[j].end;
        for (int k = 0; k < 2; ++k) after[k] = entered[k] ? true : (left[k] ? false : in[k]);

        const bool before = insideOf(operation, in[0], in[1]);
        const bool now = insideOf(operation, after[0], after[1]);
        if (before != now) {
            const int k = after[0] != in[0] ? 0 : 1;
            SpanEnd boundary = *(after[k] ? entered[k] : left[k]);
            if (operation == ShapeType::Difference && k == 1) {
                boundary.normal = -boundary.normal;
                boundary.geometricNormal = -boundary.geometricNormal;
            }
            if (now) {
                open = boundary;
            } else {
                result.push_back({open, boundary});
            }
        }
        in[0] = after[0];
        in[1] = after[1];
        i = j;
    }
    return withoutSlivers(result);
}

std::optional<WorldHit> intersectBoolean(const Scene& scene, const SceneObject& object, int index,
                                         const Ray& worldRay, double tMin) {
    const SpanList spans = objectSpans(scene, object, worldRay);
    for (const Span& span : spans) {
        for (const SpanEnd* end : {&span.enter, &span.exit}) {
            if (!(end->t > tMin)) continue;
            if (std::isinf(end->t)) return std::nullopt;  // nothing lies beyond +inf
            return facingHit(worldRay, end->t, end->normal, end->geometricNormal, index,
                             end->surface);
        }
    }
    return std::nullopt;
}

int csgMaxSpans(const Scene& scene, const SceneObject& object) {
    switch (object.type) {
    case ShapeType::Square: return 0;
    case ShapeType::TaperedCylinder: return object.taper >= 0 ? 1 : 2;
    case ShapeType::Torus: return 2;
    case ShapeType::Union:
    case ShapeType::Intersection:
    case ShapeType::Difference: {
        requireCsgOperands(scene, object);
        const std::int64_t sum = std::int64_t(csgMaxSpans(scene, object.operands[0])) +
                                 csgMaxSpans(scene, object.operands[1]);
        const std::int64_t bound = object.type == ShapeType::Intersection ? sum - 1 : sum;
        return int(std::min<std::int64_t>(bound, INT_MAX));
    }
    default: break;
    }
    if (isMeshShape(object.type)) {
        const TriangleMesh& mesh = meshOf(scene, object);
        if (!mesh.closed) return 0;
        return int(std::clamp<std::size_t>(mesh.triangles.size() / 2, 1, INT_MAX));
    }
    return 1;  // sphere, cube, plane, cylinder, cone
}

}  // namespace vkray::reference
