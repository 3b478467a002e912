#include "io/stats_writer.h"

#include <ctime>
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

namespace {

// Puts each field of a stats struct into its section, its name behind the prefixes of the structs around it.
struct JsonFields {
    nlohmann::json& json;
    std::string prefix;

    void count(const char* name, long long value) { json["counts"][prefix + name] = value; }
    void seconds(const char* name, double value) { json["seconds"][prefix + name] = value; }
    void value(const char* name, double value) { json["values"][prefix + name] = value; }
    void info(const char* name, const std::string& text) { json["info"][prefix + name] = text; }
    template <class Stats>
    void nest(const char* inner, const Stats& stats) {
        JsonFields nested{json, prefix + inner};
        stats.fields(nested);
    }
};

}  // namespace

nlohmann::json statsToJson(const RenderStats& stats, const StatsContext& context) {
    nlohmann::json j;
    j["frame"] = context.frame;
    j["image"] = context.image_path;
    j["threads"] = context.threads;
    j["config_hash"] = context.config_hash;
    j["start_time"] = context.start_time;
    j["peak_memory_bytes"] = peakMemoryBytes();
    j["seconds"] = nlohmann::json::object();
    j["counts"] = nlohmann::json::object();
    j["values"] = nlohmann::json::object();
    j["info"] = nlohmann::json::object();
    JsonFields fields{j, ""};
    stats.fields(fields);
    if (stats.reference)
        j["error"] = {{"rmse", stats.reference->rmse}, {"max_abs", stats.reference->max_abs},
                      {"mean_abs", stats.reference->mean_abs}};
    return j;
}

std::string utcTimestamp(std::chrono::system_clock::time_point time) {
    const std::time_t t = std::chrono::system_clock::to_time_t(time);
    std::tm utc{};
    gmtime_r(&t, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
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
