#include "renderer/render.h"

#include <string>

#include "renderer/clipped/clipped_renderer.h"
#include "renderer/clipped/error_target.h"
#include "renderer/stochastic/stochastic_renderer.h"
#include "renderer/stopwatch.h"
#include "renderer/worker_threads.h"
#include "scene/error.h"

namespace clipblur {

PixelBounds renderWindow(const RenderJob& job) {
    const int width = job.scene.film.width;
    const int height = job.scene.film.height;
    if (!job.render.window) return PixelBounds::sized(0, 0, width, height);
    const PixelBounds& w = *job.render.window;
    if (w.empty() || w.x0 < 0 || w.y0 < 0 || w.x0 > width - w.width() || w.y0 > height - w.height())
        throw Error(ExitCode::Render, "render window " + toString(w) + " is empty or not inside the " +
                                          std::to_string(width) + "x" + std::to_string(height) + " film");
    return w;
}

namespace {

RenderResult renderWithMethod(const RenderJob& job, int frame, const RenderCallbacks& callbacks) {
    switch (job.render.method) {
        case Method::Stochastic:
            return renderStochastic(job, frame, callbacks);
        case Method::Clipped:
            if (job.render.error_target > 0.0) return renderToErrorTarget(job, frame, callbacks);
            return renderClipped(job, frame, callbacks);
        case Method::Frame0Only:
            return renderClipped(job, frame, callbacks);
        case Method::Accumulation:
            return renderAccumulation(job, frame, callbacks);
    }
    throw Error(ExitCode::Internal, std::string("unknown method ") + methodName(job.render.method));
}

}  // namespace

RenderResult renderFrame(const RenderJob& job, int frame, const RenderCallbacks& callbacks) {
    const double cpu_start = processCpuSeconds();
    const auto start = Clock::now();
    RenderResult result = renderWithMethod(job, frame, callbacks);
    result.stats.frame = frame;
    result.stats.threads = workerThreads();
    result.stats.total_seconds = secondsSince(start);
    result.stats.cpu_seconds = processCpuSeconds() - cpu_start;
    return result;
}

}  // namespace clipblur
