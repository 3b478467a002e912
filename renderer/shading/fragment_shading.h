#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "renderer/fragments/screen_triangle.h"
#include "renderer/geometry/convex_polygon.h"
#include "renderer/shading/shading.h"
#include "renderer/visibility/frame_geometry.h"

namespace clipblur {

// A piece of a fragment with one colour.
struct ShadedPiece {
    ConvexPolygon polygon;  // raster space
    glm::dvec3 colour{0.0};
    double area = 0.0;
};

// Most texture-cell boundaries one fragment is cut along per axis; finer textures than that are shaded
// at the piece centroids (they alias inside the pixel, which is then the documented limit).
inline constexpr int kMaxTextureCuts = 8;

// Cuts a visible fragment polygon of `screen` along its material's checker or stripe cell boundaries
// (planes in object space, hence lines in raster space: (X - k s)/z is affine in raster), so that every
// piece has one albedo, then gives each piece the colour the shader's FragmentShading rule says: the
// surface at its area centroid, an image texture either averaged exactly over the piece's preimage in
// (s, t) (integral, the default: renderer/shading/texture_integral.h) or filtered over the piece's
// footprint (centroid: its bounding box carried into (s, t) by the perspective-correct Jacobian at the
// centroid), or a fan of triangles about the centroid shaded the centroid way (fan). Lambert lighting
// varies smoothly over a fragment, so the centroid value is second-order accurate in the fragment size; a
// directional light on a flat, faceted triangle is exact.
// The triangle a fragment lies on: in raster space and on its mesh.
struct FragmentSurface {
    const ScreenTriangle& screen;
    const SourceTriangle& source;
};
// The frame a fragment is shaded as: its time and the camera position then.
struct ShadingFrame {
    double time = 0.0;
    glm::dvec3 eye{0.0};
};
void shadeFragment(const ConvexPolygon& polygon, const FragmentSurface& on, const Shader& shader,
                   const ShadingFrame& frame, std::vector<ShadedPiece>& out);

// The area centroid of a convex polygon.
glm::dvec2 centroid(const ConvexPolygon& polygon);

}  // namespace clipblur
