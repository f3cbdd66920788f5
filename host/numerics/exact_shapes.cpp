#include "numerics/exact_shapes.h"

#include "numerics/polynomial_roots.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vkray::numerics {

namespace {

int signOf(const Bounded& x) {
    return x.positive() ? 1 : x.negative() ? -1 : 0;
}

// A quotient's bracket: [v - e, v + e].
ExactCrossing crossingAt(const Bounded& t, const BVec& normal, CrossingKind kind) {
    return {t.v, t.e, normal, kind};
}

// Whether |x| <= limit: 1 certainly inside, -1 certainly outside, 0 the oracle cannot tell.
int within(const Bounded& x, const Bounded& limit) {
    return signOf(limit - abs(x));
}

CrossingKind kindOf(RootKind kind) {
    switch (kind) {
    case RootKind::Crossing: return CrossingKind::Crossing;
    case RootKind::Tangent: return CrossingKind::Tangent;
    default: return CrossingKind::Edge;
    }
}

// A point's bracket along the ray: o + t d with t known to +-bound.
BVec pointAt(const BVec& o, const BVec& d, const Quad& t, const Quad& bound) {
    const Bounded at(t, bound);
    return o + at * d;
}

// Every root of the polynomial c along the line within |t| <= reach, the
// search's ends nudged outward until f is certainly non-zero at both (the
// reach is a root bound, so no root lies beyond it).
std::vector<Root> rootsWithin(const Bounded* c, int degree, Quad reach,
                              const std::function<Bounded(const Quad&)>& f) {
    for (int attempt = 0; attempt < 8; ++attempt, reach *= 1 + ldexp(Quad(1), -20)) {
        if (f(-reach).certain() && f(reach).certain())
            return polynomialRoots(c, degree, -reach, reach, f);
    }
    return {Root{-reach, reach, RootKind::Unresolved}};
}

// (|o| + extent) / |d|, a little more: beyond it |p| > extent.
Quad reachOf(const BVec& o, const BVec& d, double extent) {
    const Quad lengthO = sqrt(dot(valueOf(o), valueOf(o))),
               lengthD = sqrt(dot(valueOf(d), valueOf(d)));
    return (lengthO + Quad(extent)) / lengthD * (1 + ldexp(Quad(1), -30)) + ldexp(Quad(1), -60);
}

}  // namespace

void ExactCrossings::finish() {
    std::sort(at.begin(), at.begin() + count,
              [](const ExactCrossing& a, const ExactCrossing& b) { return a.t < b.t; });
    int kept = 0;
    for (int i = 0; i < count; ++i) {
        ExactCrossing& c = at[size_t(i)];
        if (kept > 0) {
            ExactCrossing& last = at[size_t(kept - 1)];
            if (c.t - c.tBound <= last.t + last.tBound) {  // overlapping brackets: one point
                const Quad lo = std::min(last.t - last.tBound, c.t - c.tBound);
                const Quad hi = std::max(last.t + last.tBound, c.t + c.tBound);
                last.t = (lo + hi) / 2;
                last.tBound = (hi - lo) / 2;
                last.kind = CrossingKind::Edge;
                continue;
            }
        }
        at[size_t(kept++)] = c;
    }
    count = kept;
}

ExactCrossings sphereCrossings(const BVec& o, const BVec& d) {
    ExactCrossings out;
    // |o + t d|^2 - 1 = (d.d) t^2 + 2 (o.d) t + (o.o - 1).
    const Bounded c[3] = {dot(o, o) - Bounded(1), Bounded(2) * dot(o, d), dot(d, d)};
    const auto f = [&](const Quad& t) {
        const BVec p = o + Bounded(t) * d;
        return dot(p, p) - Bounded(1);
    };
    for (const Root& root : rootsWithin(c, 2, reachOf(o, d, 1), f)) {
        const BVec p = pointAt(o, d, root.at(), root.halfWidth());
        out.add({root.at(), root.halfWidth(), p, kindOf(root.kind), 1.0});  // the gradient is 2p
    }
    out.finish();
    return out;
}

ExactCrossings planeCrossings(const BVec& o, const BVec& d, bool square) {
    ExactCrossings out;
    if (!d.z.certain()) return out;  // parallel to the plane within rounding: no crossing in reach
    const Bounded t = -o.z / d.z;
    const BVec up{Bounded(0), Bounded(0), Bounded(1)};
    if (!square) {
        out.add(crossingAt(t, up, CrossingKind::Crossing));
        return out;
    }
    const BVec p = o + t * d;
    const int x = within(p.x, Bounded(1)), y = within(p.y, Bounded(1));
    if (x < 0 || y < 0) return out;
    out.add(crossingAt(t, up, x > 0 && y > 0 ? CrossingKind::Crossing : CrossingKind::Edge));
    return out;
}

ExactCrossings cubeCrossings(const BVec& o, const BVec& d) {
    ExactCrossings out;
    bool edge = false;  // the ray lies in a face's plane, within rounding
    for (int axis = 0; axis < 3; ++axis) {
        if (!d[axis].certain()) {
            const int inside = within(o[axis], Bounded(1));
            if (inside < 0) return {};  // outside that slab all along
            edge = edge || inside == 0;
            continue;
        }
        for (int side : {-1, 1}) {
            const Bounded t = (Bounded(double(side)) - o[axis]) / d[axis];
            const BVec p = o + t * d;
            int inside = 1;
            for (int other = 0; other < 3; ++other)
                if (other != axis) inside = std::min(inside, within(p[other], Bounded(1)));
            if (inside < 0) continue;
            BVec normal{Bounded(0), Bounded(0), Bounded(0)};
            normal[axis] = Bounded(double(side));
            out.add(
                crossingAt(t, normal, inside > 0 ? CrossingKind::Crossing : CrossingKind::Edge));
        }
    }
    out.finish();
    if (edge)
        for (int i = 0; i < out.count; ++i) out.at[size_t(i)].kind = CrossingKind::Edge;
    return out;
}

