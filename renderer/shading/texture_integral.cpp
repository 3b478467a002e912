#include "renderer/shading/texture_integral.h"

#include <algorithm>
#include <array>
#include <utility>
#include <cmath>

namespace clipblur {

namespace {

// Keeps the part of p where side (v[axis] - c) >= 0 (side is +1 or -1). Crossing points get exactly c on
// the axis, so neighbouring cells share their edge.
void clipAxis(const ConvexPolygon& p, int axis, double c, double side, ConvexPolygon& out) {
    out.clear();
    for (int i = 0; i < p.n; ++i) {
        const glm::dvec2& a = p.v[i];
        const glm::dvec2& b = p.v[(i + 1) % p.n];
        const double da = side * (a[axis] - c), db = side * (b[axis] - c);
        if (da >= 0.0) out.push(a);
        if ((da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0)) {
            glm::dvec2 q = a + (da / (da - db)) * (b - a);
            q[axis] = c;
            out.push(q);
        }
    }
    out.close();
}

// Area moments of a polygon about a cell corner: integrals of 1, x, y, x y and, for the weight, x^2, y^2,
// x^2 y and x y^2 (Green's theorem, signed by orientation: per edge, the cross product of its ends times a
// polynomial in them).
struct Moments {
    double area = 0.0, x = 0.0, y = 0.0, xy = 0.0, xx = 0.0, yy = 0.0, xxy = 0.0, xyy = 0.0;
};

Moments moments(const ConvexPolygon& p, const glm::dvec2& corner) {
    Moments m;
    for (int i = 0; i < p.n; ++i) {
        const glm::dvec2 a = p.v[i] - corner, b = p.v[(i + 1) % p.n] - corner;
        const double c = a.x * b.y - b.x * a.y;
        m.area += c;
        m.x += (a.x + b.x) * c;
        m.y += (a.y + b.y) * c;
        m.xy += (a.x * (2.0 * a.y + b.y) + b.x * (a.y + 2.0 * b.y)) * c;
        m.xx += (a.x * a.x + a.x * b.x + b.x * b.x) * c;
        m.yy += (a.y * a.y + a.y * b.y + b.y * b.y) * c;
        m.xxy += (a.x * a.x * (3.0 * a.y + b.y) + 2.0 * a.x * b.x * (a.y + b.y) + b.x * b.x * (a.y + 3.0 * b.y)) * c;
        m.xyy += (a.y * a.y * (3.0 * a.x + b.x) + 2.0 * a.y * b.y * (a.x + b.x) + b.y * b.y * (a.x + 3.0 * b.x)) * c;
    }
    m.area /= 2.0;
    m.x /= 6.0;
    m.y /= 6.0;
    m.xy /= 24.0;
    m.xx /= 12.0;
    m.yy /= 12.0;
    m.xxy /= 60.0;
    m.xyy /= 60.0;
    return m;
}

// The weight in one cell's coordinates (x, y) = (u - i, v - j): r0 + rx x + ry y.
struct CellWeight {
    double r0 = 1.0, rx = 0.0, ry = 0.0;
};

// The texels at a cell's corners (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1): RGB each.
using CellTexels = std::array<const float*, 4>;

// The integral over a cell's part `p` (texel-centre coordinates, `corner` the cell's (i, j)) of the
// bilinear image between its corner texels, times the weight. Adds p's weighted area to `weight_sum`.
glm::dvec3 cellIntegral(const CellTexels& t, const glm::dvec2& corner, const CellWeight& w, const ConvexPolygon& p,
                        double& weight_sum) {
    const Moments m = moments(p, corner);
    // Integrals of the weight times 1, x, y and x y.
    const double i1 = w.r0 * m.area + w.rx * m.x + w.ry * m.y;
    const double ix = w.r0 * m.x + w.rx * m.xx + w.ry * m.xy;
    const double iy = w.r0 * m.y + w.rx * m.xy + w.ry * m.yy;
    const double ixy = w.r0 * m.xy + w.rx * m.xxy + w.ry * m.xyy;
    weight_sum += i1;
    glm::dvec3 out;
    for (int k = 0; k < 3; ++k)
        out[k] = t[0][k] * i1 + (double(t[1][k]) - t[0][k]) * ix + (double(t[2][k]) - t[0][k]) * iy +
                 ((double(t[0][k]) - t[1][k]) - (double(t[2][k]) - t[3][k])) * ixy;
    return out;
}

long long wrapped(long long i, int n) { return ((i % n) + n) % n; }

// Texel-centre coordinates of (s, t) at `level`, shifted by whole periods so the polygon starts in the
// first period (keeps cell indices small and the arithmetic near the origin).
glm::dvec2 toTexelCentres(const TexelLevel& level, const ConvexPolygon& st, ConvexPolygon& out) {
    double s0 = INFINITY, t0 = INFINITY;
    for (int k = 0; k < st.n; ++k) {
        s0 = std::min(s0, st.v[k].x);
        t0 = std::min(t0, st.v[k].y);
    }
    const glm::dvec2 period(std::floor(s0), std::floor(t0));
    out.clear();
    for (int k = 0; k < st.n; ++k) {
        const glm::dvec2 p = st.v[k] - period;
        out.push({p.x * level.width - 0.5, p.y * level.height - 0.5});
    }
    out.close();
    return period;
}

bool finite(const ConvexPolygon& p) {
    for (int k = 0; k < p.n; ++k)
        if (!std::isfinite(p.v[k].x) || !std::isfinite(p.v[k].y)) return false;
    return p.n > 0;
}

}  // namespace

glm::dvec3 bilinearAt(const TexelLevel& level, const glm::dvec2& st) {
    const double u = (st.x - std::floor(st.x)) * level.width - 0.5, v = (st.y - std::floor(st.y)) * level.height - 0.5;
    const double fi = std::floor(u), fj = std::floor(v);
    const double x = u - fi, y = v - fj;
    const auto i = static_cast<long long>(fi), j = static_cast<long long>(fj);
    const float* t00 = level.texel(i, j);
    const float* t10 = level.texel(i + 1, j);
    const float* t01 = level.texel(i, j + 1);
    const float* t11 = level.texel(i + 1, j + 1);
    glm::dvec3 out;
    for (int k = 0; k < 3; ++k)
        out[k] = (1.0 - y) * ((1.0 - x) * t00[k] + x * t10[k]) + y * ((1.0 - x) * t01[k] + x * t11[k]);
    return out;
}

int integralLevel(const TexelPyramid& pyramid, const ConvexPolygon& st, double cell_budget) {
    double area2 = 0.0;  // twice the signed area in (s, t)
    for (int k = 0; k < st.n; ++k) {
        const glm::dvec2 a = st.v[k], b = st.v[(k + 1) % st.n];
        area2 += a.x * b.y - b.x * a.y;
    }
    int l = 0;
    for (; l + 1 < pyramid.levels(); ++l) {
        const TexelLevel& level = pyramid.level(l);
        const glm::dvec2 size(level.width, level.height);
        double perimeter = 0.0;
        for (int k = 0; k < st.n; ++k) perimeter += glm::length((st.v[(k + 1) % st.n] - st.v[k]) * size);
        if (0.5 * std::abs(area2) * size.x * size.y + 0.5 * perimeter + 1.0 <= cell_budget) break;
    }
    return l;
}

glm::dvec3 bilinearMean(const TexelLevel& level, const ConvexPolygon& st, const AffineWeight& weight) {
    if (!finite(st)) return glm::dvec3(0.0);
    // One texel repeated: the image is constant (and a polygon there may span many periods).
    if (level.width == 1 && level.height == 1) return glm::dvec3(level.rgb[0], level.rgb[1], level.rgb[2]);
    // Ping-pong buffers: the strip or cell cut off and what is left to cut, swapped, never copied.
    std::array<ConvexPolygon, 5> buffers;
    ConvexPolygon* rest = &buffers[0];
    ConvexPolygon* next = &buffers[1];
    ConvexPolygon* column = &buffers[2];
    ConvexPolygon* column_next = &buffers[3];
    ConvexPolygon* cell = &buffers[4];
    const glm::dvec2 period = toTexelCentres(level, st, *rest);
    // The weight 1 + slope . (st - at) in texel-centre coordinates: st = (u + 1/2) / size + period.
    const glm::dvec2 size(level.width, level.height);
    const glm::dvec2 per_texel = weight.slope / size;
    const double weight_origin = 1.0 + glm::dot(weight.slope, glm::dvec2(0.5) / size + period - weight.at);
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    for (int k = 0; k < rest->n; ++k) {
        lo = glm::min(lo, rest->v[k]);
        hi = glm::max(hi, rest->v[k]);
    }
    glm::dvec3 sum(0.0);
    double weight_sum = 0.0;
    // Columns left to right, each cut off the rest, then its cells off the column bottom up; a polygon
    // within one column (or a column within one row) needs no cut.
    const double i_last = std::floor(hi.x);
    for (double i = std::floor(lo.x); i <= i_last && !rest->degenerate(); i += 1.0) {
        if (i < i_last) {
            clipAxis(*rest, 0, i + 1.0, -1.0, *column);
            clipAxis(*rest, 0, i + 1.0, 1.0, *next);
            std::swap(rest, next);
        } else {
            std::swap(column, rest);
            rest->clear();
        }
        if (column->degenerate()) continue;
        const long long ci = static_cast<long long>(i);
        const std::array<long long, 2> columns{wrapped(ci, level.width), wrapped(ci + 1, level.width)};
        double v_lo = INFINITY, v_hi = -INFINITY;
        for (int k = 0; k < column->n; ++k) {
            v_lo = std::min(v_lo, column->v[k].y);
            v_hi = std::max(v_hi, column->v[k].y);
        }
        const double j_last = std::floor(v_hi);
        for (double j = std::floor(v_lo); j <= j_last && !column->degenerate(); j += 1.0) {
            if (j < j_last) {
                clipAxis(*column, 1, j + 1.0, -1.0, *cell);
                clipAxis(*column, 1, j + 1.0, 1.0, *column_next);
                std::swap(column, column_next);
            } else {
                std::swap(cell, column);
                column->clear();
            }
            if (cell->degenerate()) continue;
            const long long cj = static_cast<long long>(j);
            const std::array<long long, 2> rows{wrapped(cj, level.height) * level.width,
                                                wrapped(cj + 1, level.height) * level.width};
            const auto at = [&](int x, int y) {
                return &level.rgb[static_cast<std::size_t>(3 * (rows[static_cast<std::size_t>(y)] + columns[static_cast<std::size_t>(x)]))];
            };
            const CellWeight w{weight_origin + per_texel.x * i + per_texel.y * j, per_texel.x, per_texel.y};
            sum += cellIntegral({at(0, 0), at(1, 0), at(0, 1), at(1, 1)}, glm::dvec2(i, j), w, *cell, weight_sum);
        }
    }
    if (weight_sum != 0.0) return sum / weight_sum;
    glm::dvec2 mean(0.0);
    for (int k = 0; k < st.n; ++k) mean += st.v[k];
    return bilinearAt(level, mean / double(st.n));
}

glm::dvec3 textureMean(const TexelPyramid& pyramid, const ConvexPolygon& st, const AffineWeight& weight,
                       double cell_budget) {
    return bilinearMean(pyramid.level(integralLevel(pyramid, st, cell_budget)), st, weight);
}

}  // namespace clipblur
