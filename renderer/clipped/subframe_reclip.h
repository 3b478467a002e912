#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/clipped/fragment_triangle.h"
#include "renderer/fragments/fragment_audit.h"
#include "renderer/fragments/fragment_tile.h"
#include "renderer/geometry/swept_footprint.h"
#include "renderer/integrate/interval_layout.h"
#include "renderer/integrate/swept_polygons.h"
#include "renderer/integrate/tile_sums.h"
#include "renderer/object_coverage.h"
#include "renderer/propagation/ode_propagation.h"
#include "renderer/propagation/surface_path.h"
#include "renderer/shading/fragment_shading.h"
#include "renderer/shading/shading.h"
#include "renderer/tiles.h"

namespace clipblur {

struct ReclipScratch {
    std::vector<ScreenTriangle> screen;
    std::vector<FragmentRef> origin;      // per screen triangle
    std::vector<SourceTriangle> sources;  // per screen triangle: its vertices on the mesh triangle
    std::vector<ShadedPiece> pieces;
    // Per screen triangle, the index of its shading in `shading`, -1 until a fragment of it is shaded:
    // both reset per re-clip, as the screen triangles are.
    std::vector<std::int32_t> shading_slot;
    std::vector<TriangleShading> shading;
    std::vector<SweptPolygon> swept;  // sweep: the tile's polygons, in fragment order
    std::vector<SweptPolygon> staging;  // sweep: one pixel's polygons after merging
    std::vector<std::pair<ConvexPolygon, glm::dvec3>> textured;  // sweep: pieces with their colour per px^2
    std::vector<glm::dvec4> stretch;  // sweep: per screen triangle, x and y stretch at the interval's ends
    TileScratch tile;
    FragmentTile fragments;
};

struct ReclipStats {
    long long propagated = 0;      // fragment triangles moved to the subframe
    long long near_clipped = 0;    // of those, clipped in 3D at the camera plane
    long long fragments = 0;       // non-overlapping pieces after the re-clip
    long long mixed = 0;           // pieces where both frames' copies of a surface coincide
    long long shaded_pieces = 0;   // shading evaluations (after texture-cell cuts)
    long long ode_fallbacks = 0;   // vertices the ODE could not carry (camera plane), moved exactly
    long long sweep_positions = 0; // sweep: fragment positions placed (one per fragment per position)
    long long sweep_unswept = 0;   // sweep: fragments left as point samples (see SweepInterval::reach)
    AuditStats audit;              // filled when reclipSubframe is asked to audit

    void merge(const ReclipStats& other) {
        propagated += other.propagated;
        near_clipped += other.near_clipped;
        fragments += other.fragments;
        mixed += other.mixed;
        shaded_pieces += other.shaded_pieces;
        ode_fallbacks += other.ode_fallbacks;
        sweep_positions += other.sweep_positions;
        sweep_unswept += other.sweep_unswept;
        audit.merge(other.audit);
    }
};

// What every re-clip of one tile shares.
struct TileReclip {
    const Scene& scene;
    const Shader& shader;
    const FragmentLayers& layers;
    std::span<const FragmentRef> refs;  // the fragment triangles that can reach the tile (MotionPlan)
    PixelBounds tile;
    bool audit = false;  // check every resolved pixel (auditTile) into ReclipStats::audit
};

// When one re-clip happens: the snapshot at its time t, t's fraction f of the segment (frame 0's
// fragments weigh 1 - f, frame 1's f) and, with sweep integration, the interval around t it stands for.
struct ReclipTime {
    const MotionSnapshot& snapshot;
    double fraction = 0.0;
    const SweepInterval* sweep = nullptr;
};

// Sections 3.2-3.4 for one (tile, subframe): moves every referenced fragment triangle to the snapshot's
// time along its exact path (frame-0 ones forward, frame-1 ones backward: the same function of time),
// clips pieces crossing the camera plane in 3D, re-clips the union per pixel into non-overlapping
// fragments (equal range: one kept, colours mixed with weights 1-f and f), shades each piece at the
// snapshot's time, and reduces each pixel. With a sweep the fragments of sweep->resolve are swept over the
// interval into sweep->box; without, the tile's pixels get the point sample at the snapshot's time.
void reclipSubframe(const TileReclip& tile, const ReclipTime& at, ReclipScratch& scratch, TileSums& out,
                    ReclipStats& stats);

}  // namespace clipblur
