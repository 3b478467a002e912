#include "renderer/visibility/candidates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

namespace clipblur {

MeshAdjacency::MeshAdjacency(const Scene& scene) : scene_(scene) {
    objects_.resize(scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Mesh& mesh = scene.objects[o].mesh;
        auto& po = objects_[o];
        po.offsets.assign(mesh.positions.size() + 1, 0);
        for (const auto& t : mesh.triangles)
            for (std::uint32_t v : t) ++po.offsets[v + 1];
        for (std::size_t i = 1; i < po.offsets.size(); ++i) po.offsets[i] += po.offsets[i - 1];
        po.items.resize(po.offsets.back());
        std::vector<std::uint32_t> cursor(po.offsets.begin(), po.offsets.end() - 1);
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
            for (std::uint32_t v : mesh.triangles[t]) po.items[cursor[v]++] = t;
    }
}

namespace {

std::uint64_t key(std::uint32_t object, std::uint32_t triangle) {
    return (static_cast<std::uint64_t>(object) << 32) | triangle;
}

void sortUnique(std::vector<std::uint64_t>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
}

// The clipper's cost per binned triangle before its pixels, in pixel pieces (setup, binning, the
// sort by depth); and what one ray costs in pixel pieces. Fitted at 1280x720 on the propeller and the
// dense sphere (the fit: docs/history/performance-runs.md, "Candidate rays where they pay").
constexpr double kTriangleSetupPixels = 4.0, kRayPixels = 1.25;

// Rays sample a grid of spacing 1/n. A disk as wide as the grid cell's diagonal holds a sample
// wherever it lies, so a triangle is certain to hold one only if its inner disk is that wide; a
// narrower one may fall between rays, at any angle, and is a candidate whatever they hit.
double thinDiameter(int rays_per_side) { return std::sqrt(2.0) / rays_per_side; }

}  // namespace

bool raysPayOff(const FrameGeometry& frame, std::span<const std::uint32_t> binned, const PixelBounds& tile,
                int rays_per_side) {
    if (rays_per_side <= 0) return false;
    const double pixels = static_cast<double>(tile.width()) * tile.height();
    const double with_rays = pixels * (1.0 + kRayPixels * rays_per_side * rays_per_side);
    const double thin = thinDiameter(rays_per_side);
    double without = 0.0;
    for (std::uint32_t s : binned) {
        if (frame.innerDiameter(s) < thin) continue;  // a candidate either way: nothing for rays to save
        const std::array<glm::dvec2, 3>& r = frame.triangles()[s].raster;
        const double x0 = std::max(std::min({r[0].x, r[1].x, r[2].x}), static_cast<double>(tile.x0));
        const double x1 = std::min(std::max({r[0].x, r[1].x, r[2].x}), static_cast<double>(tile.x1));
        const double y0 = std::max(std::min({r[0].y, r[1].y, r[2].y}), static_cast<double>(tile.y0));
        const double y1 = std::min(std::max({r[0].y, r[1].y, r[2].y}), static_cast<double>(tile.y1));
        without += kTriangleSetupPixels + std::max(0.0, x1 - x0) * std::max(0.0, y1 - y0);
        if (without > with_rays) return true;
    }
    return false;
}

std::vector<std::uint32_t> findCandidates(const FrameGeometry& frame, const CandidateRays& rays, int tile_index,
                                          CandidateScratch& scratch, CandidateStats& stats) {
    std::vector<std::uint32_t> out;
    const PixelBounds tile = frame.tile(tile_index);
    const int rays_per_side = rays.per_side;
    const auto binned = frame.tileTriangles(tile_index);
    stats.binned += static_cast<long long>(binned.size());
    if (!raysPayOff(frame, binned, tile, rays_per_side)) {
        out.assign(binned.begin(), binned.end());
        stats.candidates += static_cast<long long>(out.size());
        if (rays_per_side > 0) ++stats.exhaustive_tiles;
        return out;
    }

    const CameraFrame& camera = frame.camera();
    const int n = rays_per_side;
    scratch.hits.clear();
    for (int y = tile.y0 - 1; y <= tile.y1; ++y) {
        for (int x = tile.x0 - 1; x <= tile.x1; ++x) {
            for (int j = 0; j < n; ++j) {
                for (int i = 0; i < n; ++i) {
                    const glm::dvec2 p = frame.projection().toImagePlane({x + (i + 0.5) / n, y + (j + 0.5) / n});
                    const glm::dvec3 dir = camera.e3 + p.x * camera.e1 + p.y * camera.e2;
                    const EmbreeHit hit = rays.embree.intersect(camera.position, dir, frame.time());
                    ++stats.rays;
                    if (hit.hit) scratch.hits.push_back(key(static_cast<std::uint32_t>(hit.object), hit.triangle));
                }
            }
        }
    }
    sortUnique(scratch.hits);
    stats.hit_triangles += static_cast<long long>(scratch.hits.size());

    scratch.ring = scratch.hits;
    for (std::uint64_t h : scratch.hits) {
        const auto object = static_cast<std::uint32_t>(h >> 32);
        rays.adjacency.forEachNeighbour(object, static_cast<std::uint32_t>(h), [&](std::uint32_t t) {
            scratch.ring.push_back(key(object, t));
        });
    }
    sortUnique(scratch.ring);
    for (std::uint64_t h : scratch.ring)
        for (std::uint32_t s : frame.ofMeshTriangle(static_cast<std::uint32_t>(h >> 32), static_cast<std::uint32_t>(h)))
            out.push_back(s);
    const double thin = thinDiameter(n);
    for (std::uint32_t s : binned)
        if (frame.innerDiameter(s) < thin) out.push_back(s);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    // Only what can touch the tile: a hit triangle's neighbours may lie elsewhere.
    std::vector<std::uint32_t>& kept = scratch.kept;
    kept.clear();
    std::set_intersection(out.begin(), out.end(), binned.begin(), binned.end(), std::back_inserter(kept));
    out.swap(kept);
    stats.candidates += static_cast<long long>(out.size());
    return out;
}

}  // namespace clipblur
