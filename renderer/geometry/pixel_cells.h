#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include "renderer/geometry/convex_polygon.h"
#include "scene/pixel_bounds.h"

namespace clipblur {

struct PixelWeight {
    int x = 0;
    int y = 0;
    double weight = 0.0;  // covered area, px^2
};

// Overlaps of [lo, hi] with the unit cells [c, c + 1]: calls add(c, length) for each cell it meets.
template <class Add>
void cellOverlaps(double lo, double hi, Add&& add) {
    const int c0 = static_cast<int>(std::floor(lo));
    const int c1 = std::max(c0, static_cast<int>(std::ceil(hi)) - 1);
    for (int c = c0; c <= c1; ++c) {
        const double length = std::min(hi, c + 1.0) - std::max(lo, static_cast<double>(c));
        if (length > 0.0) add(c, length);
    }
}

// A small polygon for the per-position cuts: cheaper to copy than ConvexPolygon's full capacity. A
// convex polygon of n vertices cut by axis lines stays within n + 4 vertices.
struct SmallPolygon {
    std::array<glm::dvec2, kMaxStoredVertices + 8> v;
    int n = 0;
};

// Splits p along the line coordinate `axis` = c into the part below (< c) and the part above, in one
// pass: each vertex goes to its side, each crossing point (placed on the line exactly) to both.
inline void splitAxis(const SmallPolygon& p, int axis, double c, SmallPolygon& below, SmallPolygon& above) {
    below.n = 0;
    above.n = 0;
    for (int i = 0; i < p.n; ++i) {
        const glm::dvec2& a = p.v[i];
        const glm::dvec2& b = p.v[i + 1 == p.n ? 0 : i + 1];
        const double sa = a[axis] - c, sb = b[axis] - c;
        if (sa <= 0.0) below.v[below.n++] = a;
        if (sa >= 0.0) above.v[above.n++] = a;
        if ((sa > 0.0 && sb < 0.0) || (sa < 0.0 && sb > 0.0)) {
            glm::dvec2 x = a + (sa / (sa - sb)) * (b - a);
            x[axis] = c;  // on the cut line exactly
            below.v[below.n++] = x;
            above.v[above.n++] = x;
        }
    }
}

inline double area(const SmallPolygon& p) {
    double twice = 0.0;
    for (int i = 1; i + 1 < p.n; ++i) {
        const glm::dvec2 e1 = p.v[i] - p.v[0], e2 = p.v[i + 1] - p.v[0];
        twice += e1.x * e2.y - e1.y * e2.x;
    }
    return 0.5 * std::abs(twice);
}

// Every cell, for the unclipped forms below.
inline const PixelBounds kAllCells = PixelBounds::corners(std::numeric_limits<int>::min() / 2, std::numeric_limits<int>::min() / 2,
                                                          std::numeric_limits<int>::max() / 2, std::numeric_limits<int>::max() / 2);

namespace cells_detail {

// Cuts p at the cell boundaries along `axis` (0: x, 1: y) within [c0, c1): once where it enters, then one
// split per boundary; calls piece(c, part) for each cell c whose part has three or more vertices.
// Coordinates are clamped as doubles before the cast, so a vertex far beyond int's range (near the camera
// plane) is never cast.
template <class Piece>
void cutCells(const SmallPolygon& p, int axis, int c0, int c1, Piece&& piece) {
    double lo = p.v[0][axis], hi = lo;
    for (int i = 1; i < p.n; ++i) {
        lo = std::min(lo, p.v[i][axis]);
        hi = std::max(hi, p.v[i][axis]);
    }
    const double all_first = std::floor(lo), all_last = std::max(all_first, std::ceil(hi) - 1.0);  // one cell where lo = hi
    const double first = std::max(all_first, static_cast<double>(c0)), last = std::min(all_last, static_cast<double>(c1) - 1.0);
    if (last < first) return;
    const int f = static_cast<int>(first), l = static_cast<int>(last);
    SmallPolygon rest[2], part, inside;
    const SmallPolygon* ahead = &p;
    if (first > all_first) {
        splitAxis(p, axis, f, part, inside);
        ahead = &inside;
    }
    for (int c = f; c <= l; ++c) {
        const SmallPolygon* here = ahead;
        if (c < l || last < all_last) {
            splitAxis(*ahead, axis, c + 1.0, part, rest[c & 1]);
            here = &part;
            ahead = &rest[c & 1];
        }
        if (here->n >= 3) piece(c, *here);
    }
}

}  // namespace cells_detail

// Exact pixel pieces of a convex polygon in the cells of `clip`: chopped into columns, each column over its
// own rows into cells, one split per cell boundary; calls add(x, y, piece) for each piece with three or
// more vertices. Cells outside `clip` are never cut, so a polygon far larger than the pixels wanted (a
// surface near the camera plane) costs what those cost.
template <class Add>
void polygonPieces(const SmallPolygon& p, const PixelBounds& clip, Add&& add) {
    cells_detail::cutCells(p, 0, clip.x0, clip.x1, [&](int x, const SmallPolygon& column) {
        cells_detail::cutCells(column, 1, clip.y0, clip.y1, [&](int y, const SmallPolygon& cell) { add(x, y, cell); });
    });
}

template <class Add>
void polygonPieces(const SmallPolygon& p, Add&& add) {
    polygonPieces(p, kAllCells, add);
}

// The area of each pixel piece of p in `clip` (polygonPieces) times scale: add(x, y, weight) where positive.
template <class Add>
void polygonCells(const SmallPolygon& p, const PixelBounds& clip, double scale, Add&& add) {
    polygonPieces(p, clip, [&](int x, int y, const SmallPolygon& piece) {
        const double a = area(piece);
        if (a > 0.0) add(x, y, a * scale);
    });
}

template <class Add>
void polygonCells(const SmallPolygon& p, double scale, Add&& add) {
    polygonCells(p, kAllCells, scale, add);
}

}  // namespace clipblur
