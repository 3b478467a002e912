#include "renderer/fragments/screen_triangle.h"

#include <cmath>

#include "renderer/geometry/predicates.h"

namespace clipblur {

bool validScreenTriangle(const ScreenTriangle& t) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(t.raster[i].x) || !std::isfinite(t.raster[i].y)) return false;
        if (!std::isfinite(t.inv_depth[i]) || t.inv_depth[i] <= 0.0) return false;
    }
    const double a2 = orient2d(t.raster[0], t.raster[1], t.raster[2]);
    return a2 != 0.0 && std::isfinite(a2);
}

bool inverseDepthSlopes(const ScreenTriangle& t, DepthPlane& slopes) {
    const glm::dvec2 d1 = t.raster[1] - t.raster[0];
    const glm::dvec2 d2 = t.raster[2] - t.raster[0];
    const double a2 = differenceOfProducts(d1.x, d2.y, d1.y, d2.x);
    if (a2 == 0.0 || !std::isfinite(a2)) return false;
    const double w0 = t.inv_depth[0];
    const double dw1 = t.inv_depth[1] - w0;
    const double dw2 = t.inv_depth[2] - w0;
    // Cramer's rule for a*d_i.x + b*d_i.y = dw_i, i = 1, 2.
    slopes.a = differenceOfProducts(dw1, d2.y, dw2, d1.y) / a2;
    slopes.b = differenceOfProducts(dw2, d1.x, dw1, d2.x) / a2;
    slopes.c = 0.0;
    return std::isfinite(slopes.a) && std::isfinite(slopes.b);
}

bool anchorPlane(const ScreenTriangle& t, const DepthPlane& slopes, const glm::dvec2& origin, DepthPlane& plane) {
    const glm::dvec2 q0 = t.raster[0] - origin;
    plane.a = slopes.a;
    plane.b = slopes.b;
    plane.c = t.inv_depth[0] - std::fma(slopes.a, q0.x, slopes.b * q0.y);
    return std::isfinite(plane.c);
}

bool inverseDepthPlane(const ScreenTriangle& t, const glm::dvec2& origin, DepthPlane& plane) {
    DepthPlane slopes;
    return inverseDepthSlopes(t, slopes) && anchorPlane(t, slopes, origin, plane);
}

bool evalSource(const ScreenTriangle& t, const glm::dvec2& raster, SourceSample& out) {
    const double a2 = orient2d(t.raster[0], t.raster[1], t.raster[2]);
    if (a2 == 0.0 || !std::isfinite(a2)) return false;
    const std::array<double, 3> l{orient2d(t.raster[1], t.raster[2], raster) / a2,
                                  orient2d(t.raster[2], t.raster[0], raster) / a2,
                                  orient2d(t.raster[0], t.raster[1], raster) / a2};
    const std::array<double, 3> lw{l[0] * t.inv_depth[0], l[1] * t.inv_depth[1], l[2] * t.inv_depth[2]};
    out.screen_bary = l;
    out.inv_depth = lw[0] + lw[1] + lw[2];
    for (int i = 0; i < 3; ++i) out.bary[i] = lw[i] / out.inv_depth;
    return true;
}

}  // namespace clipblur
