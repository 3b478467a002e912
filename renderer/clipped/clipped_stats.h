#pragma once

#include <optional>

#include "renderer/clipped/frame_fragments.h"
#include "renderer/clipped/subframe_reclip.h"

namespace clipblur {

// render.error_target: what the pilot measured and what it chose (error_target.h).
struct ErrorTargetStats {
    double error_target = 0.0;
    double pilot_estimated_error = 0.0;
    double pilot_seconds = 0.0;
    long long renders = 0;       // pilots, the render, corrections and re-clip checks
    double sweep_spacing = 0.0;  // sweep: the chosen spacing
    double reclip_spacing = 0.0;  // sweep: the re-clip spacing where the re-clip check chose one
    double reclip_order = 0.0;    // sweep: the re-clip error's order, where the check measured it
    long long subframes = 0;     // point subframes: the chosen count
    double reached_error = 0.0;  // what the choice was judged by: against the pilot, or the estimate
    bool against_pilot = false;  // the render was well coarser than the pilot and measured against it
    bool pilot_kept = false;     // the coarser renders missed the target: the pilot is the result
    long long bisections = 0;    // renders bisecting between one under the target and one over
    double finer_pilot = 0.0;    // the interval of a second pilot, where the target was finer than the first's
    long long max_subframes = 0;  // the re-clip cap, where capped tiles' error made the target raise it
    long long max_segments = 0;   // the segment cap, where a target far above the answer's error lowered it

    template <class Fields>
    void fields(Fields& f) const {
        f.value("error", error_target);
        f.value("pilot_estimated_error", pilot_estimated_error);
        f.seconds("pilot", pilot_seconds);
        f.count("renders", renders);
        if (sweep_spacing > 0.0) f.value("sweep_spacing", sweep_spacing);
        if (reclip_spacing > 0.0) f.value("reclip_spacing", reclip_spacing);
        if (reclip_order > 0.0) f.value("reclip_order", reclip_order);
        if (subframes > 0) f.count("subframes", subframes);
        f.value(against_pilot ? "error_against_pilot" : "estimated_error", reached_error);
        f.count("pilot_kept", pilot_kept ? 1 : 0);
        f.count("bisections", bisections);
        if (finer_pilot > 0.0) f.value("finer_pilot", finer_pilot);
        if (max_subframes > 0) f.count("max_subframes", max_subframes);
        if (max_segments > 0) f.count("max_segments", max_segments);
    }
};

// What the paper's method (and its frame-0-only ablation) did for one frame.
struct ClippedStats {
    struct Seconds {
        double scene_build = 0.0, hidden_probe = 0.0, segments = 0.0;
        double frame_fragments = 0.0, motion_plan = 0.0, tiles = 0.0;  // the parts of `segments`
        // The render's thread outside its parallel loops (ParallelLedger): what more threads cannot shorten.
        double serial = 0.0;
    } seconds;
    bool both_frames = true;  // false: render.method frame0_only
    bool auto_integration = false;  // render.time_integration auto
    bool ode = false;         // render.path_method euler or rk4
    long long tiles = 0, triangles = 0, segments = 0, frame_sets = 0, guard_band_pixels = 0;
    long long hidden_probe_samples = 0, hidden_probe_hits = 0;
    long long still_tiles = 0, subframes_total = 0, subframes_max_per_tile = 0, capped_tiles = 0;
    long long measured_fragment_paths = 0, near_crossing_fragments = 0;
    long long sweep_spilled_pixels = 0, sweep_backdrop_tiles = 0;  // sweep: see SegmentTotals, MotionPlan
    long long segments_points = 0, segments_sweep = 0;  // segments integrated by each (time_integration)
    // auto: integrationCost summed over segments; sweep's a lower bound (sweepFloor, or without positions)
    // where that already lost
    double auto_cost_points = 0.0, auto_cost_sweep = 0.0;
    bool backdrop_behind_everything = false;
    // The image's RMS time-sampling error over R, G, B as the render estimates it (time_error.h).
    double estimated_error = 0.0;
    std::optional<ErrorTargetStats> target;  // render.error_target
    ReclipStats reclip;
    FrameFragmentStats open, close;
    std::optional<FrameFragmentStats> mid, backdrop;  // the mid-shutter depth set, the still backdrop
    std::optional<AuditStats> audit;                  // render.audit: every set and re-clip merged

    template <class Fields>
    void fields(Fields& f) const {
        f.info("method", both_frames ? "clipped" : "frame0_only");
        f.seconds("scene_build", seconds.scene_build);
        f.seconds("hidden_probe", seconds.hidden_probe);
        f.seconds("segments", seconds.segments);
        f.seconds("frame_fragments", seconds.frame_fragments);
        f.seconds("motion_plan", seconds.motion_plan);
        f.seconds("tiles", seconds.tiles);
        f.seconds("serial", seconds.serial);
        f.count("tiles", tiles);
        f.count("triangles", triangles);
        f.count("segments", segments);
        f.count("hidden_probe_samples", hidden_probe_samples);
        f.count("hidden_probe_hits", hidden_probe_hits);
        f.count("frame_sets", frame_sets);
        f.count("segments_points", segments_points);
        f.count("segments_sweep", segments_sweep);
        if (auto_integration) {
            f.value("auto_cost_points", auto_cost_points);
            f.value("auto_cost_sweep", auto_cost_sweep);
        }
        f.count("guard_band_pixels", guard_band_pixels);
        f.count("still_tiles", still_tiles);
        f.count("subframes_total", subframes_total);
        f.count("subframes_max_per_tile", subframes_max_per_tile);
        f.count("capped_tiles", capped_tiles);
        f.count("measured_fragment_paths", measured_fragment_paths);
        f.count("near_crossing_fragments", near_crossing_fragments);
        f.value("estimated_error", estimated_error);
        f.count("propagated_triangles", reclip.propagated);
        f.count("reclip_near_clipped", reclip.near_clipped);
        f.count("reclip_fragments", reclip.fragments);
        f.count("reclip_mixed_fragments", reclip.mixed);
        f.count("reclip_shaded_pieces", reclip.shaded_pieces);
        if (segments_sweep > 0) {
            f.count("sweep_positions", reclip.sweep_positions);
            f.count("sweep_unswept_fragments", reclip.sweep_unswept);
            f.count("sweep_spilled_pixels", sweep_spilled_pixels);
            f.count("sweep_backdrop_tiles", sweep_backdrop_tiles);
            f.count("sweep_backdrop_behind_everything", backdrop_behind_everything ? 1 : 0);
        }
        if (ode) f.count("ode_fallbacks", reclip.ode_fallbacks);
        f.nest("open_", open);
        if (both_frames) f.nest("close_", close);
        if (mid) f.nest("mid_", *mid);
        if (backdrop) f.nest("backdrop_", *backdrop);
        if (audit) f.nest("audit_", *audit);
        if (target) f.nest("target_", *target);
    }
};

// What the accumulation buffer did for one frame.
struct AccumulationStats {
    long long renders = 0;
    FrameFragmentStats all;  // every still render's fragment set
    std::optional<FrameFragmentStats> mid;
    std::optional<AuditStats> audit;

    template <class Fields>
    void fields(Fields& f) const {
        f.info("method", "accumulation");
        f.count("renders", renders);
        f.nest("all_", all);
        if (mid) f.nest("mid_", *mid);
        if (audit) f.nest("audit_", *audit);
    }
};

}  // namespace clipblur
