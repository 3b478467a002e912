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

// The cells [first, last] of [lo, hi] (one cell where lo = hi) that lie in [c0, c1); last < first when
// none do. Clamped as doubles, so coordinates far beyond int's range (a vertex near the camera plane)
// are never cast.
struct CellSpan {
    double first, last;  // in the clip
    bool cut_below, cut_above;  // the polygon goes on past first and past last + 1
};
inline CellSpan cellSpan(double lo, double hi, int c0, int c1) {
    const double all_first = std::floor(lo), all_last = std::max(all_first, std::ceil(hi) - 1.0);
    const double first = std::max(all_first, static_cast<double>(c0)), last = std::min(all_last, static_cast<double>(c1) - 1.0);
    return {first, last, first > all_first, last < all_last};
}

// The cells y of column x of a polygon (already cut to that column), one split per cell boundary.
template <class Add>
void columnPieces(const SmallPolygon& col, int x, const PixelBounds& clip, Add&& add) {
    double lo = col.v[0].y, hi = lo;
    for (int i = 1; i < col.n; ++i) {
        lo = std::min(lo, col.v[i].y);
        hi = std::max(hi, col.v[i].y);
    }
    const CellSpan rows = cellSpan(lo, hi, clip.y0, clip.y1);
    if (rows.last < rows.first) return;
    const int y0 = static_cast<int>(rows.first), y1 = static_cast<int>(rows.last);
    SmallPolygon cells[2], cell, inside;
    const SmallPolygon* above = &col;
    if (rows.cut_below) {
        splitAxis(col, 1, y0, cell, inside);
        above = &inside;
    }
    for (int y = y0; y <= y1; ++y) {
        const SmallPolygon* c = above;
        if (y < y1 || rows.cut_above) {
            splitAxis(*above, 1, y + 1.0, cell, cells[y & 1]);
            c = &cell;
            above = &cells[y & 1];
        }
        if (c->n >= 3) add(x, y, *c);
    }
}

}  // namespace cells_detail

// Exact pixel pieces of a convex polygon in the cells of `clip`: cut where it leaves clip's columns, then
// chopped into columns, each column over its own rows into cells, one split per cell boundary; calls
// add(x, y, piece) for each piece with three or more vertices. Cells outside `clip` are never cut, so a
// polygon far larger than the pixels wanted (a surface near the camera plane) costs what those cost.
template <class Add>
void polygonPieces(const SmallPolygon& p, const PixelBounds& clip, Add&& add) {
    double lo = p.v[0].x, hi = lo;
    for (int i = 1; i < p.n; ++i) {
        lo = std::min(lo, p.v[i].x);
        hi = std::max(hi, p.v[i].x);
    }
    const cells_detail::CellSpan columns = cells_detail::cellSpan(lo, hi, clip.x0, clip.x1);
    if (columns.last < columns.first) return;
    const int x0 = static_cast<int>(columns.first), x1 = static_cast<int>(columns.last);
    SmallPolygon rest[2], column, inside;
    const SmallPolygon* right = &p;
    if (columns.cut_below) {
        splitAxis(p, 0, x0, column, inside);
        right = &inside;
    }
    for (int x = x0; x <= x1; ++x) {
        const SmallPolygon* col = right;
        if (x < x1 || columns.cut_above) {
            splitAxis(*right, 0, x + 1.0, column, rest[x & 1]);
            col = &column;
            right = &rest[x & 1];
        }
        if (col->n >= 3) cells_detail::columnPieces(*col, x, clip, add);
    }
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
