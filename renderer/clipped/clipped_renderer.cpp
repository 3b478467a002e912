#include "renderer/clipped/clipped_renderer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <initializer_list>
#include <utility>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include "renderer/clipped/frame_fragments.h"
#include "renderer/clipped/guard_band.h"
#include "renderer/clipped/hidden_probe.h"
#include "renderer/clipped/integration_cost.h"
#include "renderer/clipped/motion_plan.h"
#include "renderer/clipped/shutter_segments.h"
#include "renderer/clipped/still_backdrop.h"
#include "renderer/clipped/subframe_reclip.h"
#include "renderer/clipped/time_error.h"
#include "renderer/integrate/tile_integrator.h"
#include "renderer/integrate/window_sums.h"
#include "renderer/parallel_time.h"
#include "renderer/stopwatch.h"
#include "renderer/visibility/candidates.h"
#include "renderer/visibility/embree_scene.h"
#include "scene/error.h"

namespace clipblur {

namespace {

// What a pixel's sums are scaled by when written: 1, or 1 / covered where the covered fraction exceeds 1.
// Sweep integration holds visibility as resolved at each re-clip, so surfaces moving differently can
// overlap within an interval (its occlusion error, falling with re-clips): their sums count the overlap
// twice. Scaling the colour and the per-object shares alike keeps the colour premultiplied by A = 1 and
// the shares summing to A. Elsewhere covered exceeds 1 by rounding only.
double overCoverScale(double covered) { return covered > 1.0 ? 1.0 / covered : 1.0; }

// Writes one pixel's averaged sums (colour, covered area, depth and motion sums). The colour is
// premultiplied: what the surfaces contribute only, so compositors can "over" it onto any background.
struct ImageWriter {
    Image& image;
    Image::Channel* depth;
    Image::Channel* coverage;
    Image::Channel* mx;
    Image::Channel* my;

    explicit ImageWriter(Image& img)
        : image(img), depth(img.find("Z")), coverage(img.find("coverage")), mx(img.find("motion.x")),
          my(img.find("motion.y")) {}

