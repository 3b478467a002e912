#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "renderer/object_coverage.h"
#include "renderer/tiles.h"

namespace clipblur {

// One subframe's pixel values over a box of pixels (box-local, row-major), before the background is
// added. The box is the tile, or with sweep integration the tile and the margin its fragments reach.
struct TileSums {
    PixelBounds box;
    std::vector<glm::dvec3> colour;
    std::vector<double> covered;
    std::vector<double> depth;
    std::vector<glm::dvec2> motion;
    bool track_objects = false;         // set before reclipSubframe: fill `objects` (ID mattes)
    std::vector<ObjectShares> objects;  // per object its covered area, as `covered` sums all of them
    // Sweep: per pixel what the interval's coarser nested rule (NestedRule; exact sweep: chords through its
    // knots, SweepKnots::Nested) differs by, Q_3h - Q_h over its positions, in colour and covered area.
    // Filled when track_error is set.
    bool track_error = false;
    std::vector<glm::dvec4> d3;

    void reset(const PixelBounds& box);
};

}  // namespace clipblur
