#include "support/translating_coverage.h"

#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace clipblur::testing {
namespace {

std::vector<glm::dvec2> square(double x, double y, double side) {
    return {{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}};
}

TEST(TranslatingCoverage, StaticPolygonIsClippedArea) {
    const std::vector<glm::dvec2> tri = {{0, 0}, {1, 0}, {0, 1}};
    EXPECT_NEAR(translatingPixelCoverage(tri, {0, 0}, 0, 0), 0.5, 1e-15);
    // The half-plane x + y <= 2 holds the whole pixel (0, 0) and half of pixel (1, 0).
    const std::vector<glm::dvec2> big = {{0, 0}, {2, 0}, {0, 2}};
    EXPECT_NEAR(translatingPixelCoverage(big, {0, 0}, 0, 0), 1.0, 1e-15);
    EXPECT_NEAR(translatingPixelCoverage(big, {0, 0}, 1, 0), 0.5, 1e-15);
    EXPECT_NEAR(translatingPixelCoverage(big, {0, 0}, 1, 1), 0.0, 1e-15);
}

TEST(TranslatingCoverage, UnitSquareSlidingOnePixelRight) {
    // area(s) = 1 - s, average 1/2; the neighbour pixel gets area s, average 1/2.
    const auto sq = square(0, 0, 1);
    EXPECT_NEAR(translatingPixelCoverage(sq, {1, 0}, 0, 0), 0.5, 1e-14);
    EXPECT_NEAR(translatingPixelCoverage(sq, {1, 0}, 1, 0), 0.5, 1e-14);
    EXPECT_NEAR(translatingPixelCoverage(sq, {1, 0}, 0, 1), 0.0, 1e-14);
}

TEST(TranslatingCoverage, UnitSquareSlidingTwoPixels) {
    // area(s) = max(0, 1 - 2s): the integral is 1/4. Neighbour: 2s then 2 - 2s, integral 1/2.
    const auto sq = square(0, 0, 1);
    EXPECT_NEAR(translatingPixelCoverage(sq, {2, 0}, 0, 0), 0.25, 1e-14);
    EXPECT_NEAR(translatingPixelCoverage(sq, {2, 0}, 1, 0), 0.5, 1e-14);
    EXPECT_NEAR(translatingPixelCoverage(sq, {2, 0}, 2, 0), 0.25, 1e-14);
}

TEST(TranslatingCoverage, DiagonalSlideIsQuadratic) {
    // area(s) = (1 - s)^2, integral 1/3; the diagonal neighbour gets s^2, also 1/3.
    const auto sq = square(0, 0, 1);
    EXPECT_NEAR(translatingPixelCoverage(sq, {1, 1}, 0, 0), 1.0 / 3.0, 1e-14);
    EXPECT_NEAR(translatingPixelCoverage(sq, {1, 1}, 1, 1), 1.0 / 3.0, 1e-14);
    // Side neighbours: (1 - s) s each, integral 1/6.
    EXPECT_NEAR(translatingPixelCoverage(sq, {1, 1}, 1, 0), 1.0 / 6.0, 1e-14);
}

TEST(TranslatingCoverage, TriangleEdgeSweepsCornerAtAnAngle) {
    // Half-plane y <= x (a big triangle) moving up by 1: the pixel part below y = x - s has area
    // (1 - s)^2 / 2, integral 1/6. The edge line passes the pixel corners at s = 0 and s = 1 only.
    const std::vector<glm::dvec2> tri = {{-10, -10}, {10, -10}, {10, 10}};
    EXPECT_NEAR(translatingPixelCoverage(tri, {0, -1}, 0, 0), 1.0 / 6.0, 1e-14);
    // Moving right by 0.5: region y <= x - s/2, area (1 - s/2)^2 / 2, integral 7/24.
    EXPECT_NEAR(translatingPixelCoverage(tri, {0.5, 0}, 0, 0), 7.0 / 24.0, 1e-14);
}

TEST(TranslatingCoverage, RandomisedAgainstMonteCarlo) {
    // Brute force in (x, y, s): the fraction of uniform samples inside the moving polygon. With 400k samples
    // the standard error is at most 0.5 / sqrt(4e5) < 8e-4; the tolerance 4e-3 is five standard errors.
    std::mt19937_64 rng(20040612);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_real_distribution<double> coord(-1.0, 2.0);
    std::uniform_real_distribution<double> vel(-3.0, 3.0);
    auto inside = [](const std::vector<glm::dvec2>& poly, const glm::dvec2& p) {
        // Convex, counter-clockwise: left of every edge.
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const glm::dvec2 a = poly[i];
            const glm::dvec2 e = poly[(i + 1) % poly.size()] - a;
            if (e.x * (p.y - a.y) - e.y * (p.x - a.x) < 0.0) return false;
        }
        return true;
    };
    for (int trial = 0; trial < 12; ++trial) {
        std::vector<glm::dvec2> tri = {{coord(rng), coord(rng)}, {coord(rng), coord(rng)}, {coord(rng), coord(rng)}};
        const glm::dvec2 e1 = tri[1] - tri[0];
        const glm::dvec2 e2 = tri[2] - tri[0];
        if (e1.x * e2.y - e1.y * e2.x < 0.0) std::swap(tri[1], tri[2]);
        const glm::dvec2 v(vel(rng), vel(rng));
        const int samples = 400000;
        int hits = 0;
        for (int i = 0; i < samples; ++i) {
            const glm::dvec2 p(u(rng), u(rng));
            const double s = u(rng);
            if (inside(tri, p - s * v)) ++hits;
        }
        const double brute = static_cast<double>(hits) / samples;
        EXPECT_NEAR(translatingPixelCoverage(tri, v, 0, 0), brute, 4e-3) << "trial " << trial;
    }
}

TEST(TranslatingCoverage, PolygonPassingThroughPixel) {
    // Unit square from x in [-1, 0] to [1, 2]: overlap 2s then 2 - 2s, average 1/2.
    EXPECT_NEAR(translatingPixelCoverage(square(-1, 0, 1), {2, 0}, 0, 0), 0.5, 1e-14);
    // A 0.5 x 0.5 square crossing the pixel with v = (3, 0): its overlap width ramps 0 -> 0.5 over
    // s in [1/6, 1/3], stays 0.5 until 1/2 and ramps down by 2/3: width integral 1/6, times height 1/2.
    EXPECT_NEAR(translatingPixelCoverage(square(-1, 0.25, 0.5), {3, 0}, 0, 0), 1.0 / 12.0, 1e-14);
}

TEST(TranslatingCoverage, ClipToBoxKeepsInsidePolygon) {
    const auto sq = square(0.25, 0.25, 0.5);
    EXPECT_NEAR(polygonArea(clipToBox(sq, {0, 0}, {1, 1})), 0.25, 1e-15);
    EXPECT_TRUE(clipToBox(sq, {2, 2}, {3, 3}).empty());
}

}  // namespace
}  // namespace clipblur::testing
