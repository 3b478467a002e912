#pragma once

#include <atomic>
#include <functional>

#include "renderer/image.h"
#include "renderer/object_coverage.h"
#include "scene/job.h"

namespace clipblur {

struct RenderCallbacks {
    std::function<void(long long done, long long total)> progress;  // called from worker threads, serialised
    const std::atomic<bool>* cancel = nullptr;                      // set by a signal handler to stop early
};

struct RenderResult {
    Image image;  // R, G, B, A and the AOVs the job asks for, over renderWindow(job) only
    ObjectCoverage objects;  // per-object coverage over the same window when output.cryptomatte asks
    RenderStats stats;
};

// The pixels a render of `job` computes: job.render.window, or the whole film when unset. Throws
// Error(ExitCode::Render) for an empty window or one reaching outside the film.
DataWindow renderWindow(const RenderJob& job);

// Renders frame `frame` of the job with the job's method. Throws Error(ExitCode::Interrupted) when cancelled.
RenderResult renderFrame(const RenderJob& job, int frame, const RenderCallbacks& callbacks = {});

}  // namespace clipblur
