#include "renderer/geometry/closest_point.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "renderer/geometry/predicates.h"

namespace clipblur {

namespace {

glm::dvec2 closestOnSegment(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& x) {
    const glm::dvec2 e = b - a;
    const double length2 = glm::dot(e, e);
    if (!(length2 > 0.0)) return a;
    return a + std::clamp(glm::dot(x - a, e) / length2, 0.0, 1.0) * e;
}

}  // namespace

glm::dvec2 closestPointInTriangle(const std::array<glm::dvec2, 3>& v, const glm::dvec2& x) {
    const double area = orient2d(v[0], v[1], v[2]);
    if (area != 0.0) {
        const double s0 = orient2d(v[0], v[1], x), s1 = orient2d(v[1], v[2], x), s2 = orient2d(v[2], v[0], x);
        const bool inside = area > 0.0 ? (s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) : (s0 <= 0.0 && s1 <= 0.0 && s2 <= 0.0);
        if (inside) return x;
    }
    glm::dvec2 best = closestOnSegment(v[0], v[1], x);
    for (int i = 1; i < 3; ++i) {
        const glm::dvec2 c = closestOnSegment(v[static_cast<std::size_t>(i)], v[static_cast<std::size_t>((i + 1) % 3)], x);
        if (glm::length(c - x) < glm::length(best - x)) best = c;
    }
    return best;
}

}  // namespace clipblur
