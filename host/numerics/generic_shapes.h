// Hill's generic shapes, written once over the scalar type T: long double for
// the stress suite's oracle (x87 80-bit, u = 2^-64), float to replay shadow
// feelers the way a float32 GPU would (numerics/feelers.cpp). Independent of
// the CPU reference (host/reference) and of the shader: its own derivations
// from the implicit equations, with the origin shifts of docs/numerics.md
// ("Precision modes") so that
// even T = float stays well conditioned, and the polynomial roots found by
// bisection on monotone intervals (Yuksel, HPG 2022) to the last bit.
//
// Included only by the numerics sources that instantiate it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace vkray::numerics {

template <typename T>
struct Vec3 {
    T x = 0, y = 0, z = 0;
    T& operator[](int i) { return i == 0 ? x : i == 1 ? y : z; }
    T operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
    friend Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
    friend Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
    friend Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
    friend Vec3 operator*(T s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
    friend Vec3 operator/(Vec3 a, T s) { return {a.x / s, a.y / s, a.z / s}; }
};

template <typename T> T dot(Vec3<T> a, Vec3<T> b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <typename T> Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T> T length(Vec3<T> a) { return std::sqrt(dot(a, a)); }
template <typename T> Vec3<T> normalize(Vec3<T> a) { return a / length(a); }

// A crossing of a generic surface: t along the ray and the outward normal
// (the gradient, not normalised).
template <typename T>
struct Crossing {
    T t;
    Vec3<T> normal;
};

// Every crossing of the ray o + d t with one surface, ascending in t.
template <typename T>
struct Crossings {
    std::array<Crossing<T>, 4> at{};
    int count = 0;
    void add(T t, Vec3<T> n) {
        if (count < 4 && std::isfinite(t)) at[count++] = {t, n};
    }
    void sort() {  // insertion sort: at most four
        for (int i = 1; i < count; ++i)
            for (int j = i; j > 0 && at[size_t(j)].t < at[size_t(j - 1)].t; --j)
                std::swap(at[size_t(j)], at[size_t(j - 1)]);
    }
};

// Roots of A t^2 + 2 B t + C from the stable pair q / A and C / q, with
// q = -(B + sign(B) sqrt(B^2 - A C)). Returns how many (0 or 2; a linear
// equation gives 1).
template <typename T>
int quadraticRoots(T A, T B, T C, T roots[2]) {
    if (A == 0) {
        if (B == 0) return 0;
        roots[0] = -C / (2 * B);
        return 1;
    }
    const T disc = B * B - A * C;
    if (disc < 0) return 0;
    const T q = -(B + std::copysign(std::sqrt(disc), B));
    roots[0] = q / A;
    roots[1] = q != 0 ? C / q : roots[0];
    if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
    return 2;
}

// ---- Sphere x^2 + y^2 + z^2 = 1 ------------------------------------------
// Ray Tracing Gems ch. 7: the discriminant a (1 - |f_perp|^2) from the line's
// point nearest the centre (no |o|^2 cancellation) and the stable root pair
// c / q, q / a (no cancellation in the root near the origin). f_perp is
// projected twice (the rounding of the first projection lies along d) and the
// normals are f_perp -+ h d: both keep huge anisotropy (|o| ~ 1e8 generic
// radii along one axis) from cancelling to noise, as in shapes/sphere.glsl.
template <typename T>
Crossings<T> sphereCrossings(Vec3<T> o, Vec3<T> d) {
    Crossings<T> out;
    const T a = dot(d, d);
    const T b = dot(o, d);
    Vec3<T> fPerp = o - (b / a) * d;
    fPerp = fPerp - (dot(fPerp, d) / a) * d;
    const T disc = a * (1 - dot(fPerp, fPerp));
    if (disc < 0) return out;
    const T root = std::sqrt(disc);
    const T q = -(b + std::copysign(root, b));
    if (q == 0) return out;  // o at the centre and d = 0: no ray
    T t0 = (dot(o, o) - 1) / q, t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    const Vec3<T> halfChord = (root / a) * d;
    out.add(t0, fPerp - halfChord);
    out.add(t1, fPerp + halfChord);
    return out;
}

// ---- Plane z = 0 and square |x|, |y| <= 1 in it ----------------------------
template <typename T>
Crossings<T> planeCrossings(Vec3<T> o, Vec3<T> d, bool square) {
    Crossings<T> out;
    if (d.z == 0) return out;
    const T t = -o.z / d.z;
    const Vec3<T> p = o + t * d;
    if (!square || (std::abs(p.x) <= 1 && std::abs(p.y) <= 1)) out.add(t, Vec3<T>{0, 0, 1});
    return out;
}

// ---- Cube [-1, 1]^3 by slabs -----------------------------------------------
template <typename T>
Crossings<T> cubeCrossings(Vec3<T> o, Vec3<T> d) {
    Crossings<T> out;
    T t0 = -std::numeric_limits<T>::infinity(), t1 = std::numeric_limits<T>::infinity();
    int enter = 0, exit = 0;
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0) {
            if (std::abs(o[i]) > 1) return out;
            continue;
        }
        T a = (-1 - o[i]) / d[i], b = (1 - o[i]) / d[i];
        if (a > b) std::swap(a, b);
        if (a > t0) { t0 = a; enter = i; }
        if (b < t1) { t1 = b; exit = i; }
    }
    if (t0 > t1) return out;
    Vec3<T> n0, n1;
    n0[enter] = d[enter] > 0 ? -1 : 1;
    n1[exit] = d[exit] > 0 ? 1 : -1;
    out.add(t0, n0);
    out.add(t1, n1);
    return out;
}

