// Real roots of a polynomial on an interval, in double, without closed forms
// beyond the quadratic: the method of C. Yuksel, "High-Performance Polynomial
// Root Finding for Graphics" (HPG 2022), written from the paper's idea.
//
// The roots of the derivative split [lo, hi] into pieces on which the
// polynomial is monotone; a piece whose ends differ in sign holds exactly one
// root, found by Newton steps kept inside the bracket (bisection when a step
// leaves it). The derivative's roots come the same way, recursively, down to
// a quadratic solved in the stable form. Nothing here depends on a
// discriminant's sign being computed right, which is what makes Ferrari's
// and Descartes' closed forms fragile near double roots (docs/numerics-background.md,
// "Torus"); the price is a few dozen polynomial evaluations per root.
#pragma once

#include <span>

namespace vkray::reference {

inline constexpr int kMaxPolynomialDegree = 8;

// p(x) = sum_i coeffs[i] x^i, by Horner's rule.
double evaluatePolynomial(std::span<const double> coeffs, double x);

// The distinct real roots of p in [lo, hi] (closed), ascending, written to
// roots (room for coeffs.size() - 1 values); returns how many. Leading zero
// coefficients lower the degree. A root where p touches zero without changing
// sign (a double root: a tangent ray) is reported once, at the extremum, when
// p there is within its rounding error of zero. Degree at most
// kMaxPolynomialDegree; a constant has no roots reported.
int polynomialRoots(std::span<const double> coeffs, double lo, double hi, double* roots);

}  // namespace vkray::reference
