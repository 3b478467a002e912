#include "renderer/geometry/pixel_clip.h"

#include <algorithm>
#include <cmath>

#include "renderer/geometry/predicates.h"

namespace clipblur {

namespace {

void pushTagged(TriangleClipper::Piece& out, const glm::dvec2& p, std::int8_t edge) {
    ConvexPolygon& poly = out.poly;
    if (poly.n > 0 && poly.v[poly.n - 1] == p) {
        // A repeated point: the zero-length edge vanishes and the outgoing edge is the new one.
        out.edge[poly.n - 1] = edge;
        return;
    }
    if (poly.n < kMaxPolygonVertices) {
        out.edge[poly.n] = edge;
        poly.v[poly.n++] = p;
    }
}

void closeTagged(TriangleClipper::Piece& out) {
    ConvexPolygon& poly = out.poly;
    while (poly.n > 1 && poly.v[poly.n - 1] == poly.v[0]) --poly.n;
}

}  // namespace

TriangleClipper::TriangleClipper(const std::array<glm::dvec2, 3>& raster) : tri_(raster) {
    const double a2 = orient2d(tri_[0], tri_[1], tri_[2]);
    if (a2 < 0.0) std::swap(tri_[1], tri_[2]);
    area_ = 0.5 * std::abs(a2);
    valid_ = a2 != 0.0 && std::isfinite(a2);
    for (int e = 0; e < 3; ++e) {
        const glm::dvec2& a = tri_[e];
        const glm::dvec2& b = tri_[(e + 1) % 3];
        const bool a_first = (a.x < b.x) || (a.x == b.x && a.y <= b.y);
        lo_[e] = a_first ? a : b;
        hi_[e] = a_first ? b : a;
    }
}

double TriangleClipper::crossingOrdinate(int edge, int axis, double c) const {
    const int o = 1 - axis;
    const glm::dvec2& p = lo_[edge];
    const glm::dvec2& q = hi_[edge];
    const double den = q[axis] - p[axis];
    if (den == 0.0) return p[o];
    const double t = (c - p[axis]) / den;
    const double val = std::fma(t, q[o] - p[o], p[o]);
    return std::clamp(val, std::min(p[o], q[o]), std::max(p[o], q[o]));
}

void TriangleClipper::clipAxis(const Piece& in, int axis, double c, Keep keep, Piece& out) const {
    const bool keep_greater = keep == Keep::Above;
    out.poly.clear();
    const ConvexPolygon& p = in.poly;
    for (int i = 0; i < p.n; ++i) {
        const int j = i + 1 == p.n ? 0 : i + 1;
        // Exact side tests: a comparison with the grid coordinate, no arithmetic.
        const double si = keep_greater ? p.v[i][axis] - c : c - p.v[i][axis];
        const double sj = keep_greater ? p.v[j][axis] - c : c - p.v[j][axis];
        const bool crosses = (si > 0.0 && sj < 0.0) || (si < 0.0 && sj > 0.0);
        // A vertex on the line whose edge leaves the kept side starts an edge along the cut.
        if (si >= 0.0) pushTagged(out, p.v[i], si == 0.0 && sj < 0.0 ? kGridEdge : in.edge[i]);
        if (!crosses) continue;
        glm::dvec2 x;
        x[axis] = c;
        // A grid edge crossing this line is perpendicular to it, so its other ordinate is constant.
        x[1 - axis] = in.edge[i] == kGridEdge ? p.v[i][1 - axis] : crossingOrdinate(in.edge[i], axis, c);
        // Leaving: the new edge runs along the cut. Entering: the rest of the original edge follows.
        pushTagged(out, x, si > 0.0 ? kGridEdge : in.edge[i]);
    }
    closeTagged(out);
}

void TriangleClipper::clipToStrip(double y0, double y1, Piece& out) const {
    Piece tri;
    for (int i = 0; i < 3; ++i) {
        tri.poly.v[i] = tri_[i];
        tri.edge[i] = static_cast<std::int8_t>(i);
    }
    tri.poly.n = 3;
    Piece low;
    clipAxis(tri, 1, y0, Keep::Above, low);
    clipAxis(low, 1, y1, Keep::Below, out);
}

void TriangleClipper::clipToColumn(const Piece& strip, double x0, double x1, ConvexPolygon& out) const {
    Piece left;
    clipAxis(strip, 0, x0, Keep::Above, left);
    Piece both;
    clipAxis(left, 0, x1, Keep::Below, both);
    out = both.poly;
}

void TriangleClipper::clipToPixel(int px, int py, ConvexPolygon& out) const {
    Piece strip;
    clipToStrip(py, py + 1.0, strip);
    clipToColumn(strip, px, px + 1.0, out);
}

}  // namespace clipblur
