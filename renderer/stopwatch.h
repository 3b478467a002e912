#pragma once

#include <chrono>

#include <sys/resource.h>

namespace clipblur {

// Wall-clock timing of render stages for the stats file.
using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU seconds (user + system, all threads) this process has used so far. Unlike wall clock, other
// processes on the machine barely move it, so the perf gate compares renders by it.
inline double processCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

}  // namespace clipblur
