// Generic shapes of the CPU reference, derived from each implicit equation
// F(S + c t) = 0 with S the ray origin and c its direction, both in the
// shape's own generic space (Hill ch. 14). Everything is double; the roots
// are taken in forms that avoid cancellation (see docs/numerics-background.md, "Sphere"
// and "Hand-worked rays"), because this is the renderer the GPU is judged against. The
// tapered cylinder and the torus have files of their own.
#include "reference/shapes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vkray::reference {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

std::optional<GenericHit> firstBoundary(const SpanPair& spans, double tMin) {
    for (const GenericSpan& span : spans) {
        // An end at +-inf is no surface: never a hit.
        if (span.enter.t > tMin && !std::isinf(span.enter.t)) return span.enter;
        if (span.exit.t > tMin)
            return std::isinf(span.exit.t) ? std::nullopt : std::optional(span.exit);
    }
    return std::nullopt;
}

// Unit sphere |P|^2 = 1. Substituting P = S + c t gives
//     A t^2 + 2 B t + C = 0,  A = c.c,  B = S.c,  C = S.S - 1,
// with discriminant B^2 - A C. Written that way it subtracts two numbers of
// size |S|^2 |c|^2 and is noise once |S| ~ 1e8; the same quantity equals
//     A (1 - |S_perp|^2),  S_perp = S - (B / A) c,
// the point of the line nearest the centre, whose error grows only like |S|
// (Ray Tracing Gems ch. 7).
SpanPair sphereSpans(const Ray& ray) {
    SpanPair spans;
    const glm::dvec3& S = ray.origin;
    const glm::dvec3& c = ray.direction;
    const double A = glm::dot(c, c);
    if (!(A > 0)) return spans;  // a zero direction is not a ray
    const double B = glm::dot(S, c);
    const double C = glm::dot(S, S) - 1;
    const glm::dvec3 sPerp = S - (B / A) * c;
    const double disc = A * (1 - glm::dot(sPerp, sPerp));
    if (disc < 0) return spans;  // disc == 0 is a tangent ray: a span of length 0

    // The roots are (-B -+ sqrt(disc)) / A. One of them subtracts nearly equal
    // numbers; take q with the sign of B so that -(B + sign(B) sqrt(disc)) adds,
    // then t1 = q / A and t2 = C / q (the product of the roots is C / A).
    const double q = -(B + std::copysign(std::sqrt(disc), B));
    double t1 = q / A;
    double t2 = q != 0 ? C / q : t1;  // q == 0 only for B == disc == 0: a double root at 0
    if (t1 > t2) std::swap(t1, t2);
    spans.push({{t1, S + t1 * c}, {t2, S + t2 * c}});  // the gradient of |P|^2 is 2P
    return spans;
}

std::optional<GenericHit> intersectSphere(const Ray& ray, double tMin) {
    return firstBoundary(sphereSpans(ray), tMin);
}

// Plane z = 0: S.z + c.z t = 0.
std::optional<GenericHit> intersectPlane(const Ray& ray, double tMin) {
    // A ray parallel to the plane never crosses it; one lying in it is seen
    // edge-on, which we count as a miss too.
    if (ray.direction.z == 0) return std::nullopt;
    const double t = -ray.origin.z / ray.direction.z;
    if (!(t > tMin)) return std::nullopt;
    return GenericHit{t, {0, 0, 1}};
}

// The half-space z <= 0: the ray is below the plane before (c.z > 0) or
// after (c.z < 0) its crossing, always or never when parallel to it.
SpanPair planeSpans(const Ray& ray) {
    SpanPair spans;
    const GenericHit below{-kInf, glm::dvec3(0)}, above{kInf, glm::dvec3(0)};
    const double dz = ray.direction.z;
    if (dz == 0) {
        if (ray.origin.z <= 0) spans.push({below, above});
        return spans;
    }
    const GenericHit crossing{-ray.origin.z / dz, {0, 0, 1}};
    spans.push(dz > 0 ? GenericSpan{below, crossing} : GenericSpan{crossing, above});
    return spans;
}

// The part of z = 0 with |x| <= 1 and |y| <= 1; the edges belong to it.
std::optional<GenericHit> intersectSquare(const Ray& ray, double tMin) {
    const std::optional<GenericHit> hit = intersectPlane(ray, tMin);
    if (!hit) return std::nullopt;
    const double x = ray.origin.x + hit->t * ray.direction.x;
    const double y = ray.origin.y + hit->t * ray.direction.y;
    if (!(std::abs(x) <= 1 && std::abs(y) <= 1)) return std::nullopt;
    return hit;
}

// Cube [-1, 1]^3 as the intersection of three slabs -1 <= P_i <= 1. Along
// axis i the ray is inside its slab for t between (-1 - S_i) / c_i and
// (1 - S_i) / c_i; the ray is inside the cube on the overlap of the three
// intervals, [tEnter, tExit]. An axis with c_i == 0 is handled apart: the
// ray is then inside that slab for every t or for none, and the division
// would give inf and, on a face plane (S_i = +-1), 0 / 0 = NaN.
SpanPair cubeSpans(const Ray& ray) {
    SpanPair spans;
    const glm::dvec3& S = ray.origin;
    const glm::dvec3& c = ray.direction;
    double tEnter = -kInf, tExit = kInf;
    int enterAxis = -1, exitAxis = -1;
    for (int i = 0; i < 3; ++i) {
        if (c[i] == 0) {
            if (std::abs(S[i]) > 1) return spans;  // parallel to the slab and outside it
            continue;
        }
        double tNear = (-1 - S[i]) / c[i];
        double tFar = (1 - S[i]) / c[i];
        if (tNear > tFar) std::swap(tNear, tFar);
        if (tNear > tEnter) {
            tEnter = tNear;
            enterAxis = i;
        }
        if (tFar < tExit) {
            tExit = tFar;
            exitAxis = i;
        }
    }
    if (enterAxis < 0 || tEnter > tExit) return spans;  // zero direction, or a miss

    // The outward normal is the face's axis, signed like the hit coordinate
    // on it: entering, we meet the face looking against c_i; leaving, along it.
    glm::dvec3 enterNormal(0), exitNormal(0);
    enterNormal[enterAxis] = c[enterAxis] > 0 ? -1 : 1;
    exitNormal[exitAxis] = c[exitAxis] > 0 ? 1 : -1;
    spans.push({{tEnter, enterNormal}, {tExit, exitNormal}});
    return spans;
}

std::optional<GenericHit> intersectCube(const Ray& ray, double tMin) {
    return firstBoundary(cubeSpans(ray), tMin);
}

}  // namespace vkray::reference
