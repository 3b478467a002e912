#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "scene/data_window.h"
#include "scene/job.h"

namespace clipblur {

// A planar float image: named channels (R, G, B, A, Z, coverage, motion.x, motion.y, ...) over a
// data window inside the full display window, so tile shards can be written and merged.
struct Image {
    int width = 0;    // display window
    int height = 0;
    int x0 = 0;       // data window origin and size
    int y0 = 0;
    int data_width = 0;
    int data_height = 0;

    struct Channel {
        std::string name;
        std::vector<float> values;  // data_width * data_height, row-major
    };
    std::vector<Channel> channels;

    static Image make(int width, int height, const std::vector<std::string>& names);
    // Zeroed channels over `window` only, inside a width x height display window.
    static Image make(int width, int height, const DataWindow& window, const std::vector<std::string>& names);
    DataWindow window() const { return {x0, y0, data_width, data_height}; }
    // Row-major index into the channel values of display pixel (x, y), which must be inside window().
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y - y0) * static_cast<std::size_t>(data_width) + static_cast<std::size_t>(x - x0);
    }
    Channel* find(const std::string& name);
    const Channel* find(const std::string& name) const;
};

// The channels an image for `output` carries: R, G, B, A, then Z, coverage, motion.x, motion.y as asked.
std::vector<std::string> outputChannels(const OutputSettings& output);

// Counters and timings of one render, written to the stats JSON; ordered so output is deterministic.
struct RenderStats {
    std::map<std::string, double> seconds;
    std::map<std::string, long long> counts;
    std::map<std::string, std::string> info;
    std::map<std::string, double> error;  // against `render --reference`: rmse, max_abs, mean_abs
};

}  // namespace clipblur
