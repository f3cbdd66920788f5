// Bounded: a float128 value (Boost.Multiprecision, 113-bit significand)
// that carries a rigorous bound on its distance from the exact result of the
// same expression on the same inputs: running error analysis, one rounding
// of at most kQuadUnit relative per operation (Higham, "Accuracy and
// Stability of Numerical Algorithms", ch. 3). The stress oracle computes
// with it, so that every sign it decides (a root bracketed, a point inside a
// face) is certain, or known to be uncertain.
//
// The true unit roundoff of float128 is 2^-113; kQuadUnit = 2^-112 also
// covers the rounding of the bounds themselves (each a sum of a few terms far
// smaller than the value they bound), and grow() adds 2^-100 relative to
// every new bound for the same reason. Underflow is out of reach: the
// oracle's quantities are within 1e-300 to 1e300.
#pragma once

#include <boost/multiprecision/float128.hpp>

#include <algorithm>

namespace vkray::numerics {

using Quad = boost::multiprecision::float128;

inline const Quad kQuadUnit = ldexp(Quad(1), -112);

struct Bounded {
    Quad v = 0;  // the computed value
    Quad e = 0;  // |v - exact| <= e

    Bounded() = default;
    Bounded(const Quad& value) : v(value) {}  // an exact input
    Bounded(double value) : v(value) {}       // an exact input
    Bounded(const Quad& value, const Quad& error) : v(value), e(error) {}

    bool positive() const { return v > e; }   // certainly > 0
    bool negative() const { return v < -e; }  // certainly < 0
    bool certain() const { return positive() || negative(); }
};

namespace bounded_detail {
inline Quad grow(const Quad& bound) {
    return bound * (1 + ldexp(Quad(1), -100));
}
inline Quad rounding(const Quad& v) {
    return kQuadUnit * abs(v);
}
}  // namespace bounded_detail

inline Bounded operator-(const Bounded& a) {
    return {-a.v, a.e};
}

inline Bounded operator+(const Bounded& a, const Bounded& b) {
    const Quad v = a.v + b.v;
    return {v, bounded_detail::grow(a.e + b.e + bounded_detail::rounding(v))};
}

inline Bounded operator-(const Bounded& a, const Bounded& b) {
    return a + (-b);
}

inline Bounded operator*(const Bounded& a, const Bounded& b) {
    const Quad v = a.v * b.v;
    return {v, bounded_detail::grow(abs(a.v) * b.e + abs(b.v) * a.e + a.e * b.e +
                                    bounded_detail::rounding(v))};
}

// Defined only where the divisor's sign is certain; otherwise the quotient
// is unbounded (e = inf).
inline Bounded operator/(const Bounded& a, const Bounded& b) {
    const Quad v = a.v / b.v;
    if (!b.certain()) return {v, std::numeric_limits<Quad>::infinity()};
    return {v, bounded_detail::grow((a.e + abs(v) * b.e) / (abs(b.v) - b.e) +
                                    bounded_detail::rounding(v))};
}

// |sqrt x - sqrt y| <= min(sqrt |x - y|, |x - y| / sqrt x).
inline Bounded sqrt(const Bounded& a) {
    using std::min;
    if (!(a.v > 0)) return {0, bounded_detail::grow(boost::multiprecision::sqrt(a.e + abs(a.v)))};
    const Quad v = boost::multiprecision::sqrt(a.v);
    const Quad from = min(boost::multiprecision::sqrt(a.e), a.e / v);
    return {v, bounded_detail::grow(from + bounded_detail::rounding(v))};
}

inline Bounded abs(const Bounded& a) {
    return {boost::multiprecision::abs(a.v), a.e};
}

}  // namespace vkray::numerics
