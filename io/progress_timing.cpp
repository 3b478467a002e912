#include "io/progress_timing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace clipblur {

std::string formatDuration(double seconds) {
    char text[32];
    const double s = std::max(0.0, seconds);
    if (s < 60.0) {
        std::snprintf(text, sizeof text, "%.1f s", s);
    } else if (s < 3600.0) {
        const long long whole = std::llround(s);
        std::snprintf(text, sizeof text, "%lld min %02lld s", whole / 60, whole % 60);
    } else {
        const long long minutes = std::llround(s / 60.0);
        std::snprintf(text, sizeof text, "%lld h %02lld min", minutes / 60, minutes % 60);
    }
    return text;
}

std::string progressTiming(double elapsed_seconds, long long done, long long total) {
    std::string text = formatDuration(elapsed_seconds) + " elapsed, ETA ";
    if (done <= 0 || total <= 0) return text + "?";
    const double remaining = elapsed_seconds * static_cast<double>(total - done) / static_cast<double>(done);
    return text + formatDuration(remaining);
}

}  // namespace clipblur
