#pragma once

#include <cmath>

#include <glm/vec2.hpp>

namespace clipblur {

// a*b - c*d with about one rounding error instead of the catastrophic cancellation of the naive form:
// the rounding error of c*d is recovered exactly by an FMA and added back (Kahan's algorithm).
inline double differenceOfProducts(double a, double b, double c, double d) {
    const double cd = c * d;
    const double err = std::fma(-c, d, cd);
    const double dop = std::fma(a, b, -cd);
    return dop + err;
}

// Twice the signed area of triangle (a, b, c): positive when c lies to the left of a->b (counter-clockwise
// in a y-up frame). When the coordinate differences are exact (e.g. nearby points), the sign is exact.
inline double orient2d(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    return differenceOfProducts(b.x - a.x, c.y - a.y, b.y - a.y, c.x - a.x);
}

// Neumaier's compensated summation: area sums over many tiny pieces stay accurate to a few ulps.
class CompensatedSum {
public:
    void add(double x) {
        const double t = sum_ + x;
        if (std::abs(sum_) >= std::abs(x)) {
            comp_ += (sum_ - t) + x;
        } else {
            comp_ += (x - t) + sum_;
        }
        sum_ = t;
    }
    double value() const { return sum_ + comp_; }

private:
    double sum_ = 0.0;
    double comp_ = 0.0;
};

}  // namespace clipblur
