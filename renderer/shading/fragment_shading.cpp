#include "renderer/shading/fragment_shading.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "renderer/geometry/predicates.h"
#include "renderer/thread_scratch.h"

namespace clipblur {

glm::dvec2 centroid(const ConvexPolygon& p) {
    glm::dvec2 sum(0.0);
    double area2 = 0.0;
    for (int i = 1; i + 1 < p.n; ++i) {
        const glm::dvec2 a = p.v[i] - p.v[0];
        const glm::dvec2 b = p.v[i + 1] - p.v[0];
        const double w = a.x * b.y - a.y * b.x;
        sum += w * (a + b) / 3.0;
        area2 += w;
    }
    if (area2 == 0.0) {
        glm::dvec2 mean(0.0);
        for (int i = 0; i < p.n; ++i) mean += p.v[i];
        return p.n > 0 ? mean / double(p.n) : mean;
    }
    return p.v[0] + sum / area2;
}

namespace {

std::array<glm::dvec3, 3> objectPositions(const Scene& scene, const SourceTriangle& source) {
    const Object& object = scene.objects[source.object];
    const auto& idx = object.mesh.triangles[source.triangle];
    const auto& rest = object.mesh.positions;
    std::array<glm::dvec3, 3> out;
    for (int i = 0; i < 3; ++i)
        out[i] = source.bary[i].x * rest[idx[0]] + source.bary[i].y * rest[idx[1]] + source.bary[i].z * rest[idx[2]];
    return out;
}

struct ShadingCall {
    const ScreenTriangle& screen;
    const SourceTriangle& source;
    const Shader& shader;
    double time;
    const glm::dvec3& eye;
    const TriangleFunctions& f;
    const UvFunctions& uv;
    bool integral;  // the `integral` rule: image textures averaged exactly over the piece's preimage
};

// One colour for a piece: the surface at its area centroid, the texture filtered over its bounding box
// or, under the `integral` rule, averaged over its preimage in (s, t).
glm::dvec3 shadeAt(const ConvexPolygon& piece, const ShadingCall& c) {
    const glm::dvec2 at = centroid(piece);
    const glm::dvec3 b = c.f.bary(at, c.screen);
    const glm::dvec3 m = b.x * c.source.bary[0] + b.y * c.source.bary[1] + b.z * c.source.bary[2];
    const SurfacePoint point{static_cast<int>(c.source.object), c.source.triangle, m.y, m.z, c.time};
    if (!c.uv.valid) return c.shader.shade(point, c.eye);
    SurfaceGeometry surface = c.shader.geometry(point);
    const RasterBounds box = piece.bounds();
    surface.footprint = c.uv.footprint(at - c.f.origin, box.hi - box.lo, c.f.inv_depth);
    TexturePiece st;
    if (c.integral) {
        c.uv.preimage(piece, c.f.origin, at, c.f.inv_depth, st);
        surface.texture_piece = &st;
    }
    return c.shader.shade(point, surface, c.eye);
}

// The piece cut into triangles about its centroid, each shaded by shadeAt, averaged by area.
glm::dvec3 shadeFan(const ConvexPolygon& piece, const ShadingCall& c) {
    const glm::dvec2 middle = centroid(piece);
    glm::dvec3 sum(0.0);
    double total = 0.0;
    for (int i = 0; i < piece.n; ++i) {
        const ConvexPolygon part = ConvexPolygon::triangle(middle, piece.v[i], piece.v[(i + 1) % piece.n]);
        const double area = part.area();
        if (!(area > 0.0)) continue;
        sum += area * shadeAt(part, c);
        total += area;
    }
    return total > 0.0 ? sum / total : shadeAt(piece, c);
}

}  // namespace

namespace {

int textureAxes(const Texture& texture) {
    if (texture.kind == Texture::Kind::None || !(texture.scale > 0.0)) return 0;
    return texture.kind == Texture::Kind::Stripe ? 1 : 3;
}

const Texture& materialTexture(const Scene& scene, const SourceTriangle& source) {
    return scene.materials[static_cast<std::size_t>(scene.objects[source.object].material)].texture;
}

}  // namespace

TriangleShading::TriangleShading(const FragmentSurface& on, const Shader& shader)
    : screen_(&on.screen),
      source_(&on.source),
      shader_(&shader),
      texture_(&materialTexture(shader.scene(), on.source)),
      axes_(textureAxes(*texture_)),
      f_(on.screen, axes_ > 0 ? objectPositions(shader.scene(), on.source) : std::array<glm::dvec3, 3>{}, axes_),
      uv_(on.screen, on.source, shader.scene(), f_),
      // Faceted, untextured pieces keep one centroid: their colour is exact there for directional light.
      fan_(shader.fragmentShading() == FragmentShading::Fan &&
           (uv_.valid || shader.scene().objects[on.source.object].mesh.smooth())) {}

void TriangleShading::shade(const ConvexPolygon& polygon, const ShadingFrame& frame, std::vector<ShadedPiece>& out) const {
    if (!f_.valid) return;
    const Texture& texture = *texture_;
    // Per-thread buffers: one fragment's cells never outlive this call, and reuse avoids an allocation
    // per fragment in the subframe loop.
    struct Cells {
        std::vector<ConvexPolygon> cells, next;
    };
    auto& [cells, next] = threadScratch<Cells>();
    cells.assign(1, polygon);
    for (int axis = 0; axis < axes_; ++axis) {
        next.clear();
        for (const ConvexPolygon& cell : cells) {
            // Object-space coordinate at each vertex: the cell range this piece spans on this axis.
            double lo = INFINITY, hi = -INFINITY;
            for (int k = 0; k < cell.n; ++k) {
                const glm::dvec2 d = cell.v[k] - f_.origin;
                const double x = f_.object_over_z[axis](d) / f_.inv_depth(d) / texture.scale;
                lo = std::min(lo, x);
                hi = std::max(hi, x);
            }
            const double first = std::floor(lo) + 1.0;
            const double last = std::floor(hi);
            if (!(last >= first) || last - first >= kMaxTextureCuts) {
                next.push_back(cell);
                continue;
            }
            ConvexPolygon rest = cell;
            for (double k = first; k <= last && !rest.degenerate(); k += 1.0) {
                // (X - k s)/z is affine in raster, so splitting on its vertex values cuts along the exact
                // cell boundary.
                std::array<double, kMaxPolygonVertices> g{};
                for (int v = 0; v < rest.n; ++v) {
                    const glm::dvec2 d = rest.v[v] - f_.origin;
                    g[v] = f_.object_over_z[axis](d) - k * texture.scale * f_.inv_depth(d);
                }
                ConvexPolygon below, above;
                splitByValues(rest, g.data(), above, below);
                if (!below.degenerate()) next.push_back(below);
                rest = above;
            }
            if (!rest.degenerate()) next.push_back(rest);
        }
        cells.swap(next);
    }
    const ShadingCall call{*screen_, *source_, *shader_, frame.time, frame.eye, f_, uv_,
                           shader_->fragmentShading() == FragmentShading::Integral};
    for (const ConvexPolygon& cell : cells) {
        const double area = cell.area();
        if (!(area > 0.0)) continue;
        ShadedPiece piece;
        piece.polygon = cell;
        piece.area = area;
        piece.colour = fan_ ? shadeFan(cell, call) : shadeAt(cell, call);
        out.push_back(piece);
    }
}

void shadeFragment(const ConvexPolygon& polygon, const FragmentSurface& on, const Shader& shader,
                   const ShadingFrame& frame, std::vector<ShadedPiece>& out) {
    TriangleShading(on, shader).shade(polygon, frame, out);
}

}  // namespace clipblur
