// Hill's generic tapered cylinder (cylinder s = 1, cone s = 0), written as
// the intersection of two simpler sets along the ray, like the cube's slabs:
//
//     slab:   0 <= z <= 1
//     quadric: Q(P) = x^2 + y^2 - rho(z)^2 <= 0,  rho(z) = 1 + k z,  k = s - 1
//
// The ray is inside the solid exactly where it is inside both, so each span
// is [max of the entries, min of the exits], and the binding constraint
// names the surface: slab -> cap, quadric -> wall. The caps' disks need no
// test of their own (the quadric clips them), so side and cap use one and
// the same inequality at the rim and no ray can slip between them
// (docs/numerics-background.md, "Tapered cylinder"). Within the slab the quadric is one nappe for
// s >= 0 (its apex z = 1 / (1 - s) lies at or beyond z = 1, or below z = 0
// for s > 1): a convex solid, one span. For s < 0 both nappes meet inside the
// slab: an hourglass, two spans.
#include "reference/shapes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vkray::reference {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Interval {
    double lo, hi;
};

// Where A t^2 + 2 B t + C <= 0: up to two intervals, possibly unbounded,
// sorted. The roots come from the stable pair q = -(B + sign(B) sqrt(B^2 - AC)),
// t = q / A and C / q (docs/numerics-background.md, "Sphere"), which also covers A -> 0 (a
// ray parallel to a generator) without dividing by it.
int insideQuadratic(double A, double B, double C, Interval out[2]) {
    if (A == 0) {  // linear: 2 B t + C <= 0
        if (B == 0) {
            // Parallel to the axis of a cylinder: inside all along, or never.
            if (C > 0) return 0;
            out[0] = {-kInf, kInf};
            return 1;
        }
        const double t = -C / (2 * B);
        out[0] = B > 0 ? Interval{-kInf, t} : Interval{t, kInf};
        return 1;
    }
    const double disc = B * B - A * C;
    if (disc < 0) {  // no real root: Q has the sign of A everywhere
        if (A > 0) return 0;
        out[0] = {-kInf, kInf};
        return 1;
    }
    const double q = -(B + std::copysign(std::sqrt(disc), B));
    // q == 0 needs B == 0 and disc == 0, so A C == 0 and C == 0: a double root at 0.
    double t1 = q / A;
    double t2 = q != 0 ? C / q : t1;
    if (t1 > t2) std::swap(t1, t2);
    if (A > 0) {
        out[0] = {t1, t2};
        return 1;
    }
    // A < 0 (steeper than the generators): the line crosses both nappes.
    out[0] = {-kInf, t1};
    out[1] = {t2, kInf};
    return 2;
}

}  // namespace

SpanPair taperedCylinderSpans(const Ray& ray, double s) {
    SpanPair spans;
    const glm::dvec3& d = ray.direction;
    const double dd = glm::dot(d, d);
    if (!(dd > 0)) return spans;  // a zero direction is not a ray

    // Work from the point of the line nearest the solid's middle (0, 0, 1/2):
    // the coefficients below are then of the size of the shape, not of the
    // distance to it, so C and B'^2 - AC do not cancel for far grazing rays.
    // t = t0 + tau keeps naming the same points.
    const glm::dvec3 middle(0, 0, 0.5);
    const double t0 = -glm::dot(ray.origin - middle, d) / dd;
    const glm::dvec3 o = ray.origin + t0 * d;

    const double k = s - 1;
    const auto rho = [k](double z) { return 1 + k * z; };
    const double A = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
    const double B = o.x * d.x + o.y * d.y - k * rho(o.z) * d.z;
    const double C = o.x * o.x + o.y * o.y - rho(o.z) * rho(o.z);
    Interval wall[2];
    const int wallCount = insideQuadratic(A, B, C, wall);

    // The slab, entered through z = 0 going up and through z = 1 going down.
    Interval slab{-kInf, kInf};
    glm::dvec3 capIn(0), capOut(0);
    if (d.z == 0) {
        if (!(o.z >= 0 && o.z <= 1)) return spans;
    } else {
        const double tBottom = -o.z / d.z, tTop = (1 - o.z) / d.z;
        slab = d.z > 0 ? Interval{tBottom, tTop} : Interval{tTop, tBottom};
        capIn = {0, 0, d.z > 0 ? -1 : 1};
        capOut = -capIn;
    }

    // The wall's outward normal is grad Q / 2 = (x, y, -k rho(z)). At a cone's
    // apex it vanishes: the axis stands in for it there.
    const auto wallNormal = [&](double tau) {
        const glm::dvec3 p = o + tau * d;
        const glm::dvec3 n(p.x, p.y, -k * rho(p.z));
        return n == glm::dvec3(0) ? glm::dvec3(0, 0, 1) : n;
    };

    for (int i = 0; i < wallCount; ++i) {
        // On a tie (the rim) the cap's plane, computed exactly, names the surface.
        const bool capIsIn = slab.lo >= wall[i].lo, capIsOut = slab.hi <= wall[i].hi;
        const double lo = capIsIn ? slab.lo : wall[i].lo;
        const double hi = capIsOut ? slab.hi : wall[i].hi;
        if (!(lo <= hi)) continue;
        const GenericSpan span{{t0 + lo, capIsIn ? capIn : wallNormal(lo)},
                               {t0 + hi, capIsOut ? capOut : wallNormal(hi)}};
        if (spans.empty()) {
            spans.push(span);
        } else if (s >= 0 || span.enter.t <= spans[0].exit.t) {
            // Convex (s >= 0): the second piece can only be the apex point
            // itself, reached by rounding; an hourglass's two pieces that
            // touch are one. Either way: one span over both.
            GenericSpan merged = spans[0];
            if (span.exit.t > merged.exit.t) merged.exit = span.exit;
            spans = SpanPair();
            spans.push(merged);
        } else {
            spans.push(span);
        }
    }
    return spans;
}

std::optional<GenericHit> intersectTaperedCylinder(const Ray& ray, double s, double tMin) {
    return firstBoundary(taperedCylinderSpans(ray, s), tMin);
}

}  // namespace vkray::reference
