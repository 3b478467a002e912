#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include "renderer/geometry/convex_polygon.h"

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

// Exact pixel pieces of a convex polygon: chopped into columns, each column into cells, one split per
// cell boundary; calls add(x, y, piece) for each piece with three or more vertices.
template <class Add>
void polygonPieces(const SmallPolygon& p, Add&& add) {
    glm::dvec2 lo = p.v[0], hi = p.v[0];
    for (int i = 1; i < p.n; ++i) {
        lo = glm::min(lo, p.v[i]);
        hi = glm::max(hi, p.v[i]);
    }
    const int x0 = static_cast<int>(std::floor(lo.x));
    const int x1 = std::max(x0, static_cast<int>(std::ceil(hi.x)) - 1);
    const int y0 = static_cast<int>(std::floor(lo.y));
    const int y1 = std::max(y0, static_cast<int>(std::ceil(hi.y)) - 1);
    SmallPolygon rest[2], column, cells[2], cell;
    const SmallPolygon* right = &p;
    for (int x = x0; x <= x1; ++x) {
        const SmallPolygon* col = right;
        if (x < x1) {
            splitAxis(*right, 0, x + 1.0, column, rest[x & 1]);
            col = &column;
            right = &rest[x & 1];
        }
        if (col->n < 3) continue;
        const SmallPolygon* above = col;
        for (int y = y0; y <= y1; ++y) {
            const SmallPolygon* c = above;
            if (y < y1) {
                splitAxis(*above, 1, y + 1.0, cell, cells[y & 1]);
                c = &cell;
                above = &cells[y & 1];
            }
            if (c->n >= 3) add(x, y, *c);
        }
    }
}

// The area of each pixel piece of p (polygonPieces) times scale: add(x, y, weight) where positive.
template <class Add>
void polygonCells(const SmallPolygon& p, double scale, Add&& add) {
    polygonPieces(p, [&](int x, int y, const SmallPolygon& piece) {
        const double a = area(piece);
        if (a > 0.0) add(x, y, a * scale);
    });
}

}  // namespace clipblur
