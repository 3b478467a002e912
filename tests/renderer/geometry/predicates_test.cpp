#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "renderer/geometry/predicates.h"

namespace clipblur {

namespace {

__extension__ typedef __int128 Int128;  // GCC/Clang extension, test-only exact oracle

// Exact orientation of points on the 2^-30 grid with |coord| < 2^20: scaled to 50-bit integers the
// cross product fits in 128 bits.
int exactOrientSign(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    auto fix = [](double v) { return static_cast<Int128>(std::ldexp(v, 30)); };
    const Int128 bx = fix(b.x) - fix(a.x), by = fix(b.y) - fix(a.y);
    const Int128 cx = fix(c.x) - fix(a.x), cy = fix(c.y) - fix(a.y);
    const Int128 det = bx * cy - by * cx;
    return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

int sign(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

}  // namespace

TEST(Predicates, DifferenceOfProductsRecoversCancelledBits) {
    // (1 + 2^-30)^2 - (1 + 2^-29) = 2^-60 exactly; the naive product rounds the 2^-60 term away.
    const double a = 1.0 + std::ldexp(1.0, -30);
    const double c = 1.0 + std::ldexp(1.0, -29);
    EXPECT_EQ(differenceOfProducts(a, a, c, 1.0), std::ldexp(1.0, -60));
}

TEST(Predicates, SliverOrientationMatchesExactArithmetic) {
    std::mt19937_64 rng(20040612);
    std::uniform_real_distribution<double> pos(-1000.0, 1000.0);
    std::uniform_int_distribution<int> offset(-3, 3);
    auto grid = [](double v) { return std::ldexp(std::round(std::ldexp(v, 30)), -30); };
    int nonzero = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::dvec2 a(grid(pos(rng)), grid(pos(rng)));
        const glm::dvec2 b(grid(pos(rng)), grid(pos(rng)));
        // c near the line a-b: a grid point at parameter t, nudged by a few grid units (~1e-9 px).
        const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const glm::dvec2 c(grid(a.x + t * (b.x - a.x)) + std::ldexp(offset(rng), -30),
                           grid(a.y + t * (b.y - a.y)) + std::ldexp(offset(rng), -30));
        const int expected = exactOrientSign(a, b, c);
        nonzero += expected != 0;
        ASSERT_EQ(sign(orient2d(a, b, c)), expected) << i;
        ASSERT_EQ(sign(orient2d(b, c, a)), expected) << i;
        ASSERT_EQ(sign(orient2d(b, a, c)), -expected) << i;
    }
    EXPECT_GT(nonzero, 10000);
}

TEST(Predicates, CompensatedSumKeepsSmallTerms) {
    CompensatedSum sum;
    sum.add(1.0);
    for (int i = 0; i < 1000000; ++i) sum.add(1e-16);
    // The naive sum stays exactly 1.0; the exact answer is 1 + 1e-10, representable to 1 ulp.
    EXPECT_NEAR(sum.value(), 1.0 + 1e-10, 4e-16);
}

}  // namespace clipblur
