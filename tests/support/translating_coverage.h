#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace clipblur::testing {

// Exactness oracle for motion-blurred coverage, deliberately sharing no code with the renderer.

// Area of a simple polygon (either orientation).
double polygonArea(std::span<const glm::dvec2> polygon);

// Sutherland-Hodgman clip of a convex polygon to the box [lo, hi].
std::vector<glm::dvec2> clipToBox(std::span<const glm::dvec2> polygon, const glm::dvec2& lo, const glm::dvec2& hi);

// Time-averaged coverage of the box [lo, hi] by the convex polygon P translating to P + v over the
// shutter: integral over s in [0, 1] of area(box and (P + s v)) ds, divided by the box area.
// Between breakpoints (a polygon vertex crossing a box edge line, or a box corner crossing a polygon edge
// line) the clipped polygon keeps its combinatorics and its vertices move linearly, so the area is a
// quadratic in s and Gauss-Legendre with 3 points per interval is exact.
double translatingCoverage(std::span<const glm::dvec2> polygon, const glm::dvec2& velocity, const glm::dvec2& lo,
                           const glm::dvec2& hi);

// The unit pixel with corner (x, y).
inline double translatingPixelCoverage(std::span<const glm::dvec2> polygon, const glm::dvec2& velocity, int x, int y) {
    return translatingCoverage(polygon, velocity, glm::dvec2(x, y), glm::dvec2(x + 1, y + 1));
}

}  // namespace clipblur::testing
