#include "renderer/geometry/translating_coverage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace clipblur {

namespace {

// Splits p by the sign of dot(n, x) - c into the part where it is <= 0 and the part where it is >= 0;
// both get the same crossing points, so the parts tile p.
void splitLine(const SmallPolygon& p, const glm::dvec2& n, double c, SmallPolygon& below, SmallPolygon& above) {
    below.n = 0;
    above.n = 0;
    for (int i = 0; i < p.n; ++i) {
        const glm::dvec2& a = p.v[i];
        const glm::dvec2& b = p.v[i + 1 == p.n ? 0 : i + 1];
        const double sa = glm::dot(n, a) - c, sb = glm::dot(n, b) - c;
        if (sa <= 0.0) below.v[below.n++] = a;
        if (sa >= 0.0) above.v[above.n++] = a;
        if ((sa > 0.0 && sb < 0.0) || (sa < 0.0 && sb > 0.0)) {
            const glm::dvec2 x = a + (sa / (sa - sb)) * (b - a);
            below.v[below.n++] = x;
            above.v[above.n++] = x;
        }
    }
}

// On one piece of the plane: the times u_lo(x) <= u <= u_hi(x) when the moving polygon covers x, each
// linear in x (dot(g, x) + c; g = 0 and c = 0 or 1 where the chord's end bounds it), and the weight.
struct CoveredTime {
    glm::dvec2 g_lo{0.0}, g_hi{0.0};
    double c_lo = 0.0, c_hi = 1.0;
    ChordWeight w;

    // The weight of x's covered time: W(u_hi) - W(u_lo), W(u) = w0 u + w1 u^2 / 2.
    // Clamped to the chord: exact arithmetic keeps them there on their piece; rounding need not on pieces
    // thinner than it, whose times are scaled by 1 / k (a velocity nearly along an edge).
    double at(const glm::dvec2& x) const {
        const double lo = std::clamp(glm::dot(g_lo, x) + c_lo, 0.0, 1.0), hi = std::clamp(glm::dot(g_hi, x) + c_hi, 0.0, 1.0);
        return (hi - lo) * (w.w0 + 0.5 * w.w1 * (hi + lo));
    }
    // Its integral over a convex polygon: a fan of triangles about v[0], each by the centroid rule (exact
    // for a linear integrand) or the edge-midpoint rule (exact for a quadratic one).
    double integral(const SmallPolygon& p) const {
        double sum = 0.0, area = 0.0;
        for (int i = 1; i + 1 < p.n; ++i) {
            const glm::dvec2 a = p.v[0], b = p.v[i], c = p.v[i + 1];
            const glm::dvec2 e1 = b - a, e2 = c - a;
            const double twice = e1.x * e2.y - e1.y * e2.x;
            const double mean = w.w1 == 0.0 ? at((a + b + c) / 3.0)
                                            : (at(0.5 * (a + b)) + at(0.5 * (b + c)) + at(0.5 * (c + a))) / 3.0;
            sum += 0.5 * twice * mean;
            area += twice;
        }
        return area < 0.0 ? -sum : sum;  // either orientation
    }
};

void addPiece(const SmallPolygon& piece, const CoveredTime& time, CellSink add) {
    if (piece.n < 3) return;
    polygonPieces(piece, [&](int x, int y, const SmallPolygon& cell) {
        const double v = time.integral(cell);
        if (v != 0.0) add(x, y, v);
    });
}

// A polygon edge a -> b as a half-plane dot(n, x) >= c (n pointing inside) and k = dot(n, d): the edge is
// the back one (the polygon leaves points through it) where k > 0, the front one where k < 0.
struct EdgeLine {
    glm::dvec2 n{0.0};
    double c = 0.0, k = 0.0;
};

}  // namespace

