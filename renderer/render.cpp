#include "renderer/render.h"

#include <string>

#include "renderer/clipped/clipped_renderer.h"
#include "renderer/stochastic/stochastic_renderer.h"
#include "scene/error.h"

namespace clipblur {

namespace {

const char* methodName(Method method) {
    switch (method) {
        case Method::Clipped: return "clipped";
        case Method::Stochastic: return "stochastic";
        case Method::Accumulation: return "accumulation";
        case Method::Frame0Only: return "frame0_only";
    }
    return "unknown";
}

}  // namespace

RenderResult renderFrame(const RenderJob& job, int frame, const RenderCallbacks& callbacks) {
    switch (job.render.method) {
        case Method::Stochastic:
            return renderStochastic(job, frame, callbacks);
        case Method::Clipped:
        case Method::Frame0Only:
            return renderClipped(job, frame, callbacks);
        case Method::Accumulation:
            return renderAccumulation(job, frame, callbacks);
    }
    throw Error(ExitCode::Internal, std::string("unknown method ") + methodName(job.render.method));
}

}  // namespace clipblur
