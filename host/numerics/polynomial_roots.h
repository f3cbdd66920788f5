// The real roots of a polynomial of degree at most 4 on an interval, each
// bracketed with certainty, for the stress oracle (numerics/exact_shapes.h).
//
// Isolation by interval bisection in the Bernstein basis (Lane and
// Riesenfeld): on [a, b] the polynomial's Bernstein coefficients bound its
// values (their convex hull holds its graph), so an interval whose
// coefficients all have one certain sign holds no root, and one whose
// coefficients change sign exactly once holds exactly one, a crossing
// (Descartes' rule of signs in the Bernstein basis). Any other interval is
// halved (a little off centre, so that a root at a simple number never sits
// on a cut) until its coefficients are all within their error bounds of 0
// (the polynomial is rounding noise there: near a double root that is
// within about the square root of float128's unit, 1e-17 relative) or it
// is narrower than 2^-90 of [a, b]: what is left is classified from the
// signs of f at its ends, evaluated with certainty:
//   the same sign   an even number of roots closer than that width: a
//                   tangent (the ray touches the surface, or crosses it
//                   twice closer than float128 can tell apart);
//   opposite signs  an odd number: a crossing (a triple root, or three
//                   roots as close);
//   not certain     unresolved.
// Nothing is missed: every root lies in an interval that was never excluded.
// A crossing's bracket is then narrowed (Newton's method on the polynomial,
// regula falsi on f) and certified by the signs of f (the shape's implicit
// function evaluated at the point itself, with its error bound) at its two
// ends: the root is inside. Coefficients and f carry rigorous error bounds
// (numerics/bounded.h).
#pragma once

#include "numerics/bounded.h"

#include <functional>
#include <vector>

namespace vkray::numerics {

enum class RootKind { Crossing, Tangent, Unresolved };

struct Root {
    Quad lo, hi;  // the root is in [lo, hi]
    RootKind kind = RootKind::Crossing;
    bool unresolvedPiece = false;  // classified where halving could tell no more
    Quad at() const { return (lo + hi) / 2; }
    Quad halfWidth() const { return (hi - lo) / 2; }
};

// The roots in (a, b) of c[0] + c[1] t + ... + c[degree] t^degree, ascending;
// f(t) is the same function evaluated another way (at the point itself), used
// to certify brackets. f(a) and f(b) must be certainly non-zero.
std::vector<Root> polynomialRoots(const Bounded* c, int degree, const Quad& a, const Quad& b,
                                  const std::function<Bounded(const Quad&)>& f);

}  // namespace vkray::numerics
