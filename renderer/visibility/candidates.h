#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "renderer/tiles.h"
#include "renderer/visibility/embree_scene.h"
#include "renderer/visibility/frame_geometry.h"
#include "scene/scene.h"

namespace clipblur {

// Triangles sharing a vertex with a given triangle, per object (vertex -> triangles in CSR form).
class MeshAdjacency {
public:
    // Keeps a reference to the scene's meshes, which must outlive it (the renderers hold both).
    explicit MeshAdjacency(const Scene& scene);

    template <typename F>
    void forEachNeighbour(std::uint32_t object, std::uint32_t triangle, F&& f) const {
        const auto& o = objects_[object];
        for (std::uint32_t v : scene_.objects[object].mesh.triangles[triangle])
            for (std::uint32_t i = o.offsets[v]; i < o.offsets[v + 1]; ++i) f(o.items[i]);
    }

private:
    struct PerObject {
        std::vector<std::uint32_t> offsets;
        std::vector<std::uint32_t> items;
    };
    const Scene& scene_;
    std::vector<PerObject> objects_;
};

struct CandidateStats {
    long long rays = 0;
    long long hit_triangles = 0;  // distinct mesh triangles hit
    long long candidates = 0;     // screen triangles handed to the clipper
    long long binned = 0;         // screen triangles whose box overlaps the tile (the exhaustive set)
    long long exhaustive_tiles = 0;  // tiles where rays were asked for but would cost more than they cull

    template <class Fields>
    void fields(Fields& f) const {
        f.count("rays", rays);
        f.count("hit_triangles", hit_triangles);
        f.count("candidates", candidates);
        f.count("binned_triangles", binned);
        f.count("exhaustive_tiles", exhaustive_tiles);
    }
    friend bool operator==(const CandidateStats&, const CandidateStats&) = default;
};

// The Embree rays that narrow a tile's candidates: the scene they hit, the mesh one-rings added around
// each hit, and rays per pixel side (0: no rays, every binned triangle).
struct CandidateRays {
    const EmbreeScene& embree;
    const MeshAdjacency& adjacency;
    int per_side = 2;
};

struct CandidateScratch {
    std::vector<std::uint64_t> hits;
    std::vector<std::uint64_t> ring;
    std::vector<std::uint32_t> kept;
};

// Whether Embree's rays over `tile` cost less than the clipper spends on the binned triangles they
// could cull: the boxes inside the tile of those not thin enough to be candidates anyway, plus a setup
// per triangle, against the tile's pixels once (what is visible is clipped either way) plus the rays.
// A wall of a few large triangles has nothing to cull, a mesh of sub-pixel triangles neither (all
// thin); many pixel-sized triangles or large ones stacked in depth have. False for rays_per_side <= 0.
bool raysPayOff(const FrameGeometry& frame, std::span<const std::uint32_t> binned, const PixelBounds& tile,
                int rays_per_side);

// The screen triangles of tile `tile_index` of the frame's grid that the clipper must see at the frame's time.
//
// rays_per_side == 0, or rays would not pay off (raysPayOff): every triangle whose bounding box
// overlaps the tile (exact, the oracle). Otherwise Embree traces rays_per_side^2 rays per pixel over
// the tile and a one-pixel border; the candidates are the triangles hit, their one-ring neighbours in
// the mesh (a triangle visible only between rays is usually next to one that was hit) and every
// triangle whose inscribed circle is narrower than the ray grid's cell diagonal (it may fit between
// rays at any angle). What this can still miss is a large triangle seen only through a gap narrower
// than the ray spacing and not adjacent to a hit; docs/design.md measures it.
std::vector<std::uint32_t> findCandidates(const FrameGeometry& frame, const CandidateRays& rays, int tile_index,
                                          CandidateScratch& scratch, CandidateStats& stats);

}  // namespace clipblur
