// The oracle's float128 with error bounds: each bound holds the exact result.
#include "numerics/bounded.h"

#include <gtest/gtest.h>

namespace vkray::numerics {
namespace {

TEST(Bounded, BoundsHoldTheExactResult) {
    // 1/3 * 3 is 1 within its bound, sqrt(2)^2 is 2 within its bound, and
    // each bound is a few float128 units, not more.
    const Bounded third = Bounded(1) / Bounded(3);
    const Bounded one = third * Bounded(3);
    EXPECT_LE(abs(one.v - 1), one.e);
    EXPECT_LT(one.e, 8 * kQuadUnit);
    const Bounded root = sqrt(Bounded(2));
    const Bounded two = root * root;
    EXPECT_LE(abs(two.v - 2), two.e);
    EXPECT_LT(two.e, 16 * kQuadUnit);
}

TEST(Bounded, SignsAreCertainOnlyBeyondTheBound) {
    const Bounded third = Bounded(1) / Bounded(3);
    const Bounded zero = third * Bounded(3) - Bounded(1);  // 0, or a rounding away from it
    EXPECT_FALSE(zero.certain());
    EXPECT_TRUE((Bounded(1) - third * Bounded(2)).positive());
    EXPECT_TRUE((third * Bounded(2) - Bounded(1)).negative());
    // Cancellation keeps the inputs' error: (1e20 + 1) - 1e20 is 1 to within 1e20 units.
    const Bounded big = Bounded(1e20) + Bounded(1);
    const Bounded small = big - Bounded(1e20);
    EXPECT_GE(small.e, Quad(1e20) * kQuadUnit);
    EXPECT_LE(abs(small.v - 1), small.e);
    // Division by an uncertain sign is unbounded.
    EXPECT_TRUE(isinf((Bounded(1) / zero).e));
}

}  // namespace
}  // namespace vkray::numerics
