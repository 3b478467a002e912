#pragma once

#include <vector>

#include <glm/vec4.hpp>

#include "renderer/image.h"
#include "renderer/object_coverage.h"
#include "renderer/render_callbacks.h"
#include "renderer/render_stats.h"
#include "scene/job.h"

namespace clipblur {

struct RenderResult {
    Image image;  // R, G, B, A and the AOVs the job asks for, over renderWindow(job) only
    ObjectCoverage objects;  // per-object coverage over the same window when output.cryptomatte asks
    RenderStats stats;
    // Clipped: per pixel of the window, the nested rules' difference Q_3h - Q_h in R, G, B and covered
    // area (renderer/clipped/time_error.h), the signed time error its estimated_error sums; else empty.
    std::vector<glm::vec4> level_differences;
};

// The pixels a render of `job` computes: job.render.window, or the whole film when unset. Throws
// Error(ExitCode::Render) for an empty window or one reaching outside the film.
PixelBounds renderWindow(const RenderJob& job);

// Renders frame `frame` of the job with the job's method. Throws Error(ExitCode::Interrupted) when cancelled.
RenderResult renderFrame(const RenderJob& job, int frame, const RenderCallbacks& callbacks = {});

}  // namespace clipblur
