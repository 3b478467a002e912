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

// An affine function of raster position, kept relative to the screen triangle's first vertex so that
// large raster coordinates do not cancel.
struct Affine {
    double a = 0.0, b = 0.0, c = 0.0;
    double operator()(const glm::dvec2& d) const { return a * d.x + b * d.y + c; }
};

// Everything shading one fragment of a screen triangle needs as affine functions of d = raster - r0:
// the raster barycentrics l_i, 1/z = sum l_i w_i and, per texture axis, sum l_i w_i X_i (object-space
// coordinate X over z), whose zero sets after subtracting k s / z are the texture cell boundaries.
struct TriangleFunctions {
    glm::dvec2 origin{0.0};
    std::array<Affine, 3> l{};
    Affine inv_depth;
    std::array<Affine, 3> object_over_z{};
    bool valid = false;

    // `axes`: how many texture axes need object_over_z (0 for an untextured material).
    TriangleFunctions(const ScreenTriangle& t, const std::array<glm::dvec3, 3>& object, int axes)
        : origin(t.raster[0]) {
        const glm::dvec2 e1 = t.raster[1] - origin, e2 = t.raster[2] - origin;
        const double a2 = differenceOfProducts(e1.x, e2.y, e1.y, e2.x);
        if (a2 == 0.0 || !std::isfinite(a2)) return;
        // l1 = cross(e1 -> d) / a2 reversed: l1(d) = (e2.y d.x - e2.x d.y) / a2, l2(d) = (e1.x d.y - e1.y d.x) / a2.
        l[1] = {e2.y / a2, -e2.x / a2, 0.0};
        l[2] = {-e1.y / a2, e1.x / a2, 0.0};
        l[0] = {-l[1].a - l[2].a, -l[1].b - l[2].b, 1.0};
        const auto combine = [&](const std::array<double, 3>& k) {
            Affine f;
            for (int i = 0; i < 3; ++i) {
                f.a += k[i] * l[i].a;
                f.b += k[i] * l[i].b;
                f.c += k[i] * l[i].c;
            }
            return f;
        };
        inv_depth = combine(t.inv_depth);
        for (int axis = 0; axis < axes; ++axis)
            object_over_z[axis] = combine({t.inv_depth[0] * object[0][axis], t.inv_depth[1] * object[1][axis],
                                           t.inv_depth[2] * object[2][axis]});
        valid = true;
    }

    // Perspective-correct barycentrics on the screen triangle at raster point p.
    glm::dvec3 bary(const glm::dvec2& p, const ScreenTriangle& t) const {
        const glm::dvec2 d = p - origin;
        const glm::dvec3 lw(l[0](d) * t.inv_depth[0], l[1](d) * t.inv_depth[1], l[2](d) * t.inv_depth[2]);
        return lw / (lw.x + lw.y + lw.z);
    }
};

std::array<glm::dvec3, 3> objectPositions(const Scene& scene, const SourceTriangle& source) {
    const Object& object = scene.objects[source.object];
    const auto& idx = object.mesh.triangles[source.triangle];
    const auto& rest = object.mesh.positions;
    std::array<glm::dvec3, 3> out;
    for (int i = 0; i < 3; ++i)
        out[i] = source.bary[i].x * rest[idx[0]] + source.bary[i].y * rest[idx[1]] + source.bary[i].z * rest[idx[2]];
    return out;
}


// Image-texture (s, t) over z as affine functions of d = raster - r0, so that (s, t) and its raster
// derivatives are known in closed form anywhere on the screen triangle (perspective-correct).
struct UvFunctions {
    std::array<Affine, 2> uv_over_z{};
    bool valid = false;

    UvFunctions(const ScreenTriangle& t, const SourceTriangle& source, const Scene& scene, const TriangleFunctions& f) {
        const Mesh& mesh = scene.objects[source.object].mesh;
        if (!mesh.hasUvs() || !f.valid) return;
        const std::size_t corner = 3 * static_cast<std::size_t>(source.triangle);
        for (int axis = 0; axis < 2; ++axis) {
            std::array<double, 3> k{};
            for (int i = 0; i < 3; ++i) {
                const glm::dvec3& b = source.bary[i];
                k[i] = t.inv_depth[i] * (b.x * mesh.corner_uvs[corner][axis] + b.y * mesh.corner_uvs[corner + 1][axis] +
                                         b.z * mesh.corner_uvs[corner + 2][axis]);
            }
            for (int i = 0; i < 3; ++i) {
                uv_over_z[axis].a += k[i] * f.l[i].a;
                uv_over_z[axis].b += k[i] * f.l[i].b;
                uv_over_z[axis].c += k[i] * f.l[i].c;
            }
        }
        valid = true;
    }

    // The footprint of a raster box of size `extent` at d: (s, t)'s raster Jacobian times the box's sides.
    TextureFootprint footprint(const glm::dvec2& d, const glm::dvec2& extent, const Affine& inv_depth) const {
        const double w = inv_depth(d);
        TextureFootprint out;
        for (int axis = 0; axis < 2; ++axis) {
            const double value = uv_over_z[axis](d) / w;
            out.dx[axis] = (uv_over_z[axis].a - value * inv_depth.a) / w * extent.x;
            out.dy[axis] = (uv_over_z[axis].b - value * inv_depth.b) / w * extent.y;
        }
        return out;
    }

