#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "scene/pixel_bounds.h"
#include "scene/job.h"

namespace clipblur {

// A planar float image: named channels (R, G, B, A, Z, coverage, motion.x, motion.y, ...) over a
// data window inside the full display window, so tile shards can be written and merged.
struct Image {
    int width = 0;    // display window
    int height = 0;
    PixelBounds window;  // the data window: the pixels the channels hold

    struct Channel {
        std::string name;
        std::vector<float> values;  // window.area(), row-major
    };
    std::vector<Channel> channels;

    static Image make(int width, int height, const std::vector<std::string>& names);
    // Zeroed channels over `window` only, inside a width x height display window.
    static Image make(int width, int height, const PixelBounds& window, const std::vector<std::string>& names);
    // Row-major index into the channel values of display pixel (x, y), which must be inside window().
    std::size_t index(int x, int y) const { return window.index(x, y); }
    Channel* find(const std::string& name);
    const Channel* find(const std::string& name) const;
};

// The channels an image for `output` carries: R, G, B, A, then Z, coverage, motion.x, motion.y as asked.
std::vector<std::string> outputChannels(const OutputSettings& output);

}  // namespace clipblur
