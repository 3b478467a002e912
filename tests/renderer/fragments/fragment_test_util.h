#pragma once

#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/fragments/fragment.h"
#include "renderer/fragments/screen_triangle.h"
#include "tests/renderer/geometry/halfplane_oracle.h"

namespace clipblur::testing {

// Raster-space affine inverse depth w = a*x + b*y + c (any such function is the 1/z of some plane).
struct Plane {
    double a, b, c;
    double operator()(const glm::dvec2& p) const { return a * p.x + b * p.y + c; }
};

inline ScreenTriangle makeTriangle(const glm::dvec2& p0, const glm::dvec2& p1, const glm::dvec2& p2,
                                   const Plane& w, std::uint32_t source, std::uint8_t layer = 0,
                                   float weight = 1.0f) {
    ScreenTriangle t;
    t.raster = {p0, p1, p2};
    t.inv_depth = {w(p0), w(p1), w(p2)};
    t.source = source;
    t.layer = layer;
    t.weight = weight;
    return t;
}

// An axis-aligned quad as two triangles with sources first and first+1.
inline std::vector<ScreenTriangle> makeQuad(double x0, double y0, double x1, double y1, const Plane& w,
                                            std::uint32_t first, std::uint8_t layer = 0, float weight = 1.0f) {
    return {makeTriangle({x0, y0}, {x1, y0}, {x1, y1}, w, first, layer, weight),
            makeTriangle({x0, y0}, {x1, y1}, {x0, y1}, w, first + 1, layer, weight)};
}

inline double overlap1d(double a0, double a1, double b0, double b1) {
    return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}

inline double rectOverlap(double x0, double y0, double x1, double y1, double u0, double v0, double u1,
                          double v1) {
    return overlap1d(x0, x1, u0, u1) * overlap1d(y0, y1, v0, v1);
}

// Visible area per source, a mixed fragment counting for each of its sources.
inline std::map<std::uint32_t, double> areaBySource(const std::vector<Fragment>& frags) {
    std::map<std::uint32_t, double> out;
    for (const Fragment& f : frags) {
        for (int i = 0; i < f.source_count; ++i) out[f.sources[i].source] += f.area;
    }
    return out;
}

inline std::vector<HalfPlane> pixelConstraints(const glm::dvec2& lo) {
    const glm::dvec2 hi = lo + glm::dvec2(1.0);
    return {leftOf(lo, {hi.x, lo.y}), leftOf({hi.x, lo.y}, hi), leftOf(hi, {lo.x, hi.y}), leftOf({lo.x, hi.y}, lo)};
}

// Counter-clockwise vertex list of a triangle (orientation as orient2d > 0).
inline std::vector<glm::dvec2> ccw(const ScreenTriangle& t) {
    const glm::dvec2 e1 = t.raster[1] - t.raster[0], e2 = t.raster[2] - t.raster[0];
    if (e1.x * e2.y - e1.y * e2.x >= 0) return {t.raster[0], t.raster[1], t.raster[2]};
    return {t.raster[0], t.raster[2], t.raster[1]};
}

}  // namespace clipblur::testing
