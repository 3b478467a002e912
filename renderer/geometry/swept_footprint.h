#pragma once

#include <vector>

#include <glm/vec2.hpp>

#include "renderer/geometry/convex_polygon.h"

namespace clipblur {

struct PixelWeight {
    int x = 0;
    int y = 0;
    double weight = 0.0;  // covered area, px^2
};

// A translation over an interval, s in [-1/2, 1/2]: the parabola through offset 0 at s = 0 and the
// offsets -chord/2 + bend and chord/2 + bend at the ends. Three exact positions of a point give it; the
// straight chord alone would cut the corner of a curved path (a rolling camera) by `bend`.
// Optionally a stretch about `pivot` (the point the translation is of): per raster axis the factor
// 1 + s stretch_chord + 4 s^2 stretch_bend, the parabola through 1 at s = 0 and the surface's stretch at
// the ends, so a fragment on a surface the camera dollies away from shrinks with it.
struct SweepPath {
    glm::dvec2 chord{0.0};
    glm::dvec2 bend{0.0};
    glm::dvec2 pivot{0.0};
    glm::dvec2 stretch_chord{0.0};
    glm::dvec2 stretch_bend{0.0};

    glm::dvec2 at(double s) const { return s * chord + (4.0 * s * s) * bend; }
    glm::dvec2 stretchAt(double s) const { return glm::dvec2(1.0) + s * stretch_chord + (4.0 * s * s) * stretch_bend; }
    bool moves() const;
    // Farthest offset of the pivot from the start: |chord| / 2 + |bend| bounds it.
    double reach() const;
};

// The pixel coverage of a convex polygon q moving along `path`, averaged over `positions` equally spaced
// times, the midpoints s = (m + 1/2) / positions - 1/2, m = 0 .. positions-1. Appends one entry per
// (position, pixel) with the area of that position's piece in the pixel divided by `positions`; the
// weights sum to area(q). Axis-aligned rectangles (most fragments inside a surface are whole or partial
// pixels) take a separable fast path.
void sweptFootprint(const ConvexPolygon& q, const SweepPath& path, int positions, std::vector<PixelWeight>& out);

}  // namespace clipblur
