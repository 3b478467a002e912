#pragma once

#include <algorithm>

#include "renderer/geometry/convex_polygon.h"
#include "renderer/geometry/swept_footprint.h"
#include "renderer/geometry/translating_coverage.h"

namespace clipblur {

// Which knots an exact sweep's chords run through: every position, or those of the nested coarser rule
// (NestedRule: the middle position of each whole group of three, and every position after the last group),
// whose difference to the first estimates the error of the first (stats `estimated_error`).
enum class SweepKnots { All, Nested };

// Exact sweep (render.sweep_time: exact): the pixel coverage of a convex polygon q moving along `path`,
// integrated over the interval exactly in time along chords. Between consecutive knots (the `positions`
// equally spaced midpoints s = (k + 1/2) / positions - 1/2, placed exactly on the path) the pivot's offset
// and the stretch about it go linearly, and before the first and after the last knot they go on at the
// first and last chord's rates to the interval's ends. Each chord's coverage is integrated in closed form,
// weighted by the shutter curve's 1 + tilt s: an axis-aligned rectangle (most fragments inside a surface
// are whole or partial pixels) with its sides moving linearly (translatingRectangleCells), any other
// polygon translating, cut where its stretch changes into parts of one shape (translatingCells). So a
// polygon translating at constant depth is exact whatever the positions, and error comes only from how far
// the path bends away from its chords. A chord counts only while its stretch is positive along both axes
// (a surface turning edge-on and away is not there). Calls add(x, y, weight) per (chord, pixel).
void forEachChordCell(const ConvexPolygon& q, const SweepPath& path, int positions, CellSink add,
                      SweepKnots knots = SweepKnots::All);

// A chord along which a polygon's shape changes (its stretch does) is cut into parts, each translating
// its centre exactly and holding the shape about it at the part's middle, so no vertex is off by more
// than chordShapeTolerance for it; they err alike either way of the middle, so coverage errs far less.
// Axis-aligned rectangles need no cut (translatingRectangleCells).
inline constexpr double kChordShapeTolerance = 1.0 / 128.0;  // px
inline constexpr double kChordShapeShare = 1.0 / 128.0;      // of the half-size, for shapes past 2 px

// The vertex error a part may have along an axis where the stretch is `stretch` and the polygon's
// half-size `half`: kChordShapeTolerance, or that share of the stretched half-size where it is larger, so
// a sliver a turning surface stretches hundreds of times is cut by ratio (parts growing geometrically),
// not into one part per 1/128 px of growth.
inline double chordShapeTolerance(double stretch, double half) {
    return std::max(kChordShapeTolerance, stretch * half * kChordShapeShare);
}

// Raster bounds of every chord's moved polygon at both its ends (a polygon whose vertices move linearly
// stays within their hull), grown by chordShapeTolerance where a polygon is cut into parts of one shape:
// the pixels forEachChordCell can reach with every knot (SweepKnots::All).
RasterBounds chordBounds(const ConvexPolygon& q, const SweepPath& path, int positions);

}  // namespace clipblur
