#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/vec2.hpp>

namespace clipblur::testing {

// An independent reference for convex regions, sharing no code with the kernel under test: the area of
// the intersection of half-planes a*x + b*y + c >= 0, found as the convex hull of every pairwise line
// crossing that satisfies all constraints. O(n^3), exact up to rounding for well-conditioned input.
struct HalfPlane {
    double a, b, c;
};

// The half-plane left of the directed line p -> q (the inside of a counter-clockwise edge).
inline HalfPlane leftOf(const glm::dvec2& p, const glm::dvec2& q) {
    const double a = -(q.y - p.y);
    const double b = q.x - p.x;
    const double norm = std::hypot(a, b);
    return {a / norm, b / norm, -(a * p.x + b * p.y) / norm};
}

inline double hullArea(std::vector<glm::dvec2> pts) {
    if (pts.size() < 3) return 0.0;
    std::sort(pts.begin(), pts.end(), [](const glm::dvec2& u, const glm::dvec2& v) {
        return u.x != v.x ? u.x < v.x : u.y < v.y;
    });
    auto cross = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::dvec2> h(2 * pts.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
        h[k++] = pts[i];
    }
    for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
        h[k++] = pts[i - 1];
    }
    h.resize(k - 1);
    double area = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) {
        const glm::dvec2& p = h[i];
        const glm::dvec2& q = h[(i + 1) % h.size()];
        area += p.x * q.y - q.x * p.y;
    }
    return 0.5 * area;
}

// Constraints should be normalised (unit normal) so the slack is a distance; 1e-12 absorbs the rounding of
// crossings of O(1) coordinates without admitting points measurably outside.
inline double halfPlaneArea(const std::vector<HalfPlane>& hs, double slack = 1e-12) {
    std::vector<glm::dvec2> pts;
    for (std::size_t i = 0; i < hs.size(); ++i) {
        for (std::size_t j = i + 1; j < hs.size(); ++j) {
            const double det = hs[i].a * hs[j].b - hs[i].b * hs[j].a;
            if (std::abs(det) < 1e-14) continue;
            const glm::dvec2 p((hs[i].b * hs[j].c - hs[j].b * hs[i].c) / det,
                               (hs[j].a * hs[i].c - hs[i].a * hs[j].c) / det);
            bool ok = true;
            for (const HalfPlane& h : hs) ok = ok && h.a * p.x + h.b * p.y + h.c >= -slack;
            if (ok) pts.push_back(p);
        }
    }
    return hullArea(pts);
}

// Constraints of a counter-clockwise convex polygon.
inline void appendPolygon(const std::vector<glm::dvec2>& poly, std::vector<HalfPlane>& hs) {
    for (std::size_t i = 0; i < poly.size(); ++i) hs.push_back(leftOf(poly[i], poly[(i + 1) % poly.size()]));
}

}  // namespace clipblur::testing