    // The piece's preimage in (s, t): its vertices carried exactly (the map is projective, so the preimage
    // of a convex polygon is the convex polygon of the carried vertices), weighted by the raster area per
    // unit (s, t), proportional to w^3 (w = 1/z, z affine in (s, t)), linearised about raster point
    // `about` (the piece's centroid): 1 + slope . (st - st(about)) with slope = -3 grad_st(z) / z. The
    // weight is dropped (uniform) where it would not stay positive over the piece: z changes by more than
    // a third across it, an edge-on sliver.
    void preimage(const ConvexPolygon& piece, const glm::dvec2& origin, const glm::dvec2& about,
                  const Affine& inv_depth, TexturePiece& out) const {
        out.st.clear();
        for (int k = 0; k < piece.n; ++k) {
            const glm::dvec2 d = piece.v[k] - origin;
            const double w = inv_depth(d);
            out.st.push({uv_over_z[0](d) / w, uv_over_z[1](d) / w});
        }
        out.st.close();
        const glm::dvec2 d = about - origin;
        const double w = inv_depth(d);
        const glm::dvec2 st(uv_over_z[0](d) / w, uv_over_z[1](d) / w);
        // J = d(s, t)/d(x, y) and grad_x z = -grad_x w / w^2; grad_st z = J^-T grad_x z.
        const double a = (uv_over_z[0].a - st.x * inv_depth.a) / w, b = (uv_over_z[0].b - st.x * inv_depth.b) / w;
        const double c = (uv_over_z[1].a - st.y * inv_depth.a) / w, e = (uv_over_z[1].b - st.y * inv_depth.b) / w;
        const double det = a * e - b * c;
        const glm::dvec2 gx(-inv_depth.a / (w * w), -inv_depth.b / (w * w));
        const glm::dvec2 grad_z((e * gx.x - c * gx.y) / det, (a * gx.y - b * gx.x) / det);
        out.weight = {st, -3.0 * w * grad_z};
        bool positive = std::isfinite(out.weight.slope.x) && std::isfinite(out.weight.slope.y);
        for (int k = 0; k < out.st.n && positive; ++k)
            positive = 1.0 + glm::dot(out.weight.slope, out.st.v[k] - st) > 0.0;
        if (!positive) out.weight = {};
    }
};

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

void shadeFragment(const ConvexPolygon& polygon, const FragmentSurface& on, const Shader& shader,
                   const ShadingFrame& frame, std::vector<ShadedPiece>& out) {
    const ScreenTriangle& screen = on.screen;
    const SourceTriangle& source = on.source;
    const double time = frame.time;
    const glm::dvec3& eye = frame.eye;
    const Scene& scene = shader.scene();
    const Material& material =
        scene.materials[static_cast<std::size_t>(scene.objects[source.object].material)];
    const Texture& texture = material.texture;
    const int axes = texture.kind == Texture::Kind::None || !(texture.scale > 0.0)
                         ? 0
                         : (texture.kind == Texture::Kind::Stripe ? 1 : 3);
    const TriangleFunctions f(screen, axes > 0 ? objectPositions(scene, source) : std::array<glm::dvec3, 3>{}, axes);
    if (!f.valid) return;
    // Per-thread buffers: one fragment's cells never outlive this call, and reuse avoids an allocation
    // per fragment in the subframe loop.
    struct Cells {
        std::vector<ConvexPolygon> cells, next;
    };
    auto& [cells, next] = threadScratch<Cells>();
    cells.assign(1, polygon);
    for (int axis = 0; axis < axes; ++axis) {
        next.clear();
        for (const ConvexPolygon& cell : cells) {
            // Object-space coordinate at each vertex: the cell range this piece spans on this axis.
            double lo = INFINITY, hi = -INFINITY;
            for (int k = 0; k < cell.n; ++k) {
                const glm::dvec2 d = cell.v[k] - f.origin;
                const double x = f.object_over_z[axis](d) / f.inv_depth(d) / texture.scale;
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
                    const glm::dvec2 d = rest.v[v] - f.origin;
                    g[v] = f.object_over_z[axis](d) - k * texture.scale * f.inv_depth(d);
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
    const UvFunctions uv(screen, source, scene, f);
    // Faceted, untextured pieces keep one centroid: their colour is exact there for directional light.
    const bool fan = shader.fragmentShading() == FragmentShading::Fan &&
                     (uv.valid || scene.objects[source.object].mesh.smooth());
    for (const ConvexPolygon& cell : cells) {
        const double area = cell.area();
        if (!(area > 0.0)) continue;
        ShadedPiece piece;
        piece.polygon = cell;
        piece.area = area;
        const ShadingCall call{screen, source, shader, time, eye, f, uv,
                               shader.fragmentShading() == FragmentShading::Integral};
        piece.colour = fan ? shadeFan(cell, call) : shadeAt(cell, call);
        out.push_back(piece);
    }
}

}  // namespace clipblur
