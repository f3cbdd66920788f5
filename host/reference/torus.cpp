// The generic torus, F(p) = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) = 0,
// axis z, R = kTorusMajorRadius, r = kTorusTubeRadius (scene.h).
//
// Method, and why (docs/numerics-background.md, "Torus"):
//  1. Shift the origin to the point of the line nearest the torus's centre
//     and use the unit direction u there: p = o' + sigma u, t = t0 + sigma/|d|.
//     The quartic's coefficients are then O(R^2), whatever the distance to
//     the torus; unshifted they grow like |o|^4 and cancel (a double closed form was
//     measured at 3.5e-7 relative error at D = 1000; docs/numerics-background.md, "Torus").
//     The shift matters more than the solver.
//  2. Only sigma in the bounding sphere |p| <= R + r can be a root: search
//     [-h, h], h^2 = (R + r)^2 - |o'|^2; a line that misses the sphere
//     misses the torus.
//  3. Roots by bracketed Newton on monotone pieces (quartic.h, Yuksel 2022)
//     rather than Ferrari/Descartes: the closed forms branch on the signs of
//     intermediate discriminants that rounding can flip near double roots
//     (silhouettes, tangent rays), and then lose or invent roots; bracketing
//     finds every sign change of the quartic itself, in order, and keeps the
//     roots sorted, which the CSG spans need. Tangent (double) roots are
//     found at the extremum where the quartic is within rounding of zero.
// All four roots are kept: which gaps between them are inside the tube
// (F < 0 at their middle) gives the spans.
#include "reference/shapes.h"

#include "reference/quartic.h"
#include "scene/scene.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace vkray::reference {
namespace {

constexpr double R = kTorusMajorRadius;
constexpr double r = kTorusTubeRadius;

// The quartic in the shifted, unit-speed parameter, and its real roots.
struct TorusSolution {
    double t0 = 0, speed = 1;  // t = t0 + sigma / speed
    glm::dvec3 origin{0}, unit{0};
    double coeffs[5] = {};
    double sigma[4] = {};
    int count = 0;

    glm::dvec3 point(double s) const { return origin + s * unit; }
    double t(double s) const { return t0 + s / speed; }
};

TorusSolution solveTorus(const Ray& ray) {
    TorusSolution solution;
    const glm::dvec3& d = ray.direction;
    const double dd = glm::dot(d, d);
    if (!(dd > 0)) return solution;  // a zero direction is not a ray
    solution.t0 = -glm::dot(ray.origin, d) / dd;
    solution.speed = std::sqrt(dd);
    solution.origin = ray.origin + solution.t0 * d;
    solution.unit = d / solution.speed;

    const glm::dvec3& o = solution.origin;
    const glm::dvec3& u = solution.unit;
    const double bound = R + r;
    const double h2 = bound * bound - glm::dot(o, o);
    // Keep a ray that touches the outer equator (|o'| = R + r exactly).
    if (h2 < -1e-12 * bound * bound) return solution;
    const double h = std::sqrt(std::max(h2, 0.0)) + 1e-9 * bound;

    // |p|^2 + R^2 - r^2 = sigma^2 + 2 H sigma + K and x^2 + y^2 = a2 sigma^2
    // + 2 a1 sigma + a0 (u is unit), so F(sigma) = sigma^4 + 4H sigma^3
    // + (4H^2 + 2K - 4R^2 a2) sigma^2 + (4HK - 8R^2 a1) sigma + K^2 - 4R^2 a0.
    const double H = glm::dot(o, u);  // ~0 after the shift, kept for exactness
    const double K = glm::dot(o, o) + (R * R - r * r);
    const double a2 = u.x * u.x + u.y * u.y;
    const double a1 = o.x * u.x + o.y * u.y;
    const double a0 = o.x * o.x + o.y * o.y;
    double* c = solution.coeffs;
    c[4] = 1;
    c[3] = 4 * H;
    c[2] = 4 * H * H + 2 * K - 4 * R * R * a2;
    c[1] = 4 * H * K - 8 * R * R * a1;
    c[0] = K * K - 4 * R * R * a0;
    solution.count = polynomialRoots({c, 5}, -h, h, solution.sigma);
    return solution;
}

// grad F = 4 (|p|^2 + R^2 - r^2) p - 8 R^2 (x, y, 0): outward, not normalised.
glm::dvec3 torusNormal(const glm::dvec3& p) {
    const double k = glm::dot(p, p) + (R * R - r * r);
    return 4 * k * p - 8 * R * R * glm::dvec3(p.x, p.y, 0);
}

GenericHit hitAt(const TorusSolution& solution, double sigma) {
    return {solution.t(sigma), torusNormal(solution.point(sigma))};
}

}  // namespace

TorusRoots torusRoots(const Ray& ray) {
    const TorusSolution solution = solveTorus(ray);
    TorusRoots roots;
    for (int i = 0; i < solution.count; ++i) roots.hits[i] = hitAt(solution, solution.sigma[i]);
    roots.count = solution.count;
    return roots;
}

std::optional<GenericHit> intersectTorus(const Ray& ray, double tMin) {
    const TorusSolution solution = solveTorus(ray);
    for (int i = 0; i < solution.count; ++i) {
        const double t = solution.t(solution.sigma[i]);
        if (t > tMin) return GenericHit{t, torusNormal(solution.point(solution.sigma[i]))};
    }
    return std::nullopt;
}

// Outside the bounding sphere F >= 0, so the line is outside before the first
// root and after the last. Between roots the sign of F at the middle says
// inside or out; a run of inside gaps is one span (an internal tangency
// touches the surface without leaving the solid), and a root with outside
// on both sides (a tangent ray) bounds no span.
SpanPair torusSpans(const Ray& ray) {
    const TorusSolution solution = solveTorus(ray);
    SpanPair spans;
    int start = -1;  // the root where the current run of inside gaps began
    for (int i = 0; i + 1 < solution.count; ++i) {
        const double middle = 0.5 * (solution.sigma[i] + solution.sigma[i + 1]);
        const bool inside = evaluatePolynomial(solution.coeffs, middle) < 0;
        if (inside && start < 0) start = i;
        const bool runEnds = start >= 0 && (!inside || i + 2 == solution.count);
        if (!runEnds) continue;
        const int end = inside ? i + 1 : i;
        spans.push({hitAt(solution, solution.sigma[start]), hitAt(solution, solution.sigma[end])});
        start = -1;
    }
    return spans;
}

}  // namespace vkray::reference
