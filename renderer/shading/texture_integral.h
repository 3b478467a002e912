#pragma once

#include <glm/glm.hpp>

#include "renderer/geometry/convex_polygon.h"
#include "renderer/shading/texel_pyramid.h"

namespace clipblur {

// The exact mean of an image's bilinear image over a convex polygon in texture space (s, t), the
// `integral` fragment-shading rule (docs/design.md, "Integration rule over a piece"). The bilinear image
// of a level is what a point lookup reads there: texel (i, j)'s value at ((i + 1/2) / width, (j + 1/2) /
// height), interpolated bilinearly between texel centres, repeating in s and t, t = 0 the top row. The
// polygon is cut along the texel-centre grid and, in each cell, the bilinear polynomial a + b x + c y +
// d x y is integrated exactly from the cell polygon's moments (Green's theorem). Either orientation; no
// allocation.

// About how many texel cells a polygon may touch at the level it is integrated on, which bounds the cost.
// A coarser level is the box-filtered image, blurrier than level 0 by about its texel: the error that
// leaves is at the polygon's edges, so a level is judged by the cells the polygon touches (area plus half
// its perimeter plus one, in texels: (n + 1)(m + 1) for an n x m axis-aligned rectangle off the grid)
// rather than by its bounding box, which would send thin pieces (grazing views) to a level coarser than
// their width. 32: where the still globe's error stops falling (docs/design.md).
inline constexpr double kIntegralCellBudget = 32.0;

// The finest level of `pyramid` at which `st` touches at most about `cell_budget` texel cells (area + half
// the perimeter + 1, in texels); the coarsest level when none does. `pyramid` has at least one level.
int integralLevel(const TexelPyramid& pyramid, const ConvexPolygon& st, double cell_budget);

// A weight affine in (s, t), 1 + slope . (st - at), positive over the polygon it weighs. A raster piece's
// preimage is weighted by the map's Jacobian (the raster area per unit (s, t)), which goes as 1/z^3 for
// the depth z, affine in (s, t) on a triangle: linearised about the piece's centroid, the weight that
// turns the mean over (s, t) into the mean over the raster piece to second order in z's change over it.
struct AffineWeight {
    glm::dvec2 at{0.0};
    glm::dvec2 slope{0.0};
};

// The weighted mean of `level`'s bilinear image over `st` (the plain mean by default); for a polygon of
// zero area (a degenerate UV map), the image at the mean of its vertices.
glm::dvec3 bilinearMean(const TexelLevel& level, const ConvexPolygon& st, const AffineWeight& weight = {});

// bilinearMean at integralLevel.
glm::dvec3 textureMean(const TexelPyramid& pyramid, const ConvexPolygon& st, const AffineWeight& weight = {},
                       double cell_budget = kIntegralCellBudget);

// The (s, t) polygon a piece's colour stands for and its weight: what the `integral` rule averages over.
struct TexturePiece {
    ConvexPolygon st;
    AffineWeight weight;
};

// `level`'s bilinear image at (s, t): what a point lookup at level 0 returns (in double).
glm::dvec3 bilinearAt(const TexelLevel& level, const glm::dvec2& st);

}  // namespace clipblur