// Over u in [0, 1] the point x is covered while every edge's half-plane holds x - u d: u <= (n.x - c) / k
// for edges with k > 0, u >= (n.x - c) / k for k < 0. Lines through the vertices along d cut the plane into
// strips where one front and one back edge bound that (convexity); within a strip the covered region,
// from the back edge at u = 0 to the front edge at u = 1, is a trapezoid, cut where the front edge at
// u = 0 and the back edge at u = 1 pass into at most four pieces on which u_lo and u_hi are linear.
void translatingCells(const SmallPolygon& p, const glm::dvec2& d, ChordWeight w, CellSink add) {
    if (p.n < 3) return;
    // A motion below the rounding of the coordinates moves nothing they can show: the polygon stands.
    double scale = 1.0;
    for (int i = 0; i < p.n; ++i) scale = std::max({scale, std::abs(p.v[i].x), std::abs(p.v[i].y)});
    if (glm::length(d) <= 1e-13 * scale) {
        polygonCells(p, w.w0 + 0.5 * w.w1, add);
        return;
    }
    double twice = 0.0;
    for (int i = 1; i + 1 < p.n; ++i) {
        const glm::dvec2 e1 = p.v[i] - p.v[0], e2 = p.v[i + 1] - p.v[0];
        twice += e1.x * e2.y - e1.y * e2.x;
    }
    if (twice == 0.0) return;
    const double inward = twice > 0.0 ? 1.0 : -1.0;
    const glm::dvec2 across(-d.y, d.x);
    std::array<double, std::tuple_size_v<decltype(p.v)>> q{}, cuts{};
    std::array<EdgeLine, std::tuple_size_v<decltype(p.v)>> edges{};
    for (int i = 0; i < p.n; ++i) {
        const glm::dvec2& a = p.v[i];
        const glm::dvec2 e = p.v[i + 1 == p.n ? 0 : i + 1] - a;
        q[i] = glm::dot(across, a);
        edges[i].n = inward * glm::dvec2(-e.y, e.x);
        edges[i].c = glm::dot(edges[i].n, a);
        edges[i].k = glm::dot(edges[i].n, d);
    }
    std::copy(q.begin(), q.begin() + p.n, cuts.begin());
    std::sort(cuts.begin(), cuts.begin() + p.n);
    const auto along = [&](int i, double at) {
        const int j = i + 1 == p.n ? 0 : i + 1;
        if (at == q[i]) return p.v[i];
        if (at == q[j]) return p.v[j];
        return p.v[i] + ((at - q[i]) / (q[j] - q[i])) * (p.v[j] - p.v[i]);
    };
    SmallPolygon quad, entered[2], parts[2];
    for (int s = 0; s + 1 < p.n; ++s) {
        const double qa = cuts[s], qb = cuts[s + 1];
        if (!(qb > qa)) continue;
        int back = -1, front = -1;
        for (int i = 0; i < p.n; ++i) {
            const int j = i + 1 == p.n ? 0 : i + 1;
            if (std::min(q[i], q[j]) > qa || std::max(q[i], q[j]) < qb) continue;
            if (edges[i].k > 0.0 && (back < 0 || edges[i].k > edges[back].k)) back = i;
            if (edges[i].k < 0.0 && (front < 0 || edges[i].k < edges[front].k)) front = i;
        }
        if (back < 0 || front < 0) continue;
        const EdgeLine &b = edges[back], &f = edges[front];
        quad.n = 4;
        quad.v[0] = along(back, qa);
        quad.v[1] = along(back, qb);
        quad.v[2] = along(front, qb) + d;
        quad.v[3] = along(front, qa) + d;
        // Below the front edge's line at u = 0 (dot(n, x) < c) the front has not reached x yet.
        splitLine(quad, f.n, f.c, entered[0], entered[1]);
        for (int e = 0; e < 2; ++e) {
            // Below the back edge's line at u = 1 the back has passed x before the chord ends.
            splitLine(entered[e], b.n, b.c + b.k, parts[0], parts[1]);
            for (int l = 0; l < 2; ++l) {
                CoveredTime time;
                time.w = w;
                if (e == 0) {
                    time.g_lo = f.n / f.k;
                    time.c_lo = -f.c / f.k;
                }
                if (l == 0) {
                    time.g_hi = b.n / b.k;
                    time.c_hi = -b.c / b.k;
                }
                addPiece(parts[l], time, add);
            }
        }
    }
}

namespace {

// Along one axis, the overlap of the moving interval [lo + u dlo, hi + u dhi] with the cell [c, c + 1]: a
// piecewise-linear function of u, positive on one span [ua, ub] of [0, 1], with breakpoints where an end
// crosses a cell boundary.
struct AxisOverlap {
    double lo, hi, dlo, dhi;
    int c;
    double ua = 0.0, ub = 1.0;
    int count = 0;                // breakpoints strictly inside (ua, ub), ascending
    std::array<double, 4> at_u{};

