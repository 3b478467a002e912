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

// The pixel coverage of a convex polygon q moving by d over an interval, averaged over `positions`
// equally spaced times: q + s d at the midpoints s = (m + 1/2) / positions - 1/2, m = 0 .. positions-1,
// so the positions are centred on q itself. Appends one entry per (position, pixel) with the area of that
// position's piece in the pixel divided by `positions`; the weights sum to area(q). Axis-aligned
// rectangles (most fragments inside a surface are whole or partial pixels) take a separable fast path.
void sweptFootprint(const ConvexPolygon& q, const glm::dvec2& d, int positions, std::vector<PixelWeight>& out);

}  // namespace clipblur
