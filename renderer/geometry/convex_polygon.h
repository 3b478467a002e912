#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include <glm/vec2.hpp>

#include "renderer/geometry/raster_bounds.h"

namespace clipblur {

// Working capacity of a convex polygon. Stored pieces are kept at or below kMaxStoredVertices (by
// splitToCapacity), so any single operation on two stored pieces plus one extra cut (a depth split) stays
// below this bound: 12 + 12 + 1 <= 32.
inline constexpr int kMaxPolygonVertices = 32;
inline constexpr int kMaxStoredVertices = 12;

// A convex polygon with counter-clockwise vertices (positive orient2d; in raster space, where y points
// down, that is visually clockwise). Fixed capacity so the hot path never allocates.
struct ConvexPolygon {
    std::array<glm::dvec2, kMaxPolygonVertices> v;
    int n = 0;

    ConvexPolygon() = default;
    // Copies the n vertices in use only: most pieces have 3 to 6 of the 32 places, and clipping copies
    // pieces at every cut.
    ConvexPolygon(const ConvexPolygon& o) : n(o.n) { std::copy_n(o.v.begin(), o.n, v.begin()); }
    ConvexPolygon& operator=(const ConvexPolygon& o) {
        if (this == &o) return *this;
        n = o.n;
        std::copy_n(o.v.begin(), o.n, v.begin());
        return *this;
    }

    static ConvexPolygon triangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c);

    void clear() { n = 0; }
    // Appends p unless it equals the previous vertex exactly (keeps pieces free of zero-length edges).
    // Silently ignores vertices beyond capacity, which only rounding-broken input can produce.
    void push(const glm::dvec2& p) {
        if (n > 0 && v[n - 1] == p) return;
        if (n < kMaxPolygonVertices) v[n++] = p;
    }
    // Drops a closing vertex equal to the first one; call after a sequence of push().
    void close() {
        while (n > 1 && v[n - 1] == v[0]) --n;
    }
    bool degenerate() const { return n < 3; }
    // Signed area (positive for counter-clockwise), shoelace about v[0] with compensated summation.
    double area() const;
    RasterBounds bounds() const;
};

// Splits p by the sign of per-vertex values s (an affine function sampled at the vertices; s[i] for
// p.v[i]): inside gets s >= 0, outside s <= 0. Both sides share the same computed crossing points, so the
// two parts tile p exactly. Either output may be degenerate.
void splitByValues(const ConvexPolygon& p, const double* s, ConvexPolygon& inside, ConvexPolygon& outside);

// Keeps the s >= 0 part of p.
void clipByValues(const ConvexPolygon& p, const double* s, ConvexPolygon& inside);

// Keeps the part of p on the left of the directed line a->b (orient2d(a, b, x) >= 0).
void clipByLine(const ConvexPolygon& p, const glm::dvec2& a, const glm::dvec2& b, ConvexPolygon& inside);

// Whether edge e of q (v[e] -> v[e+1]) bounds q: false only for a very short edge that rounding has
// turned into a small concavity (a neighbouring vertex strictly outside its line).
bool supportingEdge(const ConvexPolygon& q, int e);

// Splits p by the convex polygon q: appends the convex pieces of p \ q to outside (one per edge line of q
// that cuts p) and writes p ∩ q to inside. Returns false if p lies entirely outside one edge line of q
// (then inside is empty and p itself is appended to outside).
bool splitByConvex(const ConvexPolygon& p, const ConvexPolygon& q, std::vector<ConvexPolygon>& outside,
                   ConvexPolygon& inside);

// Intersection of two convex polygons.
void intersect(const ConvexPolygon& p, const ConvexPolygon& q, ConvexPolygon& out);

// Appends p to out, cut into convex sub-polygons of at most max_vertices vertices (fan groups sharing
// diagonals) when it has more. max_vertices >= 3.
void splitToCapacity(const ConvexPolygon& p, int max_vertices, std::vector<ConvexPolygon>& out);

}  // namespace clipblur