    AxisOverlap(double lo_, double hi_, double dlo_, double dhi_, int c_) : lo(lo_), hi(hi_), dlo(dlo_), dhi(dhi_), c(c_) {
        // Positive while lo(u) < c + 1 and hi(u) > c.
        const auto below = [&](double start, double rate, double bound) {  // start + u rate < bound
            if (rate > 0.0) ub = std::min(ub, (bound - start) / rate);
            else if (rate < 0.0) ua = std::max(ua, (bound - start) / rate);
            else if (!(start < bound)) ub = -1.0;
        };
        below(lo, dlo, c + 1.0);
        below(-hi, -dhi, -static_cast<double>(c));
        for (const double boundary : {static_cast<double>(c), c + 1.0}) {
            for (const auto& [start, rate] : {std::pair{lo, dlo}, std::pair{hi, dhi}}) {
                if (rate == 0.0) continue;
                const double u = (boundary - start) / rate;
                if (u > ua && u < ub) at_u[static_cast<std::size_t>(count++)] = u;
            }
        }
        std::sort(at_u.begin(), at_u.begin() + count);
    }
    bool empty() const { return !(ub > ua); }
    double at(double u) const {
        return std::max(0.0, std::min(hi + u * dhi, c + 1.0) - std::max(lo + u * dlo, static_cast<double>(c)));
    }
};

}  // namespace

// Per pixel: on the span where both axes overlap, between the merged breakpoints both overlaps are
// linear, so their product times the weight is a cubic: exact by Simpson, or, for a constant weight, by
// the product rule of two linear functions from their end values, h (2 fa ga + fa gb + fb ga + 2 fb gb) / 6.
void translatingRectangleCells(const MovingRectangle& r, ChordWeight w, CellSink add) {
    const auto axis = [&](int a, std::vector<AxisOverlap>& out) {
        const int c0 = static_cast<int>(std::floor(std::min(r.lo[a], r.lo[a] + r.dlo[a])));
        const int c1 = std::max(c0, static_cast<int>(std::ceil(std::max(r.hi[a], r.hi[a] + r.dhi[a]))) - 1);
        out.clear();
        for (int c = c0; c <= c1; ++c) out.emplace_back(r.lo[a], r.hi[a], r.dlo[a], r.dhi[a], c);
    };
    thread_local std::vector<AxisOverlap> columns, rows;
    axis(0, columns);
    axis(1, rows);
    std::array<double, 10> u{};
    const int c0 = columns.empty() ? 0 : columns.front().c;
    for (const AxisOverlap& oy : rows) {
        if (oy.empty()) continue;
        // Only columns the x interval touches while the row is covered can overlap it in time: those
        // between its ends' extremes over [oy.ua, oy.ub] (the ends move linearly), one more either side
        // for rounding. A rectangle moving diagonally meets a band of cells, not its box's every cell.
        const double x_lo = std::min(r.lo.x + oy.ua * r.dlo.x, r.lo.x + oy.ub * r.dlo.x);
        const double x_hi = std::max(r.hi.x + oy.ua * r.dhi.x, r.hi.x + oy.ub * r.dhi.x);
        const long first = std::max(0L, static_cast<long>(std::floor(x_lo)) - c0 - 1);
        const long last = std::min(static_cast<long>(columns.size()), static_cast<long>(std::ceil(x_hi)) - c0 + 1);
        for (long k = first; k < last; ++k) {
            const AxisOverlap& ox = columns[static_cast<std::size_t>(k)];
            const double ua = std::max(ox.ua, oy.ua), ub = std::min(ox.ub, oy.ub);
            if (!(ub > ua)) continue;
            // Merge the two ascending breakpoint lists within (ua, ub).
            int n = 0, i = 0, j = 0;
            u[n++] = ua;
            while (i < ox.count || j < oy.count) {
                const double next = j >= oy.count || (i < ox.count && ox.at_u[i] < oy.at_u[j]) ? ox.at_u[i++] : oy.at_u[j++];
                if (next > ua && next < ub) u[n++] = next;
            }
            u[n++] = ub;
            double sum = 0.0, fa = ox.at(ua), ga = oy.at(ua);
            for (int k = 0; k + 1 < n; ++k) {
                const double a = u[k], b = u[k + 1], h = b - a;
                const double fb = ox.at(b), gb = oy.at(b);
                if (w.w1 == 0.0) {
                    sum += h * (2.0 * fa * ga + fa * gb + fb * ga + 2.0 * fb * gb) / 6.0 * w.w0;
                } else {
                    const double m = 0.5 * (a + b);
                    sum += h / 6.0 * (fa * ga * (w.w0 + w.w1 * a) + 4.0 * ox.at(m) * oy.at(m) * (w.w0 + w.w1 * m) +
                                      fb * gb * (w.w0 + w.w1 * b));
                }
                fa = fb;
                ga = gb;
            }
            if (sum != 0.0) add(ox.c, oy.c, sum);
        }
    }
}

}  // namespace clipblur
