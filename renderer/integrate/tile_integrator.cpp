#include "renderer/integrate/tile_integrator.h"

#include <algorithm>
#include <span>

#include "renderer/clipped/time_error.h"
#include "renderer/parallel_time.h"

namespace clipblur {

namespace {

// A tile's share of the segment: whether the segment-start image is its answer, its re-clip count and,
// with sweep integration, the layout every interval of the tile shares.
struct TilePass {
    const SegmentIntegration& segment;
    int index = 0;
    PixelBounds tile;
    bool still = false;
    int n = 0;            // re-clips; 0 for a still tile
    SweepInterval sweep;  // sweep and n > 0: the tile's reach, apron and motion groups
    SubframeLayout layout;
};

TilePass planTile(const SegmentIntegration& segment, int index) {
    const SubframePlan& plan = segment.motion.tiles[static_cast<std::size_t>(index)];
    const PixelBounds tile = segment.frame.grid.tile(index);
    const bool still = segment.still_scene || (plan.max_sweep_pixels == 0.0 && segment.subframes == 0 && !segment.shadows);
    const int n = still ? 0 : plan.count;
    SweepInterval sweep;
    if (segment.sweep && n > 0) {
        sweep = sweepInterval(tile, plan.max_sweep_pixels, n, segment.frame.scene().film.pixels());
        sweep.groups = segment.motion.groups;
        sweep.exact = segment.sweep->exact;
    }
    return {.segment = segment, .index = index, .tile = tile, .still = still, .n = n, .sweep = sweep, .layout = {}};
}

// Re-clips the tile at each of its subframes (in parallel, each into its own sums and stats). With sweep
// integration subframe k stands for interval k, between the snapshots at its ends.
void reclipSubframes(const TilePass& pass, tbb::enumerable_thread_specific<ReclipScratch>& scratches,
                     std::vector<TileSums>& sums, std::vector<ReclipStats>& stats) {
    const SegmentIntegration& segment = pass.segment;
    const Scene& scene = segment.frame.scene();
    const SweepSchedule* schedule = segment.sweep;
    const double ts = segment.span.t0, te = segment.span.t1, half = pass.layout.half;
    const TileReclip reclip{scene,     segment.frame.shader, segment.layers, segment.motion.refs(pass.index),
                            pass.tile, segment.audit};
    parallelFor(0, pass.n, [&](int k) {
        const auto i = static_cast<std::size_t>(k);
        const double t = pass.layout.times[i];
        const MotionSnapshot& snapshot = segment.snapshots.at(t);
        SweepInterval interval = pass.sweep;
        if (schedule) {
            interval.begin = &segment.snapshots.at(t - half);
            interval.end = &segment.snapshots.at(t + half);
            interval.positions = schedule->positions[i];
            interval.tilt = pass.layout.tilts[i];
            const IntervalTurns& turn = schedule->turns[i];
            if (pass.n == schedule->intervals && !turn.at_positions.empty()) interval.turns = &turn;
        }
        reclipSubframe(reclip, {snapshot, (t - ts) / (te - ts), schedule ? &interval : nullptr}, scratches.local(), sums[i],
                       stats[i]);
    });
}

// A tile's subframe sums and the factor each counts with (the shutter curve; exactly 1 for a box). For
// the error estimate: point subframes are the samples of a nested rule over the segment (`rule`); with
// sweep each subframe's TileSums carries its interval's.
struct WeightedSubframes {
    const std::vector<TileSums>& sums;
    std::span<const double> factors;
    const NestedRule* rule = nullptr;
};

// One pixel's sums over a tile's subframes, in subframe order: bit-identical for any thread count.
Spill subframeTotal(const WeightedSubframes& subframes, int x, int y) {
    Spill sum;
    for (std::size_t k = 0; k < subframes.sums.size(); ++k) {
        const TileSums& s = subframes.sums[k];
        if (!s.box.contains(x, y)) continue;  // sweep: no footprint of this subframe reaches the pixel
        const std::size_t i = s.box.index(x, y);
        const double f = subframes.factors[k];
        sum.colour += f * s.colour[i];
        sum.covered += f * s.covered[i];
        sum.depth += f * s.depth[i];
        sum.motion += f * s.motion[i];
        if (s.track_objects) addShares(sum.objects, s.objects[i], f);
        if (s.track_error)
            sum.level += LevelDifference(f * s.d3[i]);
        else if (subframes.rule)
            sum.level += LevelDifference(subframes.rule->to3[k] * f * glm::dvec4(s.colour[i], s.covered[i]));
    }
    return sum;
}

// The tile's own pixels of the window: w x its subframes' total, or the segment-start image's.
void addOwnPixels(const TilePass& pass, const WeightedSubframes& subframes, double w, WindowSums& sums) {
    const SegmentIntegration& segment = pass.segment;
    const PixelBounds film = segment.frame.scene().film.pixels();
    const PixelBounds& window = segment.window;
    const PixelBounds mine = pass.tile.intersect(window);
    for (int y = mine.y0; y < mine.y1; ++y) {
        for (int x = mine.x0; x < mine.x1; ++x) {
            const std::size_t pixel_out = window.index(x, y);
            if (pass.still)
                sums.addStill(pixel_out, segment.weight, segment.still, film.index(x, y));
            else
                sums.add(pixel_out, w, subframeTotal(subframes, x, y));
        }
    }
}

// Sweep: what a tile's subframes left in the window's pixels of other tiles, scaled by w, in row-major
// order.
void collectSpills(const TilePass& pass, const WeightedSubframes& subframes, double w, std::vector<Spill>& spilled) {
    const PixelBounds& tile = pass.tile;
    const PixelBounds& window = pass.segment.window;
    const std::vector<TileSums>& tile_sums = subframes.sums;
    PixelBounds reached = tile_sums[0].box;  // what the subframes' footprints reach
    for (const TileSums& s : tile_sums) reached = reached.unite(s.box);
    const PixelBounds seen = reached.intersect(window);
    for (int y = seen.y0; y < seen.y1; ++y) {
        for (int x = seen.x0; x < seen.x1; ++x) {
            if (tile.contains(x, y)) continue;
            Spill sum = subframeTotal(subframes, x, y);
            if (sum.covered == 0.0) continue;
            sum.out = window.index(x, y);
            sum.colour *= w;
            sum.covered *= w;
            sum.depth *= w;
            sum.motion *= w;
            for (ObjectShare& o : sum.objects) o.coverage *= w;
            sum.level *= static_cast<float>(w);
            spilled.push_back(std::move(sum));
        }
    }
}

}  // namespace

int integrateTile(const SegmentIntegration& segment, int index, TileOutputs& out, ReclipStats& stats) {
    TilePass pass = planTile(segment, index);
    const PixelBounds reach = pass.sweep.box.x0 < pass.sweep.box.x1 ? pass.sweep.box : pass.tile;
    if (reach.intersect(segment.window).empty()) return -1;
    pass.layout = subframeLayout(segment.span, pass.n);
    const bool sweeping = segment.sweep != nullptr;
    std::vector<TileSums> sums(static_cast<std::size_t>(pass.n));
    for (TileSums& s : sums) {
        s.track_objects = segment.track_objects;
        s.track_error = sweeping;
    }
    std::vector<ReclipStats> sub_stats(static_cast<std::size_t>(pass.n));
    reclipSubframes(pass, out.scratches, sums, sub_stats);
    const double w = segment.weight / std::max(pass.n, 1);
    const NestedRule rule(sweeping ? 1 : pass.n);
    const WeightedSubframes weighted{sums, pass.layout.factors, sweeping ? nullptr : &rule};
    addOwnPixels(pass, weighted, w, out.sums);
    if (sweeping && pass.n > 0) collectSpills(pass, weighted, w, out.spills[static_cast<std::size_t>(index)]);
    for (const ReclipStats& s : sub_stats) stats.merge(s);
    return pass.n;
}

}  // namespace clipblur
