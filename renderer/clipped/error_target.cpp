#include "renderer/clipped/error_target.h"

#include <algorithm>
#include <cmath>

#include "renderer/clipped/clipped_renderer.h"
#include "renderer/stopwatch.h"

namespace clipblur {

namespace {

constexpr double kPilotSpacing = 1.0;  // px: where the estimate's order 2 holds (docs/performance.md)
constexpr int kPilotSubframes = 27;    // point subframes: 9 groups of three per segment-free shutter
constexpr double kMinSpacing = 0.01, kMaxSpacing = 1000.0;  // render.sweep_spacing's range
constexpr double kMeasuredRatio = 1.5;  // a render this much coarser than the pilot is measured against it

// The pilot's job: the whole film, the given setting.
RenderJob pilotJob(const RenderJob& job, double spacing, int subframes) {
    RenderJob pilot = job;
    pilot.render.window.reset();
    pilot.render.error_target = 0.0;
    if (job.render.time_integration != TimeIntegration::Subframes)
        pilot.render.sweep_spacing = spacing;
    else
        pilot.render.subframes = subframes;
    return pilot;
}

// Whether two renders of one frame did the same integration work: re-clips and sweep positions.
bool sameWork(const ClippedStats& x, const ClippedStats& y) {
    return x.subframes_total == y.subframes_total && x.reclip.sweep_positions == y.reclip.sweep_positions;
}

}  // namespace

double rmsDifference(const Image& fine, const Image& image) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const char* name : {"R", "G", "B"}) {
        const Image::Channel* a = fine.find(name);
        const Image::Channel* b = image.find(name);
        if (!a || !b) continue;
        const PixelBounds& w = image.window;
        for (int y = w.y0; y < w.y1; ++y)
            for (int x = w.x0; x < w.x1; ++x) {
                const double d = double(b->values[image.index(x, y)]) - a->values[fine.index(x, y)];
                sum += d * d;
                ++n;
            }
    }
    return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

double spacingForTarget(double setting, double estimate, double target) {
    if (!(estimate > 0.0)) return setting;
    const double r = target / estimate;
    return setting * (r >= 1.0 ? r : std::sqrt(r));
}

RenderResult renderToErrorTarget(const RenderJob& job, int frame, const RenderCallbacks& callbacks) {
    const auto start = Clock::now();
    // Sweep and auto are tuned by the spacing (auto spaces point subframes by it too).
    const bool sweep = job.render.time_integration != TimeIntegration::Subframes;
    const RenderCallbacks quiet{nullptr, callbacks.cancel};
    double spacing = kPilotSpacing;
    int subframes = std::min(kPilotSubframes, job.render.max_subframes);
    RenderResult pilot;
    double estimate = 0.0;
    int renders = 0;
    for (int attempt = 0; attempt < 3; ++attempt) {
        pilot = renderClipped(pilotJob(job, spacing, subframes), frame, quiet);
        ++renders;
        estimate = pilot.stats.clipped().estimated_error;
        if (estimate > 0.0 || attempt == 2) break;
        spacing = std::max(kMinSpacing, spacing / 4.0);
        subframes = std::min(job.render.max_subframes, subframes * 4);
    }
    const double pilot_seconds = secondsSince(start);
    const double target = job.render.error_target;
    // The setting as an interval between samples: pixels of spacing, or the shutter over the subframes.
    const double pilot_interval = sweep ? spacing : 1.0 / subframes;
    const auto jobAt = [&](double interval) {
        RenderJob out = job;
        out.render.error_target = 0.0;
        if (sweep)
            out.render.sweep_spacing = std::clamp(interval, kMinSpacing, kMaxSpacing);
        else
            out.render.subframes = std::clamp(static_cast<int>(std::ceil(1.0 / interval - 1e-9)), 1, job.render.max_subframes);
        return out;
    };
    const auto intervalOf = [&](const RenderJob& j) { return sweep ? j.render.sweep_spacing : 1.0 / j.render.subframes; };
    const auto measured = [&](const RenderJob& j) { return intervalOf(j) >= kMeasuredRatio * pilot_interval; };
    // A render coarser than the pilot is judged against the pilot image: the two error fields are nearly
    // independent, so the difference is sqrt(e^2 + e_pilot^2), within 1.2x of the render's own e when the
    // pilot's is under 2/3 of it (order >= 1 at 1.5x the interval). Its own estimate falls 1.3-3x short
    // at coarse intervals (docs/performance.md). Error both share (sweep's re-clips) is not seen.
    const auto errorOf = [&](const RenderJob& j, const RenderResult& r) {
        return measured(j) ? rmsDifference(pilot.image, r.image) : r.stats.clipped().estimated_error;
    };
    RenderJob final_job = jobAt(spacingForTarget(pilot_interval, estimate, target));
    RenderResult result = renderClipped(final_job, frame, callbacks);
    ++renders;
    double reached = errorOf(final_job, result);
    ClippedStats previous = pilot.stats.clipped();
    // Corrections where the model missed by more than 4/3: the order measured between the pilot and this
    // render (kept within [1, 3]) carries this render's error to the target. One where the render is finer
    // than the pilot (renders are dear there), two where it is measured against it (they are cheap).
    // None where this render did the work of the one before it (the same re-clips and sweep positions):
    // the setting no longer sets the work there, as where re-clips leave one position per interval, so
    // another render could only repeat it.
    for (int k = 0; k < (measured(final_job) ? 2 : 1); ++k) {
        const double interval = intervalOf(final_job);
        if (!(reached > 0.0 && estimate > 0.0) || (reached <= target * 4.0 / 3.0 && reached >= target * 0.75) ||
            std::abs(std::log(interval / pilot_interval)) <= 1e-6 || sameWork(previous, result.stats.clipped()))
            break;
        const double order = std::clamp(std::log(reached / estimate) / std::log(interval / pilot_interval), 1.0, 3.0);
        const RenderJob corrected = jobAt(interval * std::pow(target / reached, 1.0 / order));
        if (intervalOf(corrected) == interval) break;
        final_job = corrected;
        previous = result.stats.clipped();
        result = renderClipped(final_job, frame, callbacks);
        ++renders;
        reached = errorOf(final_job, result);
    }
    ClippedStats& stats = std::get<ClippedStats>(result.stats.method);
    stats.target = ErrorTargetStats{.error_target = job.render.error_target,
                                    .pilot_estimated_error = estimate,
                                    .pilot_seconds = pilot_seconds,
                                    .renders = renders,
                                    .sweep_spacing = sweep ? final_job.render.sweep_spacing : 0.0,
                                    .subframes = sweep ? 0 : final_job.render.subframes,
                                    .reached_error = reached,
                                    .against_pilot = measured(final_job)};
    return result;
}

}  // namespace clipblur
