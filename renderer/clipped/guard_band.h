#pragma once

#include "renderer/frame_motion.h"
#include "scene/camera.h"

namespace clipblur {

// How far beyond the image edge (pixels) the frame-0 and frame-1 fragment sets must reach. A surface
// point seen inside the image at some time of the shutter is at shutter open or close somewhere else;
// if that is outside the image and the sets stop at the edge, the point is missing from both and the
// re-clipped subframe shows a gap (a rolling camera opens its corners this way). The band is the
// largest distance, over sampled times, from where such a point is to the nearer of where it was at open
// and where it is at close: taken over the image's corners and edge midpoints for the camera's rotation
// (depth independent) and over mesh vertices, triangle centroids and edge midpoints that come near the
// image for everything else. Zero when nothing moves; capped at `cap`.
int guardBandPixels(const FrameMotion& motion, const Projection& projection, const MotionWindow& window, int cap);

}  // namespace clipblur
