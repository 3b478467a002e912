#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/geometry/translating_coverage.h"
#include "support/translating_coverage.h"

namespace clipblur {

namespace {

using Weights = std::map<std::pair<int, int>, double>;

// A random convex polygon: points on a circle of radius r about c at sorted random angles.
SmallPolygon randomConvex(std::mt19937& rng, glm::dvec2 c, double r) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 3 + static_cast<int>(rng() % 8);
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) angles.push_back(2.0 * M_PI * u(rng));
    std::sort(angles.begin(), angles.end());
    SmallPolygon p;
    for (const double a : angles) p.v[p.n++] = c + r * glm::dvec2(std::cos(a), std::sin(a));
    return p;
}

std::vector<glm::dvec2> vertices(const SmallPolygon& p) { return {p.v.begin(), p.v.begin() + p.n}; }

Weights cells(const SmallPolygon& p, glm::dvec2 d, ChordWeight w) {
    Weights out;
    const auto add = [&](int x, int y, double weight) { out[{x, y}] += weight; };
    translatingCells(p, d, w, add);
    return out;
}

}  // namespace

// Against the test oracle (tests/support: its own clip and breakpoint-exact Gauss-Legendre time integral,
// no renderer code), seeded random convex polygons of 3 to 10 vertices and velocities up to 6 px, a third
// of them along one of the polygon's edges (edges parallel to the motion) and one still: every pixel to
// 1e-12 (rounding of cuts on coordinates ~10), and the weights sum to the area.
TEST(TranslatingCells, PolygonMatchesTheOracle) {
    std::mt19937 rng(20261127);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (int trial = 0; trial < 300; ++trial) {
        const SmallPolygon p = randomConvex(rng, glm::dvec2(10.0 + u(rng), 8.0 + u(rng)), 0.3 + 0.6 * std::abs(u(rng)));
        glm::dvec2 d(u(rng), u(rng));
        if (trial % 3 == 0) d = (p.v[1] - p.v[0]) * (u(rng) / glm::length(p.v[1] - p.v[0]));
        if (trial == 1) d = glm::dvec2(0.0);
        const Weights w = cells(p, d, {1.0, 0.0});
        double total = 0.0;
        for (const auto& [pixel, weight] : w) {
            total += weight;
            EXPECT_NEAR(weight, testing::translatingPixelCoverage(vertices(p), d, pixel.first, pixel.second), 1e-12)
                << trial << " pixel " << pixel.first << "," << pixel.second;
        }
        EXPECT_NEAR(total, testing::polygonArea(vertices(p)), 1e-12) << trial;
        // No pixel the oracle covers is missing.
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 20; ++x)
                if (!w.count({x, y})) {
                    EXPECT_LT(testing::translatingPixelCoverage(vertices(p), d, x, y), 1e-12);
                }
    }
}

// A weight linear in time, w0 + w1 u: against the oracle over 400 equal parts of the chord, each weighted
// by the weight at its middle. That sum errs by at most |w1| h^2 / 12 x the largest rate of change of a
// pixel's covered area (<= perimeter x |d| < 40 px^2 here): 1e-5 at h = 1/400. The weights sum to
// area (w0 + w1 / 2) exactly.
TEST(TranslatingCells, LinearWeightInTime) {
    std::mt19937 rng(20261128);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (int trial = 0; trial < 30; ++trial) {
        const SmallPolygon p = randomConvex(rng, glm::dvec2(10.0, 8.0), 0.8);
        const glm::dvec2 d(u(rng), u(rng));
        const ChordWeight weight{0.7, 0.2 * u(rng)};  // positive all chord long, as a shutter's
        const Weights w = cells(p, d, weight);
        double total = 0.0;
        constexpr int kParts = 400;
        for (const auto& [pixel, value] : w) {
            total += value;
            double expected = 0.0;
            for (int k = 0; k < kParts; ++k) {
                std::vector<glm::dvec2> start = vertices(p);
                for (glm::dvec2& v : start) v += (double(k) / kParts) * d;
                const double middle = (k + 0.5) / kParts;
                expected += (weight.w0 + weight.w1 * middle) / kParts *
                            testing::translatingPixelCoverage(start, d / double(kParts), pixel.first, pixel.second);
            }
            EXPECT_NEAR(value, expected, 1e-5) << trial;
        }
        EXPECT_NEAR(total, testing::polygonArea(vertices(p)) * (weight.w0 + 0.5 * weight.w1), 1e-12) << trial;
    }
}

// A rectangle: translating, it is the oracle's answer (1e-12); with its sides moving at different rates (a
// fragment stretching), it is the dense midpoint sum of its exact overlaps (20000 times: each pixel's value
// is piecewise quadratic in u, so the sum errs by at most (slope jump) h^2 / 8 per kink, < 1e-8), and the
// weights sum to the integral of its area, (a + u da)(b + u db) (w0 + w1 u), by Simpson's rule (a cubic).
// Every fourth trial translates 12x as far (up to 36 px, mostly diagonally), where only a band of its
// box's cells is met in time.
TEST(TranslatingCells, MovingRectangle) {
    std::mt19937 rng(20261129);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (int trial = 0; trial < 100; ++trial) {
        const glm::dvec2 lo(10.0 + u(rng), 8.0 + u(rng));
        const glm::dvec2 hi = lo + glm::dvec2(0.2 + std::abs(u(rng)), 0.2 + std::abs(u(rng)));
        const glm::dvec2 d = (trial % 4 == 2 ? 12.0 : 1.0) * glm::dvec2(u(rng), u(rng));
        const bool stretching = trial % 2 == 1;
        const glm::dvec2 dhi = stretching ? d + 0.15 * glm::dvec2(u(rng), u(rng)) : d;
        const ChordWeight weight{1.0, stretching ? 0.3 : 0.0};
        Weights w;
        const auto add = [&](int x, int y, double value) { w[{x, y}] += value; };
        translatingRectangleCells({lo, hi, d, dhi}, weight, add);
        double total = 0.0;
        for (const auto& [pixel, value] : w) {
            total += value;
            const glm::dvec2 cell(pixel.first, pixel.second);
            if (!stretching) {
                const std::vector<glm::dvec2> box{lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
                EXPECT_NEAR(value, testing::translatingPixelCoverage(box, d, pixel.first, pixel.second), 1e-12) << trial;
                continue;
            }
            double expected = 0.0;
            constexpr int kTimes = 20000;
            for (int k = 0; k < kTimes; ++k) {
                const double t = (k + 0.5) / kTimes;
                const glm::dvec2 a = lo + t * d, b = hi + t * dhi;
                const glm::dvec2 overlap = glm::max(glm::min(b, cell + 1.0) - glm::max(a, cell), glm::dvec2(0.0));
                expected += overlap.x * overlap.y * (weight.w0 + weight.w1 * t) / kTimes;
            }
            EXPECT_NEAR(value, expected, 1e-8) << trial;
        }
        const auto area = [&](double t) {
            const glm::dvec2 size = hi - lo + t * (dhi - d);
            return size.x * size.y * (weight.w0 + weight.w1 * t);
        };
        EXPECT_NEAR(total, (area(0.0) + 4.0 * area(0.5) + area(1.0)) / 6.0, 1e-12) << trial;
    }
}

}  // namespace clipblur
