#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <type_traits>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat2x2.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "renderer/geometry/convex_polygon.h"
#include "renderer/geometry/pixel_cells.h"

namespace clipblur {

// A translation over an interval, s in [-1/2, 1/2], of the point `pivot` (seen at s = 0). Its
// homogeneous raster coordinates (raster x depth, depth) follow the parabola through their exact values at
// the ends and the middle; the raster position is their ratio:
//     offset(s) = (s chord + 4 s^2 bend) / w(s),   w(s) = 1 + s depth_chord + 4 s^2 depth_bend,
// w being the point's depth relative to its depth at s = 0. Homogeneous coordinates are linear in the
// point's camera-space position, so under camera and object translation (a pan, a dolly, objects sliding)
// the parabola is exact (a straight line, bend 0) and so is the path. With depth_chord = depth_bend = 0 it
// is the raster parabola through the three positions.
// A turning camera turns every point's homogeneous coordinates by one homography per time (cameraTurn):
// with `turns` (one per swept position, shared by the interval's fragments) the parabola is that of the
// coordinates as the camera would see them without turning, turned back exactly at each position, so
// only object rotation leaves a third-order error.
// Optionally a stretch about the pivot: per raster axis the factor (1 + s stretch_chord + 4 s^2
// stretch_bend) / (depth ratio at s), through 1 at s = 0 and the surface's stretch at the ends, so a
// fragment on a surface the camera dollies away from shrinks with it (exactly so for a surface facing
// the camera).
// A point's raster position and camera depth at one time of its path.
struct PathPoint {
    glm::dvec2 raster{0.0};
    double depth = 1.0;
};

struct SweepPath {
    glm::dvec2 chord{0.0};
    glm::dvec2 bend{0.0};
    glm::dvec2 pivot{0.0};
    glm::dvec2 stretch_chord{0.0};
    glm::dvec2 stretch_bend{0.0};
    double depth_chord = 0.0;
    double depth_bend = 0.0;
    double depth_open = 1.0, depth_close = 1.0;  // the point's depth at s = -1/2 and 1/2 over its depth at 0
    std::span<const glm::dmat3> turns{};         // empty, or the camera's turn at each swept position
    // The exact offsets at s = -1/2 and 1/2 and the stretch there (through, setStretch): with turns, reach
    // and sweptBounds bound the path by the hull of the raster parabola through them instead.
    glm::dvec2 open_offset{0.0}, close_offset{0.0};
    glm::dvec2 open_stretch{1.0}, close_stretch{1.0};
    // A shutter curve's weight over the interval relative to its weight at s = 0, 1 + tilt s (linear
    // within a shutter segment): position s counts (1 + tilt s) / positions. 0 for a box shutter.
    double tilt = 0.0;

