#include "renderer/shading/fragment_shading.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "renderer/geometry/predicates.h"

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

}  // namespace

void shadeFragment(const ConvexPolygon& polygon, const ScreenTriangle& screen, const SourceTriangle& source,
                   const Shader& shader, double time, const glm::dvec3& eye, std::vector<ShadedPiece>& out) {
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
    thread_local std::vector<ConvexPolygon> cells, next;
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
    for (const ConvexPolygon& cell : cells) {
        const double area = cell.area();
        if (!(area > 0.0)) continue;
        ShadedPiece piece;
        piece.polygon = cell;
        piece.area = area;
        const glm::dvec3 b = f.bary(centroid(cell), screen);
        const glm::dvec3 m = b.x * source.bary[0] + b.y * source.bary[1] + b.z * source.bary[2];
        const SurfacePoint point{static_cast<int>(source.object), source.triangle, m.y, m.z, time};
        piece.colour = shader.shade(point, eye);
        out.push_back(piece);
    }
}

}  // namespace clipblur
