#include "numerics/polynomial_roots.h"

#include <array>

namespace vkray::numerics {

namespace {

constexpr int kMaxDegree = 4;
using Coefficients = std::array<Bounded, kMaxDegree + 1>;

// Intervals looked at before the search gives up (a polynomial that is 0 all
// along, a ray lying in the surface, excludes none): a ray with four roots
// isolated to 2^-90 takes a few hundred.
constexpr int kMaxIntervals = 20000;

int signOf(const Bounded& x) {
    return x.positive() ? 1 : x.negative() ? -1 : 0;
}

Quad binomial(int n, int k) {
    Quad b = 1;
    for (int i = 1; i <= k; ++i) b = b * Quad(n - k + i) / Quad(i);  // exact: small integers
    return b;
}

// The Bernstein coefficients on s in [0, 1] of q(s) = p(a + w s).
Coefficients bernsteinOf(const Bounded* c, int n, const Quad& a, const Bounded& w) {
    Coefficients q{};
    for (int i = 0; i <= n; ++i) q[size_t(i)] = c[i];
    const Bounded shift(a);
    for (int i = 0; i < n; ++i)  // Taylor shift to a (synthetic division)
        for (int j = n - 1; j >= i; --j) q[size_t(j)] = q[size_t(j)] + shift * q[size_t(j + 1)];
    Bounded power(1);
    for (int k = 1; k <= n; ++k) {
        power = power * w;
        q[size_t(k)] = q[size_t(k)] * power;
    }
    Coefficients beta{};
    for (int i = 0; i <= n; ++i) {
        Bounded sum(0);
        for (int k = 0; k <= i; ++k)
            sum = sum + Bounded(binomial(i, k)) / Bounded(binomial(n, k)) * q[size_t(k)];
        beta[size_t(i)] = sum;
    }
    return beta;
}

// de Casteljau at s: the coefficients on [0, s] and [s, 1] of the same polynomial.
void split(const Coefficients& b, int n, const Quad& s, Coefficients& left, Coefficients& right) {
    Coefficients w = b;
    const Bounded at(s), rest(1 - s);  // 1 - s is exact for s in [1/2, 1]
    left[0] = w[0];
    right[size_t(n)] = w[size_t(n)];
    for (int r = 1; r <= n; ++r) {
        for (int i = 0; i <= n - r; ++i) w[size_t(i)] = rest * w[size_t(i)] + at * w[size_t(i + 1)];
        left[size_t(r)] = w[0];
        right[size_t(n - r)] = w[size_t(n - r)];
    }
}

// Newton's method on the polynomial's values, kept inside [lo, hi] (whose
// ends have opposite signs, loSign at lo), bisecting when a step leaves it.
Quad newtonInside(const Bounded* c, int n, Quad lo, Quad hi, int loSign) {
    Quad x = (lo + hi) / 2;
    for (int iteration = 0; iteration < 200; ++iteration) {
        Quad f = c[n].v, df = 0;
        for (int k = n - 1; k >= 0; --k) {
            df = df * x + f;
            f = f * x + c[k].v;
        }
        if (f == 0) return x;
        ((f > 0 ? 1 : -1) == loSign ? lo : hi) = x;
        Quad next = df != 0 ? x - f / df : (lo + hi) / 2;
        if (!(next > lo && next < hi)) next = (lo + hi) / 2;
        if (abs(next - x) <= ldexp(abs(x) + (hi - lo), -110)) return next;
        x = next;
    }
    return x;
}

// The one root in [lo, hi] (f's sign loSign at lo, the opposite at hi):
// Newton's method on the polynomial brings it to the noise of the power
// basis, a bracket around that is certified by f, and regula falsi on f
// (Illinois) narrows it to f's own noise.
Root refined(const Bounded* c, int n, Quad lo, Quad hi, int loSign, const Quad& span,
             const std::function<Bounded(const Quad&)>& f) {
    if (signOf(f(lo)) != loSign || signOf(f(hi)) != -loSign) return {lo, hi, RootKind::Unresolved};
    const Quad x = newtonInside(c, n, lo, hi, loSign);
    for (Quad delta = ldexp(abs(x) + span, -104); delta < hi - lo; delta *= 256) {
        const Quad l = x - delta > lo ? x - delta : lo, h = x + delta < hi ? x + delta : hi;
        if (signOf(f(l)) == loSign && signOf(f(h)) == -loSign) {
            lo = l;
            hi = h;
            break;
        }
    }
    Quad fLo = f(lo).v, fHi = f(hi).v;
    int kept = 0;  // which end stayed last time (Illinois: halve its value when it stays twice)
    for (int iteration = 0; iteration < 60; ++iteration) {
        if (hi - lo <= ldexp(abs(lo) + abs(hi), -110)) break;
        Quad m = hi - fHi * (hi - lo) / (fHi - fLo);
        if (!(m > lo && m < hi)) m = (lo + hi) / 2;
        const Bounded fm = f(m);
        const int sign = signOf(fm);
        if (sign == 0) {
            // m is within f's noise of the root: the narrowest bracket about
            // it that f certifies (else [lo, hi] stays).
            for (Quad e = ldexp(abs(m) + span, -110); e < (hi - lo) / 2; e *= 16) {
                if (m - e > lo && m + e < hi && signOf(f(m - e)) == loSign &&
                    signOf(f(m + e)) == -loSign) {
                    lo = m - e;
                    hi = m + e;
                    break;
                }
            }
            break;
        }
        if (sign == loSign) {
            lo = m;
            fLo = fm.v;
            if (kept == 1) fHi /= 2;
            kept = 1;
        } else {
            hi = m;
            fHi = fm.v;
            if (kept == -1) fLo /= 2;
            kept = -1;
        }
    }
    return {lo, hi, RootKind::Crossing};
}

}  // namespace

std::vector<Root> polynomialRoots(const Bounded* c, int degree, const Quad& a, const Quad& b,
                                  const std::function<Bounded(const Quad&)>& f) {
    std::vector<Root> roots;
    const Bounded width = Bounded(b) - Bounded(a);
    const Quad t0 = a, span = width.v;
    const auto tAt = [&](const Quad& s) { return s == 1 ? b : t0 + s * span; };
    // A cut a little off the middle, so that a root at a simple number (0,
    // an endpoint's half) never falls on one.
    const Quad cut = Quad(0.5) + ldexp(sqrt(Quad(2)) - 1, -7);
    const Quad narrowest = ldexp(Quad(1), -90);

    struct Piece {
        Quad s0, s1;
        Coefficients beta;
    };
    std::vector<Piece> stack{{0, 1, bernsteinOf(c, degree, a, width)}};
    int looked = 0;
    while (!stack.empty()) {
        const Piece piece = stack.back();
        stack.pop_back();
        if (++looked > kMaxIntervals) {  // nothing excluded: the polynomial is 0 within rounding
            roots.push_back({tAt(piece.s0), b, RootKind::Unresolved});
            break;
        }
        int changes = 0, previous = 0;
        bool allCertain = true;
        for (int i = 0; i <= degree; ++i) {
            const int sign = signOf(piece.beta[size_t(i)]);
            if (sign == 0) {
                allCertain = false;
                continue;
            }
            if (previous != 0 && sign != previous) ++changes;
            previous = sign;
        }
        if (allCertain && changes == 0) continue;  // no root here
        const Quad lo = tAt(piece.s0), hi = tAt(piece.s1);
        if (allCertain && changes == 1) {
            roots.push_back(refined(c, degree, lo, hi, signOf(piece.beta[0]), span, f));
            continue;
        }
        // Every coefficient within its bound of 0: the values here are
        // rounding noise (near a double root, within about the square root of
        // float128's unit of it), and halving cannot tell more.
        bool allNoise = true;
        for (int i = 0; i <= degree; ++i) allNoise = allNoise && signOf(piece.beta[size_t(i)]) == 0;
        if (allNoise || piece.s1 - piece.s0 < narrowest) {
            const int atLo = signOf(f(lo)), atHi = signOf(f(hi));
            const RootKind kind = atLo == 0 || atHi == 0 ? RootKind::Unresolved
                                  : atLo == atHi         ? RootKind::Tangent
                                                         : RootKind::Crossing;
            roots.push_back({lo, hi, kind, true});
            continue;
        }
        Piece left{piece.s0, piece.s0 + cut * (piece.s1 - piece.s0), {}};
        Piece right{left.s1, piece.s1, {}};
        split(piece.beta, degree, cut, left.beta, right.beta);
        stack.push_back(right);
        stack.push_back(left);  // the nearer first
    }
    // Neighbouring pieces of rounding noise are one cluster (a double or
    // triple root), classified again from the signs at its ends.
    std::vector<Root> merged;
    for (const Root& r : roots) {
        if (!merged.empty() && r.unresolvedPiece && merged.back().unresolvedPiece &&
            r.lo <= merged.back().hi) {
            Root& cluster = merged.back();
            cluster.hi = r.hi;
            const int atLo = signOf(f(cluster.lo)), atHi = signOf(f(cluster.hi));
            cluster.kind = atLo == 0 || atHi == 0 ? RootKind::Unresolved
                           : atLo == atHi         ? RootKind::Tangent
                                                  : RootKind::Crossing;
            continue;
        }
        merged.push_back(r);
    }
    return merged;
}

}  // namespace vkray::numerics
