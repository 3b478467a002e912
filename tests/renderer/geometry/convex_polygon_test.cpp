#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "renderer/geometry/convex_polygon.h"
#include "renderer/geometry/predicates.h"
#include "tests/renderer/geometry/halfplane_oracle.h"

namespace clipblur {

namespace {

ConvexPolygon box(double x0, double y0, double x1, double y1) {
    ConvexPolygon p;
    p.push({x0, y0});
    p.push({x1, y0});
    p.push({x1, y1});
    p.push({x0, y1});
    return p;
}

std::vector<glm::dvec2> verts(const ConvexPolygon& p) { return {p.v.begin(), p.v.begin() + p.n}; }

ConvexPolygon randomTriangle(std::mt19937_64& rng, double lo, double hi) {
    std::uniform_real_distribution<double> u(lo, hi);
    return ConvexPolygon::triangle({u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)});
}

}  // namespace

TEST(ConvexPolygon, AreaOfBoxAndTriangle) {
    EXPECT_DOUBLE_EQ(box(1000.25, 2000.5, 1001.0, 2001.0).area(), 0.375);
    // Clockwise input is reoriented.
    EXPECT_DOUBLE_EQ(ConvexPolygon::triangle({0, 0}, {0, 2}, {3, 0}).area(), 3.0);
}

TEST(ConvexPolygon, SplitByValuesTilesThePolygon) {
    const ConvexPolygon sq = box(0, 0, 1, 1);
    // s = x - 0.3 (affine, sampled at the vertices).
    std::array<double, 4> s{};
    for (int i = 0; i < 4; ++i) s[i] = sq.v[i].x - 0.3;
    ConvexPolygon in, out;
    splitByValues(sq, s.data(), in, out);
    EXPECT_NEAR(in.area(), 0.7, 1e-15);
    EXPECT_NEAR(out.area(), 0.3, 1e-15);
}

TEST(ConvexPolygon, SplitByConvexOfOverlappingBoxes) {
    std::vector<ConvexPolygon> outside;
    ConvexPolygon inside;
    ASSERT_TRUE(splitByConvex(box(0, 0, 2, 2), box(1, 1, 3, 3), outside, inside));
    double out_area = 0.0;
    for (const auto& o : outside) out_area += o.area();
    EXPECT_DOUBLE_EQ(inside.area(), 1.0);
    EXPECT_DOUBLE_EQ(out_area, 3.0);
    outside.clear();
    EXPECT_FALSE(splitByConvex(box(0, 0, 1, 1), box(2, 0, 3, 1), outside, inside));
    EXPECT_TRUE(inside.degenerate());
    ASSERT_EQ(outside.size(), 1u);
}

TEST(ConvexPolygon, IntersectionMatchesHalfPlaneOracle) {
    std::mt19937_64 rng(4);
    for (int i = 0; i < 2000; ++i) {
        const ConvexPolygon a = randomTriangle(rng, 0.0, 1.0);
        const ConvexPolygon b = randomTriangle(rng, 0.0, 1.0);
        ConvexPolygon got;
        intersect(a, b, got);
        std::vector<testing::HalfPlane> hs;
        testing::appendPolygon(verts(a), hs);
        testing::appendPolygon(verts(b), hs);
        // Coordinates O(1): both computations are within ~1e-14; 1e-11 allows ill-conditioned crossings.
        ASSERT_NEAR(got.area(), testing::halfPlaneArea(hs), 1e-11) << i;

        // Split conserves area: (a \ b) + (a ∩ b) == a.
        std::vector<ConvexPolygon> outside;
        ConvexPolygon inside;
        splitByConvex(a, b, outside, inside);
        CompensatedSum sum;
        sum.add(inside.area());
        for (const auto& o : outside) sum.add(o.area());
        ASSERT_NEAR(sum.value(), a.area(), 1e-14) << i;
    }
}

TEST(ConvexPolygon, SplitToCapacityOfRegularPolygon) {
    const int n = 29;
    ConvexPolygon p;
    for (int i = 0; i < n; ++i) {
        const double t = 2.0 * std::numbers::pi * i / n;
        p.push({std::cos(t), std::sin(t)});
    }
    std::vector<ConvexPolygon> parts;
    splitToCapacity(p, kMaxStoredVertices, parts);
    CompensatedSum sum;
    for (const auto& part : parts) {
        EXPECT_LE(part.n, kMaxStoredVertices);
        EXPECT_GT(part.area(), 0.0);
        sum.add(part.area());
    }
    EXPECT_NEAR(sum.value(), 0.5 * n * std::sin(2.0 * std::numbers::pi / n), 1e-14);
}

}  // namespace clipblur
