#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "renderer/image.h"

namespace clipblur {

// Peak resident set size of this process so far, in bytes (getrusage ru_maxrss).
long long peakMemoryBytes();

// The stats of one frame as JSON: {"frame", "image", "threads", "peak_memory_bytes", "seconds": {stage:
// s}, "counts": {...}, "info": {...}}.
nlohmann::json statsToJson(const RenderStats& stats, int frame, const std::string& image_path, int threads);

// Writes the JSON (indented, keys sorted) atomically, alone or as part of `group`. Throws
// Error(ExitCode::Output).
void writeStats(const std::filesystem::path& path, const nlohmann::json& stats);
void writeStats(AtomicFileGroup& group, const std::filesystem::path& path, const nlohmann::json& stats);

}  // namespace clipblur
