#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "renderer/clipped/still_backdrop.h"
#include "renderer/clipped/subframe_reclip.h"
#include "renderer/propagation/subframes.h"
#include "renderer/tiles.h"

namespace clipblur {

// Per tile, the fragment triangles whose swept box overlaps it (layer 0 first, each in index order), in
// one array sized exactly: a segment bins them once, and its candidate plans share the bins.
class TileBins {
public:
    TileBins(const TileGrid& grid, const std::array<std::vector<FragmentMotion>, 2>& motion);
    std::span<const FragmentRef> operator[](int tile) const {
        const auto t = static_cast<std::size_t>(tile);
        return std::span<const FragmentRef>(refs_).subspan(begin_[t], begin_[t + 1] - begin_[t]);
    }

private:
    std::vector<std::size_t> begin_;  // per tile where its refs begin, then the end
    std::vector<FragmentRef> refs_;
};

// Which fragment triangles can reach each tile during the shutter, and how many subframes each tile needs.
struct MotionPlan {
    std::shared_ptr<const TileBins> bins;
    // Per tile whose backdrop fragments were split off (backdrop, unless they are behind everything):
    // the rest, never empty (a split needs a moving fragment). Empty elsewhere: those tiles take the bins.
    std::vector<std::vector<FragmentRef>> front;
    // The fragment triangles the tile re-clips.
    std::span<const FragmentRef> refs(int tile) const {
        const auto t = static_cast<std::size_t>(tile);
        return t < front.size() && !front[t].empty() ? std::span<const FragmentRef>(front[t]) : (*bins)[tile];
    }
    std::vector<SubframePlan> tiles;
    // Per tile: true when its fragment triangles of backdrop objects were taken out of refs, because every
    // moving one that can reach the tile stays nearer than all of them for the whole segment. Elsewhere the
    // tile re-clips everything together.
    std::vector<char> backdrop;
    // Per tile: about how many of its pixels a re-clip resolves (covered by its refs), for integrationCost.
    std::vector<double> resolved;
    std::vector<std::uint32_t> groups;  // per object, its motion group over the segment (motionGroups)
    long long backdrop_tiles = 0;
    long long capped_tiles = 0;
    long long measured = 0;     // fragment triangles whose path was sampled
    long long near_crossings = 0;  // fragment triangles reaching the camera plane during the shutter
};

// Every fragment triangle's swept raster box, peak speed and path shape over a segment, per layer
// (triangles of objects that do not move under a still camera are measured at t0 only), and the tiles
// each can reach.
struct FragmentPaths {
    std::array<std::vector<FragmentMotion>, 2> motion;
    std::array<std::vector<double>, 2> area;  // raster area at the segment's start; infinity behind the camera
    long long measured = 0;  // fragment triangles whose path was sampled
    std::shared_ptr<const TileBins> bins;  // over the frame's tile grid
};
FragmentPaths measurePaths(const FrameSetup& frame, const MotionWindow& window, const FragmentLayers& layers);

// Bins the measured fragment triangles to the tiles their swept box overlaps and plans each tile's
// subframes (the corrected eq. 24, vertices moving point_spacing pixels between subframes; 1 but under
// time_integration auto). subframes > 0 forces that count. One FragmentPaths serves both plans, so
// time_integration auto measures once and plans twice.
// With `sweep` (render.time_integration: sweep) the count follows relative motion and path curvature, and
// every moving tile gets the same count. With a `backdrop` (findBackdrop), still objects behind everything
// that moves near a tile are split off there (MotionPlan::backdrop) and their motion relative to the rest is
// not counted; when they are behind everything all shutter the fragment sets have none of them and every
// tile is a backdrop tile.
struct MotionPlanOptions {
    int subframes = 0;  // > 0: every tile's count
    int max_subframes = 1;
    bool sweep = false;
    double point_spacing = 1.0;  // point subframes: pixels a vertex moves between them
    double shutter_share = 1.0;  // the segment's share of the frame's shutter (kinkSamples)
    // Sweep: pixels surfaces of different motion groups move relative to each other between re-clips;
    // the tolerances for how far a sweep strays from a path scale with it, as its square below a pixel.
    double reclip_spacing = 1.0;
    const Backdrop& backdrop;
};
MotionPlan planMotion(const FrameSetup& frame, const MotionWindow& window, const FragmentLayers& layers,
                      const FragmentPaths& paths, const MotionPlanOptions& options);

}  // namespace clipblur
