#include "io/stats_writer.h"

#include <fstream>

#include <sys/resource.h>

#include "io/atomic_file.h"
#include "scene/error.h"

namespace clipblur {

long long peakMemoryBytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return -1;
    return static_cast<long long>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

nlohmann::json statsToJson(const RenderStats& stats, int frame, const std::string& image_path, int threads) {
    nlohmann::json j;
    j["frame"] = frame;
    j["image"] = image_path;
    j["threads"] = threads;
    j["peak_memory_bytes"] = peakMemoryBytes();
    j["seconds"] = stats.seconds;
    j["counts"] = stats.counts;
    j["info"] = stats.info;
    if (!stats.error.empty()) j["error"] = stats.error;
    return j;
}

void writeStats(const std::filesystem::path& path, const nlohmann::json& stats) {
    AtomicFileGroup group;
    writeStats(group, path, stats);
    group.commit();
}

void writeStats(AtomicFileGroup& group, const std::filesystem::path& path, const nlohmann::json& stats) {
    group.write(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary);
        out << stats.dump(2) << "\n";
        out.close();
        if (!out) throw Error(ExitCode::Output, "cannot write " + temporary.string());
    });
}

}  // namespace clipblur
