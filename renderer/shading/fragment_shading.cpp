#include "renderer/shading/fragment_shading.h"

#include <cmath>

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

// Mesh-triangle barycentrics of a raster point on `screen`.
glm::dvec3 meshBary(const ScreenTriangle& screen, const SourceTriangle& source, const glm::dvec2& raster) {
    SourceSample s;
    if (!evalSource(screen, raster, s)) return source.bary[0];
    return s.bary[0] * source.bary[0] + s.bary[1] * source.bary[1] + s.bary[2] * source.bary[2];
}

struct TexturePlanes {
    int axes = 0;                        // 0 none, 1 stripe (x), 3 checker (x, y, z)
    double scale = 1.0;
    std::array<glm::dvec3, 3> object{};  // object-space positions of the screen triangle's vertices
};

TexturePlanes texturePlanes(const Scene& scene, const SourceTriangle& source) {
    const Object& object = scene.objects[source.object];
    const Material& material = scene.materials[static_cast<std::size_t>(object.material)];
    TexturePlanes planes;
    if (material.texture.kind == Texture::Kind::None || !(material.texture.scale > 0.0)) return planes;
    planes.axes = material.texture.kind == Texture::Kind::Stripe ? 1 : 3;
    planes.scale = material.texture.scale;
    const auto& idx = object.mesh.triangles[source.triangle];
    const auto& rest = object.mesh.positions;
    for (int i = 0; i < 3; ++i)
        planes.object[i] = source.bary[i].x * rest[idx[0]] + source.bary[i].y * rest[idx[1]] + source.bary[i].z * rest[idx[2]];
    return planes;
}

}  // namespace

void shadeFragment(const ConvexPolygon& polygon, const ScreenTriangle& screen, const SourceTriangle& source,
                   const Shader& shader, double time, const glm::dvec3& eye, std::vector<ShadedPiece>& out) {
    const TexturePlanes planes = texturePlanes(shader.scene(), source);
    ConvexPolygon work[2] = {polygon, {}};
    int cur = 0;
    std::vector<ConvexPolygon> cells{polygon};
    if (planes.axes > 0) {
        std::vector<ConvexPolygon> next;
        for (int axis = 0; axis < planes.axes; ++axis) {
            next.clear();
            for (const ConvexPolygon& cell : cells) {
                // Object-space coordinate at each vertex: the cell range this piece spans on this axis.
                double lo = INFINITY, hi = -INFINITY;
                for (int k = 0; k < cell.n; ++k) {
                    SourceSample s;
                    evalSource(screen, cell.v[k], s);
                    const double x = s.bary[0] * planes.object[0][axis] + s.bary[1] * planes.object[1][axis] +
                                     s.bary[2] * planes.object[2][axis];
                    lo = std::min(lo, x / planes.scale);
                    hi = std::max(hi, x / planes.scale);
                }
                const double first = std::floor(lo) + 1.0;
                const double last = std::floor(hi);
                if (!(last >= first) || last - first >= kMaxTextureCuts) {
                    next.push_back(cell);
                    continue;
                }
                work[cur] = cell;
                for (double k = first; k <= last; k += 1.0) {
                    // (X - k s)/z = sum_i l_i w_i (X_i - k s) is affine in raster, so splitting on its
                    // values at the vertices cuts along the exact cell boundary.
                    std::array<double, kMaxPolygonVertices> g{};
                    for (int v = 0; v < work[cur].n; ++v) {
                        SourceSample s;
                        evalSource(screen, work[cur].v[v], s);
                        double value = 0.0;
                        for (int i = 0; i < 3; ++i)
                            value += s.screen_bary[i] * screen.inv_depth[i] * (planes.object[i][axis] - k * planes.scale);
                        g[v] = value;
                    }
                    ConvexPolygon below, above;
                    splitByValues(work[cur], g.data(), above, below);
                    if (!below.degenerate()) next.push_back(below);
                    work[1 - cur] = above;
                    cur = 1 - cur;
                    if (work[cur].degenerate()) break;
                }
                if (!work[cur].degenerate()) next.push_back(work[cur]);
            }
            cells.swap(next);
        }
    }
    for (const ConvexPolygon& cell : cells) {
        const double area = cell.area();
        if (!(area > 0.0)) continue;
        ShadedPiece piece;
        piece.polygon = cell;
        piece.area = area;
        for (int k = 0; k < cell.n; ++k) piece.bary[k] = meshBary(screen, source, cell.v[k]);
        const glm::dvec3 b = meshBary(screen, source, centroid(cell));
        const SurfacePoint point{static_cast<int>(source.object), source.triangle, b.y, b.z, time};
        piece.colour = shader.shade(point, eye);
        out.push_back(piece);
    }
}

}  // namespace clipblur
