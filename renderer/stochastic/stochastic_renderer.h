#pragma once

#include "renderer/render.h"

namespace clipblur {

// Reference renderer: per pixel `job.render.samples` multi-jittered space-time samples (see
// sampling/pixel_samples.h), each a primary ray traced by Embree at its own time through the raster
// sample point of the exact camera at that time, box filtered. Output channels R, G, B (background where
// no surface is hit), A = covered fraction, and the AOVs the job asks for: Z (camera depth averaged over
// covered samples; +inf where nothing is covered), coverage (= A), motion.x/motion.y (raster motion in
// pixels of the hit surface point from shutter open to close, x right and y down, averaged over covered
// samples). Tiles run in parallel, each writes only its own pixels and every random number comes from
// (seed, frame, pixel, sample), so the image is bit-identical for any thread count.
RenderResult renderStochastic(const RenderJob& job, int frame, const RenderCallbacks& callbacks = {});

}  // namespace clipblur
