#pragma once

#include "renderer/render.h"

namespace clipblur {

// The paper's method (Method::Clipped) and its frame-0-only ablation (Method::Frame0Only).
RenderResult renderClipped(const RenderJob& job, int frame, const RenderCallbacks& callbacks);

// The accumulation buffer (Haeberli & Akeley): job.render.samples still clipped renders at midpoint
// times over the shutter, averaged.
RenderResult renderAccumulation(const RenderJob& job, int frame, const RenderCallbacks& callbacks);

}  // namespace clipblur