// ---- Tapered cylinder: x^2 + y^2 = rho(z)^2, rho = 1 + (s - 1) z, 0 <= z <= 1
// The quadratic is solved from the line's point nearest (0, 0, 1/2), so its
// coefficients are of the shape's size however far the origin is.
template <typename T>
Crossings<T> taperedCylinderCrossings(Vec3<T> origin, Vec3<T> d, T s) {
    Crossings<T> out;
    const T shift = dot(Vec3<T>{0, 0, T(0.5)} - origin, d) / dot(d, d);
    const Vec3<T> o = origin + shift * d;
    const T k = s - 1;
    const T rhoO = 1 + k * o.z;
    const T A = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
    const T B = o.x * d.x + o.y * d.y - k * rhoO * d.z;
    const T C = o.x * o.x + o.y * o.y - rhoO * rhoO;
    T roots[2];
    const int n = quadraticRoots(A, B, C, roots);
    for (int i = 0; i < n; ++i) {
        const Vec3<T> p = o + roots[i] * d;
        if (!(p.z >= 0 && p.z <= 1)) continue;
        const T rho = 1 + k * p.z;
        out.add(shift + roots[i], rho != 0 ? Vec3<T>{p.x, p.y, -k * rho} : Vec3<T>{0, 0, 1});
    }
    if (d.z != 0) {
        for (int cap = 0; cap < 2; ++cap) {
            const T t = (T(cap) - o.z) / d.z;
            const Vec3<T> p = o + t * d;
            const T radius = cap == 0 ? T(1) : s;
            if (radius != 0 && p.x * p.x + p.y * p.y <= radius * radius)
                out.add(shift + t, Vec3<T>{0, 0, cap == 0 ? T(-1) : T(1)});
        }
    }
    out.sort();
    return out;
}

// ---- Polynomials: real roots with a sign change on [lo, hi] -----------------
template <typename T>
T polynomialAt(const T* c, int degree, T x) {
    T f = c[degree];
    for (int i = degree - 1; i >= 0; --i) f = f * x + c[i];
    return f;
}

// The root of a polynomial monotone on [a, b] with a sign change, by
// bisection until the bracket cannot shrink: the last bit of T.
template <typename T>
T bisectRoot(const T* c, int degree, T a, T b) {
    const bool risingAtA = polynomialAt(c, degree, a) < 0;
    for (int i = 0; i < 400; ++i) {
        const T mid = a + (b - a) / 2;
        if (!(mid > a && mid < b)) break;
        const T f = polynomialAt(c, degree, mid);
        if (f == 0) return mid;
        ((f < 0) == risingAtA ? a : b) = mid;
    }
    return a + (b - a) / 2;
}

