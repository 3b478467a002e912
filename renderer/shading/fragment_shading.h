#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "renderer/fragments/screen_triangle.h"
#include "renderer/geometry/convex_polygon.h"
#include "renderer/shading/shading.h"
#include "renderer/shading/triangle_functions.h"
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

// A screen triangle's shading set up once (its raster functions for the material's texture axes and
// image-texture coordinates: triangle_functions.h), for every fragment of it a re-clip resolves. Holds
// pointers to the triangle and the shader: they must outlive it.
class TriangleShading {
public:
    TriangleShading(const FragmentSurface& on, const Shader& shader);

    // Cuts a visible fragment polygon of the triangle along its material's checker or stripe cell
    // boundaries (planes in object space, hence lines in raster space: (X - k s)/z is affine in raster), so
    // that every piece has one albedo, then gives each piece the colour the shader's FragmentShading rule
    // says: the surface at its area centroid, an image texture either averaged exactly over the piece's
    // preimage in (s, t) (integral, the default: renderer/shading/texture_integral.h) or filtered over the
    // piece's footprint (centroid: its bounding box carried into (s, t) by the perspective-correct Jacobian
    // at the centroid), or a fan of triangles about the centroid shaded the centroid way (fan). Lambert
    // lighting varies smoothly over a fragment, so the centroid value is second-order accurate in the
    // fragment size; a directional light on a flat, faceted triangle is exact.
    void shade(const ConvexPolygon& polygon, const ShadingFrame& frame, std::vector<ShadedPiece>& out) const;

private:
    const ScreenTriangle* screen_;
    const SourceTriangle* source_;
    const Shader* shader_;
    const Texture* texture_;
    int axes_;  // texture axes the cells are cut along: 0 untextured, 1 stripe, 3 checker
    TriangleFunctions f_;
    UvFunctions uv_;
    bool fan_;  // FragmentShading::Fan where it changes anything: textured or smooth
};

// One fragment: TriangleShading(on, shader).shade(polygon, frame, out).
void shadeFragment(const ConvexPolygon& polygon, const FragmentSurface& on, const Shader& shader,
                   const ShadingFrame& frame, std::vector<ShadedPiece>& out);

// The area centroid of a convex polygon.
glm::dvec2 centroid(const ConvexPolygon& polygon);

}  // namespace clipblur
