#pragma once

#include <chrono>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "renderer/render_stats.h"

namespace clipblur {

// Peak resident set size of this process so far, in bytes (getrusage ru_maxrss).
long long peakMemoryBytes();

// What the stats say about the run beside the renderer's own counts.
struct StatsContext {
    int frame = 0;
    std::string image_path;
    int threads = 0;
    std::string config_hash;
    std::string start_time;  // UTC, ISO 8601 (utcTimestamp)
};

// The stats of one frame as JSON: {"frame", "image", "threads", "config_hash", "start_time",
// "peak_memory_bytes", "seconds": {stage: s}, "counts": {...}, "values": {...}, "info": {...}} and, against a
// reference, "error": {"rmse", "max_abs", "mean_abs"}; the keys of "seconds", "counts", "values" and "info"
// are the names the stats structs give their fields (RenderStats::fields).
nlohmann::json statsToJson(const RenderStats& stats, const StatsContext& context);

// `time` as UTC ISO 8601 to the second, e.g. 2026-11-25T01:17:28Z.
std::string utcTimestamp(std::chrono::system_clock::time_point time);

// Writes the JSON (indented, keys sorted) atomically, alone or as part of `group`. Throws
// Error(ExitCode::Output).
void writeStats(const std::filesystem::path& path, const nlohmann::json& stats);
void writeStats(AtomicFileGroup& group, const std::filesystem::path& path, const nlohmann::json& stats);

}  // namespace clipblur
