#include "renderer/geometry/swept_footprint.h"

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

double SweepPath::reach() const { return 0.5 * glm::length(chord) + glm::length(bend); }

bool SweepPath::moves() const {
    const glm::dvec2 zero(0.0);
    return chord != zero || bend != zero || stretch_chord != zero || stretch_bend != zero;
}

void sweptFootprint(const ConvexPolygon& q, const SweepPath& path, int positions, std::vector<PixelWeight>& out) {
    forEachSweptCell(q, path, positions, [&](int x, int y, double w) { out.push_back({x, y, w}); });
}

Bounds2 sweptBounds(const ConvexPolygon& q, const SweepPath& path, int positions) {
    const Bounds2 box = q.bounds();
    Bounds2 out{glm::dvec2(std::numeric_limits<double>::infinity()), glm::dvec2(-std::numeric_limits<double>::infinity())};
    const int m = std::max(1, positions);
    // Per axis, a bound's moved coordinate is a quadratic in s: extreme at the first or last position or
    // where its derivative vanishes.
    const double first = 0.5 / m - 0.5, last = -first;
    for (int axis = 0; axis < 2; ++axis) {
        for (const double b : {box.lo[axis], box.hi[axis]}) {
            const double r = b - path.pivot[axis];
            // c(s) = pivot + s chord + 4 s^2 bend + r (1 + s stretch_chord + 4 s^2 stretch_bend)
            const double linear = path.chord[axis] + r * path.stretch_chord[axis];
            const double quadratic = 4.0 * (path.bend[axis] + r * path.stretch_bend[axis]);
            const auto c = [&](double s) { return path.pivot[axis] + r + s * linear + s * s * quadratic; };
            double lo = std::min(c(first), c(last)), hi = std::max(c(first), c(last));
            if (quadratic != 0.0) {
                const double s = -linear / (2.0 * quadratic);
                if (s > first && s < last) {
                    lo = std::min(lo, c(s));
                    hi = std::max(hi, c(s));
                }
            }
            out.lo[axis] = std::min(out.lo[axis], lo);
            out.hi[axis] = std::max(out.hi[axis], hi);
        }
    }
    return out;
}

}  // namespace clipblur
