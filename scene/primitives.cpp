#include "scene/primitives.h"

#include <algorithm>
#include <cmath>

namespace clipblur {

namespace {

using Tri = std::array<std::uint32_t, 3>;

int sphereBands(int segments) { return std::max(2, segments / 2); }

}  // namespace

Mesh makeQuad(const glm::dvec2& size) { return makeGrid(size, 1, 1); }

std::uint64_t gridTriangleCount(int nx, int nz) {
    return 2ull * static_cast<std::uint64_t>(nx) * static_cast<std::uint64_t>(nz);
}

Mesh makeGrid(const glm::dvec2& size, int nx, int nz) {
    Mesh mesh;
    mesh.positions.reserve(static_cast<std::size_t>(nx + 1) * static_cast<std::size_t>(nz + 1));
    for (int k = 0; k <= nz; ++k)
        for (int i = 0; i <= nx; ++i)
            mesh.positions.emplace_back(size.x * (static_cast<double>(i) / nx - 0.5), 0.0,
                                        size.y * (static_cast<double>(k) / nz - 0.5));
    const auto at = [nx](int i, int k) { return static_cast<std::uint32_t>(k * (nx + 1) + i); };
    mesh.triangles.reserve(gridTriangleCount(nx, nz));
    // Going +x then +z is clockwise seen from +y, so each triangle lists the +z neighbour first:
    // cross(+z, +x) = +y.
    for (int k = 0; k < nz; ++k) {
        for (int i = 0; i < nx; ++i) {
            mesh.triangles.push_back(Tri{at(i, k), at(i, k + 1), at(i + 1, k + 1)});
            mesh.triangles.push_back(Tri{at(i, k), at(i + 1, k + 1), at(i + 1, k)});
        }
    }
    return mesh;
}

Mesh makeBox(const glm::dvec3& size) {
    Mesh mesh;
    // Vertex v has x from bit 0, y from bit 1, z from bit 2.
    for (std::uint32_t v = 0; v < 8; ++v)
        mesh.positions.emplace_back(size.x * ((v & 1) ? 0.5 : -0.5), size.y * ((v & 2) ? 0.5 : -0.5),
                                    size.z * ((v & 4) ? 0.5 : -0.5));
    // Each face as a quad (a, b, c, d) counter-clockwise seen from outside.
    const std::uint32_t faces[6][4] = {
        {0, 4, 6, 2},  // -x
        {1, 3, 7, 5},  // +x
        {0, 1, 5, 4},  // -y
        {2, 6, 7, 3},  // +y
        {0, 2, 3, 1},  // -z
        {4, 5, 7, 6},  // +z
    };
    for (const auto& f : faces) {
        mesh.triangles.push_back(Tri{f[0], f[1], f[2]});
        mesh.triangles.push_back(Tri{f[0], f[2], f[3]});
    }
    return mesh;
}

std::uint64_t sphereTriangleCount(int segments) {
    return 2ull * static_cast<std::uint64_t>(segments) * static_cast<std::uint64_t>(sphereBands(segments) - 1);
}

Mesh makeSphere(double radius, int segments) {
    const int bands = sphereBands(segments);
    Mesh mesh;
    mesh.positions.emplace_back(0.0, radius, 0.0);  // north pole
    for (int b = 1; b < bands; ++b) {
        const double theta = M_PI * b / bands;
        for (int s = 0; s < segments; ++s) {
            const double phi = 2.0 * M_PI * s / segments;
            mesh.positions.emplace_back(radius * std::sin(theta) * std::cos(phi), radius * std::cos(theta),
                                        -radius * std::sin(theta) * std::sin(phi));
        }
    }
    mesh.positions.emplace_back(0.0, -radius, 0.0);  // south pole
    const auto ring = [segments](int b, int s) {
        return static_cast<std::uint32_t>(1 + (b - 1) * segments + (s % segments));
    };
    const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
    mesh.triangles.reserve(sphereTriangleCount(segments));
    // phi grows counter-clockwise seen from +y (x toward -z), theta grows downward.
    for (int s = 0; s < segments; ++s) mesh.triangles.push_back(Tri{0, ring(1, s), ring(1, s + 1)});
    for (int b = 1; b + 1 < bands; ++b) {
        for (int s = 0; s < segments; ++s) {
            mesh.triangles.push_back(Tri{ring(b, s), ring(b + 1, s), ring(b + 1, s + 1)});
            mesh.triangles.push_back(Tri{ring(b, s), ring(b + 1, s + 1), ring(b, s + 1)});
        }
    }
    for (int s = 0; s < segments; ++s) mesh.triangles.push_back(Tri{south, ring(bands - 1, s + 1), ring(bands - 1, s)});
    return mesh;
}

}  // namespace clipblur
