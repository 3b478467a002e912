#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "renderer/fragments/fragment.h"
#include "renderer/fragments/pixel_resolver.h"
#include "renderer/fragments/screen_triangle.h"
#include "renderer/geometry/pixel_clip.h"
#include "scene/pixel_bounds.h"

namespace clipblur {

// Per-pixel fragment lists of a tile in CSR form: the fragments of pixel (x, y) are
// fragments[offsets[i]] .. fragments[offsets[i+1]-1] with i = (y - y0) * width + (x - x0).
struct FragmentTile {
    PixelBounds rect;
    std::vector<std::uint32_t> offsets;
    std::vector<Fragment> fragments;
    std::vector<double> covered_area;  // per pixel, px^2
    long long rejected_triangles = 0;  // non-finite, degenerate or behind the eye
    double dropped_area = 0.0;         // slivers below ResolverSettings::min_area, summed over the tile

    std::span<const Fragment> pixel(int x, int y) const {
        const std::size_t i = rect.index(x, y);
        return {fragments.data() + offsets[i], fragments.data() + offsets[i + 1]};
    }
};

// Reusable buffers for resolveTile; one per worker task.
struct TileScratch {
    struct Entry {
        std::uint32_t pixel;
        std::uint32_t triangle;
        double nearest;  // largest vertex 1/z: the sort key for front-to-back insertion
    };
    std::vector<Entry> entries;
    std::vector<std::uint32_t> counts;
    std::vector<Entry> sorted;
    // Per triangle: its clipper, and its part in the row of pixels being resolved (strip_row: which
    // row, or none yet) with that part's x extent, so each triangle is clipped to a row once, not once
    // per pixel, and not at all to the row's pixels beside it.
    std::vector<TriangleClipper> clippers;
    std::vector<TriangleClipper::Piece> strips;
    std::vector<int> strip_row;
    std::vector<glm::dvec2> strip_x;  // lowest and highest x of the strip; lo > hi when it is empty
    std::vector<glm::dvec2> strip_inner;  // x range of the whole pixel columns inside the strip; lo > hi: none
    std::vector<DepthPlane> slopes;  // per triangle: its inverse-depth plane's slopes (inverseDepthSlopes)
    PixelResolver resolver;
};

// Bins triangles to the tile's pixels by bounding box, then per pixel inserts them front to back (nearest
// vertex first, ties by triangle index) into a PixelResolver. A pixel that one surface
// (ScreenTriangle::surface) covers wholly from each layer it comes from, in front of every other piece
// there, becomes one fragment, the pixel itself, without clipping the pieces against each other. Both
// frame-0/1 visibility and the subframe re-clip of propagated fragments call this. Deterministic: the
// result depends only on the inputs.
void resolveTile(std::span<const ScreenTriangle> triangles, const PixelBounds& rect, const ResolverSettings& settings,
                 TileScratch& scratch, FragmentTile& out);

}  // namespace clipblur