    // z: the pixel's depth AOV (meanDepth).
    void write(std::size_t pixel, const glm::dvec3& colour, double covered, float z, const glm::dvec2& motion) {
        const double c = std::clamp(covered, 0.0, 1.0);
        const double scale = overCoverScale(covered);
        for (int k = 0; k < 3; ++k)
            image.channels[static_cast<std::size_t>(k)].values[pixel] = static_cast<float>(colour[k] * scale);
        image.channels[3].values[pixel] = static_cast<float>(c);
        if (coverage) coverage->values[pixel] = static_cast<float>(c);
        if (depth) depth->values[pixel] = z;
        if (mx) {
            const glm::dvec2 m = covered > 0.0 ? motion / covered : glm::dvec2(0.0);
            mx->values[pixel] = static_cast<float>(m.x);
            my->values[pixel] = static_cast<float>(m.y);
        }
    }
};

// An area-weighted depth sum over the area it covers; infinity where nothing is.
float meanDepth(double depth_sum, double covered) {
    return covered > 0.0 ? static_cast<float>(depth_sum / covered) : std::numeric_limits<float>::infinity();
}

// The depth AOV is the depth of what is seen at mid-shutter, area-weighted over the pixel's covered part
// (what a compositor pairs with motion vectors centred on the frame), so it needs the visibility of a
// still frame at that time: nullopt when no depth is asked for or nothing moves (then every time has it).
std::optional<PixelSums> midShutterDepth(const RenderJob& job, const FrameSetup& frame, FrameFragmentStats& stats) {
    if (!job.output.aov_depth || frame.motion.shutter().still()) return std::nullopt;
    PixelSums sums;
    sums.resize(job.scene.film.pixels().area());
    buildFrameFragments(frame,
                        {.time = 0.5 * (frame.motion.t0() + frame.motion.t1()),
                         .rays_per_side = job.render.visibility_rays,
                         .keep_triangles = false,
                         .audit = job.render.audit},
                        &sums, stats);
    return sums;
}

// With render.audit set every resolved tile was checked by auditTile. A violation is a renderer bug, so
// the render fails (no image is written) instead of returning a wrong picture, naming the stage of the
// first violation. Returns the stages' audits merged.
AuditStats checkAudit(std::initializer_list<std::pair<const char*, const AuditStats*>> stages) {
    AuditStats all;
    std::string where;
    for (const auto& [name, audit] : stages) {
        if (!audit) continue;
        if (audit->violations > 0 && where.empty()) where = std::string(name) + ": " + audit->first_violation;
        all.merge(*audit);
    }
    if (all.violations > 0)
        throw Error(ExitCode::Render,
                    "fragment audit: " + std::to_string(all.violations) + " invariant violations; first in " + where);
    return all;
}

// What every shutter segment shares: the job, the frame (its motion, Embree and shading state) and the
// output layout.
struct ClippedContext {
    const RenderJob& job;
    const FrameSetup& frame;
    PixelBounds window;
    const ShutterCurve& curve;
    const Backdrop& backdrop;  // findBackdrop: empty when no backdrop can exist
    // With the motion AOV, the frame at shutter open and close (FragmentLayers::shutter).
    const std::optional<std::pair<MotionSnapshot, MotionSnapshot>>& shutter;
};

// A segment with a still backdrop (MotionPlan::backdrop): what moves in front covers a backdrop tile's
// pixel for the fraction of the segment its swept coverage gives, so the pixel sees front + (1 - that) x
// backdrop. Exact where the backdrop is uniform over the part of the pixel the front crosses; an edge of
// the backdrop under a moving edge in the same pixel is where it is not. `front` carries the segment's
// weight; the backdrop image (film pixels) is the same for every segment.
struct FrontOverBackdrop {
    WindowSums& front;  // cleared where read, so the next segment can reuse it
    const PixelSums& backdrop;
    const MotionPlan& plan;
    double weight = 1.0;  // the segment's
};
// What the backdrop adds to a pixel's level differences: it shows through as much as the front leaves
// uncovered, so a covered-area difference d shows as -d x the backdrop's colour and covered area.
LevelDifference behindFront(const LevelDifference& front, const PixelSums& backdrop, std::size_t p) {
    return -front.w * LevelDifference(glm::vec3(backdrop.colour[p]), static_cast<float>(backdrop.covered[p]));
}

void compositeBackdrop(const ClippedContext& ctx, const FrontOverBackdrop& layers, WindowSums& sums) {
    const TileGrid& grid = ctx.frame.grid;
    const PixelBounds& window = ctx.window;
    const PixelBounds film = ctx.job.scene.film.pixels();
    WindowSums& front = layers.front;
    const PixelSums& backdrop = layers.backdrop;
    const double weight = layers.weight;
    parallelFor(window.y0, window.y1, [&](int y) {  // each pixel on its own
        for (int x = window.x0; x < window.x1; ++x) {
            const std::size_t i = window.index(x, y);
            const int tile = grid.indexOf(x, y);
            sums.addPixel(i, front);
            if (layers.plan.backdrop[static_cast<std::size_t>(tile)]) {
                const double seen = weight * (1.0 - std::clamp(front.covered[i] / weight, 0.0, 1.0));
                const std::size_t p = film.index(x, y);
                sums.addStill(i, seen, backdrop, p);
                if (seen > 0.0 && seen < weight) sums.levels[i] += behindFront(front.levels[i], backdrop, p);
            }
            front.clearPixel(i);
        }
    });
}

// What carries from one shutter segment to the next: the frame's stats, the backdrop image and the set
// the next segment opens with.
struct SegmentTotals {
    ClippedStats stats;
    std::optional<PixelSums> backdrop;  // the still backdrop's image, made when a segment first needs it
    // What moves in front of it, zero between segments (compositeBackdrop clears what it reads): made
    // once, as fresh pages for every segment were most of the particles' page faults.
    std::optional<WindowSums> front;
    // The last segment's closing set with its still image: the next segment's opening set, at the same time.
    std::optional<std::pair<std::vector<FragmentTriangle>, PixelSums>> carried;
    // Still images of finished segments, whose pages the next sets reuse (stillImage).
    std::vector<PixelSums> spare_stills;
};

// A zeroed still image of the film, in a finished segment's memory where there is one.
PixelSums stillImage(SegmentTotals& totals, std::size_t pixels, bool track_objects) {
    PixelSums still;
    if (!totals.spare_stills.empty()) {
        still = std::move(totals.spare_stills.back());
        totals.spare_stills.pop_back();
    }
    still.resize(pixels, track_objects);
    return still;
}

// One shutter segment of the frame (what moves over it), its share of the shutter, and every segment's
// guard band.
struct SegmentSpec {
    const MotionWindow& window;
    double weight = 1.0;
    double curve_begin = 1.0, curve_end = 1.0;  // the shutter curve at begin and end (ShutterSegment)
    int subframes = 0;  // > 0: this segment's fixed re-clip count
    // Film tiles where its sets keep every layer (ShutterSegment::deep); the next segment's, which a
    // closing set it opens with keeps as well.
    const TileSet& deep;
    const TileSet& next_deep;
    int index = 0;
    std::span<const int> bands;  // every segment's guard band (guardBandPixels), in order
    bool next_adjacent = false;  // the next segment begins where this one ends: it opens with our closing set
    std::span<const double> next_times;  // the next segment's ends: Embree keeps their scenes, frees the rest
};

// Step 1's result: the clipped, shaded fragment sets at the segment's ends and the still image at its start.
struct SegmentEnds {
    bool still_scene = false;  // nothing moves: the still image is the answer
    bool both_frames = false;
    std::vector<FragmentTriangle> open, close;
    PixelSums still;
};

// The tiles a segment's fragment sets resolve: the film and a guard band `band` wide, aligned to the
// band's corner.
TileGrid fragmentGrid(const ClippedContext& ctx, int band) {
    const Film& film = ctx.job.scene.film;
    return TileGrid(-band, -band, film.width + 2 * band, film.height + 2 * band, ctx.job.render.tile_size);
}

// Fragment sets over the image and a guard band wide enough that everything seen during the segment is
// in one of them. A closing set that the next segment opens with is built with that segment's band too,
// and its still image.
SegmentEnds buildSegmentEnds(const ClippedContext& ctx, const SegmentSpec& seg, SegmentTotals& totals) {
    const Scene& scene = ctx.job.scene;
    const RenderSettings& settings = ctx.job.render;
    const bool track_objects = ctx.job.output.cryptomatte.enabled;
    SegmentEnds ends;
    // Model no more than the scene needs: when nothing moves (and the subframe count is automatic) the
    // segment-start image is the answer, with no fragment triangles kept, no closing set and no subframes.
    ends.still_scene = seg.subframes == 0 && seg.window.still();
    ends.both_frames = settings.method != Method::Frame0Only && !ends.still_scene;
    const bool carry = ends.both_frames && seg.next_adjacent;
    int band = seg.bands[static_cast<std::size_t>(seg.index)];
    totals.stats.guard_band_pixels = std::max<long long>(totals.stats.guard_band_pixels, band);
    if (carry) band = std::max(band, seg.bands[static_cast<std::size_t>(seg.index) + 1]);
    const TileGrid grid = fragmentGrid(ctx, band);
    // Deep tiles hold what a surface hidden at both ends was seen over, within reach; its points at the
    // ends are within `band` of there.
    const TileSet open_deep = seg.deep.grown(ctx.frame.grid, band, grid);
    const TileSet close_deep = carry ? seg.deep.unite(seg.next_deep).grown(ctx.frame.grid, band, grid) : open_deep;
    const auto request = [&](double time, const TileSet& deep) {
        return FrameFragmentRequest{.time = time,
                                    .grid = &grid,
                                    .deep = &deep,
                                    .rays_per_side = settings.visibility_rays,
                                    .keep_triangles = !ends.still_scene,
                                    .audit = settings.audit,
                                    .leave_out = ctx.backdrop.behind_everything ? &ctx.backdrop.objects : nullptr};
    };
    const auto stage = Clock::now();
    const std::size_t film_pixels = scene.film.pixels().area();
    if (totals.carried) {
        ends.open = std::move(totals.carried->first);
        ends.still = std::move(totals.carried->second);
        totals.carried.reset();
    } else {
        FrameFragmentStats open_stats;
        ends.still = stillImage(totals, film_pixels, track_objects);
        ends.open = buildFrameFragments(ctx.frame, request(seg.window.t0, open_deep), &ends.still, open_stats);
        totals.stats.open.merge(open_stats);
        ++totals.stats.frame_sets;
    }
    if (ends.both_frames) {
        FrameFragmentStats close_stats;
        PixelSums next_still;
        if (carry) next_still = stillImage(totals, film_pixels, track_objects);
        ends.close = buildFrameFragments(ctx.frame, request(seg.window.t1, close_deep), carry ? &next_still : nullptr, close_stats);
        totals.stats.close.merge(close_stats);
        ++totals.stats.frame_sets;
        if (carry) totals.carried.emplace(ends.close, std::move(next_still));
    }
    totals.stats.seconds.frame_fragments += secondsSince(stage);
    return ends;
}

// Step 2's result: how the fragments move, each tile's re-clips, and with sweep integration the
// positions and camera turns of each interval, shared by every moving tile. Filled in place: `layers`
// points into `ode` and into the segment's ends.
struct SegmentPlan {
    FragmentLayers layers;
    std::optional<OdePropagator> ode;
    MotionPlan motion;
    bool sweep = false;  // the segment's time integration, time_integration auto resolved
    SweepSchedule intervals;  // sweep: what its moving tiles share
};

// Sweep positions per interval of a sweep plan.
std::vector<int> positionsOf(const ClippedContext& ctx, const SegmentSpec& seg, const SegmentPlan& plan,
                             const MotionPlan& motion) {
    return sweepPositions(ctx.job.scene, ctx.frame.projection, plan.layers,
                          {.t0 = seg.window.t0,
                           .t1 = seg.window.t1,
                           .intervals = sharedIntervals(motion.tiles),
                           .spacing = ctx.job.render.sweep_spacing,
                           .max_positions = ctx.job.render.max_subframes,
                           .exact = ctx.job.render.sweep_time == SweepTime::Exact,
                           .reach = largestReach(motion.tiles),
                           .shutter_share = seg.weight});
}

// The tile plans and, for time_integration auto, which of point subframes and sweep the segment uses:
// both are planned from one measurement and the cheaper by integrationCost is kept. A fixed subframe
// count is point subframes' (nothing to trade at equal spacing), and a backdrop left out of the fragment
// sets (Backdrop::behind_everything) is only composited by sweep.
void chooseIntegration(const ClippedContext& ctx, const SegmentSpec& seg, SegmentPlan& plan, ClippedStats& stats) {
    const RenderSettings& settings = ctx.job.render;
    const FragmentPaths paths = measurePaths(ctx.frame, seg.window, plan.layers);
    // Sweep re-clips sample relative motion as positions sample each fragment's own: as far apart as the
    // spacing, finer too. A finer spacing that kept the re-clips would leave their error (visibility
    // frozen over an interval, falling about as the spacing of relative motion) where it was.
    MotionPlanOptions options{.subframes = seg.subframes,
                              .max_subframes = settings.max_subframes,
                              .shutter_share = seg.weight,
                              .reclip_spacing = settings.reclip_spacing > 0.0 ? settings.reclip_spacing : settings.sweep_spacing,
                              .backdrop = ctx.backdrop};
    const bool automatic = settings.time_integration == TimeIntegration::Auto;
    if (automatic && seg.subframes == 0 && !ctx.backdrop.behind_everything) {
        options.point_spacing = settings.sweep_spacing;
        MotionPlan points = planMotion(ctx.frame, seg.window, plan.layers, paths, options);
        // Each bound below only raises sweep's cost, so the choice is the full model's.
        IntegrationCost cost{.points = pointsCost(points), .sweep = 0.0};
        if (ctx.backdrop.empty()) cost.sweep = sweepFloor(points);
        std::optional<MotionPlan> swept;
        std::vector<int> positions;
        if (cost.sweep < cost.points) {
            options.sweep = true;
            swept = planMotion(ctx.frame, seg.window, plan.layers, paths, options);
            // Positions only add to sweep's cost: where its re-clips alone cost more, none are laid out.
            cost = integrationCost(points, *swept, {});
            if (cost.sweep < cost.points) {
                positions = positionsOf(ctx, seg, plan, *swept);
                cost = integrationCost(points, *swept, positions);
            }
        }
        plan.sweep = cost.sweep < cost.points;
        plan.motion = std::move(plan.sweep ? *swept : points);
        if (plan.sweep) plan.intervals.positions = std::move(positions);
        stats.auto_cost_points += cost.points;
        stats.auto_cost_sweep += cost.sweep;
    } else {
        plan.sweep = settings.maySweep();
        options.sweep = plan.sweep;
        plan.motion = planMotion(ctx.frame, seg.window, plan.layers, paths, options);
        if (plan.sweep) plan.intervals.positions = positionsOf(ctx, seg, plan, plan.motion);
    }
    ++(plan.sweep ? stats.segments_sweep : stats.segments_points);
}

// Re-clips per tile from the fragments' image-plane speeds (eq. 24, corrected) or, with sweep
// integration, from relative motion and path bend (planMotion).
void planSegment(const ClippedContext& ctx, const SegmentSpec& seg, const SegmentEnds& ends, SegmentTotals& totals,
                 SegmentPlan& plan) {
    const Scene& scene = ctx.job.scene;
    const RenderSettings& settings = ctx.job.render;
    const auto stage = Clock::now();
    FragmentLayers& layers = plan.layers;
    layers.triangles = {&ends.open, ends.both_frames ? &ends.close : nullptr};
    if (settings.path_method != PathMethod::Exact) {
        plan.ode.emplace(scene, ctx.frame.projection, seg.window.t0, seg.window.t1,
                         OdeStepping{.method = settings.path_method == PathMethod::Euler ? OdeMethod::Euler : OdeMethod::Rk4,
                                     .steps = settings.ode_steps});
        layers.ode = &*plan.ode;
    }
    if (ctx.shutter) layers.shutter = {&ctx.shutter->first, &ctx.shutter->second};
    chooseIntegration(ctx, seg, plan, totals.stats);
    totals.stats.capped_tiles += plan.motion.capped_tiles;
    totals.stats.measured_fragment_paths += plan.motion.measured;
    totals.stats.near_crossing_fragments += plan.motion.near_crossings;
    totals.stats.sweep_backdrop_tiles += plan.motion.backdrop_tiles;
    plan.intervals.intervals = sharedIntervals(plan.motion.tiles);
    plan.intervals.exact = ctx.job.render.sweep_time == SweepTime::Exact;
    if (plan.sweep)
        plan.intervals.turns =
            turnsPerInterval(scene, ctx.frame.projection, seg.window.t0, seg.window.t1, plan.intervals.positions);
    totals.stats.seconds.motion_plan += secondsSince(stage);
}

// What the tiles of a segment integrate: its span, weight and fixed count, its ends and its plan.
SegmentIntegration integrationOf(const ClippedContext& ctx, const SegmentSpec& seg, const SegmentEnds& ends,
                                 const SegmentPlan& plan, const SnapshotCache& snapshots) {
    const RenderSettings& settings = ctx.job.render;
    return {.frame = ctx.frame,
            .window = ctx.window,
            .span = {.t0 = seg.window.t0, .t1 = seg.window.t1, .curve_begin = seg.curve_begin, .curve_end = seg.curve_end},
            .weight = seg.weight,
            .subframes = seg.subframes,
            .shadows = settings.shadows,
            .audit = settings.audit,
            .track_objects = ctx.job.output.cryptomatte.enabled,
            .still = ends.still,
            .still_scene = ends.still_scene,
            .layers = plan.layers,
            .motion = plan.motion,
            .sweep = plan.sweep ? &plan.intervals : nullptr,
            .snapshots = snapshots};
}

// With a backdrop in some tile (MotionPlan::backdrop), the sums the segment's front goes to, kept apart
// until every spill is in (null otherwise); they and the backdrop's image are made when a segment first
// needs them.
WindowSums* backdropFront(const ClippedContext& ctx, const SegmentPlan& plan, std::size_t pixels, SegmentTotals& totals) {
    if (plan.motion.backdrop_tiles == 0) return nullptr;
    if (!totals.front) totals.front.emplace(pixels, ctx.job.output.cryptomatte.enabled);
    if (!totals.backdrop)
        totals.backdrop = renderBackdrop(ctx.job, ctx.frame, ctx.backdrop, 0.5 * (ctx.frame.motion.t0() + ctx.frame.motion.t1()),
                                         totals.stats.backdrop.emplace());
    return &*totals.front;
}

// Integrates every tile of the segment into `target` (integrateTile), with progress and cancellation;
// returns what sweep spilled into other tiles' pixels, per tile. Visibility and the plan stay global so a
// window's pixels are bit-identical to the same pixels of the whole film; only the tiles the window
// touches are integrated.
std::vector<std::vector<Spill>> integrateTiles(const ClippedContext& ctx, const SegmentSpec& seg,
                                               const SegmentIntegration& segment, WindowSums& target, ClippedStats& stats) {
    const int tiles = ctx.frame.grid.count();
    std::atomic<bool> cancelled{false};
    std::atomic<long long> tiles_done{0};
    std::mutex merge_mutex;
    const long long progress_total = static_cast<long long>(tiles) * static_cast<long long>(seg.bands.size());
    std::vector<std::vector<Spill>> spills(segment.sweep ? static_cast<std::size_t>(tiles) : 0);
    tbb::enumerable_thread_specific<ReclipScratch> scratches;
    TileOutputs outputs{target, spills, scratches};
    parallelFor(0, tiles, [&](int index) {
        if (ctx.frame.callbacks.cancel && ctx.frame.callbacks.cancel->load(std::memory_order_relaxed)) {
            cancelled = true;
            return;
        }
        ReclipStats tile_stats;
        const int n = integrateTile(segment, index, outputs, tile_stats);
        std::lock_guard lock(merge_mutex);
        if (n >= 0) {
            stats.reclip.merge(tile_stats);
            stats.subframes_total += n;
            stats.still_tiles += n == 0 ? 1 : 0;
            stats.subframes_max_per_tile = std::max<long long>(stats.subframes_max_per_tile, n);
        }
        const long long done = ++tiles_done + static_cast<long long>(seg.index) * tiles;
        if (ctx.frame.callbacks.progress) ctx.frame.callbacks.progress(done, progress_total);
    });
    if (cancelled) throw Error(ExitCode::Interrupted, "render cancelled");
    for (const auto& tile_spills : spills) stats.sweep_spilled_pixels += static_cast<long long>(tile_spills.size());
    return spills;
}

// The paper's method over one shutter segment: fragment sets at both ends, the plan of each tile's
// re-clips, integration of each tile, then the merge of what tiles spilled, in tile order, and a
// backdrop's composite; adds weight x (the segment's average) to `sums`.
void renderSegment(const ClippedContext& ctx, const SegmentSpec& seg, WindowSums& sums, SegmentTotals& totals) {
    SegmentEnds ends = buildSegmentEnds(ctx, seg, totals);
    ctx.frame.embree.releaseSegmentScenes(seg.next_times);
    SegmentPlan plan;
    planSegment(ctx, seg, ends, totals, plan);

    WindowSums* front = backdropFront(ctx, plan, sums.colour.size(), totals);
    WindowSums& target = front ? *front : sums;
    const auto stage = Clock::now();
    const SnapshotCache snapshots(ctx.job.scene, ctx.frame.projection);
    std::vector<std::vector<Spill>> spills =
        integrateTiles(ctx, seg, integrationOf(ctx, seg, ends, plan, snapshots), target, totals.stats);
    addSpills(spills, ctx.window, ctx.frame.grid.tileSize(), target);
    if (front) compositeBackdrop(ctx, {*front, *totals.backdrop, plan.motion, seg.weight}, sums);
    totals.spare_stills.push_back(std::move(ends.still));
    totals.stats.seconds.tiles += secondsSince(stage);
}

}  // namespace

namespace {

// Shutter segments (one unless something turns far), each rendered by the paper's method and weighted
// by its length, with deep tiles where something is hidden at both its ends.
std::vector<ShutterSegment> shutterSegmentsOf(const ClippedContext& ctx, ClippedStats& stats) {
    const RenderSettings& settings = ctx.job.render;
    const auto stage = Clock::now();
    std::vector<ShutterSegment> segments = equalSegments(
        ctx.frame.motion.t0(), ctx.frame.motion.t1(),
        stats.both_frames ? shutterSegments(ctx.frame.motion, settings.segments, settings.max_segments) : 1);
    if (stats.both_frames) segments = splitAtCurve(segments, ctx.curve);  // frame0_only: the opening image
    HiddenProbe probe;
    if (stats.both_frames && settings.segments == 0 && visibilityCanChange(ctx.frame.motion.shutter())) {
        const int cap = std::max(ctx.job.scene.film.width, ctx.job.scene.film.height) / 2;
        for (ShutterSegment& s : segments) {
            std::optional<int> band;  // the segment's guard band: a scan of the scene, so only where needed
            const auto reach = [&] {
                if (!band) band = guardBandPixels(ctx.frame.motion, ctx.frame.projection, ctx.frame.motion.window(s.begin, s.end), cap);
                return *band;
            };
            s.deep = hiddenTiles(ctx.frame, s, reach, probe).unite(turningObjectTiles(ctx.frame, s, reach));
        }
    }
    stats.segments = static_cast<long long>(segments.size());
    // The probe's Embree scenes but those the first segment's fragment sets need.
    const MotionWindow first = ctx.frame.motion.window(segments.front().begin, segments.front().end);
    ctx.frame.embree.releaseSegmentScenes(std::array{first.t0, first.t1});
    stats.hidden_probe_samples = probe.samples;
    stats.hidden_probe_hits = probe.hidden;
    stats.seconds.hidden_probe = secondsSince(stage);
    return segments;
}

// Renders every segment into `sums`. A fixed subframe count is shared out so the shutter has that many
// in total.
void renderSegments(const ClippedContext& ctx, const std::vector<ShutterSegment>& segments, WindowSums& sums,
                    SegmentTotals& totals) {
    const Scene& scene = ctx.job.scene;
    const int fixed_total = ctx.job.render.subframes;
    const auto stage = Clock::now();
    std::vector<MotionWindow> windows;
    std::vector<int> bands;
    for (const ShutterSegment& s : segments) {
        windows.push_back(ctx.frame.motion.window(s.begin, s.end));
        bands.push_back(guardBandPixels(ctx.frame.motion, ctx.frame.projection, windows.back(),
                                        std::max(scene.film.width, scene.film.height) / 2));
    }
    // A fixed count's share before a fraction of the shutter (1e-9: sums of 1/n reach whole numbers).
    const auto before = [&](double fraction) { return static_cast<int>(std::floor(fixed_total * fraction + 1e-9)); };
    double share = 0.0;  // of the shutter, before segment s
    for (std::size_t s = 0; s < segments.size(); ++s) {
        const bool last = s + 1 == segments.size();
        const std::array<double, 2> next = last ? std::array<double, 2>{} : std::array{windows[s + 1].t0, windows[s + 1].t1};
        const int fixed = fixed_total > 0 ? std::max(1, before(share + segments[s].weight) - before(share)) : 0;
        const ShutterSegment& segment = segments[s];
        const SegmentSpec spec{.window = windows[s],
                               .weight = segment.weight,
                               .curve_begin = segment.curve_begin,
                               .curve_end = segment.curve_end,
                               .subframes = fixed,
                               .deep = segment.deep,
                               .next_deep = last ? segment.deep : segments[s + 1].deep,
                               .index = static_cast<int>(s),
                               .bands = bands,
                               .next_adjacent = !last && segments[s + 1].begin == segment.end,
                               .next_times = last ? std::span<const double>() : std::span<const double>(next)};
        renderSegment(ctx, spec, sums, totals);
        share += segment.weight;
    }
    totals.stats.seconds.segments = secondsSince(stage);
}

// The window's pixels from the shutter's sums; depth from the mid-shutter set when there is one.
void writeWindow(const ClippedContext& ctx, WindowSums& sums, const std::optional<PixelSums>& mid, RenderResult& result) {
    const Scene& scene = ctx.job.scene;
    result.image = Image::make(scene.film.width, scene.film.height, ctx.window, outputChannels(ctx.job.output));
    ImageWriter writer(result.image);
    parallelFor(ctx.window.y0, ctx.window.y1, [&](int y) {  // each pixel on its own
        for (int x = ctx.window.x0; x < ctx.window.x1; ++x) {
            const std::size_t i = ctx.window.index(x, y);
            const std::size_t p = scene.film.pixels().index(x, y);
            const float z = mid ? meanDepth(mid->depth[p], mid->covered[p]) : meanDepth(sums.depth[i], sums.covered[i]);
            writer.write(result.image.index(x, y), sums.colour[i], sums.covered[i], z, sums.motion[i]);
            if (sums.objects.empty()) continue;
            const double scale = overCoverScale(sums.covered[i]);
            for (ObjectShare& o : sums.objects[i]) o.coverage *= scale;
        }
    });
    result.objects.pixels = std::move(sums.objects);  // window-local row-major, as the image
}

}  // namespace

RenderResult renderClipped(const RenderJob& job, int frame, const RenderCallbacks& callbacks) {
    const auto start = Clock::now();
    const ParallelLedger parallel;
    const Scene& scene = job.scene;
    const RenderSettings& settings = job.render;
    const FrameMotion motion(scene, frame + job.shutter.open, frame + job.shutter.close);

    // A backdrop behind everything is rendered on its own: rays for the fragment sets need not meet it.
    const Backdrop backdrop = findBackdrop(job, motion);
    const FrameBuild build(motion,
                           {.tile_size = settings.tile_size,
                            .shadows = settings.shadows,
                            .fragment_shading = settings.fragment_shading,
                            .leave_out = backdrop.behind_everything ? &backdrop.objects : nullptr},
                           callbacks);
    const FrameSetup& setup = build.setup();
    const ShutterCurve curve(job.shutter, frame);
    std::optional<std::pair<MotionSnapshot, MotionSnapshot>> shutter;
    if (job.output.aov_motion)
        shutter.emplace(MotionSnapshot(scene, setup.projection, motion.t0()), MotionSnapshot(scene, setup.projection, motion.t1()));
    const ClippedContext ctx{job, setup, renderWindow(job), curve, backdrop, shutter};
    RenderResult result;
    SegmentTotals totals;
    ClippedStats& stats = totals.stats;
    stats.both_frames = settings.method != Method::Frame0Only;
    stats.auto_integration = settings.time_integration == TimeIntegration::Auto;
    stats.ode = settings.path_method != PathMethod::Exact;
    stats.tiles = ctx.frame.grid.count();
    stats.triangles = setup.embree.stats().triangles;
    stats.backdrop_behind_everything = backdrop.behind_everything;
    stats.seconds.scene_build = secondsSince(start);

    const std::vector<ShutterSegment> segments = shutterSegmentsOf(ctx, stats);
    WindowSums sums(ctx.window.area(), job.output.cryptomatte.enabled);
    renderSegments(ctx, segments, sums, totals);
    stats.estimated_error = estimateTimeError(sums.levels);
    FrameFragmentStats mid_stats;
    std::optional<EmbreeScene> whole;  // the mid-shutter depth sees the backdrop too
    if (backdrop.behind_everything && job.output.aov_depth) whole.emplace(build.device(), motion);
    const std::optional<PixelSums> mid = midShutterDepth(
        job,
        whole ? FrameSetup{motion, *whole, setup.adjacency, setup.shader, setup.projection, setup.grid, callbacks} : setup,
        mid_stats);
    writeWindow(ctx, sums, mid, result);
    result.level_differences = std::move(sums.levels);

    if (mid) stats.mid = mid_stats;
    if (settings.audit)
        stats.audit = checkAudit({{"the open sets", &stats.open.audit},
                                  {"the backdrop", stats.backdrop ? &stats.backdrop->audit : nullptr},
                                  {"the close sets", &stats.close.audit},
                                  {"the mid-shutter set", &mid_stats.audit},
                                  {"a re-clip", &stats.reclip.audit}});
    if (stats.capped_tiles > 0)
        result.stats.warnings.push_back(std::to_string(stats.capped_tiles) + " tiles needed more than max_subframes (" +
                                        std::to_string(settings.max_subframes) + "); motion there may strobe");
    stats.seconds.serial = secondsSince(start) - parallel.seconds();
    result.stats.method = std::move(stats);
    return result;
}

RenderResult renderAccumulation(const RenderJob& job, int frame, const RenderCallbacks& callbacks) {
    const Scene& scene = job.scene;
    const RenderSettings& settings = job.render;
    const FrameMotion motion(scene, frame + job.shutter.open, frame + job.shutter.close);
    const std::size_t pixels = scene.film.pixels().area();
    const int n = std::max(1, settings.samples);

    const FrameBuild build(
        motion,
        {.tile_size = settings.tile_size, .shadows = settings.shadows, .fragment_shading = settings.fragment_shading},
        callbacks);
    const FrameSetup& setup = build.setup();

    const bool track_objects = job.output.cryptomatte.enabled;
    PixelSums total;
    total.resize(pixels, track_objects);
    FrameFragmentStats frame_stats;
    // An accumulation buffer's renders at equal weights; a shutter curve places them at its quantiles
    // (k + 1/2) / n, as the stochastic method draws its times from the curve.
    const ShutterCurve curve(job.shutter, frame);
    std::vector<double> times = subframeTimes(motion.t0(), motion.t1(), n);
    if (!curve.box())
        for (int k = 0; k < n; ++k) times[static_cast<std::size_t>(k)] = curve.timeAt((k + 0.5) / n);
    for (const double t : times) {
        PixelSums sums;
        sums.resize(pixels, track_objects);
        buildFrameFragments(
            setup, {.time = t, .rays_per_side = settings.visibility_rays, .keep_triangles = false, .audit = settings.audit},
            &sums, frame_stats);
        for (std::size_t p = 0; p < pixels; ++p) {
            total.colour[p] += sums.colour[p];
            total.covered[p] += sums.covered[p];
            total.depth[p] += sums.depth[p];
            if (track_objects) addShares(total.objects[p], sums.objects[p], 1.0);
        }
    }
    FrameFragmentStats mid_stats;
    const std::optional<PixelSums> mid = midShutterDepth(job, setup, mid_stats);
    RenderResult result;
    const PixelBounds window = renderWindow(job);
    result.image = Image::make(scene.film.width, scene.film.height, window, outputChannels(job.output));
    ImageWriter writer(result.image);
    for (int y = window.y0; y < window.y1; ++y) {
        for (int x = window.x0; x < window.x1; ++x) {
            const std::size_t p = scene.film.pixels().index(x, y);
            const float z = mid ? meanDepth(mid->depth[p], mid->covered[p]) : meanDepth(total.depth[p], total.covered[p]);
            writer.write(result.image.index(x, y), total.colour[p] / double(n), total.covered[p] / double(n), z,
                         glm::dvec2(0.0));
            if (!track_objects) continue;
            ObjectShares& shares = total.objects[p];
            const double scale = overCoverScale(total.covered[p] / double(n));
            for (ObjectShare& o : shares) o.coverage = o.coverage / double(n) * scale;
            result.objects.pixels.push_back(std::move(shares));  // the window in row-major order
        }
    }
    AccumulationStats stats;
    stats.renders = n;
    stats.all = frame_stats;
    if (mid) stats.mid = mid_stats;
    if (settings.audit)
        stats.audit = checkAudit({{"a subframe's set", &frame_stats.audit}, {"the mid-shutter set", &mid_stats.audit}});
    result.stats.method = std::move(stats);
    return result;
}

}  // namespace clipblur
