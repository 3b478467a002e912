#pragma once

#include <span>
#include <string>

#include "renderer/fragments/fragment_tile.h"
#include "renderer/fragments/screen_triangle.h"

namespace clipblur {

// Tolerances of the audit. Resolution works in pixel-local coordinates (raster minus the pixel corner,
// an exact subtraction), so rounding is that of O(1) numbers, ~1e-16 per operation; converting back to
// raster adds one rounding of the raster coordinate (1e-12 px at 8192 px). The bounds below sit three
// orders of magnitude above that and six below anything a wrong clip or visibility decision produces.
struct AuditTolerance {
    double outside = 1e-9;      // px a fragment vertex may lie outside its pixel
    double area = 1e-9;         // px^2 per pixel for overlap and for coverage against the union
    double depth_rel = 1e-6;    // relative 1/z: the resolver's coincidence tolerance (ResolverSettings)
    int max_union_inputs = 64;  // pixels with more input triangles skip the (cubic) union check
};

struct AuditStats {
    long long pixels = 0;          // pixels checked
    long long union_pixels = 0;    // of those, compared with the independent union of their inputs
    long long union_skipped = 0;   // more inputs than max_union_inputs
    long long violations = 0;
    double worst_outside = 0.0;    // px
    double worst_overlap = 0.0;    // px^2
    double worst_coverage = 0.0;   // px^2, |sum of fragment areas - union of inputs|
    std::string first_violation;   // "pixel (x, y): what"; the least such message, so it is deterministic

    void merge(const AuditStats& other);
    template <class Fields>
    void fields(Fields& f) const {
        f.count("pixels", pixels);
        f.count("union_pixels", union_pixels);
        f.count("union_skipped", union_skipped);
        f.count("violations", violations);
        f.info("worst", worstText());
    }
    std::string worstText() const;  // "outside 0 px, overlap 0 px^2, coverage 0 px^2"
    friend bool operator==(const AuditStats&, const AuditStats&) = default;
};

// Checks a tile resolved by resolveTile against its input triangles, with computations that share no
// code with the resolver:
//   - every fragment vertex lies inside its pixel, and each fragment's stored area is its shoelace area;
//   - fragments of a pixel are pairwise disjoint: the area of their union equals the sum of their areas;
//   - the fragments cover exactly what the inputs cover: their area sum equals the pixel's recorded
//     covered area and the area of the union of the input triangles inside the pixel;
//   - visibility: at every fragment's centroid no input triangle is nearer (1/z larger) than the
//     fragment's own surface by more than the coincidence tolerance. Fragments below the area tolerance
//     are not checked: a sliver's vertex mean is ill-conditioned and its weight in the pixel is < 1e-9.
// Union areas come from a vertical slab sweep: between consecutive event abscissae (vertices, pairwise
// edge crossings, crossings of the pixel's top and bottom) every convex piece's cross-section is one
// interval whose ends are linear in x and keep their order, so the union length is linear in x and its
// value at the slab midpoint times the slab width is exact.
void auditTile(std::span<const ScreenTriangle> triangles, const FragmentTile& tile, AuditStats& stats,
               const AuditTolerance& tolerance = {});

}  // namespace clipblur
