#pragma once

#include <chrono>

namespace clipblur {

// Wall-clock timing of render stages for the stats file.
using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace clipblur
