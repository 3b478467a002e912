#include "renderer/shading/triangle_functions.h"

#include <cmath>

#include "renderer/geometry/predicates.h"

namespace clipblur {

TriangleFunctions::TriangleFunctions(const ScreenTriangle& t, const std::array<glm::dvec3, 3>& object, int axes)
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

UvFunctions::UvFunctions(const ScreenTriangle& t, const SourceTriangle& source, const Scene& scene,
                         const TriangleFunctions& f) {
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

TextureFootprint UvFunctions::footprint(const glm::dvec2& d, const glm::dvec2& extent, const Affine& inv_depth) const {
    const double w = inv_depth(d);
    TextureFootprint out;
    for (int axis = 0; axis < 2; ++axis) {
        const double value = uv_over_z[axis](d) / w;
        out.dx[axis] = (uv_over_z[axis].a - value * inv_depth.a) / w * extent.x;
        out.dy[axis] = (uv_over_z[axis].b - value * inv_depth.b) / w * extent.y;
    }
    return out;
}

void UvFunctions::preimage(const ConvexPolygon& piece, const glm::dvec2& origin, const glm::dvec2& about,
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

}  // namespace clipblur
