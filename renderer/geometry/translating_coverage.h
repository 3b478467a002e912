#pragma once

#include <glm/vec2.hpp>

#include "renderer/geometry/pixel_cells.h"

namespace clipblur {

// A weight over a chord of time, u in [0, 1]: w0 + w1 u per unit of u (a shutter curve is linear within a
// shutter segment, so over any part of it).
struct ChordWeight {
    double w0 = 1.0;
    double w1 = 0.0;
};

// A callable add(x, y, weight), passed by reference without a template (the callers' lambdas outlive it).
class CellSink {
public:
    template <class F>
    CellSink(F& f)  // NOLINT(google-explicit-constructor): any add(x, y, weight) converts
        : context_(const_cast<void*>(static_cast<const void*>(&f))), call_([](void* c, int x, int y, double w) { (*static_cast<F*>(c))(x, y, w); }) {}
    void operator()(int x, int y, double w) const { call_(context_, x, y, w); }

private:
    void* context_;
    void (*call_)(void*, int, int, double);
};

// The time integral of the pixel coverage of the convex polygon p translating to p + d, exact to
// rounding: per pixel, add(x, y, integral over u in [0, 1] of area(pixel and (p + u d)) (w0 + w1 u) du).
// No time samples: the plane is cut into pieces on which the time a point is covered is a polynomial of
// degree 1 (box) or 2 (with w1) in the point, and each piece's pixel cells are integrated in closed form.
// The weights sum to area(p) (w0 + w1 / 2).
void translatingCells(const SmallPolygon& p, const glm::dvec2& d, ChordWeight w, CellSink add);

// An axis-aligned rectangle whose sides move linearly: [lo + u dlo, hi + u dhi] at u in [0, 1] (a fragment
// translating and stretching along the raster axes).
struct MovingRectangle {
    glm::dvec2 lo{0.0}, hi{0.0};
    glm::dvec2 dlo{0.0}, dhi{0.0};
};

// The same integral for a moving rectangle, exact to rounding, separably: per pixel the overlap along
// each axis is piecewise linear in u, so the integrand is a piecewise cubic that Simpson's rule
// integrates exactly between the breakpoints.
void translatingRectangleCells(const MovingRectangle& r, ChordWeight w, CellSink add);

}  // namespace clipblur
