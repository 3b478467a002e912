#pragma once

#include <functional>
#include <vector>

#include <glm/vec2.hpp>

#include "renderer/clipped/shutter_segments.h"
#include "renderer/frame_setup.h"

namespace clipblur {

// A shutter segment's fragment sets hold what is visible at its two ends. A surface seen in between but
// hidden at both ends is in neither: two objects passing over the same spot of a wall, one ending where
// the other started, leave a background-coloured hole there. Rotation-based segments do not see this
// (nothing turns), so the probe looks for it directly: one Embree ray per probe cell at a time inside
// the segment, and for each surface point it hits, whether that point is visible (in front of the
// camera and not behind another surface) at either end.
struct HiddenProbe {
    long long samples = 0;  // probe rays that hit a surface
    long long hidden = 0;   // of those, surface points hidden at both ends of the segment
    std::vector<glm::ivec2> pixels;  // the pixel each hidden point was seen in, in row-major order
};

// Probe cells are kProbeStride x kProbeStride pixels, one ray at a cell point; each probe time shifts the
// point within the cell (probeOffset), so the probes of one segment together look at 3 of every 4 pixels.
inline constexpr int kProbeStride = 2;

// A point seen at time `at` is held at an end when its depth there is in front of the camera and no other
// surface is nearer along the ray to it by more than this fraction of its distance (the fragment sets
// resolve exact geometry; Embree's time steps follow it to 0.1 px, so a point on a surface facing the
// camera can appear a hair behind its own neighbours).
inline constexpr double kHeldDepthTolerance = 1e-3;

// Probes the film at time `at`, strictly inside [a, b], with probe offset `offset` (0-3).
HiddenProbe probeHiddenAtBothEnds(const FrameSetup& frame, double a, double b, double at, int offset);

// Whether anything seen from the camera can change what it hides during [t0, t1]: false when the eye does
// not move and no object moves (a camera that only turns sees the same surfaces from the same point).
bool visibilityCanChange(const MotionWindow& window);

// The film tiles (frame.grid) where the probe, at times a quarter, half and three quarters into the
// segment, finds a surface hidden at both its ends: those within reach() pixels (how far anything moves
// over the segment; asked only when something is hidden, as measuring it scans the scene) plus a probe
// cell of a hidden point, since the surface can show anywhere it passes. Empty when nothing is hidden.
// Counts every probe it ran into `total`.
TileSet hiddenTiles(const FrameSetup& frame, const ShutterSegment& segment, const std::function<int()>& reach,
                    HiddenProbe& total);

// The film tiles over which an object turning more than kAutoSegmentTurnDegrees during the segment
// passes (its vertices' raster box at 9 times, grown by reach() pixels, the segment's guard band): what
// its turn uncovers there, a sliver between a spinning tyre's facets or the wall behind a propeller,
// was behind it, so keeping every layer there draws it whatever the probe's cells meet. Every tile
// where such an object reaches the camera plane. Empty when no object turns that far.
TileSet turningObjectTiles(const FrameSetup& frame, const ShutterSegment& segment, const std::function<int()>& reach);

}  // namespace clipblur
