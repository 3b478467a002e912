#pragma once

#include <array>
#include <cstdint>

#include <glm/vec2.hpp>

#include "renderer/geometry/convex_polygon.h"

namespace clipblur {

// One surface contributing to a fragment.
struct FragmentSource {
    std::uint32_t source = 0;
    std::uint8_t layer = 0;
    float weight = 1.0f;

    bool operator==(const FragmentSource&) const = default;
};

// A visible convex piece of one pixel. Fragments of a pixel do not overlap. Normally one source; two when
// surfaces from both layers coincide there (same surface seen at frames 0 and 1): then the colour is
// sum(weight_i * colour_i) / sum(weight_i), and the geometry is that of sources[0] (the lower layer).
struct Fragment {
    std::array<glm::dvec2, kMaxStoredVertices> vertices{};  // raster space, counter-clockwise
    std::uint8_t vertex_count = 0;
    std::uint8_t source_count = 0;
    std::array<FragmentSource, 2> sources{};  // sorted by layer
    double area = 0.0;                        // px^2

    // Normalised mix factor of source i (1 for a single-source fragment).
    double mix(int i) const {
        if (source_count < 2) return 1.0;
        const double total = double(sources[0].weight) + double(sources[1].weight);
        return total > 0.0 ? sources[i].weight / total : 0.5;
    }
};

}  // namespace clipblur
