#include "renderer/geometry/swept_footprint.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace clipblur {

namespace {

// Every edge horizontal or vertical: a convex polygon like that is its bounding box (fragments inside a
// surface are whole or partial pixels, often with extra vertices where other pieces were cut off).
bool axisAlignedRectangle(const ConvexPolygon& q) {
    for (int i = 0; i < q.n; ++i) {
        const glm::dvec2& a = q.v[i];
        const glm::dvec2& b = q.v[i + 1 == q.n ? 0 : i + 1];
        if (a.x != b.x && a.y != b.y) return false;
    }
    return true;
}

// Overlaps of [lo, hi] with the unit cells [c, c + 1]: calls add(c, length) for each cell it meets.
template <class Add>
void cellOverlaps(double lo, double hi, Add add) {
    const int c0 = static_cast<int>(std::floor(lo));
    const int c1 = std::max(c0, static_cast<int>(std::ceil(hi)) - 1);
    for (int c = c0; c <= c1; ++c) {
        const double length = std::min(hi, c + 1.0) - std::max(lo, static_cast<double>(c));
        if (length > 0.0) add(c, length);
    }
}

void rectangleFootprint(const glm::dvec2& lo, const glm::dvec2& hi, double scale, std::vector<PixelWeight>& out) {
    cellOverlaps(lo.y, hi.y, [&](int y, double h) {
        cellOverlaps(lo.x, hi.x, [&](int x, double w) { out.push_back({x, y, w * h * scale}); });
    });
}

// A small polygon for the per-position cuts: cheaper to copy than ConvexPolygon's full capacity. A
// convex polygon of n vertices cut by axis lines stays within n + 4 vertices.
struct SmallPolygon {
    std::array<glm::dvec2, kMaxStoredVertices + 8> v;
    int n = 0;
};

// Splits p along the line coordinate `axis` = c into the part below (< c) and the part above, in one
// pass: each vertex goes to its side, each crossing point (placed on the line exactly) to both.
void splitAxis(const SmallPolygon& p, int axis, double c, SmallPolygon& below, SmallPolygon& above) {
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

double area(const SmallPolygon& p) {
    double twice = 0.0;
    for (int i = 1; i + 1 < p.n; ++i) {
        const glm::dvec2 e1 = p.v[i] - p.v[0], e2 = p.v[i + 1] - p.v[0];
        twice += e1.x * e2.y - e1.y * e2.x;
    }
    return 0.5 * std::abs(twice);
}

// Exact pixel pieces of a convex polygon: chopped into columns, each column into cells, one split per
// cell boundary (a fragment, at most a pixel wide, needs at most one split per axis).
void polygonFootprint(const SmallPolygon& p, double scale, std::vector<PixelWeight>& out) {
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
            if (c->n < 3) continue;
            const double a = area(*c);
            if (a > 0.0) out.push_back({x, y, a * scale});
        }
    }
}

}  // namespace

double SweepPath::reach() const { return 0.5 * glm::length(chord) + glm::length(bend); }

bool SweepPath::moves() const {
    const glm::dvec2 zero(0.0);
    return chord != zero || bend != zero || stretch_chord != zero || stretch_bend != zero;
}

void sweptFootprint(const ConvexPolygon& q, const SweepPath& path, int positions, std::vector<PixelWeight>& out) {
    if (q.degenerate() || q.n > kMaxStoredVertices) {
        if (!q.degenerate()) {  // more vertices than stored fragments have: cut it into stored-size pieces
            thread_local std::vector<ConvexPolygon> parts;
            parts.clear();
            splitToCapacity(q, kMaxStoredVertices, parts);
            for (const ConvexPolygon& part : parts) sweptFootprint(part, path, positions, out);
        }
        return;
    }
    const int m = std::max(1, positions);
    const double scale = 1.0 / m;
    // A stretch along the raster axes keeps an axis-aligned rectangle axis-aligned.
    if (axisAlignedRectangle(q)) {
        const Bounds2 box = q.bounds();
        for (int k = 0; k < m; ++k) {
            const double s = (k + 0.5) / m - 0.5;
            const glm::dvec2 at = path.pivot + path.at(s), stretch = path.stretchAt(s);
            rectangleFootprint(at + stretch * (box.lo - path.pivot), at + stretch * (box.hi - path.pivot), scale, out);
        }
        return;
    }
    SmallPolygon moved;
    moved.n = q.n;
    for (int k = 0; k < m; ++k) {
        const double s = (k + 0.5) / m - 0.5;
        const glm::dvec2 at = path.pivot + path.at(s), stretch = path.stretchAt(s);
        for (int i = 0; i < q.n; ++i) moved.v[i] = at + stretch * (q.v[i] - path.pivot);
        polygonFootprint(moved, scale, out);
    }
}

}  // namespace clipblur