// The roots in [lo, hi] where the polynomial changes sign, ascending: split
// at the sign-changing roots of the derivative (recursively), where it is
// monotone in between. Double roots without a sign change (tangents) are
// not roots here.
template <typename T>
int signChangeRoots(const T* c, int degree, T lo, T hi, T* roots) {
    int count = 0;
    if (degree < 1) return 0;
    T splits[4];
    int splitCount = 0;
    if (degree > 1) {
        T derivative[4];
        for (int i = 1; i <= degree; ++i) derivative[i - 1] = T(i) * c[i];
        splitCount = signChangeRoots(derivative, degree - 1, lo, hi, splits);
    }
    T a = lo, fa = polynomialAt(c, degree, lo);
    for (int i = 0; i <= splitCount; ++i) {
        const T b = i < splitCount ? splits[i] : hi;
        const T fb = polynomialAt(c, degree, b);
        if (b > a && ((fa < 0 && fb > 0) || (fa > 0 && fb < 0))) roots[count++] = bisectRoot(c, degree, a, b);
        else if (fb == 0 && b < hi && (fa != 0)) roots[count++] = b;
        a = b;
        fa = fb;
    }
    return count;
}

// ---- Torus: (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) = 0, axis z ------------
// Solved from where the line enters a bounding sphere, along the unit
// direction: the quartic's coefficients are then O(1) (docs/numerics-background.md, "Torus").
// Each root is polished by Newton steps on F at the point itself.
template <typename T>
T torusF(Vec3<T> p, T R, T r) {
    const T k = dot(p, p) + R * R - r * r;
    return k * k - 4 * R * R * (p.x * p.x + p.y * p.y);
}

template <typename T>
Vec3<T> torusGradient(Vec3<T> p, T R, T r) {
    const T k = dot(p, p) + R * R - r * r;
    return Vec3<T>{4 * k * p.x - 8 * R * R * p.x, 4 * k * p.y - 8 * R * R * p.y, 4 * k * p.z};
}

template <typename T>
Crossings<T> torusCrossings(Vec3<T> o, Vec3<T> d, T R, T r) {
    Crossings<T> out;
    const T dLength = length(d);
    const Vec3<T> u = d / dLength;
    const T bound = T(1.01) * (R + r);
    const T b = dot(o, u);
    const Vec3<T> foot = o - b * u;
    const T halfChord2 = bound * bound - dot(foot, foot);
    if (halfChord2 <= 0) return out;
    const T halfChord = std::sqrt(halfChord2);
    const T sEnter = -b - halfChord;  // along u from o
    const Vec3<T> e = foot - halfChord * u;  // the entry point, from the foot (no cancellation)
    const T H = dot(e, u);
    const T K = dot(e, e) + R * R - r * r;
    const T a2 = u.x * u.x + u.y * u.y, a1 = e.x * u.x + e.y * u.y, a0 = e.x * e.x + e.y * e.y;
    const T c[5] = {K * K - 4 * R * R * a0, 4 * H * K - 8 * R * R * a1,
                    4 * H * H + 2 * K - 4 * R * R * a2, 4 * H, 1};
    T roots[4];
    const int n = signChangeRoots(c, 4, T(0), 2 * halfChord, roots);
    for (int i = 0; i < n; ++i) {
        T s = roots[i];
        for (int step = 0; step < 2; ++step) {
            const Vec3<T> p = e + s * u;
            const T slope = dot(torusGradient(p, R, r), u);
            if (slope == 0) break;
            const T delta = torusF(p, R, r) / slope;
            if (!(std::abs(delta) < T(1e-3))) break;  // a polish, never a jump
            s -= delta;
        }
        out.add((sEnter + s) / dLength, torusGradient(e + s * u, R, r));
    }
    return out;
}

}  // namespace vkray::numerics
