#pragma once

#include <atomic>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/clipped/fragment_triangle.h"
#include "renderer/fragments/fragment_audit.h"
#include "renderer/fragments/pixel_resolver.h"
#include "renderer/object_coverage.h"
#include "renderer/frame_setup.h"

namespace clipblur {

// A still image before the background is added: per pixel the area-weighted colour sum and covered area.
struct PixelSums {
    std::vector<glm::dvec3> colour;
    std::vector<double> covered;
    std::vector<double> depth;  // area-weighted camera depth sum (for the Z AOV)
    std::vector<ObjectShares> objects;  // per object its covered area; empty unless asked for (ID mattes)

    // Zeroed sums for `pixels` pixels, with per-object areas when `objects` is set.
    void resize(std::size_t pixels, bool objects = false);
};

struct FrameFragmentStats {
    CandidateStats candidates;
    long long fragments = 0;           // visible convex pieces after clipping
    long long shaded_pieces = 0;       // after texture-cell cuts
    long long merged_triangles = 0;    // candidates fully visible in a tile, kept whole rather than per pixel
    long long triangles = 0;           // fragment triangles kept for propagation
    long long near_clipped = 0;
    long long deep_tiles = 0;          // tiles whose every layer was kept (FrameFragmentRequest::deep)
    long long rejected_triangles = 0;
    double dropped_area = 0.0;
    std::array<long long, 6> fragments_per_pixel{};  // pixels with 0, 1, 2, 3-4, 5-8, >8 fragments
    AuditStats audit;                                 // filled when FrameFragmentRequest::audit is set

    void merge(const FrameFragmentStats& other);
    // The audit is reported once per render (ClippedStats), not per fragment set.
    template <class Fields>
    void fields(Fields& f) const {
        f.nest("", candidates);
        f.count("fragments", fragments);
        f.count("shaded_pieces", shaded_pieces);
        f.count("merged_triangles", merged_triangles);
        f.count("fragment_triangles", triangles);
        f.count("near_clipped", near_clipped);
        f.count("deep_tiles", deep_tiles);
        static const char* buckets[] = {"pixels_with_fragments_0",   "pixels_with_fragments_1",
                                        "pixels_with_fragments_2",   "pixels_with_fragments_3_4",
                                        "pixels_with_fragments_5_8", "pixels_with_fragments_over_8"};
        for (std::size_t b = 0; b < fragments_per_pixel.size(); ++b) f.count(buckets[b], fragments_per_pixel[b]);
    }
    friend bool operator==(const FrameFragmentStats&, const FrameFragmentStats&) = default;
};

// Which fragment set to build: at what time, over which tiles, and how.
struct FrameFragmentRequest {
    double time = 0.0;
    const TileGrid* grid = nullptr;  // the tiles to resolve (a film plus a guard band); null: the film's
    // Of those, the tiles whose sets keep every layer: each triangle over the tile, clipped to it, hidden
    // or not (near surfaces hidden at both ends of a segment but seen in between); null: none.
    const TileSet* deep = nullptr;
    int rays_per_side = 2;       // Embree candidate rays per pixel side; 0: every binned triangle
    bool keep_triangles = true;  // return the fragment triangles (false: only the still image)
    bool audit = false;          // check every resolved tile's invariants (auditTile)
    // Per object: leave its triangles out (a still backdrop behind everything, resolved on its own).
    const std::vector<char>* leave_out = nullptr;
};

// Section 1 of the paper at one instant: Embree finds the candidate triangles per tile, the clipping
// kernel makes each pixel's non-overlapping fragments, and each fragment is shaded with that time's
// lighting. Returns the fragments as triangles on their meshes (in tile order, so deterministic; empty
// unless keep_triangles) and, when `still` is given, the frame's pixel sums. Parallel over tiles.
std::vector<FragmentTriangle> buildFrameFragments(const FrameSetup& frame, const FrameFragmentRequest& request,
                                                  PixelSums* still, FrameFragmentStats& stats);

}  // namespace clipblur
