#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/clipped/frame_fragments.h"
#include "renderer/clipped/time_error.h"
#include "renderer/object_coverage.h"
#include "renderer/tiles.h"

namespace clipblur {

// One pixel's sums from one tile: to the window pixel `out` when it is another tile's pixel.
struct Spill {
    std::size_t out = 0;
    glm::dvec3 colour{0.0};
    double covered = 0.0, depth = 0.0;
    glm::dvec2 motion{0.0};
    ObjectShares objects;  // ID mattes only
    LevelDifference level{0.0f};  // the time-sampling error estimate's (time_error.h)
};

// Per-pixel sums over the render window (window-local, row-major).
struct WindowSums {
    std::vector<glm::dvec3> colour;
    std::vector<double> covered;
    std::vector<double> depth;
    std::vector<glm::dvec2> motion;
    std::vector<ObjectShares> objects;  // per object its share of `covered`; empty unless ID mattes are asked for
    std::vector<LevelDifference> levels;  // per pixel, for estimateTimeError

    // About 70 bytes a pixel, first touched (page faults) on a task per array.
    WindowSums(std::size_t pixels, bool with_objects);

    // Adds scale x one pixel's sums to pixel i, with its per-object areas when they are tracked.
    void add(std::size_t i, double scale, const Spill& s);
    // Adds scale x pixel p of a still image (no motion) to pixel i.
    void addStill(std::size_t i, double scale, const PixelSums& still, std::size_t p);
    // Adds pixel i of `other` (the same window) to pixel i.
    void addPixel(std::size_t i, const WindowSums& other);
    // Pixel i as a new WindowSums has it: zero.
    void clearPixel(std::size_t i);
};

// Adds the tiles' spills after all tiles, in tile order per pixel, so the sums do not depend on which
// thread finished first. Bands of `band_rows` rows are independent: each takes, from every tile in order,
// the run of its spills that lands in the band (each tile's spills are in row-major order). Then frees
// them, in parallel too: tens of MB, each spill's object shares visited.
void addSpills(std::vector<std::vector<Spill>>& spills, const PixelBounds& window, int band_rows, WindowSums& target);

}  // namespace clipblur
