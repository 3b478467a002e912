#include "renderer/geometry/swept_footprint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

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

SweepPath SweepPath::through(const PathPoint& pa, const PathPoint& pm, const PathPoint& pb, const glm::dmat3& unturn_a,
                             const glm::dmat3& unturn_b) {
    const glm::dvec2 &a = pa.raster, &m = pm.raster, &b = pb.raster;
    const double za = pa.depth, zm = pm.depth, zb = pb.depth;
    // Homogeneous coordinates over zm, unturned: h(s) = (m w(s) + g(s), w(s)), g the offset numerator.
    const glm::dvec3 ha = unturn_a * glm::dvec3(a * (za / zm), za / zm), hb = unturn_b * glm::dvec3(b * (zb / zm), zb / zm);
    const glm::dvec2 ga = glm::dvec2(ha) - m * ha.z, gb = glm::dvec2(hb) - m * hb.z;
    SweepPath path;
    path.chord = gb - ga;
    path.bend = 0.5 * (ga + gb);
    path.pivot = m;
    path.depth_chord = hb.z - ha.z;
    path.depth_bend = 0.5 * (ha.z + hb.z) - 1.0;
    path.depth_open = za / zm;
    path.depth_close = zb / zm;
    path.open_offset = a - m;
    path.close_offset = b - m;
    return path;
}

void SweepPath::setStretch(const glm::dvec2& open, const glm::dvec2& close) {
    // The numerator at the ends: stretch x depth ratio.
    open_stretch = open;
    close_stretch = close;
    const glm::dvec2 na = open * depth_open, nb = close * depth_close;
    stretch_chord = nb - na;
    stretch_bend = 0.5 * (na + nb) - 1.0;
}

namespace {

// With turns: the Bezier hull of the raster parabola through the offsets at the ends and 0 at s = 0.
std::array<glm::dvec2, 3> turnedHull(const SweepPath& path) {
    return {path.open_offset, path.close_offset, -0.5 * (path.open_offset + path.close_offset)};
}

constexpr double kTurnedGrowth = 1.1, kTurnedMargin = 0.1;  // px

}  // namespace

double SweepPath::reach() const {
    if (!turns.empty()) {
        double farthest = 0.0;
        for (const glm::dvec2& p : turnedHull(*this)) farthest = std::max(farthest, glm::length(p));
        return kTurnedGrowth * farthest + kTurnedMargin;
    }
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
           depth_bend != 0.0 || !turns.empty();
}

bool SweepPath::translates() const {
    const glm::dvec2 zero(0.0);
    return bend == zero && stretch_chord == zero && stretch_bend == zero && depth_chord == 0.0 && depth_bend == 0.0 &&
           turns.empty();
}

void sweptFootprint(const ConvexPolygon& q, const SweepPath& path, int positions, std::vector<PixelWeight>& out) {
    forEachSweptCell(q, path, positions, [&](int x, int y, double w) { out.push_back({x, y, w}); });
}

RasterBounds sweptBounds(const ConvexPolygon& q, const SweepPath& path, int positions) {
    const RasterBounds box = q.bounds();
    RasterBounds out;
    const int m = std::max(1, positions);
    // Per axis, a bound's moved coordinate is pivot + N(s) / W(s), N and W quadratics in s:
    //     N(s) = r + s (chord + r stretch_chord) + 4 s^2 (bend + r stretch_bend),  r = bound - pivot.
    // It is extreme at the first or last position or where N' W - N W' vanishes, a quadratic (the cubic
    // terms cancel): (n2 w1 - n1 w2) s^2 + 2 (n2 - n0 w2) s + (n1 - n0 w1).
    if (path.turnAt(0, m)) {
        const std::array<glm::dvec2, 3> hull = turnedHull(path);
        for (int axis = 0; axis < 2; ++axis) {
            double offset_lo = 0.0, offset_hi = 0.0;
            for (const glm::dvec2& p : hull) {
                offset_lo = std::min(offset_lo, p[axis]);
                offset_hi = std::max(offset_hi, p[axis]);
            }
            const double stretch_lo = std::min({1.0, path.open_stretch[axis], path.close_stretch[axis]});
            const double stretch_hi = std::max({1.0, path.open_stretch[axis], path.close_stretch[axis]});
            for (const double b : {box.lo[axis], box.hi[axis]}) {
                const double r = b - path.pivot[axis];
                const double lo = path.pivot[axis] + offset_lo + std::min(stretch_lo * r, stretch_hi * r);
                const double hi = path.pivot[axis] + offset_hi + std::max(stretch_lo * r, stretch_hi * r);
                const double grow = (kTurnedGrowth - 1.0) * (hi - lo) + kTurnedMargin;
                out.lo[axis] = std::min(out.lo[axis], lo - grow);
                out.hi[axis] = std::max(out.hi[axis], hi + grow);
            }
        }
        return out;
    }
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
