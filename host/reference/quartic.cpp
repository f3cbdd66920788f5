// Bracketed Newton on monotone pieces (see quartic.h).
#include "reference/quartic.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace vkray::reference {
namespace {

// p and p' at x together (Horner on both).
void evaluateWithDerivative(std::span<const double> c, double x, double& p, double& dp) {
    p = c.back();
    dp = 0;
    for (std::size_t i = c.size() - 1; i-- > 0;) {
        dp = dp * x + p;
        p = p * x + c[i];
    }
}

// Appends x unless it repeats the last root (a root on a piece's shared end).
void addRoot(double* roots, int& count, double x) {
    if (count > 0 && roots[count - 1] == x) return;
    roots[count++] = x;
}

// The one root of a monotone p in [a, b], where p(a) and p(b) have strictly
// opposite signs. Newton from the middle; every step also shrinks the bracket
// by the sign of p, and a step that leaves the bracket (or stalls, p' = 0) is
// replaced by bisection, so it always converges, quadratically near a simple
// root. It stops when a step no longer moves x by more than a few ulps, or
// when the bracket cannot be split any further.
double bracketedRoot(std::span<const double> c, double a, double b, bool negativeAtA) {
    double x = 0.5 * (a + b);
    for (int iteration = 0; iteration < 200; ++iteration) {
        double p, dp;
        evaluateWithDerivative(c, x, p, dp);
        if (p == 0) return x;
        if ((p < 0) == negativeAtA) {
            a = x;
        } else {
            b = x;
        }
        double next = x - p / dp;
        if (!(next > a && next < b)) next = 0.5 * (a + b);  // also catches dp == 0 (NaN, inf)
        const double step = std::abs(next - x);
        x = next;
        if (step <= 4 * std::numeric_limits<double>::epsilon() * std::abs(x) || !(a < x && x < b))
            break;
    }
    return x;
}

// Roots of a x^2 + b x + c (a != 0) in [lo, hi], ascending; the stable form
// q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2, roots q / a and c / q.
int quadraticRoots(double a, double b, double c, double lo, double hi, double* roots) {
    const double disc = b * b - 4 * a * c;
    if (disc < 0) return 0;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    double r1 = q / a;
    double r2 = q != 0 ? c / q : r1;  // q == 0: b == 0 and c == 0, a double root at 0
    if (r1 > r2) std::swap(r1, r2);
    int count = 0;
    if (r1 >= lo && r1 <= hi) roots[count++] = r1;
    if (r2 >= lo && r2 <= hi && r2 != r1) roots[count++] = r2;
    return count;
}

}  // namespace

double evaluatePolynomial(std::span<const double> coeffs, double x) {
    double p = 0;
    for (std::size_t i = coeffs.size(); i-- > 0;) p = p * x + coeffs[i];
    return p;
}

int polynomialRoots(std::span<const double> coeffs, double lo, double hi, double* roots) {
    std::size_t size = coeffs.size();
    while (size > 0 && coeffs[size - 1] == 0) --size;  // the true degree
    assert(size <= kMaxPolynomialDegree + 1);
    const std::span<const double> c = coeffs.first(size);
    if (size <= 1 || !(lo <= hi)) return 0;  // a constant: no root worth naming
    if (size == 2) {
        const double x = -c[0] / c[1];
        if (!(x >= lo && x <= hi)) return 0;
        roots[0] = x;
        return 1;
    }
    if (size == 3) return quadraticRoots(c[2], c[1], c[0], lo, hi, roots);

    // The derivative's roots split [lo, hi] into monotone pieces.
    double derivative[kMaxPolynomialDegree];
    for (std::size_t i = 1; i < size; ++i) derivative[i - 1] = double(i) * c[i];
    double ends[kMaxPolynomialDegree + 1];
    ends[0] = lo;
    int endCount = 1 + polynomialRoots({derivative, size - 1}, lo, hi, ends + 1);
    if (ends[endCount - 1] != hi) ends[endCount++] = hi;

    // A value within rounding of zero at a piece's end is a root there: at an
    // extremum that is a double root (a tangent ray), which no sign change
    // would reveal. The bound is Horner's, 2n roundings of sum |c_i x^i|,
    // doubled for the rounding already in the coefficients.
    const auto nearZero = [&](double x, double p) {
        double magnitude = 0;
        for (std::size_t i = size; i-- > 0;) magnitude = magnitude * std::abs(x) + std::abs(c[i]);
        return std::abs(p) <= 4 * double(size) * std::numeric_limits<double>::epsilon() * magnitude;
    };
    int count = 0;
    double a = ends[0];
    double pa = evaluatePolynomial(c, a);
    bool zeroA = nearZero(a, pa);
    for (int i = 1; i < endCount; ++i) {
        const double b = ends[i];
        const double pb = evaluatePolynomial(c, b);
        const bool zeroB = nearZero(b, pb);
        if (zeroA) {
            addRoot(roots, count, a);
        } else if (!zeroB && (pa < 0) != (pb < 0)) {
            addRoot(roots, count, bracketedRoot(c, a, b, pa < 0));
        }
        a = b;
        pa = pb;
        zeroA = zeroB;
    }
    if (zeroA) addRoot(roots, count, a);
    return count;
}

}  // namespace vkray::reference
