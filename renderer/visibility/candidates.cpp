#include "renderer/visibility/candidates.h"

#include <algorithm>
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

}  // namespace

void findCandidates(const FrameGeometry& frame, const EmbreeScene& embree, const MeshAdjacency& adjacency,
                    const Projection& projection, const Tile& tile, int tile_index, int rays_per_side,
                    CandidateScratch& scratch, std::vector<std::uint32_t>& out, CandidateStats& stats) {
    out.clear();
    const auto binned = frame.tileTriangles(tile_index);
    stats.binned += static_cast<long long>(binned.size());
    if (rays_per_side <= 0) {
        out.assign(binned.begin(), binned.end());
        stats.candidates += static_cast<long long>(out.size());
        return;
    }

    const CameraFrame& camera = frame.camera();
    const int n = rays_per_side;
    scratch.hits.clear();
    for (int y = tile.y0 - 1; y <= tile.y1; ++y) {
        for (int x = tile.x0 - 1; x <= tile.x1; ++x) {
            for (int j = 0; j < n; ++j) {
                for (int i = 0; i < n; ++i) {
                    const glm::dvec2 p = projection.toImagePlane({x + (i + 0.5) / n, y + (j + 0.5) / n});
                    const glm::dvec3 dir = camera.e3 + p.x * camera.e1 + p.y * camera.e2;
                    const EmbreeHit hit = embree.intersect(camera.position, dir, frame.time());
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
        adjacency.forEachNeighbour(object, static_cast<std::uint32_t>(h), [&](std::uint32_t t) {
            scratch.ring.push_back(key(object, t));
        });
    }
    sortUnique(scratch.ring);
    for (std::uint64_t h : scratch.ring)
        for (std::uint32_t s : frame.ofMeshTriangle(static_cast<std::uint32_t>(h >> 32), static_cast<std::uint32_t>(h)))
            out.push_back(s);
    const double thin = 2.0 / n;
    for (std::uint32_t s : binned)
        if (frame.minExtent(s) < thin) out.push_back(s);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    // Only what can touch the tile: a hit triangle's neighbours may lie elsewhere.
    std::vector<std::uint32_t>& kept = scratch.kept;
    kept.clear();
    std::set_intersection(out.begin(), out.end(), binned.begin(), binned.end(), std::back_inserter(kept));
    out.swap(kept);
    stats.candidates += static_cast<long long>(out.size());
}

}  // namespace clipblur
