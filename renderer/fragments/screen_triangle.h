#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>

namespace clipblur {

// A triangle projected to raster space, the input of the clipping kernel.
//
// inv_depth is 1/z with z the camera-space depth (distance along the view axis, > 0). For a planar 3D
// triangle under a pinhole projection, 1/z is an affine function of raster (x, y), and so is b_i/z for each
// perspective-correct barycentric b_i; both are therefore known exactly from the three raster vertices. The
// paper sorts by range (distance to the eye); along one eye ray range and z are proportional, so the
// visibility order is the same, but only 1/z interpolates affinely.
struct ScreenTriangle {
    std::array<glm::dvec2, 3> raster{};
    std::array<double, 3> inv_depth{};
    std::uint32_t source = 0;  // caller's index (mesh triangle, propagated fragment, ...)
    std::uint8_t layer = 0;    // 0 or 1: which bounding frame the triangle comes from
    float weight = 1.0f;       // mix weight when surfaces of both layers coincide
    // The planar surface (mesh triangle) the triangle is a piece of, or kNoSurface. Pieces with one key lie
    // on one plane and those of one layer do not overlap: what lets resolveTile skip clipping a pixel that
    // one surface covers wholly.
    std::uint64_t surface = kNoSurface;

    static constexpr std::uint64_t kNoSurface = ~std::uint64_t(0);
};

// Finite raster vertices, finite positive inverse depths (in front of the eye) and non-zero area.
bool validScreenTriangle(const ScreenTriangle& t);

// An affine function a*x + b*y + c of (pixel-local or raster) position.
struct DepthPlane {
    double a = 0.0;
    double b = 0.0;
    double c = 0.0;

    double operator()(const glm::dvec2& p) const { return std::fma(a, p.x, std::fma(b, p.y, c)); }
};

// How inverse depth wp compares with wq: equal when |wp - wq| <= rel * max(|wp|, |wq|) (the resolver's
// coincidence test), else nearer (wp larger) or farther. The one depth tolerance that every clip and
// skip of clipping shares, so that they agree on what is in front.
enum class DepthOrder { Coincident, Nearer, Farther };
inline DepthOrder compareDepth(double wp, double wq, double rel) {
    const double d = wp - wq;
    const double tol = rel * std::max(std::abs(wp), std::abs(wq));
    if (std::abs(d) <= tol) return DepthOrder::Coincident;
    return d > 0.0 ? DepthOrder::Nearer : DepthOrder::Farther;
}

// The inverse-depth plane of t in coordinates relative to origin (raster minus origin), so that evaluating
// it near the origin does not cancel. Returns false for degenerate (zero-area) triangles.
bool inverseDepthPlane(const ScreenTriangle& t, const glm::dvec2& origin, DepthPlane& plane);
// The same in two steps, for a caller that needs t's plane at many origins: the slopes a, b do not depend
// on the origin (c is left 0; false for degenerate triangles), and anchorPlane sets c for one origin. The
// result is inverseDepthPlane's, bit for bit.
bool inverseDepthSlopes(const ScreenTriangle& t, DepthPlane& slopes);
bool anchorPlane(const ScreenTriangle& t, const DepthPlane& slopes, const glm::dvec2& origin, DepthPlane& plane);

// What a raster point means on the source triangle.
struct SourceSample {
    double inv_depth = 0.0;               // 1/z at the point
    std::array<double, 3> bary{};         // perspective-correct barycentrics on the 3D triangle, sum 1
    std::array<double, 3> screen_bary{};  // affine raster-space barycentrics
};

// 1/z = sum(l_i w_i) and b_i = l_i w_i / (1/z), where l_i are the raster barycentrics and w_i = 1/z_i:
// b_i/z is affine in raster space and equals w_i at vertex i and 0 at the others. Returns false for a
// degenerate triangle.
bool evalSource(const ScreenTriangle& t, const glm::dvec2& raster, SourceSample& out);

}  // namespace clipblur
