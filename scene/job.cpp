#include "scene/job.h"

namespace clipblur {

const char* methodName(Method method) {
    switch (method) {
        case Method::Clipped: return "clipped";
        case Method::Stochastic: return "stochastic";
        case Method::Accumulation: return "accumulation";
        case Method::Frame0Only: return "frame0_only";
    }
    return "unknown";
}

}  // namespace clipblur
