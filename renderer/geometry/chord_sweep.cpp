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
    // The farthest a vertex is from the pivot along each axis.
    const glm::dvec2 extent = glm::max(glm::abs(box.lo - path.pivot), glm::abs(box.hi - path.pivot));
    SmallPolygon moved;
    moved.n = q.n;
    forEachChord(path, positions, knots, [&](const SweepChord& c) {
        // Half the stretch change over a part times the extent is how far a vertex is off at its ends.
        const glm::dvec2 change = glm::abs(c.stretch_to - c.stretch_from) * extent;
        const int parts = std::max(1, static_cast<int>(std::ceil(0.5 * std::max(change.x, change.y) / kChordShapeTolerance)));
        const double span = (c.s1 - c.s0) / parts;
        for (int k = 0; k < parts; ++k) {
            const double u0 = double(k) / parts, u1 = double(k + 1) / parts, um = 0.5 * (u0 + u1);
            const SweepChord part{c.s0 + k * span, c.s0 + (k + 1) * span, c.from + u0 * (c.to - c.from),
                                  c.from + u1 * (c.to - c.from), {}, {}};
            const glm::dvec2 stretch = c.stretch_from + um * (c.stretch_to - c.stretch_from);
            const glm::dvec2 at = path.pivot + part.from;
            for (int i = 0; i < q.n; ++i) moved.v[i] = at + stretch * (q.v[i] - path.pivot);
            translatingCells(moved, part.to - part.from, chordWeight(part, path.tilt), add);
        }
    });
}

RasterBounds chordBounds(const ConvexPolygon& q, const SweepPath& path, int positions) {
    const RasterBounds box = q.bounds();
    const bool rectangle = swept_detail::axisAlignedRectangle(q);
    bool reshaped = false;  // a part of one shape can reach past the chord's ends (kChordShapeTolerance)
    RasterBounds out;
    forEachChord(path, positions, SweepKnots::All, [&](const SweepChord& c) {
        reshaped = reshaped || (!rectangle && c.stretch_from != c.stretch_to);
        for (const auto& [offset, stretch] : {std::pair{c.from, c.stretch_from}, std::pair{c.to, c.stretch_to}}) {
            const glm::dvec2 at = path.pivot + offset;
            const glm::dvec2 a = at + stretch * (box.lo - path.pivot), b = at + stretch * (box.hi - path.pivot);
            out.lo = glm::min(out.lo, glm::min(a, b));
            out.hi = glm::max(out.hi, glm::max(a, b));
        }
    });
    if (reshaped) out.pad(kChordShapeTolerance);
    return out;
}

}  // namespace clipblur
