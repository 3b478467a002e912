#pragma once

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

// Whether the probe at times a quarter, half and three quarters into [a, b] finds a surface hidden at
// both a and b; counts every probe it ran into `total`.
bool hidesSomethingAtBothEnds(const FrameSetup& frame, double a, double b, HiddenProbe& total);

}  // namespace clipblur
