#include "support/translating_coverage.h"

#include <algorithm>
#include <cmath>

namespace clipblur::testing {

double polygonArea(std::span<const glm::dvec2> polygon) {
    double twice = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2& a = polygon[i];
        const glm::dvec2& b = polygon[(i + 1) % polygon.size()];
        twice += a.x * b.y - a.y * b.x;
    }
    return 0.5 * std::abs(twice);
}

namespace {

// Keeps the part of the polygon where sign * (p[axis] - bound) <= 0.
std::vector<glm::dvec2> clipHalfPlane(const std::vector<glm::dvec2>& in, int axis, double bound, double sign) {
    std::vector<glm::dvec2> out;
    if (in.empty()) return out;
    auto inside = [&](const glm::dvec2& p) { return sign * (p[axis] - bound) <= 0.0; };
    for (std::size_t i = 0; i < in.size(); ++i) {
        const glm::dvec2& a = in[i];
        const glm::dvec2& b = in[(i + 1) % in.size()];
        const bool a_in = inside(a);
        const bool b_in = inside(b);
        if (a_in) out.push_back(a);
        if (a_in != b_in) {
            const double s = (bound - a[axis]) / (b[axis] - a[axis]);
            glm::dvec2 x = a + s * (b - a);
            x[axis] = bound;
            out.push_back(x);
        }
    }
    return out;
}

}  // namespace

std::vector<glm::dvec2> clipToBox(std::span<const glm::dvec2> polygon, const glm::dvec2& lo, const glm::dvec2& hi) {
    std::vector<glm::dvec2> p(polygon.begin(), polygon.end());
    p = clipHalfPlane(p, 0, lo.x, -1.0);
    p = clipHalfPlane(p, 0, hi.x, 1.0);
    p = clipHalfPlane(p, 1, lo.y, -1.0);
    p = clipHalfPlane(p, 1, hi.y, 1.0);
    return p;
}

double translatingCoverage(std::span<const glm::dvec2> polygon, const glm::dvec2& v, const glm::dvec2& lo,
                           const glm::dvec2& hi) {
    std::vector<double> breaks = {0.0, 1.0};
    auto addBreak = [&](double s) {
        if (std::isfinite(s) && s > 0.0 && s < 1.0) breaks.push_back(s);
    };
    // Polygon vertices crossing the box's edge lines.
    for (const glm::dvec2& p : polygon) {
        for (int axis = 0; axis < 2; ++axis) {
            if (v[axis] == 0.0) continue;
            addBreak((lo[axis] - p[axis]) / v[axis]);
            addBreak((hi[axis] - p[axis]) / v[axis]);
        }
    }
    // Box corners crossing polygon edge lines: cross(b - a, c - (a + s v)) = 0.
    const glm::dvec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
    auto cross = [](const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; };
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2& a = polygon[i];
        const glm::dvec2 e = polygon[(i + 1) % polygon.size()] - a;
        const double rate = cross(e, v);
        if (rate == 0.0) continue;
        for (const glm::dvec2& c : corners) addBreak(cross(e, c - a) / rate);
    }
    std::sort(breaks.begin(), breaks.end());

    const double gx = std::sqrt(0.6);
    const double nodes[3] = {-gx, 0.0, gx};
    const double weights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    std::vector<glm::dvec2> moved(polygon.size());
    double integral = 0.0;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
        const double a = breaks[k];
        const double h = breaks[k + 1] - a;
        if (h <= 0.0) continue;
        for (int g = 0; g < 3; ++g) {
            const double s = a + 0.5 * h * (1.0 + nodes[g]);
            for (std::size_t i = 0; i < polygon.size(); ++i) moved[i] = polygon[i] + s * v;
            integral += 0.5 * h * weights[g] * polygonArea(clipToBox(moved, lo, hi));
        }
    }
    return integral / ((hi.x - lo.x) * (hi.y - lo.y));
}

}  // namespace clipblur::testing
