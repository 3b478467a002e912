#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "renderer/clipped/clipped_stats.h"
#include "renderer/stochastic/stochastic_stats.h"
#include "scene/pixel_bounds.h"

namespace clipblur {

// Counters and timings of one render: typed fields, read as fields by the code and the tests.
//
// Each stage's stats struct is declared beside the code that counts (CandidateStats, FrameFragmentStats,
// ReclipStats, ClippedStats, ...) and lists its fields once, in
//     template <class Fields> void fields(Fields& f) const;
// calling f.count(name, value), f.seconds(name, value), f.value(name, value) (a measured real number)
// and f.info(name, text) per field and
// f.nest(prefix, member) per nested struct, whose names then get the prefix. The names are the stats
// JSON's keys; one writer (statsToJson) walks them.
struct RenderStats {
    int frame = 0;
    int threads = 0;  // worker threads the render could use
    double total_seconds = 0.0, cpu_seconds = 0.0;
    std::variant<ClippedStats, StochasticStats, AccumulationStats> method;
    std::vector<std::string> warnings;  // for the user: what may show in the image and why
    std::optional<PixelBounds> window;  // a tile shard's data window
    struct Reference {
        std::string path;
        double rmse = 0.0, max_abs = 0.0, mean_abs = 0.0;  // R, G, B against the reference image
    };
    std::optional<Reference> reference;

    const ClippedStats& clipped() const { return std::get<ClippedStats>(method); }
    const StochasticStats& stochastic() const { return std::get<StochasticStats>(method); }
    const AccumulationStats& accumulation() const { return std::get<AccumulationStats>(method); }
    // The largest re-clip count of a tile: 0 for methods without re-clips or when nothing moved.
    long long subframesMaxPerTile() const {
        const auto* c = std::get_if<ClippedStats>(&method);
        return c ? c->subframes_max_per_tile : 0;
    }

    template <class Fields>
    void fields(Fields& f) const {
        f.count("frame", frame);
        f.count("threads", threads);
        f.seconds("total", total_seconds);
        f.seconds("cpu", cpu_seconds);
        std::visit([&](const auto& m) { m.fields(f); }, method);
        if (!warnings.empty()) {
            std::string joined;
            for (const std::string& w : warnings) joined += (joined.empty() ? "" : "; ") + w;
            f.info("warning", joined);
        }
        if (window) f.info("window", toString(*window));
        if (reference) f.info("reference", reference->path);
    }
};

}  // namespace clipblur
