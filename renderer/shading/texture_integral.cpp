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

// Area moments of a polygon about a cell corner: integrals of 1, x, y and x y (Green's theorem, signed by
// orientation).
struct Moments {
    double area = 0.0, x = 0.0, y = 0.0, xy = 0.0;
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
    }
    m.area /= 2.0;
    m.x /= 6.0;
    m.y /= 6.0;
    m.xy /= 24.0;
    return m;
}

// The integral over cell (i, j)'s part `p` (texel-centre coordinates) of the bilinear image between the
// centres of texels (i, j), (i + 1, j), (i, j + 1) and (i + 1, j + 1); `column` and `row` are the texels'
// offsets in the level's array (wrapped). Adds p's area to `area`.
glm::dvec3 cellIntegral(const TexelLevel& level, const glm::dvec2& corner, const std::array<long long, 2>& column,
                        const std::array<long long, 2>& row, const ConvexPolygon& p, double& area) {
    const Moments m = moments(p, corner);
    area += m.area;
    const float* t00 = &level.rgb[static_cast<std::size_t>(3 * (row[0] + column[0]))];
    const float* t10 = &level.rgb[static_cast<std::size_t>(3 * (row[0] + column[1]))];
    const float* t01 = &level.rgb[static_cast<std::size_t>(3 * (row[1] + column[0]))];
    const float* t11 = &level.rgb[static_cast<std::size_t>(3 * (row[1] + column[1]))];
    glm::dvec3 out;
    for (int k = 0; k < 3; ++k)
        out[k] = t00[k] * m.area + (double(t10[k]) - t00[k]) * m.x + (double(t01[k]) - t00[k]) * m.y +
                 ((double(t00[k]) - t10[k]) - (double(t01[k]) - t11[k])) * m.xy;
    return out;
}

long long wrapped(long long i, int n) { return ((i % n) + n) % n; }

// Texel-centre coordinates of (s, t) at `level`, shifted by whole periods so the polygon starts in the
// first period (keeps cell indices small and the arithmetic near the origin).
void toTexelCentres(const TexelLevel& level, const ConvexPolygon& st, ConvexPolygon& out) {
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

glm::dvec3 bilinearMean(const TexelLevel& level, const ConvexPolygon& st) {
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
    toTexelCentres(level, st, *rest);
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    for (int k = 0; k < rest->n; ++k) {
        lo = glm::min(lo, rest->v[k]);
        hi = glm::max(hi, rest->v[k]);
    }
    glm::dvec3 sum(0.0);
    double area = 0.0;
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
            sum += cellIntegral(level, glm::dvec2(i, j), columns, rows, *cell, area);
        }
    }
    if (area != 0.0) return sum / area;
    glm::dvec2 mean(0.0);
    for (int k = 0; k < st.n; ++k) mean += st.v[k];
    return bilinearAt(level, mean / double(st.n));
}

glm::dvec3 textureMean(const TexelPyramid& pyramid, const ConvexPolygon& st, double cell_budget) {
    return bilinearMean(pyramid.level(integralLevel(pyramid, st, cell_budget)), st);
}

}  // namespace clipblur
