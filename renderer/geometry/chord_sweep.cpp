#include "renderer/geometry/chord_sweep.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

namespace clipblur {

namespace {

// One chord of a sweep: over s in [s0, s1] the pivot's offset and the stretch about it go linearly from
// their values at s0 to those at s1, so every vertex of the polygon moves linearly.
struct SweepChord {
    double s0 = 0.0, s1 = 0.0;
    glm::dvec2 from{0.0}, to{0.0};
    glm::dvec2 stretch_from{1.0}, stretch_to{1.0};

    glm::dvec2 velocity() const { return (to - from) / (s1 - s0); }
    glm::dvec2 stretchRate() const { return (stretch_to - stretch_from) / (s1 - s0); }
    // The part of it where the stretch is positive along both axes (the surface faces the camera): false
    // where there is none. The stretch is linear along the chord, so the part is one span, cut exactly.
    bool facing(SweepChord& part) const {
        double u0 = 0.0, u1 = 1.0;
        for (int axis = 0; axis < 2; ++axis) {
            const double a = stretch_from[axis], b = stretch_to[axis];
            if (a <= 0.0 && b <= 0.0) return false;
            if (a > 0.0 && b <= 0.0) u1 = std::min(u1, a / (a - b));
            if (a <= 0.0 && b > 0.0) u0 = std::max(u0, a / (a - b));
        }
        if (!(u1 > u0)) return false;
        const double span = s1 - s0;
        part = {s0 + u0 * span, s0 + u1 * span, from + u0 * (to - from), from + u1 * (to - from),
                stretch_from + u0 * (stretch_to - stretch_from), stretch_from + u1 * (stretch_to - stretch_from)};
        return true;
    }
};

// Consecutive chords of one velocity and stretch rate are one chord: a translating path's sweep is a single
// chord whatever its knots. Relative 1e-9: rounding of the knots' placement, far below any pixel weight.
bool continues(const SweepChord& a, const SweepChord& b) {
    const auto near = [](const glm::dvec2& x, const glm::dvec2& y) {
        return glm::length(x - y) <= 1e-9 * std::max(glm::length(x), glm::length(y)) + 1e-12;
    };
    return near(a.velocity(), b.velocity()) && near(a.stretchRate(), b.stretchRate());
}

// The rates of change of the offset and stretch at s along the unturned path: (g' w - g w') / w^2 and
// (n' w - n w') / w^2.
void pathRates(const SweepPath& path, double s, glm::dvec2& velocity, glm::dvec2& stretch_rate) {
    const double w = path.depthAt(s), dw = path.depth_chord + 8.0 * s * path.depth_bend;
    const glm::dvec2 g = s * path.chord + 4.0 * s * s * path.bend, dg = path.chord + 8.0 * s * path.bend;
    const glm::dvec2 n = glm::dvec2(1.0) + s * path.stretch_chord + 4.0 * s * s * path.stretch_bend;
    const glm::dvec2 dn = path.stretch_chord + 8.0 * s * path.stretch_bend;
    velocity = (dg * w - g * dw) / (w * w);
    stretch_rate = (dn * w - n * dw) / (w * w);
}

// Calls chord(c) for each merged chord of the path's sweep through `knots` (forEachChordCell).
template <class F>
void forEachChord(const SweepPath& path, int positions, SweepKnots knots, F&& chord) {
    const int m = std::max(1, positions);
    const int grouped = knots == SweepKnots::Nested ? 3 * (m / 3) : 0;
    struct Knot {
        double s;
        glm::dvec2 offset, stretch;
    };
    SweepChord pending, part;
    bool have_pending = false;
    const auto emit = [&](const SweepChord& c) {
        if (have_pending && continues(pending, c)) {
            pending.s1 = c.s1;
            pending.to = c.to;
            pending.stretch_to = c.stretch_to;
            return;
        }
        if (have_pending && pending.facing(part)) chord(part);
        pending = c;
        have_pending = true;
    };
    // The chord from knot a continued at the given rates to s.
    const auto continued = [](const Knot& a, double s, const glm::dvec2& velocity, const glm::dvec2& stretch_rate) {
        const double ds = s - a.s;
        return SweepChord{std::min(a.s, s), std::max(a.s, s), a.offset + std::min(ds, 0.0) * velocity,
                          a.offset + std::max(ds, 0.0) * velocity, a.stretch + std::min(ds, 0.0) * stretch_rate,
                          a.stretch + std::max(ds, 0.0) * stretch_rate};
    };
    // Position k of m, placed with its turn, and the chord between two such knots.
    const auto knotAt = [&](int k) {
        Knot q{(k + 0.5) / m - 0.5, {}, {}};
        path.place(q.s, path.turnAt(k, m), q.offset, q.stretch);
        return q;
    };
    const auto between = [](const Knot& a, const Knot& b) {
        return SweepChord{a.s, b.s, a.offset, b.offset, a.stretch, b.stretch};
    };
    Knot prev{};
    int count = 0;
    for (int k = 0; k < m; ++k) {
        if (k < grouped && k % 3 != 1) continue;
        const Knot cur = knotAt(k);
        if (count++ > 0) {
            const SweepChord c = between(prev, cur);
            if (count == 2) emit(continued(prev, -0.5, c.velocity(), c.stretchRate()));
            emit(c);
        }
        prev = cur;
    }
    glm::dvec2 velocity, stretch_rate;
    if (count >= 2) {
        velocity = pending.velocity();
        stretch_rate = pending.stretchRate();
    } else {
        // One knot (the nested rule of 3 positions keeps only the middle one): its rates from the chord
        // through the outer positions, placed with their turns, as the fine rule sees the path; one
        // position has no turns, and the path's own rates are its.
        if (m >= 2) {
            const SweepChord outer = between(knotAt(0), knotAt(m - 1));
            velocity = outer.velocity();
            stretch_rate = outer.stretchRate();
        } else {
            pathRates(path, prev.s, velocity, stretch_rate);
        }
        emit(continued(prev, -0.5, velocity, stretch_rate));
    }
    emit(continued(prev, 0.5, velocity, stretch_rate));
    if (pending.facing(part)) chord(part);
}

// Calls part(u0, u1) for consecutive spans of the chord's u in [0, 1] over which half the stretch change
// times the half-size stays within chordShapeTolerance along both axes. The stretch is linear in u and
// positive (SweepChord::facing), so a span's step follows from the stretch at its start: by ratio
// 1 + 2 share where the share bounds it (divided by that where the stretch falls, so the span's smaller
// end still allows it), at least 2 kChordShapeTolerance / (rate half), so there are never more spans than
// uniform 1/128 px parts would be.
template <class F>
void forEachShapePart(const SweepChord& c, const glm::dvec2& half, F&& part) {
    double u = 0.0;
    while (u < 1.0) {
        double step = 1.0 - u;
        for (int axis = 0; axis < 2; ++axis) {
            const double rate = c.stretch_to[axis] - c.stretch_from[axis];
            if (rate == 0.0 || !(half[axis] > 0.0)) continue;
            const double stretch = std::max(0.0, c.stretch_from[axis] + u * rate);
            const double allowed = chordShapeTolerance(rate < 0.0 ? stretch / (1.0 + 2.0 * kChordShapeShare) : stretch, half[axis]);
            step = std::min(step, 2.0 * allowed / (std::abs(rate) * half[axis]));
        }
        const double next = step >= 1.0 - u || u + step <= u ? 1.0 : u + step;
        part(u, next);
        u = next;
    }
}

// A chord's weight per unit of its parameter u: (s1 - s0) (1 + tilt s), s = s0 + u (s1 - s0).
ChordWeight chordWeight(const SweepChord& c, double tilt) {
    const double span = c.s1 - c.s0;
    return {span * (1.0 + tilt * c.s0), span * span * tilt};
}

}  // namespace

void forEachChordCell(const ConvexPolygon& q, const SweepPath& path, int positions, CellSink add, SweepKnots knots) {
    if (q.degenerate()) return;
    if (q.n > kMaxStoredVertices) {  // more vertices than stored fragments have: cut it into stored-size pieces
        std::vector<ConvexPolygon> parts;
        splitToCapacity(q, kMaxStoredVertices, parts);
        for (const ConvexPolygon& part : parts) forEachChordCell(part, path, positions, add, knots);
        return;
    }
    const RasterBounds box = q.bounds();
    // A stretch along the raster axes keeps an axis-aligned rectangle axis-aligned, its sides moving linearly.
    if (swept_detail::axisAlignedRectangle(q)) {
        forEachChord(path, positions, knots, [&](const SweepChord& c) {
            const auto at = [&](const glm::dvec2& offset, const glm::dvec2& stretch, const glm::dvec2& corner) {
                return path.pivot + offset + stretch * (corner - path.pivot);
            };
            const glm::dvec2 lo = at(c.from, c.stretch_from, box.lo), hi = at(c.from, c.stretch_from, box.hi);
            translatingRectangleCells({lo, hi, at(c.to, c.stretch_to, box.lo) - lo, at(c.to, c.stretch_to, box.hi) - hi},
                                      chordWeight(c, path.tilt), add);
        });
        return;
    }
    // Parts translate the box centre, which moves linearly as every vertex does, and hold the shape about
    // it, so a part errs by half its stretch change times the half-size, wherever the pivot is.
    const glm::dvec2 centre = 0.5 * (box.lo + box.hi), half = 0.5 * (box.hi - box.lo);
    SmallPolygon moved;
    moved.n = q.n;
    forEachChord(path, positions, knots, [&](const SweepChord& c) {
        const auto centreAt = [&](double u) {
            return path.pivot + c.from + u * (c.to - c.from) + (c.stretch_from + u * (c.stretch_to - c.stretch_from)) * (centre - path.pivot);
        };
        const double span = c.s1 - c.s0;
        forEachShapePart(c, half, [&](double u0, double u1) {
            const glm::dvec2 stretch = c.stretch_from + (0.5 * (u0 + u1)) * (c.stretch_to - c.stretch_from);
            const glm::dvec2 from = centreAt(u0);
            for (int i = 0; i < q.n; ++i) moved.v[i] = from + stretch * (q.v[i] - centre);
            const SweepChord part{c.s0 + u0 * span, c.s0 + u1 * span, {}, {}, {}, {}};
            translatingCells(moved, centreAt(u1) - from, chordWeight(part, path.tilt), add);
        });
    });
}

RasterBounds chordBounds(const ConvexPolygon& q, const SweepPath& path, int positions) {
    const RasterBounds box = q.bounds();
    const bool rectangle = swept_detail::axisAlignedRectangle(q);
    const glm::dvec2 half = 0.5 * (box.hi - box.lo);
    double reach = 0.0;  // how far a part of one shape can reach past the chord's ends (chordShapeTolerance)
    RasterBounds out;
    forEachChord(path, positions, SweepKnots::All, [&](const SweepChord& c) {
        if (!rectangle && c.stretch_from != c.stretch_to) {
            for (int axis = 0; axis < 2; ++axis)
                reach = std::max(reach, chordShapeTolerance(std::max(c.stretch_from[axis], c.stretch_to[axis]), half[axis]));
        }
        for (const auto& [offset, stretch] : {std::pair{c.from, c.stretch_from}, std::pair{c.to, c.stretch_to}}) {
            const glm::dvec2 at = path.pivot + offset;
            const glm::dvec2 a = at + stretch * (box.lo - path.pivot), b = at + stretch * (box.hi - path.pivot);
            out.lo = glm::min(out.lo, glm::min(a, b));
            out.hi = glm::max(out.hi, glm::max(a, b));
        }
    });
    out.pad(reach);
    return out;
}

}  // namespace clipblur
