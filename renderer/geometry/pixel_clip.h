#pragma once

#include <array>
#include <cstdint>

#include <glm/vec2.hpp>

#include "renderer/geometry/convex_polygon.h"

namespace clipblur {

// Exact clipping of one raster-space triangle to axis-aligned pixel cells.
//
// Watertightness: a crossing point of the triangle with the grid line x = X is computed from the ORIGINAL
// triangle edge it lies on (never from an already clipped sub-edge) and gets x = X exactly; where a cut runs
// along an earlier grid cut the point is the exact grid corner. So the two pixels on either side of a
// pixel edge produce bit-identical shared vertices, whatever order the cuts are made in, and the pixel
// pieces of a triangle tile it with no gap or overlap beyond the rounding of the crossing ordinates.
class TriangleClipper {
public:
    explicit TriangleClipper(const std::array<glm::dvec2, 3>& raster);

    // False for triangles with zero or non-finite signed area (nothing to clip).
    bool valid() const { return valid_; }
    // Signed area of the (counter-clockwise normalised) triangle.
    double area() const { return area_; }
    const std::array<glm::dvec2, 3>& vertices() const { return tri_; }

    // A clipped piece that remembers which line each edge lies on: edge[i] (v[i] -> v[i+1]) is a triangle
    // edge 0..2 or kGridEdge for an axis-aligned cut.
    static constexpr std::int8_t kGridEdge = -1;
    struct Piece {
        ConvexPolygon poly;
        std::array<std::int8_t, kMaxPolygonVertices> edge{};
    };

    // The part of the triangle inside the horizontal strip y in [y0, y1].
    void clipToStrip(double y0, double y1, Piece& out) const;
    // The part of a strip piece inside x in [x0, x1].
    void clipToColumn(const Piece& strip, double x0, double x1, ConvexPolygon& out) const;
    // The part of the triangle inside the pixel [px, px+1] x [py, py+1].
    void clipToPixel(int px, int py, ConvexPolygon& out) const;

private:
    enum class Keep { Below, Above };  // the side of the line axis = c that is kept
    void clipAxis(const Piece& in, int axis, double c, Keep keep, Piece& out) const;
    double crossingOrdinate(int edge, int axis, double c) const;

    std::array<glm::dvec2, 3> tri_;    // counter-clockwise
    std::array<glm::dvec2, 3> lo_;     // per edge: lexicographically smaller endpoint
    std::array<glm::dvec2, 3> hi_;     // per edge: the other endpoint
    double area_ = 0.0;
    bool valid_ = false;
};

}  // namespace clipblur
