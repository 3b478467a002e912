#pragma once

#include <string>

namespace clipblur {

// A duration for a progress display: "42.0 s" under a minute, "3 min 07 s" under an hour, else
// "2 h 05 min".
std::string formatDuration(double seconds);

// "<elapsed> elapsed, ETA <remaining>" after `done` of `total` units took `elapsed_seconds`; the ETA
// assumes the remaining units cost what the finished ones did on average, and reads "ETA ?" before
// the first unit is done.
std::string progressTiming(double elapsed_seconds, long long done, long long total);

}  // namespace clipblur
