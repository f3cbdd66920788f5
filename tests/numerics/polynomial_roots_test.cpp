// The oracle's root finder on polynomials whose roots are known: simple,
// double (tangent), triple, and closer than its resolution; every bracket
// must hold its root.
#include "numerics/polynomial_roots.h"

#include <gtest/gtest.h>

#include <vector>

namespace vkray::numerics {
namespace {

// The coefficients (ascending) of prod (t - r) over the roots.
std::vector<Bounded> withRoots(const std::vector<Quad>& roots) {
    std::vector<Quad> c{1};
    for (const Quad& r : roots) {
        std::vector<Quad> next(c.size() + 1, 0);
        for (size_t i = 0; i < c.size(); ++i) {
            next[i + 1] += c[i];
            next[i] -= r * c[i];
        }
        c = next;
    }
    return {c.begin(), c.end()};
}

std::vector<Root> rootsOf(const std::vector<Quad>& roots, Quad a, Quad b) {
    const std::vector<Bounded> c = withRoots(roots);
    const int degree = int(c.size()) - 1;
    const auto f = [&](const Quad& t) {
        Bounded v = c[size_t(degree)];
        for (int i = degree - 1; i >= 0; --i) v = v * Bounded(t) + c[size_t(i)];
        return v;
    };
    return polynomialRoots(c.data(), degree, a, b, f);
}

// f is the polynomial itself, evaluated from its power-basis coefficients:
// a bracket is as narrow as its rounding lets the sign be told, 1e-28 of the
// root's size here, 1e-20 where the coefficients are large (roots far out)
// or the slope small (roots close together).
void expectBracket(const Root& r, const Quad& root, double relative = 1e-28) {
    EXPECT_LE(r.lo, root) << double(r.lo);
    EXPECT_GE(r.hi, root) << double(r.hi);
    EXPECT_LE(double(r.hi - r.lo), relative * double(abs(root) + 1));
}

TEST(PolynomialRoots, FourSimpleRoots) {
    const std::vector<Root> r = rootsOf({1, 2, 3, 4}, -10, 10);
    ASSERT_EQ(r.size(), 4u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(r[size_t(i)].kind, RootKind::Crossing);
        expectBracket(r[size_t(i)], Quad(i + 1));
    }
}

TEST(PolynomialRoots, ADoubleRootIsATangent) {
    // (t - 1)^2 (t - 3)(t - 4): the double root touches 0 without a sign change.
    const std::vector<Root> r = rootsOf({1, 1, 3, 4}, -10, 10);
    ASSERT_EQ(r.size(), 3u);
    EXPECT_EQ(r[0].kind, RootKind::Tangent);
    EXPECT_LE(r[0].lo, 1);
    EXPECT_GE(r[0].hi, 1);
    // Near a double root the values are below their rounding within about
    // the square root of it: the tangent's bracket.
    EXPECT_LT(double(r[0].hi - r[0].lo), 1e-12);
    EXPECT_EQ(r[1].kind, RootKind::Crossing);
    expectBracket(r[1], 3);
    expectBracket(r[2], 4);
}

TEST(PolynomialRoots, ATripleRootCrosses) {
    const std::vector<Root> r = rootsOf({2, 2, 2, 5}, -10, 10);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].kind, RootKind::Crossing);  // odd multiplicity: a sign change
    EXPECT_LE(r[0].lo, 2);
    EXPECT_GE(r[0].hi, 2);
    EXPECT_LT(double(r[0].hi - r[0].lo), 1e-8);  // about the cube root of the rounding
    expectBracket(r[1], 5);
}

TEST(PolynomialRoots, CloseRootsResolvedOrCalledTangent) {
    // 1e-12 apart: two crossings. 1e-20 apart, below the resolution of the
    // polynomial's values near them (~sqrt(u) = 1e-17): one tangent.
    const Quad near = 1 + Quad(1e-12);
    std::vector<Root> r = rootsOf({1, near}, -4, 4);
    ASSERT_EQ(r.size(), 2u);
    expectBracket(r[0], 1, 1e-20);
    expectBracket(r[1], near, 1e-20);
    r = rootsOf({1, 1 + Quad(1e-20)}, -4, 4);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].kind, RootKind::Tangent);
    EXPECT_LE(r[0].lo, 1);
    EXPECT_GE(r[0].hi, 1 + Quad(1e-20));
}

TEST(PolynomialRoots, NoRootAndRootsOutsideTheInterval) {
    EXPECT_TRUE(rootsOf({5, 6}, -1, 1).empty());
    // t^2 + 1 has no real root.
    const Bounded c[3] = {Bounded(1), Bounded(0), Bounded(1)};
    const auto f = [&](const Quad& t) { return Bounded(t) * Bounded(t) + Bounded(1); };
    EXPECT_TRUE(polynomialRoots(c, 2, -100, 100, f).empty());
}

TEST(PolynomialRoots, FarRootsOfAShiftedQuartic) {
    // Roots near 1e3 found on [-2e3, 2e3], as the torus from afar has them.
    const std::vector<Root> r = rootsOf({998.75, 999.25, 1000.75, 1001.25}, -2000, 2000);
    ASSERT_EQ(r.size(), 4u);
    expectBracket(r[0], Quad(998.75), 1e-20);
    expectBracket(r[3], Quad(1001.25), 1e-20);
}

}  // namespace
}  // namespace vkray::numerics
