#pragma once

#include <vector>

#include "renderer/frame_motion.h"
#include "renderer/tiles.h"
#include "scene/shutter_curve.h"

namespace clipblur {

// The paper builds fragment sets only at shutter open and close, so a surface hidden at both ends but
// seen in between (the side of the world a camera turning 90 degrees sweeps past) is missing from both.
// Splitting the shutter into segments, each with its own fragment sets at its ends, bounds how far
// anything turns between two sets; what is still hidden at both ends of a segment (the wall behind a
// propeller whose blades return to the same places) is kept in its sets' deep tiles (ShutterSegment).
// `requested` > 0 is used as given; 0 (auto) gives one segment per kAutoSegmentTurnDegrees of the
// camera's turn or per kAutoSegmentObjectTurnDegrees of the largest object turn, whichever is more, at
// most max_segments; a shutter with no rotation is one segment, the paper's method.
// The two differ because what a camera turns to see can lie outside both end frames, where no set
// holds it, while what an object's turn uncovers lies where the object passes: a segment in which an
// object turns more than kAutoSegmentTurnDegrees keeps every layer over its swept footprint
// (turningObjectTiles), which no end sets, however close, guarantee.
inline constexpr double kAutoSegmentTurnDegrees = 15.0;
inline constexpr double kAutoSegmentObjectTurnDegrees = 60.0;
int shutterSegments(const FrameMotion& motion, int requested, int max_segments);

// One shutter segment and its share of the shutter.
struct ShutterSegment {
    double begin = 0.0, end = 0.0;
    double weight = 1.0;  // its share of the shutter: 1 / count for equal segments
    // The shutter curve's (unnormalised) weight at begin and end, linear between: equal for a box.
    double curve_begin = 1.0, curve_end = 1.0;
    // Film tiles near surfaces hidden at both its ends but seen in between (hiddenTiles) and over
    // objects turning far within it (turningObjectTiles): there its fragment sets keep every layer, and
    // the re-clips find what shows.
    TileSet deep = TileSet::none();
};

// `count` equal segments of [t0, t1]; each boundary is computed once, so neighbours meet at the same double.
std::vector<ShutterSegment> equalSegments(double t0, double t1, int count);

// A shutter curve that is not a box: each segment cut at the curve's breakpoints inside it, so the
// curve is linear over every piece, with the piece's share of the curve's integral as its weight. Pieces
// where the curve is 0 throughout are left out (nothing there counts). A box returns `segments` as given.
std::vector<ShutterSegment> splitAtCurve(const std::vector<ShutterSegment>& segments, const ShutterCurve& curve);

}  // namespace clipblur
