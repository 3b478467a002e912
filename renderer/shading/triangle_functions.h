#pragma once

#include <array>

#include <glm/glm.hpp>

#include "renderer/fragments/screen_triangle.h"
#include "renderer/geometry/convex_polygon.h"
#include "renderer/shading/image_textures.h"
#include "renderer/shading/texture_integral.h"
#include "renderer/visibility/frame_geometry.h"
#include "scene/scene.h"

namespace clipblur {

// An affine function of raster position, kept relative to the screen triangle's first vertex so that
// large raster coordinates do not cancel.
struct Affine {
    double a = 0.0, b = 0.0, c = 0.0;
    double operator()(const glm::dvec2& d) const { return a * d.x + b * d.y + c; }
};

// Everything shading a fragment of a screen triangle needs as affine functions of d = raster - r0:
// the raster barycentrics l_i, 1/z = sum l_i w_i and, per texture axis, sum l_i w_i X_i (object-space
// coordinate X over z), whose zero sets after subtracting k s / z are the texture cell boundaries.
struct TriangleFunctions {
    glm::dvec2 origin{0.0};
    std::array<Affine, 3> l{};
    Affine inv_depth;
    std::array<Affine, 3> object_over_z{};
    bool valid = false;

    // `axes`: how many texture axes need object_over_z (0 for an untextured material).
    TriangleFunctions(const ScreenTriangle& t, const std::array<glm::dvec3, 3>& object, int axes);

    // Perspective-correct barycentrics on the screen triangle at raster point p.
    glm::dvec3 bary(const glm::dvec2& p, const ScreenTriangle& t) const {
        const glm::dvec2 d = p - origin;
        const glm::dvec3 lw(l[0](d) * t.inv_depth[0], l[1](d) * t.inv_depth[1], l[2](d) * t.inv_depth[2]);
        return lw / (lw.x + lw.y + lw.z);
    }
};

// Image-texture (s, t) over z as affine functions of d = raster - r0, so that (s, t) and its raster
// derivatives are known in closed form anywhere on the screen triangle (perspective-correct).
struct UvFunctions {
    std::array<Affine, 2> uv_over_z{};
    bool valid = false;

    UvFunctions(const ScreenTriangle& t, const SourceTriangle& source, const Scene& scene, const TriangleFunctions& f);

    // The footprint of a raster box of size `extent` at d: (s, t)'s raster Jacobian times the box's sides.
    TextureFootprint footprint(const glm::dvec2& d, const glm::dvec2& extent, const Affine& inv_depth) const;

    // The piece's preimage in (s, t): its vertices carried exactly (the map is projective, so the preimage
    // of a convex polygon is the convex polygon of the carried vertices), weighted by the raster area per
    // unit (s, t), proportional to w^3 (w = 1/z, z affine in (s, t)), linearised about raster point
    // `about` (the piece's centroid): 1 + slope . (st - st(about)) with slope = -3 grad_st(z) / z. The
    // weight is dropped (uniform) where it would not stay positive over the piece: z changes by more than
    // a third across it, an edge-on sliver.
    void preimage(const ConvexPolygon& piece, const glm::dvec2& origin, const glm::dvec2& about,
                  const Affine& inv_depth, TexturePiece& out) const;
};

}  // namespace clipblur
