#include "renderer/render.h"

#include <string>

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
        case Method::Accumulation:
        case Method::Frame0Only:
            break;
    }
    throw Error(ExitCode::Render, std::string("method '") + methodName(job.render.method) +
                                      "' is not available in this build");
}

}  // namespace clipblur
