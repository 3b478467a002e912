#include "renderer/geometry/swept_footprint.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace clipblur {

namespace swept_detail {

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

}  // namespace swept_detail

SweepPath SweepPath::through(const glm::dvec2& a, double za, const glm::dvec2& m, double zm, const glm::dvec2& b,
                             double zb) {
    // Homogeneous offsets from m, scaled by 1 / zm: h(s) = (raster(s) - m) w(s), w(s) = depth(s) / zm.
    const double wa = za / zm, wb = zb / zm;
    const glm::dvec2 ha = (a - m) * wa, hb = (b - m) * wb;
    SweepPath path;
    path.chord = hb - ha;
    path.bend = 0.5 * (ha + hb);
    path.pivot = m;
    path.depth_chord = wb - wa;
    path.depth_bend = 0.5 * (wa + wb) - 1.0;
    return path;
}

void SweepPath::setStretch(const glm::dvec2& open, const glm::dvec2& close) {
    // The numerator at the ends: stretch x w.
    const glm::dvec2 na = open * depthAt(-0.5), nb = close * depthAt(0.5);
    stretch_chord = nb - na;
    stretch_bend = 0.5 * (na + nb) - 1.0;
}

double SweepPath::reach() const {
    // Least w over [-1/2, 1/2]: at an end or at the parabola's vertex.
    double least = std::min(depthAt(-0.5), depthAt(0.5));
    if (depth_bend > 0.0) {
        const double s = -depth_chord / (8.0 * depth_bend);
        if (s > -0.5 && s < 0.5) least = std::min(least, depthAt(s));
    }
    if (!(least > 0.0)) return std::numeric_limits<double>::infinity();
    return (0.5 * glm::length(chord) + glm::length(bend)) / least;
}

bool SweepPath::moves() const {
    const glm::dvec2 zero(0.0);
    return chord != zero || bend != zero || stretch_chord != zero || stretch_bend != zero || depth_chord != 0.0 ||
           depth_bend != 0.0;
}

void sweptFootprint(const ConvexPolygon& q, const SweepPath& path, int positions, std::vector<PixelWeight>& out) {
    forEachSweptCell(q, path, positions, [&](int x, int y, double w) { out.push_back({x, y, w}); });
}

Bounds2 sweptBounds(const ConvexPolygon& q, const SweepPath& path, int positions) {
    const Bounds2 box = q.bounds();
    Bounds2 out{glm::dvec2(std::numeric_limits<double>::infinity()), glm::dvec2(-std::numeric_limits<double>::infinity())};
    const int m = std::max(1, positions);
    // Per axis, a bound's moved coordinate is pivot + N(s) / W(s), N and W quadratics in s:
    //     N(s) = r + s (chord + r stretch_chord) + 4 s^2 (bend + r stretch_bend),  r = bound - pivot.
    // It is extreme at the first or last position or where N' W - N W' vanishes, a quadratic (the cubic
    // terms cancel): (n2 w1 - n1 w2) s^2 + 2 (n2 - n0 w2) s + (n1 - n0 w1).
    const double first = 0.5 / m - 0.5, last = -first;
    const double w1 = path.depth_chord, w2 = 4.0 * path.depth_bend;
    for (int axis = 0; axis < 2; ++axis) {
        for (const double b : {box.lo[axis], box.hi[axis]}) {
            const double n0 = b - path.pivot[axis];
            const double n1 = path.chord[axis] + n0 * path.stretch_chord[axis];
            const double n2 = 4.0 * (path.bend[axis] + n0 * path.stretch_bend[axis]);
            const auto c = [&](double s) { return path.pivot[axis] + (n0 + s * n1 + s * s * n2) / (1.0 + s * w1 + s * s * w2); };
            double lo = std::min(c(first), c(last)), hi = std::max(c(first), c(last));
            const auto extreme = [&](double s) {
                if (s > first && s < last) {
                    lo = std::min(lo, c(s));
                    hi = std::max(hi, c(s));
                }
            };
            const double qa = n2 * w1 - n1 * w2, qb = 2.0 * (n2 - n0 * w2), qc = n1 - n0 * w1;
            if (qa == 0.0) {
                if (qb != 0.0) extreme(-qc / qb);
            } else {
                const double disc = qb * qb - 4.0 * qa * qc;
                if (disc >= 0.0) {
                    const double root = std::sqrt(disc);
                    extreme((-qb - root) / (2.0 * qa));
                    extreme((-qb + root) / (2.0 * qa));
                }
            }
            out.lo[axis] = std::min(out.lo[axis], lo);
            out.hi[axis] = std::max(out.hi[axis], hi);
        }
    }
    return out;
}

}  // namespace clipblur
