#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/geometry/convex_polygon.h"
#include "renderer/geometry/swept_footprint.h"
#include "renderer/integrate/interval_layout.h"
#include "renderer/integrate/tile_sums.h"
#include "renderer/object_coverage.h"

namespace clipblur {

// Per px^2 of a swept polygon, what each object adds to its coverage: a fragment's sources with their
// mix factors; a fragment merged into its pixel's rectangle (mergePixel) its difference to the
// rectangle's, signed, as its colour is carried; nothing for a texture piece.
struct PolygonObjects {
    std::array<ObjectShare, 4> shares{};
    int count = 0;

    void add(int object, double amount);  // merged into an entry of the same object
    bool none() const;                    // every entry zero: the polygon adds no coverage
};

// Sweep: one polygon to sweep and what it adds per px^2 of its footprint. Texture pieces add only their
// colour difference (coverage false); fragments add colour, coverage, motion and depth.
struct SweptPolygon {
    ConvexPolygon polygon;
    SweepPath path;
    int positions = 1;
    glm::dvec3 colour{0.0};
    glm::dvec2 motion{0.0};
    double depth = 0.0;  // 0 where unknown: adds nothing to the depth sums
    bool coverage = true;
    PolygonObjects objects;
};

// Sweep: a pixel whose fragments are all of one motion group (objects moving as one, MotionPlan::groups),
// stretch alike and together fill an axis-aligned rectangle
// (mostly the whole pixel, cut only where the two frames' triangulations of one surface cross it) is
// swept as that rectangle, with the largest fragment's path and colour; the other fragments add only
// their colour differences (none on a flat-shaded surface). The rectangle takes the separable fast path,
// where each cut piece took the general one at several times the cost. Within a pixel surfaces that move
// as one in the world move alike on screen to well under a pixel, so one path serves the pixel; the AOVs
// take the fragments' area-weighted means. `swept` holds the pixel's entries from `begin` on; `staging` is scratch.
void mergePixel(std::vector<SweptPolygon>& swept, std::size_t begin, std::vector<SweptPolygon>& staging);

// Sweep: adds a tile's swept polygons into `out`, sized to the pixels their footprints reach (within
// sweep.box, which bounds them but can be a film's worth of pixels when a fast fragment makes it large).
void accumulateSwept(const SweepInterval& sweep, const PixelBounds& tile, std::span<const SweptPolygon> swept, TileSums& out);

}  // namespace clipblur