ExactCrossings taperedCylinderCrossings(const BVec& o, const BVec& d, double s) {
    ExactCrossings out;
    const Bounded k = Bounded(s) - Bounded(1);
    const auto rho = [&](const Bounded& z) { return Bounded(1) + k * z; };
    // Q(o + t d) = (ox + t dx)^2 + (oy + t dy)^2 - (rho(oz) + t k dz)^2.
    const Bounded kdz = k * d.z, rhoO = rho(o.z);
    const Bounded c[3] = {o.x * o.x + o.y * o.y - rhoO * rhoO,
                          Bounded(2) * (o.x * d.x + o.y * d.y - rhoO * kdz),
                          d.x * d.x + d.y * d.y - kdz * kdz};
    const auto f = [&](const Quad& t) {
        const BVec p = o + Bounded(t) * d;
        const Bounded r = rho(p.z);
        return p.x * p.x + p.y * p.y - r * r;
    };
    // The wall that matters is within the box |x|, |y| <= max(1, |s|), 0 <= z <= 1.
    const double extent = std::sqrt(2 * std::max(1.0, s * s) + 1);
    for (const Root& root : rootsWithin(c, 2, reachOf(o, d, extent), f)) {
        const BVec p = pointAt(o, d, root.at(), root.halfWidth());
        const int below = signOf(p.z), above = signOf(Bounded(1) - p.z);
        if (below < 0 || above < 0) continue;  // beyond the slab
        // The wall's outward normal is grad Q / 2 = (x, y, -k rho(z)).
        const BVec normal{p.x, p.y, -k * rho(p.z)};
        const bool onRim = below == 0 || above == 0;
        // Across the wall it curves like a circle of radius |rho| (along it, not at all).
        const double radius = std::abs(double(rho(p.z).v));
        out.add({root.at(), root.halfWidth(), normal,
                 onRim ? CrossingKind::Edge : kindOf(root.kind),
                 radius > 0 ? 1 / radius : std::numeric_limits<double>::infinity()});
    }
    if (d.z.certain()) {
        for (int cap = 0; cap < 2; ++cap) {
            if (cap == 1 && s == 0) continue;  // a cone: its top is the apex
            const Bounded t = (Bounded(double(cap)) - o.z) / d.z;
            const BVec p = o + t * d;
            const Bounded radius2 = cap == 0 ? Bounded(1) : Bounded(s) * Bounded(s);
            const int inside = signOf(radius2 - (p.x * p.x + p.y * p.y));
            if (inside < 0) continue;
            const BVec normal{Bounded(0), Bounded(0), Bounded(cap == 0 ? -1.0 : 1.0)};
            out.add(
                crossingAt(t, normal, inside > 0 ? CrossingKind::Crossing : CrossingKind::Edge));
        }
    }
    out.finish();
    return out;
}

ExactCrossings torusCrossings(const BVec& o, const BVec& d, double majorRadius, double tubeRadius) {
    ExactCrossings out;
    const Bounded R2 = Bounded(majorRadius) * Bounded(majorRadius);
    const Bounded offset = R2 - Bounded(tubeRadius) * Bounded(tubeRadius);  // R^2 - r^2
    // With G = d.d, H = o.d, K = o.o + R^2 - r^2 and a2, a1, a0 the terms of
    // (ox + t dx)^2 + (oy + t dy)^2: F = (G t^2 + 2 H t + K)^2 - 4 R^2 (a2 t^2 + 2 a1 t + a0).
    const Bounded G = dot(d, d), H = dot(o, d), K = dot(o, o) + offset;
    const Bounded a2 = d.x * d.x + d.y * d.y, a1 = o.x * d.x + o.y * d.y,
                  a0 = o.x * o.x + o.y * o.y;
    const Bounded four(4), eight(8), two(2);
    const Bounded c[5] = {K * K - four * R2 * a0, four * H * K - eight * R2 * a1,
                          four * H * H + two * G * K - four * R2 * a2, four * G * H, G * G};
    const auto f = [&](const Quad& t) {
        const BVec p = o + Bounded(t) * d;
        const Bounded q = dot(p, p) + offset;
        return q * q - four * R2 * (p.x * p.x + p.y * p.y);
    };
    for (const Root& root : rootsWithin(c, 4, reachOf(o, d, majorRadius + tubeRadius), f)) {
        const BVec p = pointAt(o, d, root.at(), root.halfWidth());
        const Bounded q = dot(p, p) + offset;
        // grad F = 4 q p - 8 R^2 (px, py, 0).
        const BVec normal{four * q * p.x - eight * R2 * p.x, four * q * p.y - eight * R2 * p.y,
                          four * q * p.z};
        // Curvatures 1 / r around the tube and cos(phi) / (R + r cos(phi)) around the axis.
        out.add({root.at(), root.halfWidth(), normal, kindOf(root.kind), 1 / tubeRadius});
    }
    out.finish();
    return out;
}

}  // namespace vkray::numerics
