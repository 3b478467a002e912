#include "renderer/geometry/closest_point.h"

#include <array>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace clipblur {

TEST(ClosestPoint, InsideIsItselfOutsideIsOnTheNearestEdgeOrCorner) {
    const std::array<glm::dvec2, 3> t{glm::dvec2(0, 0), glm::dvec2(4, 0), glm::dvec2(0, 3)};
    const std::array<glm::dvec2, 3> flipped{t[0], t[2], t[1]};
    for (const auto& v : {t, flipped}) {
        EXPECT_EQ(closestPointInTriangle(v, {1, 1}), glm::dvec2(1, 1));
        EXPECT_EQ(closestPointInTriangle(v, {2, -5}), glm::dvec2(2, 0));
        EXPECT_EQ(closestPointInTriangle(v, {-2, -2}), glm::dvec2(0, 0));
        EXPECT_EQ(closestPointInTriangle(v, {-1, 1.5}), glm::dvec2(0, 1.5));
        // Beyond the hypotenuse 3x + 4y = 12: the foot of the perpendicular from (4, 3) is (2.56, 1.08).
        const glm::dvec2 foot = closestPointInTriangle(v, {4, 3});
        EXPECT_NEAR(foot.x, 2.56, 1e-12);
        EXPECT_NEAR(foot.y, 1.08, 1e-12);
    }
    // Degenerate: a segment, and a point.
    const std::array<glm::dvec2, 3> segment{glm::dvec2(0, 0), glm::dvec2(2, 0), glm::dvec2(1, 0)};
    EXPECT_EQ(closestPointInTriangle(segment, {1.5, 2}), glm::dvec2(1.5, 0));
    const std::array<glm::dvec2, 3> point{glm::dvec2(1, 1), glm::dvec2(1, 1), glm::dvec2(1, 1)};
    EXPECT_EQ(closestPointInTriangle(point, {5, 5}), glm::dvec2(1, 1));
}

// Seeded triangles and points against a brute force over a 200 x 200 barycentric grid: the answer lies
// in the triangle and no grid point is nearer, and the nearest grid point is at most half a grid cell's
// longer diagonal farther: (|e1| + |e2|) / 400, below the longest edge / 200.
TEST(ClosestPoint, NoPointOfTheTriangleIsNearer) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-5.0, 5.0);
    for (int trial = 0; trial < 40; ++trial) {
        const std::array<glm::dvec2, 3> v{glm::dvec2(u(rng), u(rng)), glm::dvec2(u(rng), u(rng)), glm::dvec2(u(rng), u(rng))};
        const glm::dvec2 x(u(rng), u(rng));
        const glm::dvec2 c = closestPointInTriangle(v, x);
        const double d = glm::length(c - x);
        double nearest = 1e300;
        constexpr int kSteps = 200;
        for (int i = 0; i <= kSteps; ++i)
            for (int j = 0; i + j <= kSteps; ++j) {
                const double s = double(i) / kSteps, t = double(j) / kSteps;
                nearest = std::min(nearest, glm::length(v[0] + s * (v[1] - v[0]) + t * (v[2] - v[0]) - x));
            }
        const double edge = std::max({glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2])});
        EXPECT_LE(d, nearest + 1e-12) << trial;
        EXPECT_GE(d, nearest - edge / kSteps) << trial;
    }
}

}  // namespace clipblur
