#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "scene/shutter_curve.h"

namespace clipblur {

namespace {

Shutter shutterOf(double open, double close, std::vector<ShutterPoint> curve) {
    Shutter s;
    s.open = open;
    s.close = close;
    s.curve = std::move(curve);
    return s;
}

// The curve's integral from open to t by a fine composite midpoint rule over the points themselves,
// sharing no code with ShutterCurve. Its error is at most h^2 / 8 times the slope jump at each of the
// few kinks, below 1e-11 for the curves here at h = 1e-6 frames.
double numericIntegral(const Shutter& s, double t) {
    const auto weight = [&](double x) {
        for (std::size_t i = 0; i + 1 < s.curve.size(); ++i) {
            const ShutterPoint a = s.curve[i], b = s.curve[i + 1];
            if (x <= b.time) return a.weight + (b.weight - a.weight) * (x - a.time) / (b.time - a.time);
        }
        return s.curve.back().weight;
    };
    const int steps = std::max(1, static_cast<int>(std::ceil((t - s.open) / 1e-6)));
    const double h = (t - s.open) / steps;
    double sum = 0.0;
    for (int k = 0; k < steps; ++k) sum += weight(s.open + (k + 0.5) * h);
    return sum * h;
}

}  // namespace

// The stochastic method's and the accumulation buffer's times: timeAt(u) must put a share u of the
// curve's integral before it. Checked against numeric integration of the curve for a triangle, a
// trapezoid and an uneven curve with a closed stretch (weight 0 over [0.1, 0.2]); 1e-9 allows the
// numeric rule's error (above) relative to integrals of order 0.1.
TEST(ShutterCurve, TimeAtInvertsTheNumericIntegralOfTheCurve) {
    const std::vector<Shutter> shutters{
        shutterOf(-0.25, 0.25, {{-0.25, 0.0}, {0.0, 1.0}, {0.25, 0.0}}),
        shutterOf(-0.25, 0.25, {{-0.25, 0.0}, {-0.15, 1.0}, {0.15, 1.0}, {0.25, 0.0}}),
        shutterOf(0.0, 0.6, {{0.0, 2.0}, {0.1, 0.0}, {0.2, 0.0}, {0.35, 3.0}, {0.6, 0.5}}),
    };
    for (const Shutter& s : shutters) {
        const ShutterCurve curve(s, 3);  // frame 3: times are absolute, 3 + the offsets
        EXPECT_FALSE(curve.box());
        const double total = numericIntegral(s, s.close);
        for (double u = 0.0; u <= 1.0; u += 1.0 / 64.0) {
            const double t = curve.timeAt(u);
            ASSERT_GE(t, 3.0 + s.open);
            ASSERT_LE(t, 3.0 + s.close);
            EXPECT_NEAR(numericIntegral(s, t - 3.0) / total, u, 1e-9) << "u " << u << " t " << t;
            EXPECT_NEAR(curve.mass(3.0 + s.open, t), u, 1e-12) << "mass and its inverse agree";
        }
        EXPECT_NEAR(curve.mass(3.0 + s.open, 3.0 + s.close), 1.0, 1e-15);
    }
}

// Equal weights are a box wherever the points are: times linear in u, every piece's mass its length.
TEST(ShutterCurve, EqualWeightsAreABox) {
    const ShutterCurve none(shutterOf(-0.25, 0.25, {}), 0);
    const ShutterCurve flat(shutterOf(-0.25, 0.25, {{-0.25, 2.0}, {0.1, 2.0}, {0.25, 2.0}}), 0);
    EXPECT_TRUE(none.box());
    EXPECT_TRUE(flat.box());
    for (double u : {0.0, 0.125, 0.5, 0.9, 1.0}) {
        EXPECT_DOUBLE_EQ(none.timeAt(u), -0.25 + 0.5 * u);
        EXPECT_DOUBLE_EQ(flat.timeAt(u), -0.25 + 0.5 * u);
    }
    EXPECT_DOUBLE_EQ(flat.mass(-0.25, 0.1), 0.7);
    EXPECT_FALSE(ShutterCurve(shutterOf(0.0, 1.0, {{0.0, 1.0}, {1.0, 1.0 + 1e-12}}), 0).box());
}

// The weight is linear between points and 0 outside the shutter.
TEST(ShutterCurve, WeightIsPiecewiseLinear) {
    const ShutterCurve curve(shutterOf(-0.25, 0.25, {{-0.25, 0.0}, {-0.15, 1.0}, {0.15, 1.0}, {0.25, 0.0}}), 0);
    EXPECT_DOUBLE_EQ(curve.weightAt(-0.2), 0.5);
    EXPECT_DOUBLE_EQ(curve.weightAt(0.0), 1.0);
    EXPECT_DOUBLE_EQ(curve.weightAt(0.2), 0.5);
    EXPECT_EQ(curve.weightAt(0.25), 0.0);
    EXPECT_EQ(curve.weightAt(-0.3), 0.0);
    EXPECT_EQ(curve.weightAt(0.3), 0.0);
    // The trapezoid's integral is (0.5 + 0.3) / 2 = 0.4; its rising ramp holds 0.05 of it.
    EXPECT_NEAR(curve.mass(-0.25, -0.15), 0.05 / 0.4, 1e-15);
}

}  // namespace clipblur
