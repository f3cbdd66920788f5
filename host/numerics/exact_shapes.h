// Hill's generic shapes for the stress oracle, each derived from its own
// implicit equation and solved in float128 with rigorous error bounds
// (numerics/bounded.h): no code, formula or shortcut of the shader's (no
// origin shift to a bounding sphere or to the line's nearest point, no
// stable-root rewriting, no Newton polish on a shifted quartic). Along the
// ray o + t d (generic space, d not normalised: t is the world t) each
// crossing of the surface comes with a certified bracket of t:
//
//   sphere     F = |p|^2 - 1; the quadratic F(o + t d) solved by
//              polynomialRoots on |t| <= (|o| + 1) / |d| (no root lies
//              beyond: |p| = 1 there).
//   plane      p_z = 0: t = -o_z / d_z, one division; the square keeps
//              |p_x|, |p_y| <= 1.
//   cube       max(|p_x|, |p_y|, |p_z|) = 1: each of the six face planes
//              p_i = +-1 crossed where the other two coordinates are within
//              [-1, 1] (not slabs).
//   tapered cylinder
//              the quadric x^2 + y^2 = rho(z)^2, rho = 1 + (s - 1) z, both
//              nappes (for s < 0 the apex z = 1 / (1 - s) lies inside the
//              slab: an hourglass), where 0 <= z <= 1, and the caps z = 0
//              (x^2 + y^2 <= 1) and z = 1 (x^2 + y^2 <= s^2; none for s = 0).
//   torus      F = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (p_x^2 + p_y^2), its quartic
//              along the ray from the unshifted o and d; roots isolated by
//              interval bisection (polynomialRoots) on |t| <= (|o| + R + r)
//              / |d| (F > 0 wherever |p| > R + r), tangent roots found and
//              classified.
//
// A crossing the oracle cannot place on one side of an edge (a face's edge,
// a cylinder's rim, within its error bound) or resolve (a root left
// unresolved) is of kind Edge; a ray touching the surface, Tangent.
#pragma once

#include "numerics/bounded.h"

#include <array>

namespace vkray::numerics {

template <typename T>
struct Vec3 {
    T x = 0, y = 0, z = 0;
    T& operator[](int i) { return i == 0 ? x : i == 1 ? y : z; }
    const T& operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
    friend Vec3 operator+(const Vec3& a, const Vec3& b) {
        return {a.x + b.x, a.y + b.y, a.z + b.z};
    }
    friend Vec3 operator-(const Vec3& a, const Vec3& b) {
        return {a.x - b.x, a.y - b.y, a.z - b.z};
    }
    friend Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
    friend Vec3 operator*(const T& s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
    friend Vec3 operator/(const Vec3& a, const T& s) { return {a.x / s, a.y / s, a.z / s}; }
};

template <typename T>
T dot(const Vec3<T>& a, const Vec3<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
T length(const Vec3<T>& a) {
    using std::sqrt;
    return sqrt(dot(a, a));
}
template <typename T>
Vec3<T> normalize(const Vec3<T>& a) {
    return a / length(a);
}

using QVec = Vec3<Quad>;
using BVec = Vec3<Bounded>;

inline QVec valueOf(const BVec& v) {
    return {v.x.v, v.y.v, v.z.v};
}
// The largest error bound of the three coordinates.
inline Quad errorOf(const BVec& v) {
    return std::max({v.x.e, v.y.e, v.z.e});
}

enum class CrossingKind { Crossing, Tangent, Edge };

struct ExactCrossing {
    Quad t;       // the middle of its certified bracket
    Quad tBound;  // |t - t exact| <= tBound
    BVec normal;  // the outward gradient in generic space (not unit)
    CrossingKind kind = CrossingKind::Crossing;
    double curvature = 0;  // the surface's largest principal curvature there (generic)
};

// Every crossing of the whole line, ascending in t.
struct ExactCrossings {
    std::array<ExactCrossing, 8> at{};
    int count = 0;
    void add(const ExactCrossing& c) {
        if (count < int(at.size())) at[size_t(count++)] = c;
    }
    // Ascending; crossings whose brackets overlap (a rim, an edge: two
    // surfaces at one point) become one of kind Edge.
    void finish();
};

ExactCrossings sphereCrossings(const BVec& o, const BVec& d);
ExactCrossings planeCrossings(const BVec& o, const BVec& d, bool square);
ExactCrossings cubeCrossings(const BVec& o, const BVec& d);
ExactCrossings taperedCylinderCrossings(const BVec& o, const BVec& d, double s);
ExactCrossings torusCrossings(const BVec& o, const BVec& d, double R, double r);

}  // namespace vkray::numerics