    // The path of a point at a, m, b (depths > 0) at s = -1/2, 0, 1/2;
    // with a turning camera, unturn_a and unturn_b take homogeneous coordinates at the ends back to the
    // camera's orientation at s = 0 (the inverses of cameraTurn there).
    static SweepPath through(const PathPoint& a, const PathPoint& m, const PathPoint& b,
                             const glm::dmat3& unturn_a = glm::dmat3(1.0), const glm::dmat3& unturn_b = glm::dmat3(1.0));
    double depthAt(double s) const { return 1.0 + s * depth_chord + (4.0 * s * s) * depth_bend; }
    // Offset and stretch at s, the camera turned by `turn` there (null: no turn), with one division.
    void place(double s, const glm::dmat3* turn, glm::dvec2& offset, glm::dvec2& stretch) const {
        const double q = 4.0 * s * s, w = 1.0 + s * depth_chord + q * depth_bend;
        const glm::dvec2 g = s * chord + q * bend, n = glm::dvec2(1.0) + s * stretch_chord + q * stretch_bend;
        if (!turn) {
            const double inv = 1.0 / w;
            offset = g * inv;
            stretch = n * inv;
            return;
        }
        const glm::dvec3 h = *turn * glm::dvec3(pivot * w + g, w);
        const double inv = 1.0 / h.z;
        offset = glm::dvec2(h) * inv - pivot;
        stretch = n * inv;
    }
    // The turn at position k of `positions`, or null.
    const glm::dmat3* turnAt(int k, int positions) const {
        return turns.size() == static_cast<std::size_t>(positions) ? &turns[static_cast<std::size_t>(k)] : nullptr;
    }
    // Sets the stretch so that it is `open` at s = -1/2 and `close` at s = 1/2.
    void setStretch(const glm::dvec2& open, const glm::dvec2& close);
    bool moves() const;
    // Whether it is a translation at a constant rate (no bend, depth change, stretch or turn): then an
    // exact sweep's chords all have one velocity and are one (chord_sweep.h).
    bool translates() const;
    // Bounds the pivot's offset over the interval: (|chord| / 2 + |bend|) / (least w), infinity when w
    // reaches 0 (the point would cross the camera plane). With turns, the farthest of the open and close
    // offsets and the control point of the raster parabola through them (its Bezier hull holds it),
    // plus 10% and 0.1 px for how far the turned path can leave that parabola within a re-clip interval.
    double reach() const;
};

// The stretch a sweep gives a surface along raster axis `axis`, from the affine map `map` that carries it
// between two times: the length of the axis' image, negative where that image points backwards (a face
// turning edge-on and away mirrors along the axis it narrows in).
inline double signedStretch(const glm::dmat2& map, int axis) {
    return map[axis][axis] < 0.0 ? -glm::length(map[axis]) : glm::length(map[axis]);
}

// The pixel coverage of a convex polygon q moving along `path`, averaged over `positions` equally spaced
// times, the midpoints s = (m + 1/2) / positions - 1/2, m = 0 .. positions-1: calls add(x, y, weight) per
// (position, pixel) with the area of that position's piece in the pixel divided by `positions` (and times
// the shutter curve's 1 + tilt s), or add(x, y, weight, m) when `add` takes the position index too; the
// weights sum to area(q) times the share of positions where the stretch is positive along both axes (a
// surface turning edge-on and away is not there at the others). Axis-aligned rectangles (most fragments inside a surface are whole or partial
// pixels) take a separable fast path. A template so that a caller summing into pixels does so directly.
// With `clip`, only its cells are visited (the same weights there), and a position's polygon costs what
// it covers of them: a fragment stretched huge near the camera plane, or passing far off the tile.
template <class Add>
void forEachSweptCell(const ConvexPolygon& q, const SweepPath& path, int positions, const PixelBounds& clip, Add&& add);
template <class Add>
void forEachSweptCell(const ConvexPolygon& q, const SweepPath& path, int positions, Add&& add) {
    forEachSweptCell(q, path, positions, kAllCells, add);
}

// The same, appended to `out`.
void sweptFootprint(const ConvexPolygon& q, const SweepPath& path, int positions, std::vector<PixelWeight>& out);

// Raster bounds of every position's moved polygon (for sizing the pixels a footprint can reach): tight
// without turns; with them, from the hull reach() uses and the stretch's range, with the same margins.
RasterBounds sweptBounds(const ConvexPolygon& q, const SweepPath& path, int positions);

namespace swept_detail {

bool axisAlignedRectangle(const ConvexPolygon& q);

// forEachSweptCell with add(x, y, weight, position index).
template <class Add>
void sweptCellsIndexed(const ConvexPolygon& q, const SweepPath& path, int positions, const PixelBounds& clip, Add&& add) {
    if (q.degenerate() || q.n > kMaxStoredVertices) {
        if (!q.degenerate()) {  // more vertices than stored fragments have: cut it into stored-size pieces
            std::vector<ConvexPolygon> parts;
            splitToCapacity(q, kMaxStoredVertices, parts);
            for (const ConvexPolygon& part : parts) sweptCellsIndexed(part, path, positions, clip, add);
        }
        return;
    }
    const int m = std::max(1, positions);
    const double scale = 1.0 / m;
    // A stretch along the raster axes keeps an axis-aligned rectangle axis-aligned.
    if (axisAlignedRectangle(q)) {
        const RasterBounds box = q.bounds();
        const glm::dvec2 clip_lo(clip.x0, clip.y0), clip_hi(clip.x1, clip.y1);
        for (int k = 0; k < m; ++k) {
            const double s = (k + 0.5) / m - 0.5;
            glm::dvec2 offset, stretch;
            path.place(s, path.turnAt(k, m), offset, stretch);
            if (!(stretch.x > 0.0 && stretch.y > 0.0)) continue;  // edge-on or facing away
            const double share = scale * (1.0 + path.tilt * s);  // exactly scale without a curve
            const glm::dvec2 at = path.pivot + offset;
            // Clamped to the clip, the overlaps with its cells are unchanged.
            const glm::dvec2 lo = glm::max(at + stretch * (box.lo - path.pivot), clip_lo);
            const glm::dvec2 hi = glm::min(at + stretch * (box.hi - path.pivot), clip_hi);
            if (!(lo.x < hi.x && lo.y < hi.y)) continue;
            cellOverlaps(lo.y, hi.y, [&](int y, double h) {
                cellOverlaps(lo.x, hi.x, [&](int x, double w) { add(x, y, w * h * share, k); });
            });
        }
        return;
    }
    SmallPolygon moved;
    moved.n = q.n;
    for (int k = 0; k < m; ++k) {
        const double s = (k + 0.5) / m - 0.5;
        glm::dvec2 offset, stretch;
        path.place(s, path.turnAt(k, m), offset, stretch);
        if (!(stretch.x > 0.0 && stretch.y > 0.0)) continue;
        const glm::dvec2 at = path.pivot + offset;
        for (int i = 0; i < q.n; ++i) moved.v[i] = at + stretch * (q.v[i] - path.pivot);
        polygonCells(moved, clip, scale * (1.0 + path.tilt * s), [&](int x, int y, double w) { add(x, y, w, k); });
    }
}

}  // namespace swept_detail

template <class Add>
void forEachSweptCell(const ConvexPolygon& q, const SweepPath& path, int positions, const PixelBounds& clip, Add&& add) {
    if constexpr (std::is_invocable_v<Add&, int, int, double, int>)
        swept_detail::sweptCellsIndexed(q, path, positions, clip, add);
    else
        swept_detail::sweptCellsIndexed(q, path, positions, clip, [&](int x, int y, double w, int) { add(x, y, w); });
}

}  // namespace clipblur
